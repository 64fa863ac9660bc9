// SPDX-License-Identifier: LGPL-2.1-or-later
// PreparedSheet::change() with a few constraint rows added keeps the penalty factor: the added
// rows through the Sherman-Morrison-Woodbury formula, the new weight by conjugate gradients
// (FactorCorrection). Checked against dense solves of the same systems, and against fresh
// solves of the changed sheets.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <random>
#include <vector>

#include "factor_correction.hpp"
#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// A bending-like energy (second differences squared) on n unknowns, and `rows` random sample
// rows of four consecutive entries each.
struct System {
  Sparse q;
  RowSparse b;
};

System random_system(int n, int rows, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 1; i + 1 < n; ++i) {
    const int idx[3] = {i - 1, i, i + 1};
    const double c[3] = {1.0, -2.0, 1.0};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) t.emplace_back(idx[a], idx[b], c[a] * c[b]);
  }
  System s;
  s.q.resize(n, n);
  s.q.setFromTriplets(t.begin(), t.end());
  t.clear();
  std::uniform_int_distribution<int> start(0, n - 4);
  for (int r = 0; r < rows; ++r) {
    const int j = start(rng);
    for (int k = 0; k < 4; ++k) t.emplace_back(r, j + k, unit(rng));
  }
  s.b.resize(rows, n);
  s.b.setFromTriplets(t.begin(), t.end());
  return s;
}

Eigen::MatrixXd dense_penalty(const System& s, double weight, double eps) {
  Eigen::MatrixXd k = Eigen::MatrixXd(s.q) + weight * Eigen::MatrixXd(s.b.transpose() * s.b);
  k.diagonal().array() += eps;
  return k;
}

}  // namespace

// The preconditioner is exactly (K_o + w U^T U)^-1, and the solve K^-1 for K with the added rows
// under a weight 5 % (and 10 %) off the factor's, as a dense Cholesky of K gives it.
TEST(FactorCorrection, SolvesTheSystemWithAddedRowsAndAMovedWeight) {
  std::mt19937 rng(3);
  const int n = 80;
  const double eps = 1e-6;
  const System all = random_system(n, 120, rng);
  for (const double drift : {-0.05, 0.1}) {
    for (const int added : {0, 1, 3}) {
      System old = all;
      old.b = all.b.topRows(120 - added);
      const RowSparse u = all.b.bottomRows(added);
      const double w_old = 1e4, w = w_old * (1.0 + drift);
      Sparse k_old = old.q + Sparse(w_old * Sparse(old.b.transpose() * old.b));
      for (int i = 0; i < n; ++i) k_old.coeffRef(i, i) += eps;
      const Eigen::SimplicialLDLT<Sparse> f(k_old);
      ASSERT_EQ(f.info(), Eigen::Success);
      int base_calls = 0;
      const FactorCorrection c(
          [&](const Eigen::MatrixXd& r) {
            ++base_calls;
            return Eigen::MatrixXd(f.solve(r));
          },
          u, w);
      EXPECT_EQ(c.setup_substitutions(), added);
      const Eigen::MatrixXd r = Eigen::MatrixXd::Random(n, 3);
      // P = K_o + w U^T U, dense.
      Eigen::MatrixXd p = dense_penalty(old, w_old, eps);
      p += w * Eigen::MatrixXd(u.transpose() * u);
      const Eigen::MatrixXd want_p = p.llt().solve(r);
      EXPECT_LT((c.precondition(r) - want_p).norm(), 1e-10 * want_p.norm()) << drift << added;
      const Eigen::MatrixXd k = dense_penalty(all, w, eps);
      const Eigen::MatrixXd want = k.llt().solve(r);
      Eigen::MatrixXd x;
      int substitutions = 0;
      base_calls = 0;
      ASSERT_TRUE(c.solve(
          r, [&](const Eigen::MatrixXd& v) { return Eigen::MatrixXd(k * v); }, x, substitutions))
          << drift << " " << added;
      EXPECT_LT((x - want).norm(), 1e-9 * want.norm()) << drift << " " << added;
      EXPECT_EQ(substitutions, base_calls);
      EXPECT_LE(substitutions, 12) << drift << " " << added;
    }
  }
}

