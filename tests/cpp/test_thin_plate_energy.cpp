// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/thin_plate_energy.hpp"

using namespace varsurf;

namespace {

SplineSpace nonuniform_space(int pu, int pv, bool rational) {
  SplineSpace sp = SplineSpace::uniform(pu, pv, 4, 3);
  // Move interior knots off the uniform grid (keeps them distinct).
  sp.knots_u[static_cast<size_t>(pu + 1)] = 0.1;
  sp.knots_v[static_cast<size_t>(pv + 2)] = 0.8;
  if (rational) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uni(0.6, 1.6);
    sp.weights.resize(sp.size());
    for (int k = 0; k < sp.size(); ++k) sp.weights(k) = uni(rng);
  }
  return sp;
}

double energy(const Eigen::SparseMatrix<double>& h, const Eigen::MatrixX3d& p) {
  return (p.transpose() * (h * p)).trace();
}

}  // namespace

class EnergyBySpace : public ::testing::TestWithParam<std::tuple<int, int, bool>> {};

TEST_P(EnergyBySpace, SymmetricPositiveSemiDefinite) {
  const auto [pu, pv, rational] = GetParam();
  const SplineSpace sp = nonuniform_space(pu, pv, rational);
  const Eigen::SparseMatrix<double> h =
      assemble_thin_plate(sp, ThinPlateWeights::isotropic(0.3, 1.0));
  const Eigen::MatrixXd d(h);
  EXPECT_LT((d - d.transpose()).cwiseAbs().maxCoeff(), 1e-12 * d.cwiseAbs().maxCoeff());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(d);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-10 * eig.eigenvalues().maxCoeff());
}

TEST_P(EnergyBySpace, BendingIsZeroOnAffineSurfaces) {
  const auto [pu, pv, rational] = GetParam();
  const SplineSpace sp = nonuniform_space(pu, pv, rational);
  const Eigen::SparseMatrix<double> bend =
      assemble_thin_plate(sp, ThinPlateWeights::isotropic(0.0, 1.0));
  auto affine = [](double u, double v) {
    return Eigen::Vector3d(2 + 3 * u - v, -1 + 0.5 * u + 4 * v, 7 * u + 2 * v);
  };
  const Eigen::MatrixX3d p = test::fit_poles(sp, affine);
  if (rational) {
    // A rational space reproduces constants (its basis sums to one) but not affine maps.
    Eigen::MatrixX3d c(sp.size(), 3);
    c.rowwise() = Eigen::RowVector3d(1.5, -2.0, 4.0);
    const Eigen::SparseMatrix<double> full =
        assemble_thin_plate(sp, ThinPlateWeights::isotropic(1.0, 1.0));
    EXPECT_LT(std::abs(energy(full, c)), 1e-10 * c.squaredNorm());
  } else {
    EXPECT_LT(std::abs(energy(bend, p)), 1e-9 * p.squaredNorm());
  }
  // The stretch part is never zero on a non-constant map.
  const Eigen::SparseMatrix<double> stretch =
      assemble_thin_plate(sp, ThinPlateWeights::isotropic(1.0, 0.0));
  EXPECT_GT(energy(stretch, p), 1.0);
}

INSTANTIATE_TEST_SUITE_P(
    Degrees, EnergyBySpace,
    ::testing::Values(std::make_tuple(2, 2, false), std::make_tuple(3, 3, false),
                      std::make_tuple(4, 3, false), std::make_tuple(3, 5, false),
                      std::make_tuple(3, 3, true), std::make_tuple(2, 4, true)));

TEST(ThinPlateEnergy, AnalyticIntegralsOfPolynomials) {
  // On [0,1]^2 with alpha = a I and beta = b 1: Q(w) = a (|w_u|^2 + |w_v|^2) + b (w_uu^2 + 2 w_uv^2
  // + w_vv^2).
  SplineSpace sp = SplineSpace::uniform(3, 3, 3, 4);
  sp.knots_u = {0, 0, 0, 0, 0.2, 0.45, 1, 1, 1, 1};
  const Eigen::SparseMatrix<double> h =
      assemble_thin_plate(sp, ThinPlateWeights::isotropic(0.5, 2.0));
  auto q = [&](const std::function<Eigen::Vector3d(double, double)>& f) {
    return energy(h, test::fit_poles(sp, f));
  };
  // w = (u^2, 0, 0): stretch 0.5 * int 4u^2 = 2/3, bend 2 * int 4 = 8.
  EXPECT_NEAR(q([](double u, double) { return Eigen::Vector3d(u * u, 0, 0); }), 2.0 / 3.0 + 8.0,
              1e-10);
  // w = (0, u v, 0): stretch 0.5 * int (v^2 + u^2) = 1/3, bend 2 * 2 * int 1 = 4.
  EXPECT_NEAR(q([](double u, double v) { return Eigen::Vector3d(0, u * v, 0); }), 1.0 / 3.0 + 4.0,
              1e-10);
  // w = (0, 0, v^3): stretch 0.5 * int 9 v^4 = 0.9, bend 2 * int 36 v^2 = 24.
  EXPECT_NEAR(q([](double, double v) { return Eigen::Vector3d(0, 0, v * v * v); }), 0.9 + 24.0,
              1e-9);
}

TEST(ThinPlateEnergy, AnisotropicWeights) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 2, 2);
  ThinPlateWeights w;
  w.alpha << 2.0, 0.5, 0.5, 1.0;
  w.beta << 3.0, 0.25, 0.25, 0.0;
  const Eigen::SparseMatrix<double> h = assemble_thin_plate(sp, w);
  // w = u^2 + v: w_u = 2u, w_v = 1, w_uu = 2, others 0.
  // alpha: int 2*4u^2 + 2*0.5*2u*1 + 1*1 = 8/3 + 1 + 1; beta: 3*4 = 12.
  const Eigen::MatrixX3d p =
      test::fit_poles(sp, [](double u, double v) { return Eigen::Vector3d(u * u + v, 0, 0); });
  EXPECT_NEAR(energy(h, p), 8.0 / 3.0 + 2.0 + 12.0, 1e-10);
}

TEST(ThinPlateEnergy, RejectsBadWeightsAndDegrees) {
  EXPECT_THROW(ThinPlateWeights::isotropic(-1.0, 1.0), InvalidInput);
  EXPECT_THROW(ThinPlateWeights::isotropic(0.0, 0.0), InvalidInput);
  EXPECT_THROW(ThinPlateWeights::isotropic(NAN, 1.0), InvalidInput);
  EXPECT_THROW(
      assemble_thin_plate(SplineSpace::uniform(1, 3, 2, 2), ThinPlateWeights::isotropic(0, 1)),
      InvalidInput);
  EXPECT_NO_THROW(
      assemble_thin_plate(SplineSpace::uniform(1, 1, 2, 2), ThinPlateWeights::isotropic(1, 0)));
}
