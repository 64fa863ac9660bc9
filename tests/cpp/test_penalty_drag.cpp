// SPDX-License-Identifier: LGPL-2.1-or-later
// The penalty mode's drag responses: an update that translates one or two whole constraints
// after a one-step solve takes that step from kept responses, with no back-substitution, and
// gives the poles the back-substituted step gives; anything else (a rotated curve, three moved
// constraints, a move too large for one step) goes through the refinement as before.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "test_support.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

SolveOptions options(bool responses) {
  SolveOptions opt;
  opt.mode = SolveMode::penalty;
  opt.fit_tolerance = 1e-4;
  opt.drag_responses = responses;
  return opt;
}

void translate(CurveConstraint& c, const Eigen::Vector3d& t) {
  c.target.poles.rowwise() += t.transpose();
}

}  // namespace

// 19 x 19 poles (Eigen's LDL^T) and 35 x 35 (CHOLMOD's supernodal Cholesky where built with it).
TEST(PenaltyDrag, TranslatedConstraintsTakeTheStepFromKeptResponses) {
  for (int spans : {16, 32}) {
    const SheetProblem pb = test::penalty_scene(spans);
    PreparedSheet with(pb, options(true)), without(pb, options(false));
    ASSERT_EQ(with.result().report.inner_iterations, 1) << spans;
    EXPECT_EQ(with.result().poles, without.result().poles);
    struct Move {
      const char* what;
      std::function<void(SheetProblem&)> apply;
      int responses;  // back-substitutions the responses need (-1: the refinement's)
    };
    const std::vector<Move> moves{
        {"pin", [](SheetProblem& m) { m.points[0].target += Eigen::Vector3d(0.001, 0, 0.002); }, 1},
        {"pin again", [](SheetProblem& m) { m.points[0].target.z() -= 0.003; }, 0},
        {"curve",
         [](SheetProblem& m) {
           translate(m.curves[5], {0, 0.001, 0.003});
         },
         1},
        {"curve and pin",
         [](SheetProblem& m) {
           translate(m.curves[5], {0, 0, -0.002});
           m.points[0].target.z() += 0.001;
         },
         0},
        {"nothing", [](SheetProblem&) {}, 0},
        {"other pin", [](SheetProblem& m) { m.points[1].target.z() += 0.002; }, 1},
        {"rotated curve",
         [](SheetProblem& m) {  // about the x axis: lengths, and so the samples' weights, kept
           const double c = std::cos(0.003), s = std::sin(0.003);
           Eigen::MatrixXd& poles = m.curves[4].target.poles;
           for (Eigen::Index i = 0; i < poles.rows(); ++i) {
             const double y = poles(i, 1), z = poles(i, 2);
             poles(i, 1) = c * y - s * z;
             poles(i, 2) = s * y + c * z;
           }
         },
         -1},
        {"three pins and curves",
         [](SheetProblem& m) {
           m.points[0].target.z() += 0.001;
           m.points[1].target.z() += 0.001;
           translate(m.curves[6], {0, 0, 0.001});
         },
         -1},
        {"pin far up", [](SheetProblem& m) { m.points[0].target.z() += 0.2; }, 0},
    };
    SheetProblem moved = pb;
    for (const Move& move : moves) {
      move.apply(moved);
      const SolveResult a = with.update(moved), b = without.update(moved);
      // The back-substitution's rounding (measured up to 1.5e-10 on these unit-sized sheets).
      EXPECT_LT((a.poles - b.poles).cwiseAbs().maxCoeff(), 1e-9) << spans << " " << move.what;
      EXPECT_EQ(a.report.inner_iterations, b.report.inner_iterations) << spans << " " << move.what;
      EXPECT_EQ(b.report.back_substitutions, b.report.inner_iterations) << move.what;
      if (move.responses >= 0) {
        EXPECT_EQ(a.report.inner_iterations, 1) << spans << " " << move.what;
        EXPECT_EQ(a.report.back_substitutions, move.responses) << spans << " " << move.what;
      } else {
        EXPECT_GE(a.report.back_substitutions, a.report.inner_iterations)
            << spans << " " << move.what;
      }
      EXPECT_NEAR(a.report.constraint_residual, b.report.constraint_residual, 1e-9)
          << spans << " " << move.what;
    }
    EXPECT_GT(moves.size(), 8u);
  }
}

// A drag whose one step misses the tolerance is refined as before: a pin on a curve, where the
// curve passes, moved off it (the two then contradict each other).
TEST(PenaltyDrag, AMoveOneStepCannotFitIsRefinedAsBefore) {
  SheetProblem pb = test::penalty_scene(16);
  pb.points[0].u = 0.25;  // the first slanted curve's middle, 0.05 high there
  pb.points[0].target = Eigen::Vector3d(0.25, 0.5, 0.05);
  PreparedSheet with(pb, options(true)), without(pb, options(false));
  ASSERT_EQ(with.result().report.inner_iterations, 1);
  SheetProblem moved = pb;
  moved.points[0].target.z() += 0.01;
  const SolveResult a = with.update(moved), b = without.update(moved);
  EXPECT_GT(a.report.inner_iterations, 1);
  EXPECT_EQ(a.report.inner_iterations, b.report.inner_iterations);
  EXPECT_LT((a.poles - b.poles).cwiseAbs().maxCoeff(), 1e-9);
  // The response was computed (its step missed), then every step back-substituted.
  EXPECT_EQ(a.report.back_substitutions, a.report.inner_iterations + 1);
  EXPECT_GT(a.report.conflict, 0.0);
}
