// SPDX-License-Identifier: LGPL-2.1-or-later
// Curves projected onto sheets: known pre-images recovered across knot lines and a cylinder's C0
// knots, curves above or beyond a sheet or across its seam, and bad input. Curves on the base
// face's own boundary: their pre-images are the boundary exactly (not a rounding error inside it),
// closed faces' seams are entered from the right side, and a sheet through its base's boundary
// edges, with the boundary kept and the base as rest shape, is the base. The faces and edges are
// built as a modeller builds them: primitives and their own edges.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAbs_SurfaceType.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Circ.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "occ_test_support.hpp"
#include "test_support.hpp"
#include "varsurf/core/constraints.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"
#include "varsurf/core/spline_space.hpp"
#include "varsurf/occ/curve_projection.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/point_projection.hpp"
#include "varsurf/occ/sheet_domain.hpp"
#include "varsurf/occ/surface_refinement.hpp"

namespace varsurf {
namespace {

using test::face_of;

std::vector<TopoDS_Edge> edges_of(const TopoDS_Shape& shape) {
  std::vector<TopoDS_Edge> out;
  for (TopExp_Explorer ex(shape, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge e = TopoDS::Edge(ex.Current());
    bool seen = false;
    for (const TopoDS_Edge& o : out) seen = seen || o.IsSame(e);
    if (!seen && !BRep_Tool::Degenerated(e)) out.push_back(e);
  }
  return out;
}

// 0 when the pre-image lies exactly on a bound of the domain in some direction (every pole's
// coordinate equal to the bound), else the smallest distance of a pole's coordinate to a bound.
double off_boundary(const BSplineSurface& base, const BSplineCurve& pre) {
  const Eigen::Vector2d lo(base.space.u_first(), base.space.v_first());
  const Eigen::Vector2d hi(base.space.u_last(), base.space.v_last());
  double best = INFINITY;
  for (int c = 0; c < 2; ++c) {
    for (double bound : {lo(c), hi(c)}) {
      double worst = 0.0;
      for (int i = 0; i < pre.pole_count(); ++i)
        worst = std::max(worst, std::abs(pre.poles(i, c) - bound));
      best = std::min(best, worst);
    }
  }
  return best;
}

// Max distance between the target and the sheet at the pre-image, at 1000 parameters.
double incidence(const BSplineSurface& base, const occ::PreImage& pre, const BSplineCurve& target) {
  double worst = 0.0;
  for (int k = 0; k <= 1000; ++k) {
    const double t = target.first() + (target.last() - target.first()) * k / 1000.0;
    const Eigen::Vector2d uv = pre.curve.evaluate(t);
    worst =
        std::max(worst, (base.evaluate(uv(0), uv(1)) - Eigen::Vector3d(target.evaluate(t))).norm());
  }
  return worst;
}

// Sheet on `base` (refined to 16 spans, cubic) through `curves`, boundary kept, base as rest
// shape: the largest pole displacement from the base.
double sheet_moves(const BSplineSurface& base, const std::vector<BSplineCurve>& curves) {
  const BSplineSurface sheet = occ::refine_surface(base, 16, 16, 3);
  SheetProblem pb;
  pb.space = sheet.space;
  pb.initial_poles = sheet.poles;
  pb.rest_poles = sheet.poles;
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  pb.fixed_poles = boundary_pole_indices(sheet.space);
  for (const BSplineCurve& target : curves)
    pb.curves.push_back({occ::project_curve(base, target).curve, target, 1.0});
  SolveOptions opt;
  opt.fit_tolerance = 0.25 * 0.01;
  const SolveResult r = solve_sheet(pb, opt);
  return (r.poles - sheet.poles).rowwise().norm().maxCoeff();
}

TopoDS_Face interpolated_face() {
  TColgp_Array2OfPnt grid(1, 8, 1, 8);
  for (int i = 1; i <= 8; ++i)
    for (int j = 1; j <= 8; ++j)
      grid(i, j) = gp_Pnt(10.0 * (i - 1), 10.0 * (j - 1),
                          3.0 * ((i - 4) * (i - 4) - (j - 4) * (j - 4)) / 9.0);
  GeomAPI_PointsToBSplineSurface fit;
  fit.Interpolate(grid);
  return BRepBuilderAPI_MakeFace(fit.Surface(), 1e-7).Face();
}

// Part.makePlane(100, 60): each of its four edges is a side of the domain exactly.
TEST(BoundaryCurves, PlaneEdgesProjectOntoTheDomainsSides) {
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0.0, 100.0, 0.0, 60.0).Face();
  const BSplineSurface base = occ::surface_from_face(face);
  std::vector<BSplineCurve> curves;
  for (const TopoDS_Edge& e : edges_of(face)) {
    const BSplineCurve target = occ::curve_from_edge(e);
    const occ::PreImage pre = occ::project_curve(base, target);
    EXPECT_EQ(off_boundary(base, pre.curve), 0.0);
    EXPECT_LT(pre.max_distance, 1e-12);
    EXPECT_LT(incidence(base, pre, target), 1e-12);
    curves.push_back(target);
  }
  ASSERT_EQ(curves.size(), 4u);
  EXPECT_LT(sheet_moves(base, {curves[0]}), 1e-12);
  // How far a kept boundary would have to move: the edge raised by 5; none for a curve inside.
  BSplineCurve raised = curves[0];
  raised.poles.col(2).array() += 5.0;
  EXPECT_NEAR(occ::project_curve(base, raised).boundary_distance, 5.0, 1e-12);
  Eigen::VectorXd a(3), b(3);
  a << 10, 10, 0;
  b << 90, 50, 0;
  EXPECT_EQ(occ::project_curve(base, test::line_curve(a, b)).boundary_distance, -1.0);
  EXPECT_LT(sheet_moves(base, curves), 1e-12);
}

// A Part box's top face (a plane placed at z = 40) through its own four edges.
TEST(BoundaryCurves, BoxTopFaceThroughItsOwnEdgesIsTheFace) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(100.0, 60.0, 40.0).Shape();
  const TopoDS_Face top = face_of(box, GeomAbs_Plane, 39.0);
  ASSERT_FALSE(top.IsNull());
  const BSplineSurface base = occ::surface_from_face(top);
  std::vector<BSplineCurve> curves;
  for (const TopoDS_Edge& e : edges_of(top)) {
    curves.push_back(occ::curve_from_edge(e));
    const occ::PreImage pre = occ::project_curve(base, curves.back());
    EXPECT_EQ(off_boundary(base, pre.curve), 0.0);
    EXPECT_LT(incidence(base, pre, curves.back()), 1e-12);
  }
  EXPECT_LT(sheet_moves(base, curves), 1e-12);
}

// An interpolated bicubic face (70 x 70 mm) through its own boundary edges.
TEST(BoundaryCurves, InterpolatedBSplineFaceThroughItsOwnEdgesIsTheFace) {
  const TopoDS_Face face = interpolated_face();
  const BSplineSurface base = occ::surface_from_face(face);
  std::vector<BSplineCurve> curves;
  for (const TopoDS_Edge& e : edges_of(face)) {
    curves.push_back(occ::curve_from_edge(e));
    const occ::PreImage pre = occ::project_curve(base, curves.back());
    EXPECT_EQ(off_boundary(base, pre.curve), 0.0);
    EXPECT_LT(incidence(base, pre, curves.back()), 1e-9);
  }
  ASSERT_EQ(curves.size(), 4u);
  EXPECT_LT(sheet_moves(base, curves), 1e-9);
}

// A cylinder's lateral face through its own two circles: each starts on the seam and goes once
// around, so its pre-image runs from one side of the seam to the other.
TEST(BoundaryCurves, CylinderCirclesRunFromSeamToSeam) {
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(20.0, 50.0).Shape();
  const TopoDS_Face lateral = face_of(cylinder, GeomAbs_Cylinder);
  const BSplineSurface base = occ::surface_from_face(lateral);
  std::vector<BSplineCurve> circles;
  for (const TopoDS_Edge& e : edges_of(lateral)) {
    double first, last;
    if (BRep_Tool::Curve(e, first, last)->DynamicType()->Name() != std::string("Geom_Circle"))
      continue;
    circles.push_back(occ::curve_from_edge(e));
    const occ::PreImage pre = occ::project_curve(base, circles.back());
    EXPECT_EQ(off_boundary(base, pre.curve), 0.0);
    // Within the fit's tolerance, 1e-7 of the turn (the base's NURBS form need not share the
    // circle's parametrization); the sheet is exact whatever it is, being on fixed poles there.
    EXPECT_LT(incidence(base, pre, circles.back()), 2e-7 * 2 * M_PI * 20.0);
    const double u0 = pre.curve.evaluate(pre.curve.first())(0);
    const double u1 = pre.curve.evaluate(pre.curve.last())(0);
    EXPECT_NEAR(std::abs(u1 - u0), 2 * M_PI, 1e-12);
  }
  ASSERT_EQ(circles.size(), 2u);
  EXPECT_LT(sheet_moves(base, circles), 1e-9);
}

// A circle starting a quarter turn from the seam goes around across it: refused with that cause.
TEST(BoundaryCurves, CircleAcrossTheSeamSaysSo) {
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(20.0, 50.0).Shape();
  const BSplineSurface base = occ::surface_from_face(face_of(cylinder, GeomAbs_Cylinder));
  const gp_Circ circle(gp_Ax2(gp_Pnt(0, 0, 25), gp::DZ()), 20.0);
  const BSplineCurve target =
      occ::curve_from_edge(BRepBuilderAPI_MakeEdge(circle, M_PI / 2, 2.5 * M_PI).Edge());
  try {
    occ::project_curve(base, target);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("crosses the seam of the closed face"), std::string::npos)
        << e.what();
  }
}

