// Faces of Part-like primitives (cylinders, cones, spheres, tori; whole, partial, placed) convert
// to B-spline surfaces that are exact (measured by projecting onto the primitive's own surface,
// both ways) and smooth by their knots before and after the sheet's refinement to cubic: OCCT's
// Boolean argument check refuses any face whose surface is C0 by multiplicity ("BOPAlgo
// GeomAbs_C0"), which its own circle conversion (double knots) is.
#include <gtest/gtest.h>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/revolved_surface.hpp"
#include "varsurf/occ/surface_refinement.hpp"

using namespace varsurf;

namespace {

struct Case {
  std::string name;
  TopoDS_Shape shape;
};

std::vector<Case> primitives() {
  // Placed off the origin and tilted: the conversion must follow the surface's own frame.
  const gp_Ax2 frame(gp_Pnt(3.0, -2.0, 7.0), gp_Dir(1.0, 1.0, 2.0), gp_Dir(1.0, -1.0, 0.0));
  return {
      {"cylinder", BRepPrimAPI_MakeCylinder(5.0, 10.0).Shape()},
      {"placed cylinder", BRepPrimAPI_MakeCylinder(frame, 40.0, 3.0).Shape()},
      {"cylinder 120 deg", BRepPrimAPI_MakeCylinder(5.0, 10.0, 2.0 * M_PI / 3.0).Shape()},
      {"cone", BRepPrimAPI_MakeCone(5.0, 2.0, 10.0).Shape()},
      {"cone from its apex", BRepPrimAPI_MakeCone(frame, 0.0, 5.0, 10.0).Shape()},
      {"cone 200 deg", BRepPrimAPI_MakeCone(5.0, 2.0, 10.0, 200.0 * M_PI / 180.0).Shape()},
      {"sphere", BRepPrimAPI_MakeSphere(frame, 5.0).Shape()},
      {"sphere band", BRepPrimAPI_MakeSphere(5.0, -0.7, 1.0, 3.5).Shape()},
      {"torus", BRepPrimAPI_MakeTorus(frame, 30.0, 8.0).Shape()},
      {"torus piece", BRepPrimAPI_MakeTorus(30.0, 8.0, -1.0, 2.0, 4.0).Shape()},
  };
}

// The primitive's curved (lateral) face: the first face whose surface is not a plane.
TopoDS_Face curved_face(const TopoDS_Shape& shape) {
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face face = TopoDS::Face(ex.Current());
    if (GeomAdaptor_Surface(BRep_Tool::Surface(face)).GetType() != GeomAbs_Plane) return face;
  }
  return TopoDS_Face();
}

double size_of(const TopoDS_Face& face) {
  double u1, u2, v1, v2;
  BRepTools::UVBounds(face, u1, u2, v1, v2);
  const Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  double size = 0.0;
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j)
      size = std::max(size, s->Value(u1, v1).Distance(
                                s->Value(u1 + (u2 - u1) * i / 8, v1 + (v2 - v1) * j / 8)));
  return size;
}

// Largest distance from `from` sampled over its domain (off the knots) to `to`.
double farthest(const Handle(Geom_Surface) & from, double u1, double u2, double v1, double v2,
                const Handle(Geom_Surface) & to) {
  double worst = 0.0;
  for (int i = 0; i <= 12; ++i) {
    for (int j = 0; j <= 12; ++j) {
      const double u = u1 + (u2 - u1) * std::min(1.0, (i + 0.37) / 12.37);
      const double v = v1 + (v2 - v1) * std::min(1.0, (j + 0.61) / 12.61);
      const gp_Pnt p = from->Value(u, v);
      GeomAPI_ProjectPointOnSurf foot(p, to);
      EXPECT_GT(foot.NbPoints(), 0);
      if (foot.NbPoints() > 0) worst = std::max(worst, foot.LowerDistance());
    }
  }
  return worst;
}

// Smooth by its knots as OCCT judges it: no interior knot of multiplicity >= the degree.
void expect_smooth_knots(const Handle(Geom_BSplineSurface) & s, const std::string& what) {
  EXPECT_NE(s->Continuity(), GeomAbs_C0) << what;
  for (int i = 2; i < s->NbUKnots(); ++i)
    EXPECT_LT(s->UMultiplicity(i), s->UDegree()) << what << " u knot " << s->UKnot(i);
  for (int i = 2; i < s->NbVKnots(); ++i)
    EXPECT_LT(s->VMultiplicity(i), s->VDegree()) << what << " v knot " << s->VKnot(i);
}

}  // namespace

TEST(GeomConvert, ElementaryFacesConvertExactlyAndSmoothly) {
  for (const Case& c : primitives()) {
    SCOPED_TRACE(c.name);
    const TopoDS_Face face = curved_face(c.shape);
    ASSERT_FALSE(face.IsNull());
    const Handle(Geom_Surface) analytic = BRep_Tool::Surface(face);
    double u1, u2, v1, v2;
    BRepTools::UVBounds(face, u1, u2, v1, v2);
    const double size = size_of(face);

    const Handle(Geom_BSplineSurface) nurbs = occ::to_geom(occ::surface_from_face(face));
    expect_smooth_knots(nurbs, c.name);
    double a1, a2, b1, b2;
    nurbs->Bounds(a1, a2, b1, b2);
    // Each direction keeps the face's own parameters at its ends (a sphere's latitude too).
    EXPECT_NEAR(a1, u1, 1e-12);
    EXPECT_NEAR(a2, u2, 1e-12);
    EXPECT_NEAR(b1, v1, 1e-12);
    EXPECT_NEAR(b2, v2, 1e-12);
    for (double su : {0.0, 1.0})
      for (double sv : {0.0, 1.0})
        EXPECT_LE(nurbs->Value(a1 + su * (a2 - a1), b1 + sv * (b2 - b1))
                      .Distance(analytic->Value(u1 + su * (u2 - u1), v1 + sv * (v2 - v1))),
                  1e-12 * size);
    // Exact both ways: the B-spline lies on the primitive and covers the face.
    EXPECT_LE(farthest(nurbs, a1, a2, b1, b2, analytic), 1e-12 * size);
    EXPECT_LE(farthest(analytic, u1, u2, v1, v2, nurbs), 1e-10 * size);

    // The sheet's space (cubic at least, 16 spans each way) stays smooth and on the face.
    const Handle(Geom_BSplineSurface) sheet =
        occ::to_geom(occ::refine_surface(occ::surface_from_face(face), 16, 16, 3));
    expect_smooth_knots(sheet, c.name + " refined");
    EXPECT_LE(farthest(sheet, a1, a2, b1, b2, analytic), 1e-12 * size);
  }
}

TEST(GeomConvert, OcctsOwnConversionIsC0ByItsKnots) {
  // Why the conversion is not GeomConvert's: its circles are quadratic arcs joined at double
  // knots, which the Boolean argument check refuses, and degree elevation keeps them C0.
  const TopoDS_Face face = curved_face(BRepPrimAPI_MakeCylinder(5.0, 10.0).Shape());
  double u1, u2, v1, v2;
  BRepTools::UVBounds(face, u1, u2, v1, v2);
  const Handle(Geom_BSplineSurface) occt = GeomConvert::SurfaceToBSplineSurface(
      new Geom_RectangularTrimmedSurface(BRep_Tool::Surface(face), u1, u2, v1, v2));
  EXPECT_EQ(occt->Continuity(), GeomAbs_C0);
  occt->IncreaseDegree(3, 3);
  EXPECT_EQ(occt->Continuity(), GeomAbs_C0);
}

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
