// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <cmath>

#include "sheet_assembly.hpp"
#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/point_curvature.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

constexpr double kSide = 80.0;  // mm

// The paraboloid z = k/2 (x^2 + y^2) over an 80 mm square centred on the origin, exactly (it is
// quadratic in u and v).
Eigen::MatrixX3d paraboloid(const SplineSpace& sp, double k) {
  return test::fit_poles(sp, [&](double u, double v) {
    const double x = kSide * (u - 0.5), y = kSide * (v - 0.5);
    return Eigen::Vector3d(x, y, 0.5 * k * (x * x + y * y));
  });
}

// Its normal curvature along x at (x, y), in closed form: f_xx / (sqrt(1 + |grad f|^2) (1 +
// f_x^2)).
double paraboloid_kappa_x(double k, double x, double y) {
  const double fx = k * x, fy = k * y;
  return k / (std::sqrt(1.0 + fx * fx + fy * fy) * (1.0 + fx * fx));
}

SheetProblem flat_sheet(double kappa_u, double kappa_v, bool along_u = true, bool along_v = true) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, 8, 8);
  pb.initial_poles = test::flat_poles(pb.space) * kSide;
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  pb.point_curvatures.push_back({0.5, 0.5, kappa_u, kappa_v, along_u, along_v, 1.0});
  return pb;
}

}  // namespace

TEST(PointCurvature, NormalCurvaturesOfAParaboloidMatchTheClosedForm) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  const double k = 0.02;
  const Eigen::MatrixX3d poles = paraboloid(sp, k);
  const Eigen::Vector2d centre = normal_curvatures(sp, poles, 0.5, 0.5);
  EXPECT_NEAR(centre(0), k, 1e-12);
  EXPECT_NEAR(centre(1), k, 1e-12);
  for (double u : {0.1, 0.37, 0.8})
    for (double v : {0.2, 0.55, 0.9}) {
      const double x = kSide * (u - 0.5), y = kSide * (v - 0.5);
      const Eigen::Vector2d kk = normal_curvatures(sp, poles, u, v);
      EXPECT_NEAR(kk(0), paraboloid_kappa_x(k, x, y), 1e-12 * k / 1e-2) << u << " " << v;
      EXPECT_NEAR(kk(1), paraboloid_kappa_x(k, y, x), 1e-12 * k / 1e-2) << u << " " << v;
    }
}

TEST(PointCurvature, RowsVanishWhereTheSheetAlreadyHasTheCurvature) {
  // Linearized at poles that meet the condition, each row holds there exactly.
  const SplineSpace sp = SplineSpace::uniform(3, 3, 5, 5);
  const Eigen::MatrixX3d poles = paraboloid(sp, 0.015);
  const double u = 0.3, v = 0.65;
  const Eigen::Vector2d kk = normal_curvatures(sp, poles, u, v);
  const ConstraintSamples s =
      sample_point_curvature(sp, {u, v, kk(0), kk(1), true, true, 1.0}, poles);
  ASSERT_EQ(s.rows(), 2);
  ASSERT_TRUE(s.coupled());
  for (int r = 0; r < s.rows(); ++r) {
    double value = 0.0;
    for (size_t j = 0; j < s.index[static_cast<size_t>(r)].size(); ++j) {
      const int col = s.index[static_cast<size_t>(r)][j];
      value +=
          s.coeff[static_cast<size_t>(r)](static_cast<Eigen::Index>(j)) * poles(col / 3, col % 3);
    }
    EXPECT_NEAR(value, s.rhs(r, 0), 1e-9) << r;
    EXPECT_NEAR(s.coeff[static_cast<size_t>(r)].norm(), 1.0, 1e-12);  // a point row's scale
  }
  // One direction asked: one row.
  EXPECT_EQ(sample_point_curvature(sp, {u, v, kk(0), 0.0, true, false, 1.0}, poles).rows(), 1);
}