// The cylinder's seam line lies on both sides of its domain: the pre-image keeps to one.
TEST(BoundaryCurves, SeamLineStaysOnOneSide) {
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(20.0, 50.0).Shape();
  const TopoDS_Face lateral = face_of(cylinder, GeomAbs_Cylinder);
  const BSplineSurface base = occ::surface_from_face(lateral);
  int lines = 0;
  for (const TopoDS_Edge& e : edges_of(lateral)) {
    double first, last;
    if (BRep_Tool::Curve(e, first, last)->DynamicType()->Name() != std::string("Geom_Line"))
      continue;
    ++lines;
    const BSplineCurve target = occ::curve_from_edge(e);
    const occ::PreImage pre = occ::project_curve(base, target);
    EXPECT_EQ(off_boundary(base, pre.curve), 0.0);
    EXPECT_LT(incidence(base, pre, target), 1e-12);
    EXPECT_LT(sheet_moves(base, {target}), 1e-9);
  }
  EXPECT_EQ(lines, 1);
}

// A sphere segment (a quarter of its height, a third of its turn): its meridians end at the pole,
// where every u is the same point; the pre-image keeps the meridian's u up to the pole.
TEST(BoundaryCurves, MeridiansRunIntoThePole) {
  const TopoDS_Shape segment = BRepPrimAPI_MakeSphere(30.0, 0.0, M_PI / 2, 2 * M_PI / 3).Shape();
  const TopoDS_Face face = face_of(segment, GeomAbs_Sphere);
  const BSplineSurface base = occ::surface_from_face(face);
  const occ::SheetDomain domain(base);
  EXPECT_TRUE(domain.degenerate(1, 1));  // the pole
  EXPECT_FALSE(domain.degenerate(1, -1));
  EXPECT_FALSE(domain.closed(0));
  std::vector<BSplineCurve> curves;
  for (const TopoDS_Edge& e : edges_of(face)) {
    curves.push_back(occ::curve_from_edge(e));
    const occ::PreImage pre = occ::project_curve(base, curves.back());
    EXPECT_EQ(off_boundary(base, pre.curve), 0.0);  // the meridians' u up to the pole
    EXPECT_LT(incidence(base, pre, curves.back()), 2e-7 * 2 * M_PI * 30.0);
  }
  ASSERT_EQ(curves.size(), 3u);
  EXPECT_LT(sheet_moves(base, curves), 1e-9);
}

