// SPDX-License-Identifier: LGPL-2.1-or-later
// Revolved surfaces as B-splines smooth by their knots: of a cylinder's faces only the lateral one
// converts; its planes, and a box longer than a turn, are left to GeomConvert (null).
#include <gtest/gtest.h>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Surface.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax1.hxx>

#include <algorithm>
#include <cmath>

#include "occ_test_support.hpp"
#include "varsurf/occ/revolved_surface.hpp"

using namespace varsurf;

namespace {

using test::curved_face;

}  // namespace

TEST(GeomConvert, OtherSurfacesAreLeftToGeomConvert) {
  const TopoDS_Shape box = BRepPrimAPI_MakeCylinder(5.0, 10.0).Shape();
  for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face face = TopoDS::Face(ex.Current());
    const Handle(Geom_Surface) s = BRep_Tool::Surface(face);
    const bool plane = GeomAdaptor_Surface(s).GetType() == GeomAbs_Plane;
    EXPECT_EQ(occ::smooth_revolved_surface(s, 0.0, 1.0, 0.0, 1.0).IsNull(), plane);
  }
  // A box longer than a turn is not an arc.
  const Handle(Geom_Surface) cylinder =
      BRep_Tool::Surface(curved_face(BRepPrimAPI_MakeCylinder(5.0, 10.0).Shape()));
  EXPECT_TRUE(occ::smooth_revolved_surface(cylinder, 0.0, 7.0, 0.0, 1.0).IsNull());
}

TEST(GeomConvert, ARevolvedBSplineProfileIsExactAndSmoothByItsKnots) {
  // A sketch-like profile (a cubic B-spline in the xz plane) turned a whole turn about a tilted
  // axis: the tensor product is the surface of revolution to rounding, and its u knots are
  // those of one arc (no double knots, which OCCT's Boolean check refuses).
  TColgp_Array1OfPnt points(1, 4);
  points(1) = gp_Pnt(12, 0, 0);
  points(2) = gp_Pnt(16, 1, 10);
  points(3) = gp_Pnt(10, -1, 22);
  points(4) = gp_Pnt(13, 0, 34);
  const Handle(Geom_BSplineCurve) profile = GeomAPI_PointsToBSpline(points).Curve();
  const gp_Ax1 axis(gp_Pnt(1, 2, 3), gp_Dir(0.1, -0.2, 1.0));
  const Handle(Geom_SurfaceOfRevolution) rev = new Geom_SurfaceOfRevolution(profile, axis);
  const double v1 = profile->FirstParameter(), v2 = profile->LastParameter();
  const Handle(Geom_BSplineSurface) b = occ::smooth_revolved_surface(rev, 0.0, 2 * M_PI, v1, v2);
  ASSERT_FALSE(b.IsNull());
  for (int k = 1; k < b->NbUKnots(); ++k)
    EXPECT_EQ(b->UMultiplicity(k + 1), k + 1 < b->NbUKnots() ? 1 : 7);
  double worst = 0.0;
  for (int i = 0; i <= 12; ++i)
    for (int j = 0; j <= 12; ++j) {
      const double u = 2 * M_PI * i / 12, v = v1 + (v2 - v1) * j / 12;
      const gp_Pnt p = b->Value(u, v);
      GeomAPI_ProjectPointOnSurf foot(p, rev);
      ASSERT_TRUE(foot.NbPoints() > 0);
      worst = std::max(worst, foot.LowerDistance());
      // The v parameter is the profile's own: same height along the axis as its point.
      const gp_Pnt q = profile->Value(v);
      EXPECT_NEAR(gp_Vec(axis.Location(), p).Dot(gp_Vec(axis.Direction())),
                  gp_Vec(axis.Location(), q).Dot(gp_Vec(axis.Direction())), 1e-9);
    }
  EXPECT_LT(worst, 1e-9);
  // The seam closes: the two u ends are the profile itself.
  for (int j = 0; j <= 6; ++j) {
    const double v = v1 + (v2 - v1) * j / 6;
    EXPECT_LT(b->Value(0.0, v).Distance(profile->Value(v)), 1e-9);
    EXPECT_LT(b->Value(2 * M_PI, v).Distance(profile->Value(v)), 1e-9);
  }
  // A profile the conversion would reparametrize (a circle: a torus by another name) is left
  // to GeomConvert.
  const Handle(Geom_SurfaceOfRevolution) ring = new Geom_SurfaceOfRevolution(
      new Geom_Circle(gp_Ax2(gp_Pnt(20, 0, 0), gp::DY()), 3.0), gp::OZ());
  EXPECT_TRUE(occ::smooth_revolved_surface(ring, 0.0, 2 * M_PI, 0.0, M_PI).IsNull());
}
