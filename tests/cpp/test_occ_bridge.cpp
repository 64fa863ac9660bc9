// The OpenCASCADE layer: conversions, face/edge extraction, projection, face building, STEP, and
// deviation, each checked against OCCT's own evaluation or a known geometric answer.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Eigen/Geometry>
#include <GProp_GProps.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Line.hxx>
#include <Standard_DomainError.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Circ.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "test_support.hpp"
#include "varsurf/core/constraints.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/brep_io.hpp"
#include "varsurf/occ/closest_point.hpp"
#include "varsurf/occ/curve_projection.hpp"
#include "varsurf/occ/deviation.hpp"
#include "varsurf/occ/face_builder.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/normal_field.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/point_projection.hpp"
#include "varsurf/occ/shape_check.hpp"
#include "varsurf/occ/single_shape.hpp"
#include "varsurf/occ/step_io.hpp"
#include "varsurf/occ/surface_refinement.hpp"

namespace varsurf {
namespace {

using occ::GeometryError;

Eigen::Vector3d vec(const gp_Pnt& p) {
  return {p.X(), p.Y(), p.Z()};
}

// Bicubic-by-biquadratic space with non-uniform knots and a double interior knot in v.
SplineSpace irregular_space() {
  SplineSpace s;
  s.degree_u = 3;
  s.degree_v = 2;
  s.knots_u = {0, 0, 0, 0, 0.3, 0.45, 1, 1, 1, 1};
  s.knots_v = {-1, -1, -1, 0.2, 0.2, 0.7, 2, 2, 2};
  return s;
}

BSplineSurface random_surface(const SplineSpace& space, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  BSplineSurface s;
  s.space = space;
  s.poles.resize(space.size(), 3);
  for (int i = 0; i < space.nu(); ++i)
    for (int j = 0; j < space.nv(); ++j)
      s.poles.row(space.index(i, j)) << i + 0.3 * d(rng), j + 0.3 * d(rng), d(rng);
  return s;
}

// A sheet over [0, 1]^2 whose image is the square [0, size]^2 in the plane z = height.
BSplineSurface plane_sheet(double size, double height = 0.0) {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 2, 2);
  s.poles = test::fit_poles(
      s.space, [&](double u, double v) { return Eigen::Vector3d(size * u, size * v, height); });
  return s;
}

// A curved bicubic sheet over [0, 1]^2 with 3 x 2 spans.
BSplineSurface curved_sheet() {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 3, 2);
  s.poles = test::fit_poles(s.space, [](double u, double v) {
    return Eigen::Vector3d(4.0 * u + 0.3 * v * v, 3.0 * v, std::sin(2.0 * u) * std::cos(1.5 * v));
  });
  return s;
}

BSplineCurve random_curve(int dim, bool rational, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  BSplineCurve c;
  c.degree = 3;
  c.knots = {0.5, 0.5, 0.5, 0.5, 0.9, 1.0, 1.0, 1.7, 2.5, 2.5, 2.5, 2.5};
  c.poles.resize(8, dim);
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < dim; ++k) c.poles(i, k) = i * (k == 0) + d(rng);
  if (rational) {
    c.weights.resize(8);
    for (int i = 0; i < 8; ++i) c.weights(i) = 1.0 + 0.5 * d(rng);
  }
  return c;
}

// ---------------------------------------------------------------------------------------------
// Core <-> Geom

class SurfaceRoundTrip : public ::testing::TestWithParam<bool> {};

TEST_P(SurfaceRoundTrip, EvaluatesLikeOcctAndComesBackExactly) {
  BSplineSurface s = random_surface(irregular_space(), 7);
  if (GetParam()) {
    s.space.weights.resize(s.space.size());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> w(0.5, 2.0);
    for (int k = 0; k < s.space.size(); ++k) s.space.weights(k) = w(rng);
  }
  const Handle(Geom_BSplineSurface) g = occ::to_geom(s);
  EXPECT_EQ(g->NbUPoles(), s.space.nu());
  EXPECT_EQ(g->NbVPoles(), s.space.nv());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0), v(-1.0, 2.0);
  for (int k = 0; k < 200; ++k) {
    const double uu = u(rng), vv = v(rng);
    EXPECT_LT((vec(g->Value(uu, vv)) - s.evaluate(uu, vv)).norm(), 1e-12) << uu << ", " << vv;
  }
  const BSplineSurface back = occ::from_geom(g);
  EXPECT_EQ(back.space.knots_u, s.space.knots_u);
  EXPECT_EQ(back.space.knots_v, s.space.knots_v);
  EXPECT_EQ(back.space.degree_u, 3);
  EXPECT_EQ(back.space.degree_v, 2);
  EXPECT_LT((back.poles - s.poles).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(back.space.rational(), GetParam());
  if (GetParam()) {
    EXPECT_LT((back.space.weights - s.space.weights).cwiseAbs().maxCoeff(), 1e-15);
  }
}