// A line along the side v = 0 that turns into the face: exactly on the side while along it.
TEST(BoundaryCurves, CurvePartlyAlongTheBoundary) {
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0.0, 100.0, 0.0, 60.0).Face();
  const BSplineSurface base = occ::surface_from_face(face);
  TColgp_Array1OfPnt poles(1, 3);
  poles(1) = gp_Pnt(10, 0, 0);
  poles(2) = gp_Pnt(50, 0, 0);
  poles(3) = gp_Pnt(70, 30, 0);
  TColStd_Array1OfReal knots(1, 3);
  TColStd_Array1OfInteger mults(1, 3);
  knots(1) = 0.0, knots(2) = 1.0, knots(3) = 2.0;
  mults(1) = 2, mults(2) = 1, mults(3) = 2;
  const BSplineCurve target =
      occ::from_geom(Handle(Geom_BSplineCurve)(new Geom_BSplineCurve(poles, knots, mults, 1)));
  const occ::PreImage pre = occ::project_curve(base, target);
  EXPECT_LT(incidence(base, pre, target), 1e-12);
  for (int k = 0; k <= 100; ++k) {
    const Eigen::Vector2d uv = pre.curve.evaluate(k / 100.0);
    EXPECT_EQ(uv(1), 0.0) << "t = " << k / 100.0;
  }
  EXPECT_GT(pre.curve.evaluate(1.5)(1), 10.0);
  EXPECT_LT(sheet_moves(base, {target}), 1e-12);
}

