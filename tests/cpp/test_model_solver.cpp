// SPDX-License-Identifier: LGPL-2.1-or-later
// Several sheets and space curves solved as one system: curve fairness, variational curves shared
// by sheets, hinges (Welch & Witkin sec. 5).
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/curve_energy.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/model_solver.hpp"

using namespace varsurf;
using varsurf::test::fit_poles;

namespace {

constexpr double pi = 3.14159265358979323846;

// Cubic curve on `spans` uniform spans through f (exact when f is in the space).
BSplineCurve cubic_curve(int spans, const std::function<Eigen::Vector3d(double)>& f) {
  BSplineCurve c;
  c.degree = 3;
  c.knots = uniform_clamped_knots(3, spans);
  const std::vector<double> g = varsurf::test::greville(c.knots, 3);
  const int n = static_cast<int>(g.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n), b(n, 3);
  for (int r = 0; r < n; ++r) {
    const double t = g[static_cast<size_t>(r)];
    const int span = find_span(c.knots, 3, t);
    Eigen::MatrixXd nd(1, 4);
    basis_derivatives(c.knots, 3, span, t, 0, nd);
    for (int j = 0; j <= 3; ++j) a(r, span - 3 + j) = nd(0, j);
    b.row(r) = f(t).transpose();
  }
  c.poles = a.fullPivLu().solve(b);
  return c;
}

BSplineCurve segment2d(Eigen::Vector2d a, Eigen::Vector2d b) {
  BSplineCurve c;
  c.degree = 1;
  c.knots = {0.0, 0.0, 1.0, 1.0};
  c.poles.resize(2, 2);
  c.poles.row(0) = a.transpose();
  c.poles.row(1) = b.transpose();
  return c;
}

// Two sheets on either side of the seam x = 0, 0 <= y <= 1: A over x in [-1, 0] (its u = 1 edge on
// the seam, its region left of the pre-image (1, t)), B over x in [0, 1] (its u = 0 edge on the
// seam, region right of (0, t)). Each sheet's far edge is held at height `far`.
ModelProblem two_sheets(double far) {
  ModelProblem pb;
  const SplineSpace space = SplineSpace::uniform(3, 3, 6, 6);
  for (int s = 0; s < 2; ++s) {
    SheetProblem sheet;
    sheet.space = space;
    sheet.energy = ThinPlateWeights::isotropic(0.0, 1.0);  // pure bending
    const double shift = s == 0 ? -1.0 : 0.0;
    sheet.initial_poles =
        fit_poles(space, [&](double u, double v) { return Eigen::Vector3d(u + shift, v, 0.0); });
    const int far_row = s == 0 ? 0 : space.nu() - 1;
    for (int j = 0; j < space.nv(); ++j) {
      sheet.fixed_poles.push_back(space.index(far_row, j));
      sheet.initial_poles(space.index(far_row, j), 2) = far;
    }
    pb.sheets.push_back(sheet);
  }
  pb.joins.push_back({0, 0, segment2d({1, 0}, {1, 1}), +1});
  pb.joins.push_back({1, 0, segment2d({0, 0}, {0, 1}), -1});
  return pb;
}

SpaceCurve fixed_seam() {
  SpaceCurve c;
  c.start = cubic_curve(6, [](double t) { return Eigen::Vector3d(0.0, t, 0.0); });
  return c;
}

double height(const SplineSpace& space, const Eigen::MatrixX3d& poles, double u, double v) {
  return evaluate_surface(space, poles, u, v, 0)(0, 2);
}

}  // namespace

TEST(CurveEnergy, IntegratesTheCubicExactly) {
  // x(t) = t^3 on four spans: int_0^1 |x''|^2 = 12, int_0^1 |x'|^2 = 9/5.
  const BSplineCurve c = cubic_curve(4, [](double t) { return Eigen::Vector3d(t * t * t, 0, 0); });
  const Eigen::VectorXd x = c.poles.col(0);
  EXPECT_NEAR(x.dot(assemble_curve_energy(c, 0.0, 1.0) * x), 12.0, 1e-11);
  EXPECT_NEAR(x.dot(assemble_curve_energy(c, 1.0, 0.0) * x), 1.8, 1e-12);
  // A straight line bends by nothing.
  const BSplineCurve line = cubic_curve(4, [](double t) { return Eigen::Vector3d(2 * t, t, 1); });
  for (int e = 0; e < 3; ++e) {
    const Eigen::VectorXd p = line.poles.col(e);
    EXPECT_NEAR(p.dot(assemble_curve_energy(line, 0.0, 1.0) * p), 0.0, 1e-10);
  }
  EXPECT_THROW(assemble_curve_energy(c, 0.0, 0.0), InvalidInput);
  EXPECT_THROW(assemble_curve_energy(c, -1.0, 1.0), InvalidInput);
}