// Weights far apart converge too slowly to serve: the solve says so instead of answering.
TEST(FactorCorrection, RefusesWhatItCannotConvergeAndBadWeights) {
  std::mt19937 rng(4);
  const int n = 60;
  const System s = random_system(n, 90, rng);
  Sparse k_old = s.q + Sparse(1.0 * Sparse(s.b.transpose() * s.b));
  for (int i = 0; i < n; ++i) k_old.coeffRef(i, i) += 1e-6;
  const Eigen::SimplicialLDLT<Sparse> f(k_old);
  const auto base = [&](const Eigen::MatrixXd& r) { return Eigen::MatrixXd(f.solve(r)); };
  const RowSparse none(0, n);
  const double w = 1e6;  // the factor's weight is 1
  const FactorCorrection c(base, none, w);
  const Eigen::MatrixXd k = dense_penalty(s, w, 1e-6);
  Eigen::MatrixXd x;
  int substitutions = 0;
  EXPECT_FALSE(c.solve(
      Eigen::MatrixXd::Random(n, 2),
      [&](const Eigen::MatrixXd& v) { return Eigen::MatrixXd(k * v); }, x, substitutions));
  EXPECT_EQ(substitutions, FactorCorrection::kMaxSteps + 1);
  EXPECT_THROW(FactorCorrection(base, none, 0.0), InvalidInput);
  EXPECT_THROW(FactorCorrection(base, none, -1.0), InvalidInput);
}

// On sheets of 19 x 19 (LDL^T) and 35 x 35 poles (CHOLMOD): a pin added keeps the factor and
// gives the fresh solve's poles; a second pin added too; then a drag; a pin removed or a curve
// added factor anew. Each equals a fresh solve of the same sheet.
TEST(FactorCorrection, AddedPinsKeepTheFactorAndEqualFreshSolves) {
  for (int spans : {16, 32}) {
    const SheetProblem pb = test::penalty_scene(spans);
    SolveOptions opt;
    opt.mode = SolveMode::penalty;
    opt.fit_tolerance = 1e-4;
    PreparedSheet prepared(pb, opt);
    EXPECT_FALSE(prepared.result().report.factor_kept);
    const Eigen::MatrixX3d before = prepared.result().poles;
    // kept: whether the factor must have been kept (-1: either; a drag refactors once the
    // correction has cost more time than a factorization).
    const auto expect_fresh = [&](const SolveResult& got, const SheetProblem& problem, int kept,
                                  const char* what) {
      const SolveResult fresh = solve_sheet(problem, opt);
      if (kept >= 0) EXPECT_EQ(got.report.factor_kept, kept == 1) << spans << " " << what;
      // The fresh factor's own rounding on these unit-sized sheets (measured up to 3.5e-10; a
      // correction converged further changes nothing in it).
      EXPECT_LT((got.poles - fresh.poles).cwiseAbs().maxCoeff(), 1e-9) << spans << " " << what;
      EXPECT_EQ(got.report.inner_iterations, fresh.report.inner_iterations) << spans << " " << what;
      EXPECT_NEAR(got.report.constraint_residual, fresh.report.constraint_residual, 1e-9)
          << spans << " " << what;
      if (got.report
              .factor_kept) {  // the correction's conjugate gradient steps, and one per added row
        EXPECT_GT(got.report.back_substitutions, got.report.inner_iterations + 1)
            << spans << " " << what;
      }
    };
    SheetProblem changed = pb;
    PointConstraint pin;
    pin.u = 0.45;
    pin.v = 0.7;
    pin.target = Eigen::Vector3d(0.45, 0.7, 0.08);
    changed.points.push_back(pin);
    const SolveResult one = prepared.change(changed);
    expect_fresh(one, changed, 1, "one pin");
    EXPECT_GT((one.poles - before).cwiseAbs().maxCoeff(), 1e-3) << spans;
    pin.u = 0.7;
    pin.v = 0.6;
    pin.target = Eigen::Vector3d(0.7, 0.6, 0.03);
    changed.points.push_back(pin);
    // Kept for the second pin only while the correction has cost less time than a factorization
    // (a timed choice: on a loaded machine either way), and equal to a fresh solve either way.
    expect_fresh(prepared.change(changed), changed, -1, "two pins");
    changed.points.back().target.z() += 0.002;  // a drag of the new pin
    expect_fresh(prepared.update(changed), changed, -1, "drag");
    changed.points.erase(changed.points.begin());
    expect_fresh(prepared.change(changed), changed, 0, "a pin removed");
    changed.curves.push_back(pb.curves[4]);
    changed.curves.back().target.poles.col(2).array() += 0.01;
    changed.curves.back().preimage.poles.col(0).array() += 0.1;
    expect_fresh(prepared.change(changed), changed, 0, "a curve added");
  }
}