// A circle inside the face touching two of its sides (y = 0 and y = 60) at one point each.
TEST(BoundaryCurves, CircleTouchingTheBoundary) {
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0.0, 100.0, 0.0, 60.0).Face();
  const BSplineSurface base = occ::surface_from_face(face);
  const BSplineCurve target = occ::curve_from_edge(
      BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(50, 30, 0), gp::DZ()), 30.0)).Edge());
  const occ::PreImage pre = occ::project_curve(base, target);
  // Within the pre-image's fit tolerance (1e-7 of the domain's larger side) everywhere, and
  // within 1e-8 of the domain's side where it touches it (the solver clamps that much).
  EXPECT_LT(incidence(base, pre, target), 1e-5);
  for (int k = 0; k <= 1000; ++k) {
    const Eigen::Vector2d uv = pre.curve.evaluate(2 * M_PI * k / 1000.0);
    EXPECT_GE(uv(1), -60e-8);
    EXPECT_LE(uv(1), 60.0 + 60e-8);
  }
  EXPECT_LT(sheet_moves(base, {target}), 1e-9);
}

// A fit tolerance beyond the domain (found by the fuzzer as 1e300) made every fit's error
// overflow; the projection then evaluated a curve it never fitted.
TEST(ProjectionOptions, FitToleranceOutsideTheDomainIsRefused) {
  const BSplineSurface base = occ::surface_from_face(interpolated_face());
  const BSplineCurve target =
      occ::curve_from_edge(BRepBuilderAPI_MakeEdge(gp_Pnt(5, 5, 0), gp_Pnt(60, 50, 0)).Edge());
  occ::ProjectionOptions opt;
  for (double bad : {0.0, -1e-6, 0.5, 1e300, double(INFINITY), double(NAN)}) {
    opt.fit_tolerance = bad;
    EXPECT_THROW(occ::project_curve(base, target, opt), InvalidInput) << bad;
  }
  opt.fit_tolerance = 0.1;
  EXPECT_NO_THROW(occ::project_curve(base, target, opt));
}