TEST(ModelSolver, CurveAloneThroughHandlesIsTheNaturalSpline) {
  // Bending of the displacement from the line (t, 0, 0) with handles at t = 0, 1/2, 1 lifting y
  // to 0, 1, 0: the displacement is the natural cubic spline, y = 3t - 4t^3 on [0, 1/2].
  ModelProblem pb;
  SpaceCurve c;
  c.start = cubic_curve(4, [](double t) { return Eigen::Vector3d(t, 0, 0); });
  c.variational = true;
  c.handles = {{0.0, {0, 0, 0}}, {0.5, {0.5, 1, 0}}, {1.0, {1, 0, 0}}};
  pb.curves.push_back(c);
  const ModelResult r = solve_model(pb);
  BSplineCurve out = c.start;
  out.poles = r.curve_poles[0];
  for (int i = 0; i <= 50; ++i) {
    const double t = i / 50.0, s = std::min(t, 1.0 - t);
    const Eigen::VectorXd p = out.evaluate(t);
    EXPECT_NEAR(p(0), t, 1e-9);
    EXPECT_NEAR(p(1), 3 * s - 4 * s * s * s, 1e-9) << t;
    EXPECT_NEAR(p(2), 0.0, 1e-9);
  }
}

TEST(ModelSolver, AClosedCurveThroughHandlesBendsAsThePeriodicSpline) {
  // A ring (start: a circle) lifted by 1 at t = 1/4 and lowered by 1 at t = 3/4, bending only:
  // the lift is the periodic cubic spline through them (period 1, knots h = 1/2 apart, second
  // derivatives M = -48 and 48 there), the same across the closing point t = 0 = 1 as anywhere.
  ModelProblem pb;
  SpaceCurve c;
  c.start = cubic_curve(4, [](double t) {
    return Eigen::Vector3d(std::cos(2 * M_PI * t), std::sin(2 * M_PI * t), 0.0);
  });
  c.variational = true;
  c.closed = true;
  const Eigen::Vector3d a = c.start.evaluate(0.25), b = c.start.evaluate(0.75);
  c.handles = {{0.25, a + Eigen::Vector3d(0, 0, 1)}, {0.75, b - Eigen::Vector3d(0, 0, 1)}};
  pb.curves.push_back(c);
  const ModelResult r = solve_model(pb);
  BSplineCurve out = c.start;
  out.poles = r.curve_poles[0];
  const double h = 0.5, m0 = -48.0, m1 = 48.0;
  auto lift = [&](double t) {  // from 1/4 to 3/4; the other half by d(t + 1/2) = -d(t)
    const double u = std::fmod(t + 0.75, 1.0), sign = u < 0.5 ? 1.0 : -1.0;
    const double s = u < 0.5 ? u : u - 0.5;
    return sign * (m0 * std::pow(h - s, 3) / (6 * h) + m1 * s * s * s / (6 * h) +
                   (1.0 - m0 * h * h / 6) * (h - s) / h + (-1.0 - m1 * h * h / 6) * s / h);
  };
  for (int i = 0; i <= 40; ++i) {
    const double t = i / 40.0;
    const Eigen::Vector3d d = out.evaluate(t) - c.start.evaluate(t);
    EXPECT_NEAR(d(2), lift(t), 1e-9) << t;
    EXPECT_NEAR(d.head<2>().norm(), 0.0, 1e-9) << t;
  }
  // Open, the ends are free (natural: no bending there) and the ring comes apart.
  pb.curves[0].closed = false;
  BSplineCurve open = c.start;
  open.poles = solve_model(pb).curve_poles[0];
  EXPECT_GT((open.evaluate(0.0) - open.evaluate(1.0)).norm(), 0.5);
  EXPECT_LT((out.evaluate(0.0) - out.evaluate(1.0)).norm(),
            1e-9 + (c.start.evaluate(0.0) - c.start.evaluate(1.0)).norm());
  pb.curves[0].closed = true;
  pb.curves[0].variational = false;
  pb.curves[0].handles.clear();
  EXPECT_THROW(solve_model(pb), InvalidInput);
}

