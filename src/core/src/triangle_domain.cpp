// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/triangle_domain.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <utility>

#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/triangular_bezier.hpp"
#include "varsurf/core/triangular_energy.hpp"

namespace varsurf {

namespace {

double factorial_ratio(int n, int i, int j, int k) {
  return std::tgamma(n + 1.0) /
         (std::tgamma(i + 1.0) * std::tgamma(j + 1.0) * std::tgamma(k + 1.0));
}

}  // namespace

Eigen::VectorXd bernstein(int n, const Eigen::Vector3d& b) {
  Eigen::VectorXd out(triangle_points(n));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const int k = n - i - j;
      out(triangle_index(n, i, j)) =
          factorial_ratio(n, i, j, k) * std::pow(b(0), i) * std::pow(b(1), j) * std::pow(b(2), k);
    }
  return out;
}

// The derivative of B^n_ijk along d: n sum_c d_c B^(n-1)_(ijk - e_c).
Eigen::VectorXd bernstein_derivative(int n, const Eigen::Vector3d& b, const Eigen::Vector3d& d) {
  const Eigen::VectorXd lower = bernstein(n - 1, b);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(triangle_points(n));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const int k = n - i - j;
      double s = 0.0;
      if (i > 0) s += d(0) * lower(triangle_index(n - 1, i - 1, j));
      if (j > 0) s += d(1) * lower(triangle_index(n - 1, i, j - 1));
      if (k > 0) s += d(2) * lower(triangle_index(n - 1, i, j));
      out(triangle_index(n, i, j)) = n * s;
    }
  return out;
}

// The domain triangle of patch t: the equilateral triangle of its area (their eq. 25) or the mesh
// triangle laid flat, corners counterclockwise.
std::array<Eigen::Vector2d, 3> domain_corners(const TriangleNet& net, int t, bool equilateral) {
  const auto& c = net.triangles[t];
  const Eigen::Vector3d p = net.vertices.row(c[0]), a = net.vertices.row(c[1]),
                        b = net.vertices.row(c[2]);
  if (equilateral) {
    const double side = std::sqrt(4.0 * (0.5 * (a - p).cross(b - p).norm()) / std::sqrt(3.0));
    return {Eigen::Vector2d::Zero(), Eigen::Vector2d(side, 0.0),
            Eigen::Vector2d(0.5 * side, 0.5 * std::sqrt(3.0) * side)};
  }
  const Eigen::Vector3d x = (a - p).normalized();
  const Eigen::Vector3d y = ((a - p).cross(b - p)).cross(x).normalized();
  return {Eigen::Vector2d::Zero(), Eigen::Vector2d((a - p).dot(x), 0.0),
          Eigen::Vector2d((b - p).dot(x), (b - p).dot(y))};
}

// Triangles of the net as an operator's domain: on each, a collapsed Gauss rule of degree + 1
// points a direction (exact for products of two of its Bernstein polynomials), the basis values
// and their derivatives along the domain's x and y there, the area element of the domain.
OperatorDomain triangles_domain(const TriangleNet& net, std::vector<int> triangles,
                                bool equilateral) {
  return [&net, triangles = std::move(triangles), equilateral](const SampleVisitor& visit) {
    const int n = net.degree;
    const GaussRule& rule = gauss_legendre(n + 1);
    for (const int t : triangles) {
      const auto [a, b, c] = domain_corners(net, t, equilateral);
      const BarycentricAxes axes = barycentric_axes(a, b, c);
      BasisSample sample;
      sample.index = net.control[t];
      sample.values.resize(3, triangle_points(n));
      for (std::size_t i = 0; i < rule.nodes.size(); ++i)
        for (std::size_t j = 0; j < rule.nodes.size(); ++j) {
          // (s, r) in the unit square to u = s, v = (1 - s) r, w = (1 - s)(1 - r).
          const double s = 0.5 * (rule.nodes[i] + 1.0), r = 0.5 * (rule.nodes[j] + 1.0);
          const Eigen::Vector3d bary(s, (1.0 - s) * r, (1.0 - s) * (1.0 - r));
          sample.values.row(0) = bernstein(n, bary).transpose();
          sample.values.row(1) = bernstein_derivative(n, bary, axes.x).transpose();
          sample.values.row(2) = bernstein_derivative(n, bary, axes.y).transpose();
          visit(sample, 0.25 * rule.weights[i] * rule.weights[j] * (1.0 - s) * 2.0 * axes.area);
        }
    }
  };
}

}  // namespace varsurf