// A picked vertex or point of a boundary edge is placed exactly on the boundary.
TEST(BoundaryPoints, VerticesAndEdgePointsLandExactlyOnTheBoundary) {
  const BSplineSurface base = occ::surface_from_face(interpolated_face());
  const occ::PointOnSheet corner = occ::project_point(base, base.evaluate(1.0, 1.0));
  EXPECT_EQ(corner.u, 1.0);
  EXPECT_EQ(corner.v, 1.0);
  EXPECT_LT(corner.distance, 1e-12);
  const occ::PointOnSheet side = occ::project_point(base, base.evaluate(1.0, 0.3));
  EXPECT_EQ(side.u, 1.0);
  EXPECT_NEAR(side.v, 0.3, 1e-9);
  const occ::PointOnSheet inside = occ::project_point(base, base.evaluate(1.0 - 1e-4, 0.3));
  EXPECT_NEAR(inside.u, 1.0 - 1e-4, 1e-12);
}

// On a curved sheet, the target is the image of a known straight pre-image crossing knot lines;
// D = S o c0 is a polynomial of degree 6 between crossings, so the target is exact.
TEST(ProjectCurve, RecoversTheParameterOfACurveOnTheSheet) {
  const BSplineSurface sheet = test::curved_sheet();
  const double t0 = 0.5, t1 = 2.5;
  auto c0 = [&](double t) {
    const double s = (t - t0) / (t1 - t0);
    return Eigen::Vector2d(0.05 + 0.9 * s, 0.15 + 0.7 * s);
  };
  // Knot-line crossings: u = 1/3, 2/3 and v = 1/2.
  std::vector<double> breaks = {t0, t1};
  for (double u : {1.0 / 3.0, 2.0 / 3.0}) breaks.push_back(t0 + (t1 - t0) * (u - 0.05) / 0.9);
  breaks.push_back(t0 + (t1 - t0) * (0.5 - 0.15) / 0.7);
  std::sort(breaks.begin(), breaks.end());
  const BSplineCurve target = test::fit_piecewise_curve(breaks, 6, 3, [&](double t) {
    const Eigen::Vector2d uv = c0(t);
    return Eigen::VectorXd(sheet.evaluate(uv(0), uv(1)));
  });

  const occ::PreImage pre = occ::project_curve(sheet, target);
  EXPECT_EQ(pre.curve.dim(), 2);
  EXPECT_EQ(pre.curve.first(), t0);
  EXPECT_EQ(pre.curve.last(), t1);
  EXPECT_LT(pre.max_distance, 1e-10);
  EXPECT_LT(pre.fit_error, 1e-8);
  double worst = 0.0, worst_uv = 0.0;
  for (int k = 0; k <= 1000; ++k) {
    const double t = t0 + (t1 - t0) * k / 1000.0;
    const Eigen::Vector2d uv = pre.curve.evaluate(t);
    worst = std::max(worst,
                     (sheet.evaluate(uv(0), uv(1)) - Eigen::Vector3d(target.evaluate(t))).norm());
    worst_uv = std::max(worst_uv, (uv - c0(t)).norm());
  }
  EXPECT_LT(worst, 1e-8);
  EXPECT_LT(worst_uv, 1e-8);
  // The solver's own view of the constraint agrees.
  const CurveConstraint cc{pre.curve, target, 1.0};
  EXPECT_LT(incidence_error(sheet.space, sheet.poles, cc, 500), 1e-8);
}