TEST(ModelSolver, MovingAHandleOfAVariationalCurveMovesBothSheets) {
  ModelProblem pb = two_sheets(0.0);
  SpaceCurve seam = fixed_seam();
  seam.variational = true;
  seam.bend = 1e-2;
  seam.handles = {{0.0, {0, 0, 0}}, {0.5, {0, 0.5, 0.3}}, {1.0, {0, 1, 0}}};
  pb.curves.push_back(seam);
  const ModelResult r = solve_model(pb);
  const SplineSpace& space = pb.sheets[0].space;
  BSplineCurve curve = seam.start;
  curve.poles = r.curve_poles[0];
  // The handle is met and both sheets contain the curve (isoparametric pre-images: exactly).
  EXPECT_LT((curve.evaluate(0.5) - Eigen::Vector3d(0, 0.5, 0.3)).norm(), 1e-9);
  ASSERT_EQ(r.report.join_gaps.size(), 2u);
  for (double gap : r.report.join_gaps) EXPECT_LT(gap, 1e-9);
  // Both sheets follow, mirror images of each other.
  EXPECT_GT(height(space, r.sheet_poles[0], 0.9, 0.5), 0.1);
  for (int i = 0; i < space.nu(); ++i)
    for (int j = 0; j < space.nv(); ++j) {
      const Eigen::Vector3d a = r.sheet_poles[0].row(space.index(i, j));
      const Eigen::Vector3d b = r.sheet_poles[1].row(space.index(space.nu() - 1 - i, j));
      EXPECT_NEAR(a(0), -b(0), 1e-8);
      EXPECT_NEAR(a(1), b(1), 1e-8);
      EXPECT_NEAR(a(2), b(2), 1e-8);
    }
  // Independently: sheet A solved alone through the solved curve gives the same sheet.
  SheetProblem alone = pb.sheets[0];
  alone.curves.push_back({pb.joins[0].preimage, curve, 1.0, true});
  const SolveResult single = solve_sheet(alone);
  EXPECT_LT((single.poles - r.sheet_poles[0]).cwiseAbs().maxCoeff(), 1e-7);
  // With the handle at rest nothing moves.
  pb.curves[0].handles[1].target = {0, 0.5, 0};
  const ModelResult flat = solve_model(pb);
  EXPECT_LT(flat.sheet_poles[0].col(2).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ModelSolver, HingeAt180DegreesMakesTheSeamSmooth) {
  // Far edges at height h, seam on z = 0: without a hinge each pure-bending sheet is the plane
  // through its two edges (a crease of 180 - 2 atan(h) degrees); a 180-degree hinge makes both
  // leave the seam level, and then z = h (3 s^2 - s^3) / 2 (s the distance from the seam:
  // z(0) = z'(0) = 0, z(1) = h, a free end z''(1) = 0) is the fairest profile.
  const double h = 0.5;
  ModelProblem pb = two_sheets(h);
  pb.curves.push_back(fixed_seam());
  const ModelResult creased = solve_model(pb);
  EXPECT_NEAR(height(pb.sheets[0].space, creased.sheet_poles[0], 0.5, 0.5), 0.25, 1e-8);
  pb.hinges.push_back({0, 0, 1, pi});
  const ModelResult r = solve_model(pb);
  ASSERT_TRUE(r.report.converged);
  ASSERT_EQ(r.report.hinges.size(), 1u);
  EXPECT_LT(r.report.hinges[0].max_error * 180 / pi, 1e-4);
  const SplineSpace& space = pb.sheets[0].space;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 4; ++j) {
      const double s = i / 10.0, v = j / 4.0;
      const double z = h * (3 * s * s - s * s * s) / 2;
      EXPECT_NEAR(height(space, r.sheet_poles[0], 1.0 - s, v), z, 1e-6) << s << " " << v;
      EXPECT_NEAR(height(space, r.sheet_poles[1], s, v), z, 1e-6) << s << " " << v;
    }
}

TEST(ModelSolver, HingeMeetsAPrescribedAngle) {
  ModelProblem pb = two_sheets(0.3);
  pb.curves.push_back(fixed_seam());
  for (double degrees : {120.0, 150.0, 90.0}) {
    pb.hinges = {{0, 0, 1, degrees * pi / 180}};
    const ModelResult r = solve_model(pb);
    EXPECT_TRUE(r.report.converged) << degrees;
    const HingeReport& hr = r.report.hinges[0];
    EXPECT_LT(hr.max_error * 180 / pi, 0.05) << degrees;
    EXPECT_NEAR(hr.min_angle * 180 / pi, degrees, 0.05);
    EXPECT_NEAR(hr.max_angle * 180 / pi, degrees, 0.05);
    for (double gap : r.report.join_gaps) EXPECT_LT(gap, 1e-8);
  }
}

