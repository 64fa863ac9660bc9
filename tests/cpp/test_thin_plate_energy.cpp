// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <random>
#include <utility>

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

namespace {

// w = (u^2, u v, v^3) under isotropic(a, b): the integrand a (|w_u|^2 + |w_v|^2) + b (w_uu^2 +
// 2 w_uv^2 + w_vv^2) = a (5 u^2 + v^2 + 9 v^4) + b (6 + 36 v^2), integrated in v analytically.
double integrand_in_v(double a, double b, double u, double v) {
  return a * (5 * u * u * v + v * v * v / 3 + 9 * std::pow(v, 5) / 5) +
         b * (6 * v + 12 * v * v * v);
}

// Its integral over the region between v = lo(u) and v = hi(u) for u in [u0, u1]: both are
// linear in u, so the v-integral is a polynomial of degree 5 in u, which the 3-point Gauss rule
// (nodes 0, +-sqrt(3/5), weights 8/9, 5/9) integrates exactly.
double analytic_energy(double a, double b, double u0, double u1,
                       const std::function<double(double)>& lo,
                       const std::function<double(double)>& hi) {
  const double mid = 0.5 * (u0 + u1), half = 0.5 * (u1 - u0), x = std::sqrt(0.6);
  double sum = 0.0;
  for (const auto& [node, weight] : {std::pair{-x, 5.0 / 9}, {0.0, 8.0 / 9}, {x, 5.0 / 9}}) {
    const double u = mid + half * node;
    sum += weight * half * (integrand_in_v(a, b, u, hi(u)) - integrand_in_v(a, b, u, lo(u)));
  }
  return sum;
}

Eigen::MatrixX3d polynomial_poles(const SplineSpace& sp) {
  return test::fit_poles(
      sp, [](double u, double v) { return Eigen::Vector3d(u * u, u * v, v * v * v); });
}

}  // namespace

TEST(RegionEnergy, EqualsTheAnalyticIntegralOverConcaveAndSlantedRegions) {
  // Breakpoints the regions' edges cut through (0.2, 0.45, 0.3), off the uniform grid.
  SplineSpace sp = SplineSpace::uniform(3, 3, 3, 4);
  sp.knots_u = {0, 0, 0, 0, 0.2, 0.45, 1, 1, 1, 1};
  sp.knots_v[5] = 0.3;
  const double a = 0.5, b = 2.0;
  const Eigen::MatrixX3d p = polynomial_poles(sp);
  auto region_energy = [&](const std::vector<Eigen::Vector2d>& loop) {
    return energy(assemble_thin_plate(sp, ThinPlateWeights::isotropic(a, b), Region(loop), 0.0), p);
  };
  auto constant = [](double c) { return [c](double) { return c; }; };
  // A concave L: [0.1, 0.9] x [0.15, 0.35] plus [0.1, 0.35] x [0.35, 0.85], listed clockwise.
  const double l_shape = analytic_energy(a, b, 0.1, 0.35, constant(0.15), constant(0.85)) +
                         analytic_energy(a, b, 0.35, 0.9, constant(0.15), constant(0.35));
  EXPECT_NEAR(region_energy(
                  {{0.1, 0.15}, {0.1, 0.85}, {0.35, 0.85}, {0.35, 0.35}, {0.9, 0.35}, {0.9, 0.15}}),
              l_shape, 1e-10 * l_shape);
  // A triangle with a slanted edge v = 0.95 - u, across several pieces.
  const double triangle =
      analytic_energy(a, b, 0.05, 0.8, constant(0.15), [](double u) { return 0.95 - u; });
  EXPECT_NEAR(region_energy({{0.05, 0.15}, {0.8, 0.15}, {0.05, 0.9}}), triangle, 1e-10 * triangle);
}

