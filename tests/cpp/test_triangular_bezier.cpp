// SPDX-License-Identifier: LGPL-2.1-or-later
// Triangular Bezier patches against independent answers: de Casteljau against the explicit
// Bernstein sum; linear precision; derivatives against central differences; subdivisions that
// reproduce the patch; the exact energies against closed forms for affine and quadratic patches
// (built from their blossoms); the three tensor-product quads equal to the patch to 1e-12.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <string>

#include "expect_refused.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/triangle_quads.hpp"
#include "varsurf/core/triangular_bezier.hpp"
#include "varsurf/core/triangular_energy.hpp"

using namespace varsurf;

namespace {

TriangularBezier random_patch(int degree, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-5.0, 5.0);
  TriangularBezier p{degree, Eigen::MatrixX3d(triangle_points(degree), 3)};
  for (Eigen::Index r = 0; r < p.points.rows(); ++r) p.points.row(r) << d(rng), d(rng), d(rng);
  return p;
}

Eigen::Vector3d random_point(std::mt19937& rng) {
  std::uniform_real_distribution<double> d(0.02, 1.0);
  Eigen::Vector3d b(d(rng), d(rng), d(rng));
  return b / b.sum();
}

// The explicit sum of eq. 2.
Eigen::Vector3d bernstein_sum(const TriangularBezier& p, const Eigen::Vector3d& b) {
  const int n = p.degree;
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const int k = n - i - j;
      const double c = std::tgamma(n + 1.0) /
                       (std::tgamma(i + 1.0) * std::tgamma(j + 1.0) * std::tgamma(k + 1.0));
      s += c * std::pow(b(0), i) * std::pow(b(1), j) * std::pow(b(2), k) *
           p.points.row(triangle_index(n, i, j)).transpose();
    }
  return s;
}

// The equilateral domain of triangle_energy (side 1): a barycentric point's (x, y).
Eigen::Vector2d domain(const Eigen::Vector3d& b) {
  return b(1) * Eigen::Vector2d(1.0, 0.0) + b(2) * Eigen::Vector2d(0.5, std::sqrt(3.0) / 2.0);
}

// A patch of degree n >= 2 whose z is the quadratic q(x, y) = a x^2 + b xy + c y^2 + x over the
// equilateral domain: its control points are the blossom of q at the corners.
TriangularBezier quadratic_patch(int n, double a, double b, double c) {
  const Eigen::Vector2d v[3] = {domain(Eigen::Vector3d::UnitX()), domain(Eigen::Vector3d::UnitY()),
                                domain(Eigen::Vector3d::UnitZ())};
  Eigen::Matrix2d q;
  q << a, b / 2, b / 2, c;
  TriangularBezier p{n, Eigen::MatrixX3d(triangle_points(n), 3)};
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      std::vector<Eigen::Vector2d> args;
      for (int s = 0; s < i; ++s) args.push_back(v[0]);
      for (int s = 0; s < j; ++s) args.push_back(v[1]);
      while (static_cast<int>(args.size()) < n) args.push_back(v[2]);
      // The blossom of x^T Q x (degree 2, taken as degree n): the mean over pairs r < s of
      // args_r^T Q args_s; of the linear term x, the mean of the arguments' x.
      double quad = 0.0, linear = 0.0;
      for (int r = 0; r < n; ++r) {
        linear += args[r](0) / n;
        for (int s = r + 1; s < n; ++s) quad += args[r].dot(q * args[s]) / (n * (n - 1) / 2.0);
      }
      const Eigen::Vector2d mean =
          std::accumulate(args.begin(), args.end(), Eigen::Vector2d(0, 0)) / n;
      p.points.row(triangle_index(n, i, j)) << mean(0), mean(1), quad + linear;
    }
  return p;
}

}  // namespace