INSTANTIATE_TEST_SUITE_P(RationalAndNot, SurfaceRoundTrip, ::testing::Bool());

class CurveRoundTrip : public ::testing::TestWithParam<bool> {};

TEST_P(CurveRoundTrip, ThreeDimensional) {
  const BSplineCurve c = random_curve(3, GetParam(), 5);
  const Handle(Geom_BSplineCurve) g = occ::to_geom_curve(c);
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.5 + 2.0 * k / 100.0;
    EXPECT_LT((vec(g->Value(t)) - Eigen::Vector3d(c.evaluate(t))).norm(), 1e-12);
  }
  const BSplineCurve back = occ::from_geom(g);
  EXPECT_EQ(back.knots, c.knots);
  EXPECT_LT((back.poles - c.poles).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(back.rational(), GetParam());
}

TEST_P(CurveRoundTrip, TwoDimensional) {
  const BSplineCurve c = random_curve(2, GetParam(), 9);
  const Handle(Geom2d_BSplineCurve) g = occ::to_geom2d_curve(c);
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.5 + 2.0 * k / 100.0;
    const gp_Pnt2d p = g->Value(t);
    EXPECT_LT((Eigen::Vector2d(p.X(), p.Y()) - Eigen::Vector2d(c.evaluate(t))).norm(), 1e-12);
  }
  const BSplineCurve back = occ::from_geom(g);
  EXPECT_EQ(back.knots, c.knots);
  EXPECT_EQ(back.dim(), 2);
  EXPECT_LT((back.poles - c.poles).cwiseAbs().maxCoeff(), 1e-15);
}

INSTANTIATE_TEST_SUITE_P(RationalAndNot, CurveRoundTrip, ::testing::Bool());

TEST(GeomConvert, PeriodicCurveIsUnperiodized) {
  // A full circle as a periodic B-spline.
  Handle(Geom_BSplineCurve) g = GeomConvert::CurveToBSplineCurve(new Geom_Circle(gp::XOY(), 2.0));
  g->SetPeriodic();
  ASSERT_TRUE(g->IsPeriodic());
  const BSplineCurve c = occ::from_geom(g);
  EXPECT_TRUE(g->IsPeriodic()) << "the argument must be left untouched";
  for (int k = 0; k <= 50; ++k) {
    const double t = c.first() + (c.last() - c.first()) * k / 50.0;
    EXPECT_LT((vec(g->Value(t)) - Eigen::Vector3d(c.evaluate(t))).norm(), 1e-12);
    EXPECT_NEAR(Eigen::Vector3d(c.evaluate(t)).norm(), 2.0, 1e-12);
  }
}

TEST(GeomConvert, RejectsBadData) {
  BSplineSurface s = random_surface(irregular_space(), 1);
  s.poles(3, 1) = std::nan("");
  EXPECT_THROW(occ::to_geom(s), InvalidInput);
  s = random_surface(irregular_space(), 1);
  s.poles.conservativeResize(s.poles.rows() - 1, 3);
  EXPECT_THROW(occ::to_geom(s), InvalidInput);
  s = random_surface(irregular_space(), 1);
  s.space.knots_u.clear();
  EXPECT_THROW(occ::to_geom(s), InvalidInput);
  EXPECT_THROW(occ::to_geom_curve(random_curve(2, false, 1)), InvalidInput);
  EXPECT_THROW(occ::to_geom2d_curve(random_curve(3, false, 1)), InvalidInput);
  EXPECT_THROW(occ::from_geom(Handle(Geom_BSplineSurface)()), InvalidInput);
  EXPECT_THROW(occ::from_geom(Handle(Geom_BSplineCurve)()), InvalidInput);
}