TEST(ProjectCurve, CurveAboveAPlaneProjectsAtItsHeight) {
  const BSplineSurface sheet = test::plane_sheet(10.0);
  Eigen::VectorXd a(3), b(3);
  a << 1, 2, 4;
  b << 9, 7, 4;
  const BSplineCurve target = test::line_curve(a, b, -1.0, 3.0);
  const occ::PreImage pre = occ::project_curve(sheet, target);
  EXPECT_NEAR(pre.max_distance, 4.0, 1e-12);
  EXPECT_EQ(pre.curve.first(), -1.0);
  EXPECT_EQ(pre.curve.last(), 3.0);
  EXPECT_LT((Eigen::Vector2d(pre.curve.evaluate(-1.0)) - Eigen::Vector2d(0.1, 0.2)).norm(), 1e-12);
  EXPECT_LT((Eigen::Vector2d(pre.curve.evaluate(1.0)) - Eigen::Vector2d(0.5, 0.45)).norm(), 1e-10);
}

TEST(ProjectCurve, CurveFromEdgeToEdgeStaysInsideTheDomain) {
  const BSplineSurface sheet = test::plane_sheet(10.0);
  Eigen::VectorXd a(3), b(3);
  a << 0, 3, 0;
  b << 10, 3, 0;
  const occ::PreImage pre = occ::project_curve(sheet, test::line_curve(a, b));
  EXPECT_LT(pre.max_distance, 1e-12);
  for (int i = 0; i < pre.curve.pole_count(); ++i) {
    EXPECT_GE(pre.curve.poles(i, 0), 0.0);
    EXPECT_LE(pre.curve.poles(i, 0), 1.0);
  }
  EXPECT_NEAR(pre.curve.evaluate(0.0)(0), 0.0, 1e-15);
  EXPECT_NEAR(pre.curve.evaluate(1.0)(0), 1.0, 1e-15);
}

TEST(ProjectCurve, CurveBeyondTheFaceThrows) {
  const BSplineSurface sheet = test::plane_sheet(10.0);
  Eigen::VectorXd a(3), b(3);
  a << 5, 5, 1;
  b << 15, 5, 1;
  try {
    occ::project_curve(sheet, test::line_curve(a, b));
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("leaves the face"), std::string::npos) << e.what();
  }
}

// The cylinder's NURBS form has C0 knot lines (double knots of a quadratic); the pre-image of an
// arc crossing them has kinks there, which must become breakpoints for the fit to converge.
TEST(ProjectCurve, ArcAroundACylinderConvergesWithFewPoles) {
  BRepBuilderAPI_MakeFace maker(gp_Cylinder(gp::XOY(), 2.0), 0.0, 2 * M_PI, 0.0, 5.0);
  const BSplineSurface sheet = occ::surface_from_face(maker.Face());
  BRepBuilderAPI_MakeEdge arc(gp_Circ(gp_Ax2(gp_Pnt(0, 0, 2), gp::DZ()), 3.0), 0.2, 6.0);
  const BSplineCurve target = occ::curve_from_edge(arc.Edge());
  const occ::PreImage pre = occ::project_curve(sheet, target);
  EXPECT_NEAR(pre.max_distance, 1.0, 1e-12);
  EXPECT_LT(pre.fit_error, 1e-7 * 2 * M_PI);
  EXPECT_LT(pre.curve.pole_count(), 60);
  EXPECT_EQ(pre.curve.first(), target.first());
  EXPECT_EQ(pre.curve.last(), target.last());
  for (int k = 0; k <= 200; ++k) {
    const double t = target.first() + (target.last() - target.first()) * k / 200.0;
    const Eigen::Vector2d uv = pre.curve.evaluate(t);
    const Eigen::Vector3d d = target.evaluate(t);
    // The foot point of (x, y, 2) on the cylinder is 2/3 of the way out, at the same height.
    EXPECT_LT(
        (sheet.evaluate(uv(0), uv(1)) - Eigen::Vector3d(d.x() * 2 / 3, d.y() * 2 / 3, 2)).norm(),
        1e-5);
  }
}