TEST(TriangularBezier, DeCasteljauIsTheBernsteinSumAndLinearNetsAreLinear) {
  std::mt19937 rng(7);
  for (const int n : {1, 3, 5, 9}) {
    const TriangularBezier p = random_patch(n, 11u + static_cast<unsigned>(n));
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector3d b = random_point(rng);
      EXPECT_LT((p.evaluate(b) - bernstein_sum(p, b)).norm(), 1e-11) << n;
    }
    // Linear precision: control points at the domain points (i, j, k) / n give the domain.
    TriangularBezier linear{n, Eigen::MatrixX3d(triangle_points(n), 3)};
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        linear.points.row(triangle_index(n, i, j)) = Eigen::RowVector3d(i, j, n - i - j) / n;
    const Eigen::Vector3d b = random_point(rng);
    EXPECT_LT((linear.evaluate(b) - b).norm(), 1e-14);
  }
  // Corners are the corner control points.
  const TriangularBezier p = random_patch(4, 3);
  EXPECT_LT(
      (p.evaluate(Eigen::Vector3d::UnitY()) - p.points.row(triangle_index(4, 0, 4)).transpose())
          .norm(),
      1e-14);
}

TEST(TriangularBezier, DerivativesMatchCentralDifferences) {
  std::mt19937 rng(5);
  const TriangularBezier p = random_patch(5, 21);
  const Eigen::Vector3d d(1.0, -0.3, -0.7);  // a direction: entries sum to 0
  const double h = 1e-4;
  for (int k = 0; k < 10; ++k) {
    const Eigen::Vector3d b = random_point(rng);
    const Eigen::Vector3d fd = (p.evaluate(b + h * d) - p.evaluate(b - h * d)) / (2 * h);
    // Central differences miss by h^2 / 6 of the third derivative: up to about 1e-9 x 2,400 for
    // a quintic net within +-5 (the standard libraries draw different nets from one seed).
    EXPECT_LT((p.derivative(d).evaluate(b) - fd).norm(), 1e-5);
    const Eigen::Vector3d fd2 =
        (p.evaluate(b + h * d) - 2 * p.evaluate(b) + p.evaluate(b - h * d)) / (h * h);
    EXPECT_LT((p.derivative(d, 2).evaluate(b) - fd2).norm(), 1e-4);
  }
}

TEST(TriangularBezier, SplitsReproduceThePatch) {
  std::mt19937 rng(9);
  for (const int n : {3, 6}) {
    const TriangularBezier p = random_patch(n, 40u + static_cast<unsigned>(n));
    const Eigen::Vector3d at(0.2, 0.45, 0.35);
    const std::array<TriangularBezier, 3> three = split_at_point(p, at);
    const std::array<Eigen::Vector3d, 3> v = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                              Eigen::Vector3d::UnitZ()};
    for (int piece = 0; piece < 3; ++piece)
      for (int k = 0; k < 10; ++k) {
        // Sub-triangle piece has `at` in place of corner piece.
        std::array<Eigen::Vector3d, 3> corners = v;
        corners[static_cast<size_t>(piece)] = at;
        const Eigen::Vector3d s = random_point(rng);
        const Eigen::Vector3d b = s(0) * corners[0] + s(1) * corners[1] + s(2) * corners[2];
        EXPECT_LT((three[static_cast<size_t>(piece)].evaluate(s) - p.evaluate(b)).norm(), 1e-11);
      }
    // The pieces meet C0: the edge from `at` to corner 2 is shared by pieces 0 and 1.
    EXPECT_LT((three[0].evaluate({0.3, 0.0, 0.7}) - three[1].evaluate({0.0, 0.3, 0.7})).norm(),
              1e-12);
    const std::array<TriangularBezier, 2> two = split_at_edge(p, 0, 0.3);
    const Eigen::Vector3d mid(0.0, 0.7, 0.3);  // on the edge opposite corner 0, t = 0.3 from V2
    for (int k = 0; k < 10; ++k) {
      const Eigen::Vector3d s = random_point(rng);
      EXPECT_LT((two[0].evaluate(s) - p.evaluate(s(0) * v[0] + s(1) * v[1] + s(2) * mid)).norm(),
                1e-11);
      EXPECT_LT((two[1].evaluate(s) - p.evaluate(s(0) * v[0] + s(1) * mid + s(2) * v[2])).norm(),
                1e-11);
    }
  }
}

