// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/knot_vector.hpp"

using namespace varsurf;

namespace {

double binomial(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

}  // namespace

TEST(KnotVector, SingleSpanBasisIsBernstein) {
  // A clamped vector with one span is the Bernstein basis: N_i(t) = C(p,i) t^i (1-t)^(p-i).
  for (int p = 1; p <= 5; ++p) {
    std::vector<double> k(static_cast<size_t>(p + 1), 0.0);
    k.insert(k.end(), static_cast<size_t>(p + 1), 1.0);
    for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      Eigen::MatrixXd n(2, p + 1);
      basis_derivatives(k, p, find_span(k, p, t), t, 1, n);
      for (int i = 0; i <= p; ++i) {
        const double b = binomial(p, i) * std::pow(t, i) * std::pow(1.0 - t, p - i);
        EXPECT_NEAR(n(0, i), b, 1e-14) << "p=" << p << " t=" << t;
        const double db =
            binomial(p, i) *
            ((i > 0 ? i * std::pow(t, i - 1) * std::pow(1.0 - t, p - i) : 0.0) -
             (p - i > 0 ? (p - i) * std::pow(t, i) * std::pow(1.0 - t, p - i - 1) : 0.0));
        EXPECT_NEAR(n(1, i), db, 1e-12) << "p=" << p << " t=" << t;
      }
    }
  }
}

TEST(KnotVector, PartitionOfUnityAndDerivativesByFiniteDifference) {
  const std::vector<double> k = {0, 0, 0, 0, 0.1, 0.35, 0.35, 0.6, 0.9, 1, 1, 1, 1};
  const int p = 3;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double t = uni(rng);
    const int span = find_span(k, p, t);
    ASSERT_LE(k[static_cast<size_t>(span)], t);
    ASSERT_LT(t, k[static_cast<size_t>(span + 1)]);
    Eigen::MatrixXd n(3, p + 1);
    basis_derivatives(k, p, span, t, 2, n);
    EXPECT_NEAR(n.row(0).sum(), 1.0, 1e-14);
    EXPECT_NEAR(n.row(1).sum(), 0.0, 1e-11);
    EXPECT_NEAR(n.row(2).sum(), 0.0, 1e-9);
    const double h = 1e-6;
    if (t - h < k[static_cast<size_t>(span)] || t + h >= k[static_cast<size_t>(span + 1)]) continue;
    Eigen::MatrixXd np(3, p + 1), nm(3, p + 1);
    basis_derivatives(k, p, span, t + h, 2, np);
    basis_derivatives(k, p, span, t - h, 2, nm);
    for (int i = 0; i <= p; ++i) {
      EXPECT_NEAR(n(1, i), (np(0, i) - nm(0, i)) / (2 * h), 1e-6);
      EXPECT_NEAR(n(2, i), (np(1, i) - nm(1, i)) / (2 * h), 1e-4);
    }
  }
}

TEST(KnotVector, FindSpanAtDomainEnds) {
  const std::vector<double> k = uniform_clamped_knots(3, 4, 2.0, 6.0);
  EXPECT_EQ(find_span(k, 3, 2.0), 3);
  EXPECT_EQ(find_span(k, 3, 6.0), 6);  // last span, not past it
  EXPECT_EQ(find_span(k, 3, 3.0), 4);
}

TEST(KnotVector, FlatAndSplitRoundTrip) {
  const std::vector<double> knots = {0.0, 0.4, 1.0};
  const std::vector<int> mults = {4, 2, 4};
  const std::vector<double> flat = flat_knots(knots, mults);
  ASSERT_EQ(flat.size(), 10u);
  std::vector<double> k2;
  std::vector<int> m2;
  split_knots(flat, k2, m2);
  EXPECT_EQ(k2, knots);
  EXPECT_EQ(m2, mults);
  EXPECT_NO_THROW(validate_knots(flat, 3, 6, "t"));
  EXPECT_EQ(breakpoints(flat, 3), knots);
}

TEST(KnotVector, RejectsBadKnotVectors) {
  EXPECT_THROW(validate_knots({0, 0, 1, 1}, 2, 1, "t"), InvalidInput);          // too few poles
  EXPECT_THROW(validate_knots({0, 0, 0.5, 1, 1, 1}, 2, 3, "t"), InvalidInput);  // not clamped
  EXPECT_THROW(validate_knots({0, 0, 0, 0.7, 0.5, 1, 1, 1}, 2, 5, "t"),
               InvalidInput);  // decreasing
  EXPECT_THROW(validate_knots({0, 0, 0, NAN, 1, 1, 1}, 2, 4, "t"), InvalidInput);
  EXPECT_THROW(validate_knots({1, 1, 1, 1, 1, 1}, 2, 3, "t"), InvalidInput);  // empty domain
  EXPECT_THROW(validate_knots({0, 0, 0, .5, .5, .5, 1, 1, 1}, 2, 6, "t"), InvalidInput);
  EXPECT_THROW(flat_knots({0.0, 1.0}, {2}), InvalidInput);
  EXPECT_THROW(find_span(uniform_clamped_knots(3, 4), 3, NAN), InvalidInput);
  // An empty spline (default-constructed) and a knot vector too short for its degree.
  EXPECT_THROW(find_span({}, 3, 0.5), InvalidInput);
  EXPECT_THROW(find_span({0, 0, 1, 1}, 3, 0.5), InvalidInput);
}

// Finite but huge sizes are refused before they cost minutes or gigabytes; the limits themselves
// pass.
TEST(KnotVector, RefusesHugeKnotsAndSpanCounts) {
  EXPECT_THROW(validate_knots({0, 0, 1e308, 1e308}, 1, 2, "t"), InvalidInput);
  EXPECT_THROW(validate_knots({-2e12, -2e12, 0, 0}, 1, 2, "t"), InvalidInput);
  EXPECT_NO_THROW(validate_knots({0, 0, kMaxCoordinate, kMaxCoordinate}, 1, 2, "t"));
  EXPECT_THROW(uniform_clamped_knots(3, kMaxSpans + 1), InvalidInput);
  EXPECT_THROW(uniform_clamped_knots(3, 2147483647), InvalidInput);
  EXPECT_EQ(uniform_clamped_knots(1, kMaxSpans).size(), static_cast<size_t>(kMaxSpans + 3));
}

TEST(GaussLegendre, IntegratesPolynomialsExactly) {
  for (int n = 1; n <= 30; ++n) {
    const GaussRule& g = gauss_legendre(n);
    for (int deg = 0; deg <= 2 * n - 1; ++deg) {
      double s = 0.0;
      for (int i = 0; i < n; ++i)
        s += g.weights[static_cast<size_t>(i)] * std::pow(g.nodes[static_cast<size_t>(i)], deg);
      const double exact = (deg % 2 == 1) ? 0.0 : 2.0 / (deg + 1);
      EXPECT_NEAR(s, exact, 1e-13) << "n=" << n << " deg=" << deg;
    }
  }
  EXPECT_THROW(gauss_legendre(0), InvalidInput);
}