TEST(ProjectCurve, CrossingTheSeamOfAClosedSheetThrows) {
  BRepBuilderAPI_MakeFace maker(gp_Cylinder(gp::XOY(), 2.0), 0.0, 2 * M_PI, 0.0, 5.0);
  const BSplineSurface sheet = occ::surface_from_face(maker.Face());
  BRepBuilderAPI_MakeEdge arc(gp_Circ(gp_Ax2(gp_Pnt(0, 0, 2), gp::DZ()), 3.0), 3.0, 4.0 + M_PI);
  try {
    occ::project_curve(sheet, occ::curve_from_edge(arc.Edge()));
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("jumps"), std::string::npos) << e.what();
  }
}

TEST(ProjectCurve, RejectsBadInput) {
  const BSplineSurface sheet = test::plane_sheet(10.0);
  BSplineCurve flat = test::line_curve(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  EXPECT_THROW(occ::project_curve(sheet, flat), InvalidInput);  // 2D target
  Eigen::VectorXd a(3), b(3);
  a << 1, 1, std::nan("");
  b << 2, 2, 0;
  EXPECT_THROW(occ::project_curve(sheet, test::line_curve(a, b)), InvalidInput);
  BSplineSurface broken = sheet;
  broken.poles(0, 0) = INFINITY;
  a << 1, 1, 0;
  EXPECT_THROW(occ::project_curve(broken, test::line_curve(a, b)), InvalidInput);
}

}  // namespace
}  // namespace varsurf

namespace varsurf {
namespace {

// A tilted plane with a non-uniform, skewed affine parametrization S = a + u b + v c: poles on the
// affine function of the Greville abscissae (how a sheet from curves alone and every B-spline
// plane of FreeCAD's are built).
BSplineSurface affine_sheet(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  BSplineSurface s;
  s.space.degree_u = 3;
  s.space.degree_v = 2;
  s.space.knots_u = {0, 0, 0, 0, 0.2, 0.45, 1, 1, 1, 1};
  s.space.knots_v = {-1, -1, -1, 0.3, 2, 2, 2};
  s.poles = test::fit_poles(s.space, [&](double u, double v) { return a + u * b + v * c; });
  return s;
}

// A rational quadratic arc (a quarter circle of radius r about `centre` in the xy plane, lifted
// by `lift` along z at its middle pole).
BSplineCurve arc(const Eigen::Vector3d& centre, double r, double lift) {
  BSplineCurve c;
  c.degree = 2;
  c.knots = {0.5, 0.5, 0.5, 2, 2, 2};
  c.poles.resize(3, 3);
  c.poles.row(0) = (centre + Eigen::Vector3d(r, 0, 0)).transpose();
  c.poles.row(1) = (centre + Eigen::Vector3d(r, r, lift)).transpose();
  c.poles.row(2) = (centre + Eigen::Vector3d(0, r, 0)).transpose();
  c.weights.resize(3);
  c.weights << 1.0, std::sqrt(0.5), 1.0;
  return c;
}

const Eigen::Vector3d kA(3.0, -2.0, 1.0), kB(40.0, 5.0, 4.0), kC(-6.0, 15.0, 2.0);

TEST(AffinePreImage, IsTheTargetMappedPoleByPoleAndMeetsItAlongTheNormal) {
  const BSplineSurface sheet = affine_sheet(kA, kB, kC);
  const Eigen::Vector3d n = kB.cross(kC).normalized();
  const BSplineCurve target = arc(kA + 0.5 * kB + 0.4 * kC + 3.0 * n, 8.0, 2.5);
  const occ::PreImage pre = occ::project_curve(sheet, target);
  // Exact: the target's breakpoints only (no fit, no refinement), still rational, raised to the
  // degree the solver's sampling takes (3) with one more multiplicity at each knot.
  EXPECT_EQ(pre.curve.degree, 3);
  EXPECT_TRUE(pre.curve.rational());
  EXPECT_EQ(pre.curve.knots, std::vector<double>({0.5, 0.5, 0.5, 0.5, 2, 2, 2, 2}));
  EXPECT_LT(pre.fit_error, 1e-12);
  double height = 0.0;
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.5 + 1.5 * k / 400.0;
    const Eigen::Vector3d p = target.evaluate(t);
    const Eigen::Vector2d uv = pre.curve.evaluate(t);
    const Eigen::Vector3d foot = sheet.evaluate(uv(0), uv(1));
    EXPECT_LT((p - foot).cross(n).norm(), 1e-12 * 50.0) << t;  // straight above the foot
    height = std::max(height, std::abs(n.dot(p - kA)));
  }
  // The largest distance over the samples the general projection would take (64 here): the
  // height of one of them, within the sampling of the densely sampled peak.
  EXPECT_LE(pre.max_distance, height + 1e-12);
  EXPECT_GT(pre.max_distance, (1.0 - 1e-3) * height);
}

TEST(AffinePreImage, FollowsAGivenDirection) {
  const BSplineSurface sheet = affine_sheet(kA, kB, kC);
  const Eigen::Vector3d n = kB.cross(kC).normalized();
  const Eigen::Vector3d d = (n + 0.4 * kB.normalized()).normalized();
  occ::ProjectionOptions options;
  options.direction = d;
  const BSplineCurve target = arc(kA + 0.4 * kB + 0.3 * kC + 2.0 * n, 6.0, -1.5);
  const occ::PreImage pre = occ::project_curve(sheet, target, options);
  EXPECT_EQ(pre.curve.pole_count(), 4);  // the arc's one span, raised to degree 3
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.5 + 1.5 * k / 100.0;
    const Eigen::Vector2d uv = pre.curve.evaluate(t);
    const Eigen::Vector3d along =
        Eigen::Vector3d(target.evaluate(t)) - sheet.evaluate(uv(0), uv(1));
    EXPECT_LT(along.cross(d).norm(), 1e-12 * 50.0) << t;
  }
}

