// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

// The uniform cubic B-spline on [0, 4].
double cardinal(double x) {
  if (x < 0.0 || x >= 4.0) return 0.0;
  if (x < 1.0) return x * x * x / 6.0;
  if (x < 2.0) return (-3 * x * x * x + 12 * x * x - 12 * x + 4) / 6.0;
  if (x < 3.0) return (3 * x * x * x - 24 * x * x + 60 * x - 44) / 6.0;
  const double y = 4.0 - x;
  return y * y * y / 6.0;
}

constexpr int kSpans = 8;

// A closed section: a periodic cubic spline of period 1 on kSpans uniform spans, controlled by an
// irregular octagon in the xy plane.
Eigen::Vector3d section(double u) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < kSpans; ++i) {
    const double angle = 2.0 * M_PI * i / kSpans, radius = 1.0 + 0.15 * std::sin(3.0 * i);
    const double x = std::fmod(kSpans * u - i + 2.0 * kSpans, static_cast<double>(kSpans));
    p += cardinal(x) * Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle), 0.0);
  }
  return p;
}

// A tube between two sections (the second 1.2 times the first, one unit up) through a ring 1.5
// times the section at half height, its parametrization starting `shift` along the section: the
// same tube whatever the shift, seen through a seam elsewhere.
SheetProblem tube(double shift, bool closed) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, kSpans, 6);
  pb.initial_poles = test::fit_poles(pb.space, [&](double u, double v) {
    return Eigen::Vector3d((1.0 + 0.2 * v) * section(u + shift) + Eigen::Vector3d(0.0, 0.0, v));
  });
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  for (int i = 0; i < pb.space.nu(); ++i) {
    pb.fixed_poles.push_back(pb.space.index(i, 0));
    pb.fixed_poles.push_back(pb.space.index(i, pb.space.nv() - 1));
  }
  std::vector<double> breaks;
  for (int k = 0; k <= kSpans; ++k) breaks.push_back(static_cast<double>(k) / kSpans);
  CurveConstraint ring;
  ring.preimage = test::line_curve(Eigen::Vector2d(0.0, 0.5), Eigen::Vector2d(1.0, 0.5));
  ring.target = test::fit_piecewise_curve(breaks, 3, 3, [&](double u) {
    return Eigen::VectorXd(1.5 * section(u + shift) + Eigen::Vector3d(0.0, 0.0, 0.5));
  });
  pb.curves.push_back(ring);
  pb.closed_u = closed;
  return pb;
}

// Largest distance between tube A at (u + shift, v) and tube B at (u, v).
double difference(const SheetProblem& a, const Eigen::MatrixX3d& pa, const SheetProblem& b,
                  const Eigen::MatrixX3d& pb, double shift) {
  double worst = 0.0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 10; ++j) {
      const double u = (1.0 - shift) * i / 40.0, v = j / 10.0;
      const Eigen::Vector3d p = evaluate_surface(a.space, pa, u + shift, v, 0).row(0);
      const Eigen::Vector3d q = evaluate_surface(b.space, pb, u, v, 0).row(0);
      worst = std::max(worst, (p - q).norm());
    }
  return worst;
}

}  // namespace

TEST(Seam, AClosedTubeDoesNotDependOnWhereItsSeamIs) {
  // Seam at 0 and seam three spans on: the same periodic spline space, the same data; a closed
  // sheet must come out the same surface.
  const double shift = 3.0 / kSpans;
  const SheetProblem a = tube(0.0, true), b = tube(shift, true);
  const SolveResult ra = solve_sheet(a), rb = solve_sheet(b);
  EXPECT_LT(difference(a, ra.poles, b, rb.poles, shift), 1e-9);
  EXPECT_LT(seam_mismatch(a.space, ra.poles, 0), 1e-10);
  EXPECT_LT(incidence_error(a.space, ra.poles, a.curves[0]), 1e-9);
  // Not closed (the seam free like a boundary): the seam opens and the two differ.
  const SheetProblem c = tube(0.0, false), d = tube(shift, false);
  const SolveResult rc = solve_sheet(c), rd = solve_sheet(d);
  EXPECT_GT(seam_mismatch(c.space, rc.poles, 0), 1e-3);
  EXPECT_GT(difference(c, rc.poles, d, rd.poles, shift), 1e-3);
}

TEST(Seam, TiesLeaveOutRowsOfFixedPolesAndRefuseBadInput) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  const ConstraintSamples all = sample_seam(sp, 0);
  EXPECT_TRUE(all.exact);
  EXPECT_EQ(all.rows(), 3 * sp.nv());  // position, first and second derivative per abscissa
  std::vector<bool> fixed(static_cast<size_t>(sp.size()), false);
  for (int i = 0; i < sp.nu(); ++i) fixed[static_cast<size_t>(sp.index(i, 0))] = true;
  EXPECT_EQ(sample_seam(sp, 0, fixed).rows(), 3 * (sp.nv() - 1));  // the clamped end row is fixed
  EXPECT_EQ(sample_seam(SplineSpace::uniform(2, 2, 4, 4), 1).rows(), 2 * 6);  // degree 2: C1
  EXPECT_THROW(sample_seam(sp, 2), InvalidInput);
  EXPECT_THROW(sample_seam(sp, 0, std::vector<bool>(3, false)), InvalidInput);
  EXPECT_THROW(seam_mismatch(sp, test::flat_poles(sp), 0, 1), InvalidInput);
}

