// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

Eigen::VectorXd six(const Eigen::Matrix3d& k) {
  Eigen::VectorXd s(6);
  s << k(0, 0), k(1, 1), k(2, 2), k(0, 1), k(0, 2), k(1, 2);
  return s;
}

// A flat sheet over the unit square, boundary held, containing the straight segment a -> b of
// the plane z = 0 with G1 to that plane; G2 asks for the normal curvature of K across it.
SheetProblem g2_problem(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        const Eigen::Matrix3d& k, bool with_g2, int degree = 3) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(degree, degree, 12, 12);
  pb.initial_poles = test::flat_poles(pb.space);
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  CurveConstraint c;
  c.preimage = test::line_curve(a, b);
  c.target =
      test::line_curve(Eigen::Vector3d(a.x(), a.y(), 0.0), Eigen::Vector3d(b.x(), b.y(), 0.0));
  pb.curves.push_back(c);
  RibbonConstraint r;
  r.preimage = c.preimage;
  r.normals = test::line_curve(n, n);
  pb.ribbons.push_back(r);
  if (with_g2) {
    CurvatureConstraint g;
    g.preimage = c.preimage;
    g.normals = r.normals;
    g.shape = test::line_curve(six(k), six(k));
    pb.curvatures.push_back(g);
  }
  return pb;
}

// Largest |normal curvature across the segment - the neighbour's along the same direction|,
// both from second differences of the solved sheet (not from the solver's own measure).
double measured_jump(const SheetProblem& pb, const Eigen::MatrixX3d& poles,
                     const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Matrix3d& k) {
  const Eigen::Vector2d along = (b - a).normalized(), d(-along.y(), along.x());
  const double h = 1e-5;
  double worst = 0.0;
  for (int i = 1; i < 40; ++i) {
    const Eigen::Vector2d uv = a + (b - a) * (i / 40.0);
    const auto at = [&](const Eigen::Vector2d& p) {
      return Eigen::Vector3d(evaluate_surface(pb.space, poles, p.x(), p.y(), 0).row(0));
    };
    const Eigen::Vector3d p0 = at(uv), pp = at(uv + h * d), pm = at(uv - h * d);
    const Eigen::Vector3d chord = pp - pm;
    const double half = 0.5 * chord.norm();
    const double k_sheet = Eigen::Vector3d::UnitZ().dot(pp + pm - 2.0 * p0) / (half * half);
    const Eigen::Vector3d t = chord.normalized();
    worst = std::max(worst, std::abs(k_sheet - t.dot(k * t)));
  }
  return worst;
}

}  // namespace

TEST(Curvature, AcrossAStraightSegmentTheSheetTakesTheNeighboursCurvature) {
  // Neighbour: the cylinder z = c/2 y^2 (axis along x) touching z = 0 along the segment.
  const double c = 2.0;
  const Eigen::Vector2d a(0.2, 0.5), b(0.8, 0.5);
  Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
  k(1, 1) = c;
  const SheetProblem g1 = g2_problem(a, b, k, false), g2 = g2_problem(a, b, k, true);
  SolveOptions opt;
  opt.curvature_tolerance = 1e-7;
  const SolveResult r1 = solve_sheet(g1, opt), r2 = solve_sheet(g2, opt);
  // The G1 answer stays flat across the segment: the check can fail.
  EXPECT_GT(measured_jump(g1, r1.poles, a, b, k), 0.5 * c);
  EXPECT_LT(measured_jump(g2, r2.poles, a, b, k), 1e-4 * c);
  EXPECT_LT(curvature_jump(g2.space, r2.poles, g2.curvatures[0], 1.0), 1e-6);
  EXPECT_GE(r2.report.curvature_iterations, 2);  // |w_d| moves with the bend: not one linear solve
  EXPECT_LE(r2.report.curvature_iterations, 12);
  EXPECT_TRUE(r2.report.converged);
  EXPECT_LT(r2.report.curvature_jump, 1e-7);
  // The sheet still contains the segment with G1.
  EXPECT_LT(incidence_error(g2.space, r2.poles, g2.curves[0]), 1e-9);
  EXPECT_LT(ribbon_angle_error(g2.space, r2.poles, g2.ribbons[0]), 1e-8);
}

TEST(Curvature, ASkewSaddleNeighbourAcrossADiagonal) {
  // A saddle's second fundamental form, with principal directions at 30 degrees to the axes,
  // across a diagonal segment: the cross direction is neither principal.
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(M_PI / 6.0, Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Matrix3d k = rot * Eigen::Vector3d(1.5, -0.7, 0.0).asDiagonal() * rot.transpose();
  const Eigen::Vector2d a(0.3, 0.25), b(0.7, 0.75);
  const SheetProblem g2 = g2_problem(a, b, k, true);
  SolveOptions opt;
  opt.curvature_tolerance = 1e-7;
  const SolveResult r2 = solve_sheet(g2, opt);
  EXPECT_LT(measured_jump(g2, r2.poles, a, b, k), 1e-4);
  EXPECT_LT(curvature_jump(g2.space, r2.poles, g2.curvatures[0], 1.0), 1e-6);
}

TEST(Curvature, ADegreeTwoSheetIsRefusedWithTheReason) {
  Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
  k(1, 1) = 1.0;
  const SheetProblem pb = g2_problem({0.2, 0.5}, {0.8, 0.5}, k, true, 2);
  try {
    solve_sheet(pb);
    FAIL() << "a degree-2 sheet was solved with G2";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("degree 3"), std::string::npos) << e.what();
  }
}

TEST(Curvature, IteratedConditionsHaveNoFactorizationToKeep) {
  Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
  k(1, 1) = 1.0;
  const SheetProblem pb = g2_problem({0.2, 0.5}, {0.8, 0.5}, k, true);
  EXPECT_THROW(PreparedSheet{pb}, InvalidInput);
  PreparedSheet plain(g2_problem({0.2, 0.5}, {0.8, 0.5}, k, false));
  EXPECT_THROW(plain.change(pb), InvalidInput);
}

TEST(Curvature, MismatchedFieldsAreRefused) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  CurvatureConstraint g;
  g.preimage = test::line_curve(Eigen::Vector2d(0.2, 0.5), Eigen::Vector2d(0.8, 0.5));
  g.normals = test::line_curve(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ());
  g.shape = test::line_curve(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ());  // 3, not 6
  EXPECT_THROW(sample_curvature(sp, g, test::flat_poles(sp)), InvalidInput);
  g.shape = test::line_curve(Eigen::VectorXd::Zero(6), Eigen::VectorXd::Zero(6), 0.0, 2.0);
  EXPECT_THROW(sample_curvature(sp, g, test::flat_poles(sp)), InvalidInput);
}