TEST(OccError, StandardFailureBecomesGeometryError) {
  try {
    occ::guarded("testing", []() -> int { throw Standard_DomainError("boom"); });
    FAIL() << "no exception";
  } catch (const GeometryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("testing"), std::string::npos) << what;
    EXPECT_NE(what.find("Standard_DomainError"), std::string::npos) << what;
    EXPECT_NE(what.find("boom"), std::string::npos) << what;
  }
}

// ---------------------------------------------------------------------------------------------
// Faces and edges

TEST(SurfaceFromFace, BoundedPlane) {
  const gp_Pln plane(gp_Pnt(1, 2, 3), gp::DZ());
  BRepBuilderAPI_MakeFace maker(plane, -1.0, 2.0, 0.5, 3.0);
  ASSERT_TRUE(maker.IsDone());
  const BSplineSurface s = occ::surface_from_face(maker.Face());
  const double u0 = s.space.u_first(), u1 = s.space.u_last();
  const double v0 = s.space.v_first(), v1 = s.space.v_last();
  // The plane's own parameters map to (1 + u, 2 + v, 3).
  EXPECT_LT((s.evaluate(u0, v0) - Eigen::Vector3d(0, 2.5, 3)).norm(), 1e-12);
  EXPECT_LT((s.evaluate(u1, v1) - Eigen::Vector3d(3, 5, 3)).norm(), 1e-12);
  for (int k = 0; k <= 10; ++k) {
    const Eigen::Vector3d p =
        s.evaluate(u0 + (u1 - u0) * k / 10.0, v0 + (v1 - v0) * (10 - k) / 10.0);
    EXPECT_NEAR(p.z(), 3.0, 1e-12);
  }
}

TEST(SurfaceFromFace, RespectsLocation) {
  BRepBuilderAPI_MakeFace maker(gp_Pln(gp::XOY()), 0.0, 1.0, 0.0, 1.0);
  gp_Trsf move;
  move.SetTranslation(gp_Vec(10, 20, 30));
  const TopoDS_Face moved = TopoDS::Face(maker.Face().Moved(TopLoc_Location(move)));
  const BSplineSurface s = occ::surface_from_face(moved);
  EXPECT_LT((s.evaluate(s.space.u_first(), s.space.v_first()) - Eigen::Vector3d(10, 20, 30)).norm(),
            1e-12);
  EXPECT_LT((s.evaluate(s.space.u_last(), s.space.v_last()) - Eigen::Vector3d(11, 21, 30)).norm(),
            1e-12);
}

TEST(SurfaceFromFace, CylinderQuarter) {
  const double r = 2.5;
  const gp_Cylinder cyl(gp_Ax3(gp_Pnt(0, 0, 1), gp::DZ()), r);
  BRepBuilderAPI_MakeFace maker(cyl, 0.0, M_PI / 2, 0.0, 4.0);
  ASSERT_TRUE(maker.IsDone());
  const BSplineSurface s = occ::surface_from_face(maker.Face());
  EXPECT_TRUE(s.space.rational());
  double zmin = 1e9, zmax = -1e9, amin = 1e9, amax = -1e9;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) {
      const double u = s.space.u_first() + (s.space.u_last() - s.space.u_first()) * i / 20.0;
      const double v = s.space.v_first() + (s.space.v_last() - s.space.v_first()) * j / 20.0;
      const Eigen::Vector3d p = s.evaluate(u, v);
      EXPECT_NEAR(std::hypot(p.x(), p.y()), r, 1e-12);
      zmin = std::min(zmin, p.z());
      zmax = std::max(zmax, p.z());
      amin = std::min(amin, std::atan2(p.y(), p.x()));
      amax = std::max(amax, std::atan2(p.y(), p.x()));
    }
  }
  EXPECT_NEAR(zmin, 1.0, 1e-12);
  EXPECT_NEAR(zmax, 5.0, 1e-12);
  EXPECT_NEAR(amin, 0.0, 1e-12);
  EXPECT_NEAR(amax, M_PI / 2, 1e-12);
}

