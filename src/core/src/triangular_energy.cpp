// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/triangular_energy.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/triangular_bezier.hpp"

namespace varsurf {

namespace {

double factorial(int n) {
  return std::tgamma(n + 1.0);
}

double multinomial(int m, int i, int j) {
  return factorial(m) / (factorial(i) * factorial(j) * factorial(m - i - j));
}

// The derivative along a barycentric direction as a matrix: degree m nets to degree m - 1 nets.
Eigen::MatrixXd derivative_matrix(int m, const Eigen::Vector3d& d) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(triangle_points(m - 1), triangle_points(m));
  for (int i = 0; i <= m - 1; ++i)
    for (int j = 0; i + j <= m - 1; ++j) {
      const int r = triangle_index(m - 1, i, j);
      out(r, triangle_index(m, i + 1, j)) += m * d(0);
      out(r, triangle_index(m, i, j + 1)) += m * d(1);
      out(r, triangle_index(m, i, j)) += m * d(2);
    }
  return out;
}

}  // namespace

Eigen::MatrixXd bernstein_gram(int m, double area) {
  if (m < 0 || m > 40) throw InvalidInput("a Bernstein basis on a triangle has degree 0 to 40");
  if (!(area >= 0.0) || !std::isfinite(area))
    throw InvalidInput("a triangle's area must be a finite number >= 0");
  const int q = triangle_points(m);
  Eigen::MatrixXd g(q, q);
  for (int i = 0; i <= m; ++i)
    for (int j = 0; i + j <= m; ++j)
      for (int k = 0; k <= m; ++k)
        for (int l = 0; k + l <= m; ++l)
          g(triangle_index(m, i, j), triangle_index(m, k, l)) =
              2.0 * area * multinomial(m, i, j) * multinomial(m, k, l) /
              (multinomial(2 * m, i + k, j + l) * (2.0 * m + 1.0) * (2.0 * m + 2.0));
  return g;
}

TriangleEnergy triangle_energy(int degree, double side) {
  if (!(side > 0.0) || !std::isfinite(side))
    throw InvalidInput("the domain triangle's side must be a positive number");
  return triangle_energy(degree, Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(side, 0.0),
                         Eigen::Vector2d(0.5 * side, 0.5 * std::sqrt(3.0) * side));
}

BarycentricAxes barycentric_axes(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                 const Eigen::Vector2d& c) {
  // A corner's coordinate grows across the opposite edge: its gradient is that edge turned
  // inward, over twice the area.
  const double twice = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  const auto gradient = [twice](const Eigen::Vector2d& p,
                                const Eigen::Vector2d& q) -> Eigen::Vector2d {
    return Eigen::Vector2d(-(q - p).y(), (q - p).x()) / twice;  // of the corner left of p -> q
  };
  const Eigen::Vector2d ga = gradient(b, c), gb = gradient(c, a), gc = gradient(a, b);
  return {Eigen::Vector3d(ga.x(), gb.x(), gc.x()), Eigen::Vector3d(ga.y(), gb.y(), gc.y()),
          0.5 * twice};
}

TriangleEnergy triangle_energy(int degree, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& c) {
  if (degree < 1 || degree > 20)
    throw InvalidInput("a triangular patch has degree 1 to 20, not " + std::to_string(degree));
  if (!a.allFinite() || !b.allFinite() || !c.allFinite())
    throw InvalidInput("the domain triangle's corners must be finite");
  const double twice = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  if (!(twice > 1e-12 * longest))
    throw InvalidInput("the domain triangle must have area, its corners counterclockwise");
  const BarycentricAxes axes = barycentric_axes(a, b, c);
  const Eigen::Vector3d &dx = axes.x, &dy = axes.y;
  const double area = axes.area;
  const int n = degree;
  TriangleEnergy out;
  const Eigen::MatrixXd gx = derivative_matrix(n, dx), gy = derivative_matrix(n, dy);
  const Eigen::MatrixXd g1 = bernstein_gram(n - 1, area);
  out.stretch = gx.transpose() * g1 * gx + gy.transpose() * g1 * gy;
  if (n >= 2) {
    const Eigen::MatrixXd g2 = bernstein_gram(n - 2, area);
    const Eigen::MatrixXd xx = derivative_matrix(n - 1, dx) * gx;
    const Eigen::MatrixXd xy = derivative_matrix(n - 1, dy) * gx;
    const Eigen::MatrixXd yy = derivative_matrix(n - 1, dy) * gy;
    out.bend = xx.transpose() * g2 * xx + 2.0 * xy.transpose() * g2 * xy + yy.transpose() * g2 * yy;
  } else {
    out.bend = Eigen::MatrixXd::Zero(triangle_points(n), triangle_points(n));
  }
  return out;
}

}  // namespace varsurf