TEST(RegionEnergy, PartsOfTheDomainAddUpToTheWholeAndTheOverhangKeepsItsShare) {
  for (bool rational : {false, true}) {
    const SplineSpace sp = nonuniform_space(3, 2, rational);
    const ThinPlateWeights w = ThinPlateWeights::isotropic(0.3, 1.7);
    const Eigen::SparseMatrix<double> whole = assemble_thin_plate(sp, w);
    // A wavy cut from the bottom edge to the top one splits the domain into two regions.
    std::vector<Eigen::Vector2d> cut;
    for (int k = 0; k <= 12; ++k) cut.emplace_back(0.45 + 0.2 * std::sin(7.0 * k / 12), k / 12.0);
    std::vector<Eigen::Vector2d> left = cut, right = cut;
    left.insert(left.end(), {{0.0, 1.0}, {0.0, 0.0}});
    right.insert(right.end(), {{1.0, 1.0}, {1.0, 0.0}});
    const Eigen::SparseMatrix<double> a = assemble_thin_plate(sp, w, Region(left), 0.0);
    const Eigen::SparseMatrix<double> b = assemble_thin_plate(sp, w, Region(right), 0.0);
    const double scale = Eigen::MatrixXd(whole).cwiseAbs().maxCoeff();
    // Both parts' quadratures are exact (non-rational) or as accurate as the whole's (rational).
    const double tol = rational ? 1e-6 : 1e-11;
    EXPECT_LT(Eigen::MatrixXd(a + b - whole).cwiseAbs().maxCoeff(), tol * scale) << rational;
    // With the overhang at weight t: (1 - t) inside + t whole.
    const Eigen::SparseMatrix<double> t = assemble_thin_plate(sp, w, Region(left), 0.25);
    EXPECT_LT(Eigen::MatrixXd(t - a - 0.25 * b).cwiseAbs().maxCoeff(), tol * scale) << rational;
    // The whole domain as a loop is the whole energy.
    const Eigen::SparseMatrix<double> all =
        assemble_thin_plate(sp, w, Region({{0, 0}, {1, 0}, {1, 1}, {0, 1}}), 0.0);
    EXPECT_LT(Eigen::MatrixXd(all - whole).cwiseAbs().maxCoeff(), tol * scale) << rational;
  }
}

TEST(ThinPlateEnergy, SeparableAssemblyEqualsTheQuadratureOverTheWholeDomain) {
  // A polynomial space's energy is assembled from 1D Gram matrices (Kronecker products); the
  // region path integrates the same energy point by point in 2D. Anisotropic weights with every
  // coupling term, unequal degrees and non-uniform knots exercise each term of the sum.
  ThinPlateWeights w;
  w.alpha << 1.3, -0.4, -0.4, 0.7;
  w.beta << 2.0, 0.6, 0.3, 1.1;
  for (const auto& [pu, pv] : {std::pair{4, 3}, {2, 5}, {3, 3}}) {
    const SplineSpace sp = nonuniform_space(pu, pv, false);
    const Eigen::MatrixXd whole(assemble_thin_plate(sp, w));
    const Eigen::MatrixXd by_points(
        assemble_thin_plate(sp, w, Region({{0, 0}, {1, 0}, {1, 1}, {0, 1}}), 0.0));
    EXPECT_LT((whole - by_points).cwiseAbs().maxCoeff(), 1e-12 * whole.cwiseAbs().maxCoeff())
        << pu << " x " << pv;
  }
}

TEST(RegionEnergy, RefusesBadRegionsAndOverhangWeights) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 2, 2);
  const ThinPlateWeights w = ThinPlateWeights::isotropic(0, 1);
  const Region square({{0.2, 0.2}, {0.8, 0.2}, {0.8, 0.8}, {0.2, 0.8}});
  for (double t : {-0.1, 1.0, double(NAN)})
    EXPECT_THROW(assemble_thin_plate(sp, w, square, t), InvalidInput);
  EXPECT_THROW(
      assemble_thin_plate(sp, w, Region({{0.2, 0.2}, {0.8, 0.8}, {0.8, 0.2}, {0.2, 0.8}}), 0.0),
      InvalidInput);  // a bow tie
  EXPECT_THROW(assemble_thin_plate(sp, w, Region({{0.2, 0.2}, {1.8, 0.2}, {0.8, 0.8}}), 0.0),
               InvalidInput);  // outside the domain
}