TEST(SurfaceFromFace, FullCylinderIsUnperiodized) {
  const gp_Cylinder cyl(gp::XOY(), 1.0);
  BRepBuilderAPI_MakeFace maker(cyl, 0.0, 2 * M_PI, -1.0, 1.0);
  ASSERT_TRUE(maker.IsDone());
  const BSplineSurface s = occ::surface_from_face(maker.Face());
  s.validate();
  const Eigen::Vector3d a = s.evaluate(s.space.u_first(), 0.0);
  const Eigen::Vector3d b = s.evaluate(s.space.u_last(), 0.0);
  EXPECT_LT((a - b).norm(), 1e-12) << "closed in u";
  const Eigen::Vector3d m = s.evaluate(0.5 * (s.space.u_first() + s.space.u_last()), 0.5);
  EXPECT_NEAR(std::hypot(m.x(), m.y()), 1.0, 1e-12);
}

TEST(SurfaceFromFace, BSplineFaceIsSegmentedToItsBounds) {
  const BSplineSurface base = curved_sheet();
  const Handle(Geom_BSplineSurface) g = occ::to_geom(base);
  BRepBuilderAPI_MakeFace maker(g, 0.2, 0.7, 0.1, 0.9, 1e-7);
  ASSERT_TRUE(maker.IsDone());
  const BSplineSurface s = occ::surface_from_face(maker.Face());
  EXPECT_NEAR(s.space.u_first(), 0.2, 1e-15);
  EXPECT_NEAR(s.space.u_last(), 0.7, 1e-15);
  EXPECT_NEAR(s.space.v_first(), 0.1, 1e-15);
  EXPECT_NEAR(s.space.v_last(), 0.9, 1e-15);
  for (int k = 0; k <= 20; ++k) {
    const double u = 0.2 + 0.5 * k / 20.0, v = 0.9 - 0.8 * k / 20.0;
    EXPECT_LT((s.evaluate(u, v) - base.evaluate(u, v)).norm(), 1e-12);
  }
}

TEST(SurfaceFromFace, RejectsDegenerateInput) {
  EXPECT_THROW(occ::surface_from_face(TopoDS_Face()), InvalidInput);
  BRepBuilderAPI_MakeFace unbounded{gp_Pln(gp::XOY())};
  ASSERT_TRUE(unbounded.IsDone());
  EXPECT_THROW(occ::surface_from_face(unbounded.Face()), InvalidInput);
}

