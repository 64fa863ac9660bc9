// SPDX-License-Identifier: LGPL-2.1-or-later
// Core splines to Geom and back (exactly, rational or not; periodic ones unperiodized), faces and
// edges read as splines (placed, bounded, closed), and bad data refused. Faces of Part-like
// primitives (cylinders, cones, spheres, tori; whole, partial, placed) convert to B-spline
// surfaces that are exact (measured by projecting onto the primitive's own surface, both ways)
// and smooth by their knots before and after the sheet's refinement to cubic: OCCT's Boolean
// argument check refuses any face whose surface is C0 by multiplicity ("BOPAlgo GeomAbs_C0"),
// which its own circle conversion (double knots) is.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomConvert.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Line.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "occ_test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/surface_refinement.hpp"

using namespace varsurf;

namespace {

using test::curved_face;

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
  const BSplineSurface base = test::curved_sheet();
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