namespace {

// The tube's start with the pole column `column` (from the seam at u = 0) moved up by `lift`: a
// cubic's end derivatives of order k at u = 0 are made of columns 0 .. k only, so moving column
// k leaves the seam continuous in orders below k and breaks order k.
SheetProblem tube_with_moved_column(int column, double lift) {
  SheetProblem pb = tube(0.0, true);
  for (int j = 0; j < pb.space.nv(); ++j) pb.initial_poles(pb.space.index(column, j), 2) += lift;
  return pb;
}

// The k-th u-derivative at u = 0 minus that at u = 1, at v.
Eigen::Vector3d end_difference(const SheetProblem& pb, const Eigen::MatrixX3d& poles, int k,
                               double v) {
  static const int row[3] = {0, 1, 3};
  return (evaluate_surface(pb.space, poles, 0.0, v, 2).row(row[k]) -
          evaluate_surface(pb.space, poles, 1.0, v, 2).row(row[k]))
      .transpose();
}

}  // namespace

TEST(Seam, ContinuityCountsTheOrdersInWhichTheEndsAgree) {
  const SheetProblem closed = tube(0.0, true);
  EXPECT_EQ(seam_continuity(closed.space, closed.initial_poles, 0), 2);   // cubic: C2, as tied
  EXPECT_EQ(seam_continuity(closed.space, closed.initial_poles, 1), -1);  // v: two sections
  for (int column = 0; column <= 2; ++column) {
    const SheetProblem moved = tube_with_moved_column(column, 0.05);
    EXPECT_EQ(seam_continuity(moved.space, moved.initial_poles, 0), column - 1) << column;
  }
  // A quintic: beyond second derivatives the poles answer, up to C4.
  SplineSpace quintic = SplineSpace::uniform(5, 3, 6, 2);
  Eigen::MatrixX3d poles = test::fit_poles(quintic, [](double u, double v) {
    return Eigen::Vector3d(std::cos(2.0 * M_PI * u), std::sin(2.0 * M_PI * u), v);
  });
  EXPECT_GE(seam_continuity(quintic, poles, 0, 1e-3), 0);
  EXPECT_THROW(seam_continuity(closed.space, closed.initial_poles, 0, -1.0), InvalidInput);
}

TEST(Seam, TiesTheDisplacementSoAStartSmoothOnlyToC1KeepsItsOwnSecondDerivativeStep) {
  // A rational circle's parametrization is C1 across a cylinder's seam, not C2: the ties make
  // the change from the start continuous, so the result's step in each derivative across the
  // seam is the start's own, while half a ring (away from the seam: a whole ring with its own
  // C2 parametrization would contradict the start's) pulls the tube far from its start.
  SheetProblem pb = tube_with_moved_column(2, 0.05);
  std::vector<double> breaks;
  for (int k = 2; k <= 6; ++k) breaks.push_back(static_cast<double>(k) / kSpans);
  pb.curves[0].preimage =
      test::line_curve(Eigen::Vector2d(0.25, 0.5), Eigen::Vector2d(0.75, 0.5), 0.25, 0.75);
  pb.curves[0].target = test::fit_piecewise_curve(breaks, 3, 3, [&](double u) {
    return Eigen::VectorXd(1.5 * section(u) + Eigen::Vector3d(0.0, 0.0, 0.5));
  });
  const SolveResult r = solve_sheet(pb);
  EXPECT_LT(incidence_error(pb.space, r.poles, pb.curves[0]), 1e-9);
  EXPECT_GT((r.poles - pb.initial_poles).cwiseAbs().maxCoeff(), 0.1);
  double worst = 0.0, start_step = 0.0;
  for (int i = 0; i <= 20; ++i) {
    const double v = i / 20.0;
    for (int k = 0; k <= 2; ++k)
      worst = std::max(
          worst,
          (end_difference(pb, r.poles, k, v) - end_difference(pb, pb.initial_poles, k, v)).norm());
    start_step = std::max(start_step, end_difference(pb, pb.initial_poles, 2, v).norm());
  }
  EXPECT_LT(worst, 1e-8 * start_step);
  EXPECT_GT(start_step, 1.0);
}

TEST(Seam, ACurveTheRestShapeAlreadyMeetsLeavesAClosedSheetAtRest) {
  // The ties are exact rows and share poles with the curve: the curve is still judged by the
  // discrepancy principle in the directions the ties leave free. Its data is the rest shape's
  // own curve plus 1e-6 of noise, well within the 1e-4 fit tolerance: nothing moves. Fitting
  // the cluster as exact (the ties' kind) bent the sheet to the noise.
  SheetProblem pb = tube(0.0, true);
  pb.rest_poles = pb.initial_poles;
  std::vector<double> breaks;
  for (int k = 0; k <= kSpans; ++k) breaks.push_back(static_cast<double>(k) / kSpans);
  pb.curves[0].target = test::fit_piecewise_curve(breaks, 3, 3, [&](double u) {
    Eigen::Vector3d p = evaluate_surface(pb.space, pb.initial_poles, u, 0.5, 0).row(0);
    return Eigen::VectorXd(p + Eigen::Vector3d(0.0, 0.0, 1e-6 * std::sin(40.0 * u)));
  });
  SolveOptions options;
  options.fit_tolerance = 1e-4;
  const SolveResult r = solve_sheet(pb, options);
  EXPECT_LT((r.poles - pb.initial_poles).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(seam_mismatch(pb.space, r.poles, 0), 1e-10);
  // With no fit tolerance the noise is fitted in every direction, and the ties still hold (to
  // 1e-7 of the tube's size beside rows fitted to rounding).
  const SolveResult fitted = solve_sheet(pb);
  EXPECT_GT((fitted.poles - pb.initial_poles).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT(seam_mismatch(pb.space, fitted.poles, 0), 3e-7);
}