TEST(CurveFromEdge, Line) {
  BRepBuilderAPI_MakeEdge maker(gp_Pnt(1, 2, 3), gp_Pnt(4, 6, 3));
  ASSERT_TRUE(maker.IsDone());
  const BSplineCurve c = occ::curve_from_edge(maker.Edge());
  EXPECT_EQ(c.dim(), 3);
  EXPECT_LT((Eigen::Vector3d(c.evaluate(c.first())) - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
  EXPECT_LT((Eigen::Vector3d(c.evaluate(c.last())) - Eigen::Vector3d(4, 6, 3)).norm(), 1e-12);
  const Eigen::Vector3d mid = c.evaluate(0.5 * (c.first() + c.last()));
  EXPECT_LT((mid - Eigen::Vector3d(2.5, 4, 3)).norm(), 1e-12);
}

TEST(CurveFromEdge, CircleArcWithLocation) {
  const gp_Circ circ(gp_Ax2(gp_Pnt(0, 0, 0), gp::DZ()), 3.0);
  BRepBuilderAPI_MakeEdge maker(circ, 0.0, 3 * M_PI / 2);
  ASSERT_TRUE(maker.IsDone());
  gp_Trsf move;
  move.SetTranslation(gp_Vec(0, 0, 5));
  const TopoDS_Edge edge = TopoDS::Edge(maker.Edge().Moved(TopLoc_Location(move)));
  const BSplineCurve c = occ::curve_from_edge(edge);
  EXPECT_TRUE(c.rational());
  for (int k = 0; k <= 40; ++k) {
    const Eigen::Vector3d p = c.evaluate(c.first() + (c.last() - c.first()) * k / 40.0);
    EXPECT_NEAR(std::hypot(p.x(), p.y()), 3.0, 1e-12);
    EXPECT_NEAR(p.z(), 5.0, 1e-12);
  }
  EXPECT_LT((Eigen::Vector3d(c.evaluate(c.first())) - Eigen::Vector3d(3, 0, 5)).norm(), 1e-12);
  EXPECT_LT((Eigen::Vector3d(c.evaluate(c.last())) - Eigen::Vector3d(0, -3, 5)).norm(), 1e-12);
}

TEST(CurveFromEdge, RejectsDegenerateInput) {
  EXPECT_THROW(occ::curve_from_edge(TopoDS_Edge()), InvalidInput);
  // An edge whose parameter range is empty.
  BRep_Builder b;
  TopoDS_Edge e;
  b.MakeEdge(e, new Geom_Line(gp::OX()), 1e-7);
  b.Range(e, 1.0, 1.0);
  EXPECT_THROW(occ::curve_from_edge(e), InvalidInput);
  // A degenerated edge (e.g. at a sphere's pole).
  TopoDS_Edge d;
  b.MakeEdge(d, new Geom_Line(gp::OX()), 1e-7);
  b.Range(d, 0.0, 1.0);
  b.Degenerated(d, Standard_True);
  EXPECT_THROW(occ::curve_from_edge(d), InvalidInput);
}

TEST(SingleShape, PicksTheOnlyFaceOrEdge) {
  BRepBuilderAPI_MakeFace maker(gp_Pln(gp::XOY()), 0.0, 1.0, 0.0, 1.0);
  EXPECT_NO_THROW(occ::only_face(maker.Face()));
  EXPECT_THROW(occ::only_edge(maker.Face()), InvalidInput);  // four edges
  EXPECT_THROW(occ::only_face(TopoDS_Shape()), InvalidInput);
}

// ---------------------------------------------------------------------------------------------
// Projection

// On a curved sheet, the target is the image of a known straight pre-image crossing knot lines;
// D = S o c0 is a polynomial of degree 6 between crossings, so the target is exact.
TEST(ProjectCurve, RecoversTheParameterOfACurveOnTheSheet) {
  const BSplineSurface sheet = curved_sheet();
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
  const BSplineSurface sheet = plane_sheet(10.0);
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
  const BSplineSurface sheet = plane_sheet(10.0);
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
  const BSplineSurface sheet = plane_sheet(10.0);
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
  const BSplineSurface sheet = plane_sheet(10.0);
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

// ---------------------------------------------------------------------------------------------
// Faces, exchange, checks, deviation

TEST(MakeFace, IsValidAndCarriesTheSheet) {
  const BSplineSurface sheet = curved_sheet();
  const TopoDS_Face face = occ::make_face(sheet);
  const occ::ShapeCheck check = occ::check_shape(face);
  EXPECT_TRUE(check.valid) << check.message;
  EXPECT_EQ(check.message, "valid");
  const BSplineSurface back = occ::surface_from_face(face);
  EXPECT_EQ(back.space.knots_u, sheet.space.knots_u);
  EXPECT_LT((back.poles - sheet.poles).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(MakeFace, RejectsInvalidSheet) {
  BSplineSurface sheet = curved_sheet();
  sheet.poles(2, 2) = std::nan("");
  EXPECT_THROW(occ::make_face(sheet), InvalidInput);
}

TEST(ShapeCheck, ReportsProblems) {
  // A face on the plane z = 0 bounded by a wire lying in z = 1: its edges have no curves on the
  // face's surface.
  BRepBuilderAPI_MakeFace plane(gp_Pln(gp::XOY()), 0.0, 1.0, 0.0, 1.0);
  BRepBuilderAPI_MakeFace lifted(gp_Pln(gp_Ax3(gp_Pnt(0, 0, 1), gp::DZ())), 0.0, 1.0, 0.0, 1.0);
  TopoDS_Face face = TopoDS::Face(plane.Face().EmptyCopied());
  BRep_Builder b;
  for (TopExp_Explorer ex(lifted.Face(), TopAbs_WIRE); ex.More(); ex.Next())
    b.Add(face, ex.Current());
  const occ::ShapeCheck check = occ::check_shape(face);
  EXPECT_FALSE(check.valid);
  EXPECT_NE(check.message, "valid");
  EXPECT_NE(check.message.find("edge"), std::string::npos) << check.message;
  EXPECT_EQ(check.message.find('\n'), std::string::npos) << check.message;
}

TEST(ShapeCheck, NullShapeIsInvalid) {
  const occ::ShapeCheck check = occ::check_shape(TopoDS_Shape());
  EXPECT_FALSE(check.valid);
  EXPECT_EQ(check.message, "null shape");
}

TEST(BrepIo, RoundTripAndGarbage) {
  const TopoDS_Face face = occ::make_face(curved_sheet());
  const std::string text = occ::write_brep(face);
  const TopoDS_Shape back = occ::read_brep(text);
  ASSERT_FALSE(back.IsNull());
  const BSplineSurface s = occ::surface_from_face(occ::only_face(back));
  EXPECT_LT((s.poles - curved_sheet().poles).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_THROW(occ::read_brep(""), InvalidInput);
  EXPECT_THROW(occ::read_brep("hello world"), InvalidInput);
  EXPECT_THROW(occ::read_brep(text.substr(0, text.size() / 2)), InvalidInput);
  EXPECT_THROW(occ::read_brep(text.substr(0, text.size() - 8)), InvalidInput);
  EXPECT_THROW(occ::write_brep(TopoDS_Shape()), InvalidInput);
}

TEST(StepIo, RoundTripKeepsTheArea) {
  const TopoDS_Face face = occ::make_face(curved_sheet());
  GProp_GProps before, after;
  BRepGProp::SurfaceProperties(face, before);
  const std::string path =
      ::testing::TempDir() + "varsurf_step_" + std::to_string(::getpid()) + ".step";
  occ::write_step(face, path);
  const TopoDS_Shape back = occ::read_step(path);
  std::remove(path.c_str());
  ASSERT_FALSE(back.IsNull());
  int faces = 0;
  for (TopExp_Explorer ex(back, TopAbs_FACE); ex.More(); ex.Next()) ++faces;
  EXPECT_EQ(faces, 1);
  BRepGProp::SurfaceProperties(back, after);
  EXPECT_GT(before.Mass(), 1.0);
  EXPECT_NEAR(after.Mass() / before.Mass(), 1.0, 1e-6);
  EXPECT_TRUE(occ::check_shape(back).valid);
}

TEST(StepIo, ReportsBadPathsAndShapes) {
  EXPECT_THROW(occ::read_step("/nonexistent/dir/file.step"), GeometryError);
  EXPECT_THROW(occ::read_step(""), InvalidInput);
  EXPECT_THROW(occ::write_step(TopoDS_Shape(), "/tmp/x.step"), InvalidInput);
  const TopoDS_Face face = occ::make_face(curved_sheet());
  EXPECT_THROW(occ::write_step(face, "/nonexistent/dir/file.step"), GeometryError);
}

TEST(MaxDeviation, CurveAtAKnownOffsetFromAPlane) {
  const BSplineSurface sheet = plane_sheet(10.0, 1.0);
  Eigen::VectorXd a(3), b(3);
  a << 1, 1, 3.5;
  b << 8, 9, 3.5;
  EXPECT_NEAR(occ::max_deviation(sheet, test::line_curve(a, b), 50), 2.5, 1e-9);
  // Beyond the boundary the closest point is on the edge x = 10.
  a << 5, 5, 1;
  b << 15, 5, 1;
  EXPECT_NEAR(occ::max_deviation(sheet, test::line_curve(a, b), 51), 5.0, 1e-9);
  // On the sheet.
  a << 0, 0, 1;
  b << 10, 7, 1;
  EXPECT_LT(occ::max_deviation(sheet, test::line_curve(a, b), 51), 1e-9);
}

TEST(MaxDeviation, RejectsBadInput) {
  const BSplineSurface sheet = plane_sheet(10.0);
  Eigen::VectorXd a(3), b(3);
  a << 1, 1, 0;
  b << 2, 2, 0;
  EXPECT_THROW(occ::max_deviation(sheet, test::line_curve(a, b), 1), InvalidInput);
  EXPECT_THROW(occ::max_deviation(sheet, BSplineCurve(), 10), InvalidInput);
}

}  // namespace
}  // namespace varsurf

TEST(RefineSurface, KeepsTheSurfaceAndReachesTheSpanCounts) {
  // A rational, non-uniform, bilinear-in-v sheet: degree raised to 3 and spans to 7 x 5 must not
  // move a single point.
  varsurf::BSplineSurface s;
  s.space = varsurf::SplineSpace::uniform(2, 1, 2, 1);
  s.space.knots_u = {0, 0, 0, 0.3, 1, 1, 1};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uni(0.5, 1.5);
  s.space.weights.resize(s.space.size());
  s.poles.resize(s.space.size(), 3);
  for (int k = 0; k < s.space.size(); ++k) {
    s.space.weights(k) = uni(rng);
    s.poles.row(k) = Eigen::RowVector3d(uni(rng), uni(rng), uni(rng)) * 10.0;
  }
  const varsurf::BSplineSurface r = varsurf::occ::refine_surface(s, 7, 5, 3);
  EXPECT_EQ(r.space.degree_u, 3);
  EXPECT_EQ(r.space.degree_v, 3);
  EXPECT_EQ(varsurf::breakpoints(r.space.knots_u, 3).size(), 8u);
  EXPECT_EQ(varsurf::breakpoints(r.space.knots_v, 3).size(), 6u);
  for (double u = 0.0; u <= 1.0; u += 0.0625)
    for (double v = 0.0; v <= 1.0; v += 0.125)
      EXPECT_LT((r.evaluate(u, v) - s.evaluate(u, v)).norm(), 1e-12) << u << " " << v;
  // Already fine enough: returned as is.
  const varsurf::BSplineSurface same = varsurf::occ::refine_surface(r, 2, 2, 2);
  EXPECT_EQ(same.space.knots_u, r.space.knots_u);
  EXPECT_THROW(varsurf::occ::refine_surface(s, 0, 4), varsurf::InvalidInput);
  EXPECT_THROW(varsurf::occ::refine_surface(s, 4, 4, 12), varsurf::InvalidInput);
}

TEST(ProjectPoint, FindsTheParametersAndDistanceOfAPointAboveACurvedSheet) {
  varsurf::BSplineSurface s;
  s.space = varsurf::SplineSpace::uniform(3, 3, 3, 3);
  s.poles = varsurf::test::fit_poles(s.space, [](double u, double v) {
    return Eigen::Vector3d(10 * u, 8 * v, std::sin(u) + 0.5 * v * v);
  });
  const double u = 0.3, v = 0.7;
  const Eigen::MatrixXd d = varsurf::evaluate_surface(s.space, s.poles, u, v, 1);
  const Eigen::Vector3d n = Eigen::Vector3d(d.row(1)).cross(Eigen::Vector3d(d.row(2))).normalized();
  const varsurf::occ::PointOnSheet p =
      varsurf::occ::project_point(s, Eigen::Vector3d(d.row(0)) + 2.0 * n);
  EXPECT_NEAR(p.u, u, 1e-7);
  EXPECT_NEAR(p.v, v, 1e-7);
  EXPECT_NEAR(p.distance, 2.0, 1e-7);
  EXPECT_THROW(varsurf::occ::project_point(s, Eigen::Vector3d(NAN, 0, 0)), varsurf::InvalidInput);
}

TEST(NormalField, PlaneNormalTurnedAboutTheCurve) {
  // On the plane z = 0 the normal is +z; turned +30 degrees about the +x tangent of a line along
  // x it becomes (0, -sin 30, cos 30).
  const TopoDS_Face plane =
      BRepBuilderAPI_MakeFace(gp_Pln(gp::Origin(), gp::DZ()), -10, 10, -10, 10);
  const varsurf::BSplineCurve line =
      varsurf::test::line_curve(Eigen::Vector3d(-5, 1, 0), Eigen::Vector3d(5, 1, 0), 0.0, 3.0);
  const varsurf::BSplineCurve n = varsurf::occ::normal_field(plane, line, 30.0, 1e-6);
  EXPECT_DOUBLE_EQ(n.first(), 0.0);
  EXPECT_DOUBLE_EQ(n.last(), 3.0);
  for (double t : {0.0, 0.7, 1.9, 3.0}) {
    const Eigen::Vector3d v = n.evaluate(t);
    EXPECT_LT((v - Eigen::Vector3d(0.0, -0.5, std::sqrt(3.0) / 2.0)).norm(), 1e-7) << t;
  }
  const varsurf::BSplineCurve above =
      varsurf::test::line_curve(Eigen::Vector3d(-5, 1, 2), Eigen::Vector3d(5, 1, 2));
  EXPECT_THROW(varsurf::occ::normal_field(plane, above, 0.0, 1e-3), varsurf::InvalidInput);
}

TEST(NormalField, StripToASecondCurve) {
  // From a line along x at z = 0 to a parallel line at y = 1, z = 1: the strip's normal is
  // x cross (0, 1, 1) / sqrt 2 = (0, -1, 1) / sqrt 2 everywhere.
  const varsurf::BSplineCurve line =
      varsurf::test::line_curve(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 0, 0));
  const varsurf::BSplineCurve second =
      varsurf::test::line_curve(Eigen::Vector3d(-1, 1, 1), Eigen::Vector3d(5, 1, 1));
  const varsurf::BSplineCurve n = varsurf::occ::normal_field_between(line, second, 0.0);
  for (double t : {0.0, 0.3, 1.0}) {
    const Eigen::Vector3d v = n.evaluate(t);
    EXPECT_LT((v - Eigen::Vector3d(0, -1, 1) / std::sqrt(2.0)).norm(), 1e-7) << t;
  }
  // Turned by -45 degrees about x the strip's normal becomes (0, 0, 1).
  const Eigen::Vector3d turned =
      varsurf::occ::normal_field_between(line, second, -45.0).evaluate(0.5);
  EXPECT_LT((turned - Eigen::Vector3d(0, 0, 1)).norm(), 1e-7);
  // A second curve crossing the first has no strip there.
  const varsurf::BSplineCurve crossing =
      varsurf::test::line_curve(Eigen::Vector3d(2, -1, 0), Eigen::Vector3d(2, 1, 0));
  EXPECT_THROW(varsurf::occ::normal_field_between(line, crossing, 0.0), varsurf::InvalidInput);
}

TEST(ClosestPointTarget, FaceInteriorBoundaryAndEdges) {
  using varsurf::occ::ClosestPointTarget;
  const ClosestPointTarget face(
      BRepBuilderAPI_MakeFace(gp_Pln(gp::Origin(), gp::DZ()), 0, 2, 0, 1));
  EXPECT_TRUE(face.on_faces());
  // Above the interior: straight down, metric z z^T.
  varsurf::ClosestPoint c = face(Eigen::Vector3d(0.5, 0.25, 3.0));
  EXPECT_LT((c.point - Eigen::Vector3d(0.5, 0.25, 0.0)).norm(), 1e-9);
  EXPECT_LT((c.metric - Eigen::Vector3d::UnitZ() * Eigen::Vector3d::UnitZ().transpose()).norm(),
            1e-9);
  // Beyond the edge x = 2: the closest point is on that edge, with the full metric.
  c = face(Eigen::Vector3d(3.0, 0.5, 1.0));
  EXPECT_LT((c.point - Eigen::Vector3d(2.0, 0.5, 0.0)).norm(), 1e-7);
  EXPECT_LT((c.metric - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  // An edge along x: across it, metric I - x x^T; beyond its end, the end.
  const ClosestPointTarget edge(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(1, 0, 0)).Edge());
  EXPECT_FALSE(edge.on_faces());
  c = edge(Eigen::Vector3d(0.3, 2.0, -1.0));
  EXPECT_LT((c.point - Eigen::Vector3d(0.3, 0, 0)).norm(), 1e-9);
  EXPECT_LT((c.metric - Eigen::Vector3d(0, 1, 1).asDiagonal().toDenseMatrix()).norm(), 1e-9);
  c = edge(Eigen::Vector3d(4.0, 1.0, 0.0));
  EXPECT_LT((c.point - Eigen::Vector3d(1, 0, 0)).norm(), 1e-9);
  EXPECT_THROW(edge(Eigen::Vector3d(NAN, 0, 0)), varsurf::InvalidInput);
  EXPECT_THROW(ClosestPointTarget{TopoDS_Shape()}, varsurf::InvalidInput);
  EXPECT_THROW(ClosestPointTarget{BRepBuilderAPI_MakeVertex(gp_Pnt(0, 0, 0)).Vertex()},
               varsurf::InvalidInput);
}