TEST(TriangularEnergy, TheGramMatrixIntegratesTheBernsteinBasis) {
  // The basis sums to one: all entries sum to the area; B_a's integral is area / C(m + 2, 2).
  for (const int m : {0, 1, 3, 6}) {
    const Eigen::MatrixXd g = bernstein_gram(m, 2.5);
    EXPECT_NEAR(g.sum(), 2.5, 1e-12) << m;
    EXPECT_NEAR(g.row(0).sum(), 2.5 * 2.0 / ((m + 1.0) * (m + 2.0)), 1e-12) << m;
    EXPECT_LT((g - g.transpose()).cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(TriangularEnergy, AffineAndQuadraticPatchesHaveTheirClosedFormEnergies) {
  const double area = std::sqrt(3.0) / 4.0;
  for (const int n : {2, 3, 5}) {
    const TriangleEnergy e = triangle_energy(n);
    // z = a x^2 + b xy + c y^2 + x: bend = area (4 a^2 + 2 b^2 + 4 c^2) for z; x and y are the
    // domain itself, whose stretch is area each and bend zero.
    const double a = 0.7, b = -1.3, c = 0.4;
    const TriangularBezier p = quadratic_patch(n, a, b, c);
    const Eigen::VectorXd x = p.points.col(0), y = p.points.col(1), z = p.points.col(2);
    EXPECT_NEAR(x.dot(e.stretch * x), area, 1e-12) << n;
    EXPECT_NEAR(y.dot(e.stretch * y), area, 1e-12) << n;
    EXPECT_NEAR(x.dot(e.bend * x), 0.0, 1e-12) << n;
    EXPECT_NEAR(z.dot(e.bend * z), area * (4 * a * a + 2 * b * b + 4 * c * c), 1e-11) << n;
    // Its stretch, |grad z|^2 = (2ax + by + 1)^2 + (bx + 2cy)^2 of degree 2, by the edge-midpoint
    // rule (exact for degree 2).
    double sum = 0.0;
    for (const Eigen::Vector3d& mid :
         {Eigen::Vector3d(0.5, 0.5, 0.0), Eigen::Vector3d(0.0, 0.5, 0.5),
          Eigen::Vector3d(0.5, 0.0, 0.5)}) {
      const Eigen::Vector2d d = domain(mid);
      const double gx = 2 * a * d(0) + b * d(1) + 1.0, gy = b * d(0) + 2 * c * d(1);
      sum += (gx * gx + gy * gy) * area / 3.0;
    }
    EXPECT_NEAR(z.dot(e.stretch * z), sum, 1e-12 * sum) << n;
  }
}

TEST(TriangularEnergy, TheEnergyDoesNotDependOnWhichCornerComesFirst) {
  // Renaming the corners (i, j, k) -> (j, k, i) permutes the control points; over the
  // equilateral domain the energy matrices are invariant under it.
  const int n = 4, q = triangle_points(n);
  const TriangleEnergy e = triangle_energy(n, 3.0);
  Eigen::PermutationMatrix<Eigen::Dynamic> turn(q);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j)
      turn.indices()(triangle_index(n, i, j)) = triangle_index(n, j, n - i - j);
  EXPECT_LT((turn * e.stretch * turn.transpose() - e.stretch).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((turn * e.bend * turn.transpose() - e.bend).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(TriangleQuads, ThreeTensorPatchesAreThePatchExactly) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> d(0.0, 1.0);
  for (const int n : {1, 3, 4, 7}) {
    const TriangularBezier p = random_patch(n, 60u + static_cast<unsigned>(n));
    const std::array<BSplineSurface, 3> quads = triangle_quads(p);
    double worst = 0.0;
    for (int quad = 0; quad < 3; ++quad) {
      EXPECT_EQ(quads[static_cast<size_t>(quad)].space.degree_u, n);
      for (int k = 0; k < 50; ++k) {
        const double u = d(rng), v = d(rng);
        worst = std::max(worst, (quads[static_cast<size_t>(quad)].evaluate(u, v) -
                                 p.evaluate(triangle_quad_point(quad, u, v)))
                                    .norm());
      }
    }
    EXPECT_LE(worst, 1e-12) << n;
    // The internal seams: quad i's edge v = 1 ... is quad (i - 1)'s edge u = 1 (the half-edge
    // from a midpoint to the centre), both the patch there.
    for (int k = 0; k <= 10; ++k) {
      const double s = k / 10.0;
      EXPECT_LT((quads[1].evaluate(s, 1.0) - quads[0].evaluate(1.0, s)).norm(), 1e-12);
    }
  }
}

TEST(TriangularBezier, BadPatchesAndSplitsAreRefused) {
  const auto refused = [](auto call, const std::string& words) {
    test::expect_refused(call, words);
  };
  refused([] { TriangularBezier{0, Eigen::MatrixX3d(1, 3)}.validate(); }, "degree 1 to 20");
  refused(
      [] {
        TriangularBezier{3, Eigen::MatrixX3d::Zero(9, 3)}.validate();
      },
      "10 control points");
  TriangularBezier nan = random_patch(2, 1);
  nan.points(2, 1) = NAN;
  refused([&] { nan.evaluate({0.3, 0.3, 0.4}); }, "not finite");
  const TriangularBezier p = random_patch(3, 2);
  refused([&] { split_at_point(p, {0.5, 0.5, 0.0}); }, "inside the triangle");
  refused([&] { split_at_edge(p, 3, 0.5); }, "corners are 0, 1 and 2");
  refused([&] { split_at_edge(p, 1, 1.0); }, "t in (0, 1)");
  refused([&] { p.derivative({1.0, -1.0, 0.0}, 4); }, "order must lie in 0..3");
  refused([] { triangle_energy(3, -1.0); }, "positive number");
  refused([] { bernstein_gram(41, 1.0); }, "degree 0 to 40");
  refused([] { bernstein_gram(2, NAN); }, "area must be a finite number");
}

TEST(TriangularEnergy, AnyDomainTriangleIntegratesItsOwnClosedForms) {
  // Over the triangle a, b, c: the domain's own x and y have stretch = area and no bend, and
  // z = p x^2 + q xy + r y^2 has bend area (4 p^2 + 2 q^2 + 4 r^2).
  const Eigen::Vector2d a(0.3, -0.2), b(4.1, 0.5), c(1.2, 1.7);
  const double area = 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  const double p = 0.6, q = -0.9, r = 1.1;
  for (const int n : {2, 3, 6}) {
    const TriangleEnergy e = triangle_energy(n, a, b, c);
    Eigen::VectorXd x(triangle_points(n)), y(triangle_points(n)), z(triangle_points(n));
    // The quadratic's Bezier net of degree n by its blossom: for x^2 the products of pairs of
    // distinct corner x's (i.e. mean of x_s x_t over the multiset of corners), likewise xy, y^2.
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const int k = n - i - j, row = triangle_index(n, i, j);
        const Eigen::Vector2d m = (i * a + j * b + k * c) / n;
        x(row) = m.x();
        y(row) = m.y();
        // Blossom of a quadratic f at n arguments: sum over pairs s < t of f~(p_s, p_t) / C(n, 2)
        // with f~ the polar form; over corners repeated i, j, k times.
        std::vector<Eigen::Vector2d> args;
        for (int s = 0; s < i; ++s) args.push_back(a);
        for (int s = 0; s < j; ++s) args.push_back(b);
        for (int s = 0; s < k; ++s) args.push_back(c);
        double sum = 0.0;
        for (std::size_t s = 0; s < args.size(); ++s)
          for (std::size_t t = s + 1; t < args.size(); ++t)
            sum += p * args[s].x() * args[t].x() +
                   0.5 * q * (args[s].x() * args[t].y() + args[s].y() * args[t].x()) +
                   r * args[s].y() * args[t].y();
        z(row) = sum / (n * (n - 1) / 2.0);
      }
    EXPECT_NEAR(x.dot(e.stretch * x), area, 1e-12 * area) << n;
    EXPECT_NEAR(y.dot(e.stretch * y), area, 1e-12 * area) << n;
    EXPECT_NEAR(x.dot(e.bend * x), 0.0, 1e-11) << n;
    EXPECT_NEAR(z.dot(e.bend * z), area * (4 * p * p + 2 * q * q + 4 * r * r), 1e-10) << n;
  }
  // The equilateral domain is the special case, and a clockwise or flat triangle is refused.
  const double h = std::sqrt(3.0) / 2.0;
  const TriangleEnergy eq = triangle_energy(4, 2.0);
  const TriangleEnergy same =
      triangle_energy(4, Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 0), Eigen::Vector2d(1, 2 * h));
  EXPECT_LT((eq.bend - same.bend).cwiseAbs().maxCoeff(), 1e-12 * eq.bend.cwiseAbs().maxCoeff());
  EXPECT_THROW(triangle_energy(3, a, c, b), InvalidInput);
  EXPECT_THROW(triangle_energy(3, a, b, a + 2.0 * (b - a)), InvalidInput);
}