// A pole moved by 1e-9 of the sheet's size makes the sheet not affine: the general projection
// (sampling, Newton, fit) runs, and its pre-image agrees with the exact one of the flat sheet.
TEST(AffinePreImage, AgreesWithTheGeneralProjection) {
  const BSplineSurface flat = affine_sheet(kA, kB, kC);
  BSplineSurface bent = flat;
  bent.poles(bent.space.index(2, 1), 2) += 4e-8;
  const Eigen::Vector3d n = kB.cross(kC).normalized();
  const BSplineCurve target = arc(kA + 0.45 * kB + 0.5 * kC + 1.0 * n, 9.0, 3.0);
  const occ::PreImage exact = occ::project_curve(flat, target);
  const occ::PreImage general = occ::project_curve(bent, target);
  EXPECT_GT(general.curve.pole_count(), 4);  // fitted: knot-line crossings, refinement
  double worst = 0.0;
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.5 + 1.5 * k / 400.0;
    worst = std::max(worst, (exact.curve.evaluate(t) - general.curve.evaluate(t)).norm());
  }
  EXPECT_LT(worst, 1e-7);
  // Each the largest over its samples (the general one refines where it fits): within 1e-4.
  EXPECT_NEAR(exact.max_distance, general.max_distance, 1e-4 * general.max_distance);
}

// Targets the exact map cannot take go to the general projection and its messages: one leaving
// the face, one along the normal.
TEST(AffinePreImage, LeavesTheRefusalsToTheGeneralProjection) {
  const BSplineSurface sheet = affine_sheet(kA, kB, kC);
  const Eigen::Vector3d n = kB.cross(kC).normalized();
  const BSplineCurve beyond = arc(kA + 0.9 * kB + 0.5 * kC, 20.0, 0.0);
  EXPECT_THROW(occ::project_curve(sheet, beyond), InvalidInput);
  const Eigen::Vector3d p = kA + 0.5 * kB + 0.5 * kC;
  const BSplineCurve up = test::line_curve(p, p + 10.0 * n);
  try {
    occ::project_curve(sheet, up);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("along the sheet's normal"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace varsurf