TEST(PointCurvature, TheSolveMeetsTheCurvaturesAndTheirSignChoosesTheSide) {
  SolveOptions opt;
  opt.curvature_tolerance = 1e-8;
  for (double kappa : {0.01, 0.05}) {
    const SheetProblem up = flat_sheet(kappa, kappa), down = flat_sheet(-kappa, -kappa);
    const SolveResult a = solve_sheet(up, opt), b = solve_sheet(down, opt);
    EXPECT_TRUE(a.report.converged) << kappa;
    EXPECT_TRUE(b.report.converged) << kappa;
    const Eigen::Vector2d ka = normal_curvatures(up.space, a.poles, 0.5, 0.5);
    const Eigen::Vector2d kb = normal_curvatures(down.space, b.poles, 0.5, 0.5);
    EXPECT_NEAR(ka(0), kappa, 1e-8 * kappa);
    EXPECT_NEAR(ka(1), kappa, 1e-8 * kappa);
    EXPECT_NEAR(kb(0), -kappa, 1e-8 * kappa);
    EXPECT_NEAR(kb(1), -kappa, 1e-8 * kappa);
    // Mirror images in z: a sheet bent toward its normal (+z) at the centre, the other away.
    const double za = evaluate_surface(up.space, a.poles, 0.5, 0.5, 0)(0, 2);
    const double zb = evaluate_surface(down.space, b.poles, 0.5, 0.5, 0)(0, 2);
    EXPECT_GT(std::abs(za), 1e-3);
    EXPECT_NEAR(za, -zb, 1e-9 * kSide);
    EXPECT_LT(point_curvature_error(up.space, a.poles, up.point_curvatures[0], 1.0 / kSide), 1e-8);
  }
}

TEST(PointCurvature, OneDirectionLeavesTheOtherToTheEnergy) {
  SolveOptions opt;
  opt.curvature_tolerance = 1e-8;
  const SheetProblem pb = flat_sheet(0.03, 0.0, true, false);
  const SolveResult r = solve_sheet(pb, opt);
  const Eigen::Vector2d k = normal_curvatures(pb.space, r.poles, 0.5, 0.5);
  EXPECT_NEAR(k(0), 0.03, 1e-8 * 0.03);
  // Not held to 0: the plate bends the other way too, less (its energy spreads the bend).
  EXPECT_GT(std::abs(k(1)), 1e-4);
  EXPECT_LT(std::abs(k(1)), 0.03);
}

TEST(PointCurvature, BadInputIsRefused) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  const Eigen::MatrixX3d poles = paraboloid(sp, 0.01);
  const auto refused = [&](const PointCurvatureConstraint& c) {
    EXPECT_THROW(sample_point_curvature(sp, c, poles), InvalidInput);
  };
  refused({1.5, 0.5, 0.01, 0.01, true, true, 1.0});    // outside the domain
  refused({0.5, 0.5, 0.01, 0.01, false, false, 1.0});  // nothing asked
  refused({0.5, 0.5, NAN, 0.01, true, true, 1.0});
  refused({0.5, 0.5, 0.01, 0.01, true, true, 0.0});  // no weight
  const SplineSpace linear = SplineSpace::uniform(1, 1, 4, 4);
  EXPECT_THROW(sample_point_curvature(linear, {0.5, 0.5, 0.0, 0.0, true, true, 1.0},
                                      test::flat_poles(linear)),
               InvalidInput);
  // A collapsed sheet has no normal: refused, not NaN.
  EXPECT_THROW(sample_point_curvature(sp, {0.5, 0.5, 0.01, 0.01, true, true, 1.0},
                                      Eigen::MatrixX3d::Zero(sp.size(), 3)),
               InvalidInput);
  // Not part of a joint solve or a kept factorization.
  SheetProblem pb = flat_sheet(0.01, 0.01);
  EXPECT_THROW(sheet_quadratic(pb, SolveOptions{}, false, false), InvalidInput);
  EXPECT_THROW(PreparedSheet(pb, SolveOptions{}), InvalidInput);
}
