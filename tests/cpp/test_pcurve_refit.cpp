// SPDX-License-Identifier: LGPL-2.1-or-later
// Pcurves refitted to their edge's 3D curve: a circle on a flat sheet whose parametrization is
// not linear (so its exact pcurve is no polynomial), given a coarse pcurve as sewing leaves one.
#include <gtest/gtest.h>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
// (after the shapes it takes)
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib_CheckCurveOnSurface.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom_Circle.hxx>
#include <Precision.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2.hxx>

#include <cmath>

#include "occ_test_support.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/mass_properties.hpp"
#include "varsurf/occ/pcurve_refit.hpp"

using namespace varsurf;

namespace {

constexpr double kSize = 40.0;
constexpr double kRadius = 12.0;

// x = kSize * g(u) with g(u) = (u + u^3) / 2: a flat sheet, parametrized unevenly along u.
double g(double u) {
  return 0.5 * (u + u * u * u);
}

double g_inverse(double x) {
  double u = x;
  for (int it = 0; it < 60; ++it) u -= (g(u) - x) / (0.5 + 1.5 * u * u);
  return u;
}

Handle(Geom_BSplineSurface) uneven_plane() {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 2, 2);
  s.poles = test::fit_poles(
      s.space, [](double u, double v) { return Eigen::Vector3d(kSize * g(u), kSize * v, 0.0); });
  return occ::to_geom(s);
}

struct Scene {
  TopoDS_Face face;
  TopoDS_Edge edge;
};

// The sheet bounded by a circle of kRadius about its middle, `lift` above it, whose pcurve is the
// interpolant of `points` exact feet (coarse for few points).
Scene circle_on_plane(double lift, int points) {
  const Handle(Geom_BSplineSurface) surface = uneven_plane();
  const gp_Pnt centre(kSize / 2, kSize / 2, lift);
  const Handle(Geom_Circle) circle = new Geom_Circle(gp_Ax2(centre, gp::DZ()), kRadius);
  Handle(TColgp_HArray1OfPnt2d) feet = new TColgp_HArray1OfPnt2d(1, points);
  // Chord-length parameters would not match the circle's: interpolate at its own angles.
  Handle(TColStd_HArray1OfReal) angles = new TColStd_HArray1OfReal(1, points);
  for (int k = 1; k <= points; ++k) {
    angles->SetValue(k, 2 * M_PI * (k - 1) / (points - 1));
    const gp_Pnt p = circle->Value(angles->Value(k));
    feet->SetValue(k, gp_Pnt2d(g_inverse(p.X() / kSize), p.Y() / kSize));
  }
  Geom2dAPI_Interpolate fit(feet, angles, Standard_False, 1e-12);
  fit.Perform();
  BRep_Builder b;
  Scene s;
  b.MakeFace(s.face, surface, Precision::Confusion());
  TopoDS_Vertex v;
  b.MakeVertex(v, circle->Value(0.0), 1e-2);
  b.MakeEdge(s.edge, circle, 1e-2);
  b.Add(s.edge, v.Oriented(TopAbs_FORWARD));
  b.Add(s.edge, v.Oriented(TopAbs_REVERSED));
  b.Range(s.edge, 0.0, 2 * M_PI);
  b.UpdateEdge(s.edge, fit.Curve(), s.face, 1e-2);
  TopoDS_Wire w;
  b.MakeWire(w);
  b.Add(w, s.edge);
  w.Closed(Standard_True);
  b.Add(s.face, w);
  return s;
}

double deviation(const Scene& s) {
  BRepLib_CheckCurveOnSurface check(s.edge, s.face);
  check.Perform();
  return check.MaxDistance();
}

}  // namespace

TEST(PcurveRefit, ACoarsePcurveIsRefittedToTheCircleAndTheToleranceFallsToConfusion) {
  const Scene s = circle_on_plane(0.0, 9);
  const double before = deviation(s);
  ASSERT_GT(before, 1e-4);  // 9 feet: a coarse pcurve, as sewing leaves
  EXPECT_EQ(occ::refit_pcurves(s.face, Precision::Confusion()), 1);
  EXPECT_LE(deviation(s), 2e-9);  // refitted to 1e-9 of the feet, as OCCT's check measures it
  EXPECT_DOUBLE_EQ(BRep_Tool::Tolerance(s.edge), Precision::Confusion());
  EXPECT_TRUE(BRepCheck_Analyzer(s.face).IsValid());
  // The face is the disc: its area to the integration's precision.
  EXPECT_NEAR(occ::mass_properties(s.face, 1e-12).area, M_PI * kRadius * kRadius, 1e-8);
}

TEST(PcurveRefit, WhereTheSurfaceReallyPartsFromTheCurveTheToleranceStillCoversTheGap) {
  const double lift = 2e-5;
  const Scene s = circle_on_plane(lift, 9);
  ASSERT_GT(deviation(s), 5 * lift);
  EXPECT_EQ(occ::refit_pcurves(s.face, Precision::Confusion()), 1);
  EXPECT_NEAR(deviation(s), lift, 2e-9);  // the feet, no closer: the circle is above the sheet
  EXPECT_GE(BRep_Tool::Tolerance(s.edge), lift);
  EXPECT_LE(BRep_Tool::Tolerance(s.edge), 1.001 * lift);
}

TEST(PcurveRefit, CloseEnoughPcurvesAreLeftAlone) {
  const Scene s = circle_on_plane(0.0, 401);
  const Handle(Geom2d_Curve) given = [&] {
    double f = 0.0, l = 0.0;
    return BRep_Tool::CurveOnSurface(s.edge, s.face, f, l);
  }();
  const double before = deviation(s);
  // Above this threshold nothing is touched.
  EXPECT_EQ(occ::refit_pcurves(s.face, 2 * before), 0);
  double f = 0.0, l = 0.0;
  EXPECT_EQ(BRep_Tool::CurveOnSurface(s.edge, s.face, f, l), given);
  EXPECT_DOUBLE_EQ(BRep_Tool::Tolerance(s.edge), 1e-2);
}