TEST(ModelSolver, HingeFindsWhereTheFoldSits) {
  // Far edge of A at height 1, of B at 0, a smooth (180-degree) seam. Across the seam each
  // coordinate of the pure-bending sheets is a cubic in the outward parameter s with f(0) = 0,
  // f(1) = H, f''(1) = 0, whose energy is 3 (f'(0) - H)^2. Smooth means the outward derivatives
  // are opposite up to a ratio k: (-p_a, q_a) = -k (p_b, q_b) in (x, z). Minimizing over p_b, q_b
  // leaves ((k - 1)^2 + 1) / (k^2 + 1), least at k^2 = k + 1 (the golden ratio), with
  // q_b = -k / (k^2 + 1), q_a = k^2 / (k^2 + 1). Where the fold sits is thus the energy's choice:
  // aims fixed at the bisector of the sheets solved without the hinge would give another profile.
  ModelProblem pb = two_sheets(0.0);
  for (int j = 0; j < pb.sheets[0].space.nv(); ++j)
    pb.sheets[0].initial_poles(pb.sheets[0].space.index(0, j), 2) = 1.0;
  pb.curves.push_back(fixed_seam());
  pb.hinges.push_back({0, 0, 1, pi});
  const ModelResult r = solve_model(pb);
  ASSERT_TRUE(r.report.converged);
  EXPECT_LT(r.report.hinges[0].max_error * 180 / pi, 1e-4);
  const double k = (1 + std::sqrt(5.0)) / 2;
  const auto profile = [](double q, double far, double s) {
    return q * s - 1.5 * (q - far) * s * s + 0.5 * (q - far) * s * s * s;
  };
  const SplineSpace& space = pb.sheets[0].space;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 4; ++j) {
      const double s = i / 10.0, v = j / 4.0;
      EXPECT_NEAR(height(space, r.sheet_poles[1], s, v), profile(-k / (k * k + 1), 0.0, s), 1e-6)
          << s << " " << v;
      EXPECT_NEAR(height(space, r.sheet_poles[0], 1.0 - s, v), profile(k * k / (k * k + 1), 1.0, s),
                  1e-6)
          << s << " " << v;
    }
}

TEST(ModelSolver, RefusesBadModels) {
  ModelProblem pb = two_sheets(0.0);
  pb.curves.push_back(fixed_seam());
  ModelProblem bad = pb;
  bad.hinges = {{0, 0, 0, pi}};  // one sheet twice
  EXPECT_THROW(solve_model(bad), InvalidInput);
  bad = pb;
  bad.curves.push_back(fixed_seam());
  bad.hinges = {{1, 0, 1, pi}};  // a hinge on a curve the sheets do not join
  try {
    solve_model(bad);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not joined"), std::string::npos) << e.what();
  }
  bad = pb;
  bad.hinges = {{0, 0, 1, 0.0}};  // no angle
  EXPECT_THROW(solve_model(bad), InvalidInput);
  bad = pb;
  bad.joins[1].side = 0;
  bad.hinges = {{0, 0, 1, pi}};
  EXPECT_THROW(solve_model(bad), InvalidInput);
  bad = pb;
  bad.joins.push_back(bad.joins[0]);  // the same join twice
  EXPECT_THROW(solve_model(bad), InvalidInput);
  bad = pb;
  bad.curves[0].handles = {{0.5, {0, 0, 0}}};  // a handle on a fixed curve
  EXPECT_THROW(solve_model(bad), InvalidInput);
  bad = pb;
  bad.curves[0].variational = true;
  bad.curves[0].handles = {{0.5, {0, std::nan(""), 0}}};
  EXPECT_THROW(solve_model(bad), InvalidInput);
  bad = pb;
  bad.joins[0].preimage = segment2d({1.5, 0}, {1.5, 1});  // leaves the sheet's domain
  EXPECT_THROW(solve_model(bad), InvalidInput);
  bad = pb;
  bad.sheets[0].pressure = 1.0;
  EXPECT_THROW(solve_model(bad), InvalidInput);
}
