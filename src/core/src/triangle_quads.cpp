// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/triangle_quads.hpp"

#include <Eigen/LU>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

Eigen::Vector3d triangle_quad_point(int quad, double u, double v) {
  if (quad < 0 || quad > 2) throw InvalidInput("a triangle has quads 0, 1 and 2");
  const Eigen::Vector3d corner = Eigen::Vector3d::Unit(quad);
  const Eigen::Vector3d next = 0.5 * (corner + Eigen::Vector3d::Unit((quad + 1) % 3));
  const Eigen::Vector3d previous = 0.5 * (corner + Eigen::Vector3d::Unit((quad + 2) % 3));
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(1.0 / 3.0);
  return (1 - u) * (1 - v) * corner + u * (1 - v) * next + u * v * centre + (1 - u) * v * previous;
}

std::array<BSplineSurface, 3> triangle_quads(const TriangularBezier& patch) {
  patch.validate();
  const int n = patch.degree;
  // Chebyshev-Lobatto nodes: the collocation matrix of the Bernstein basis stays well
  // conditioned up to the highest degree (about 1e3 at degree 20 against 1e6 for even nodes).
  Eigen::VectorXd nodes(n + 1);
  for (int a = 0; a <= n; ++a) nodes(a) = 0.5 * (1.0 - std::cos(M_PI * a / n));
  Eigen::MatrixXd collocation(n + 1, n + 1);
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b)
      collocation(a, b) = std::tgamma(n + 1.0) / (std::tgamma(b + 1.0) * std::tgamma(n - b + 1.0)) *
                          std::pow(nodes(a), b) * std::pow(1.0 - nodes(a), n - b);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(collocation);
  SplineSpace space;
  space.degree_u = space.degree_v = n;
  space.knots_u.assign(static_cast<size_t>(n + 1), 0.0);
  space.knots_u.resize(static_cast<size_t>(2 * n + 2), 1.0);
  space.knots_v = space.knots_u;
  std::array<BSplineSurface, 3> out;
  for (int quad = 0; quad < 3; ++quad) {
    BSplineSurface& s = out[static_cast<size_t>(quad)];
    s.space = space;
    s.poles.resize(space.size(), 3);
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixXd values(n + 1, n + 1);
      for (int a = 0; a <= n; ++a)
        for (int b = 0; b <= n; ++b)
          values(a, b) = patch.evaluate(triangle_quad_point(quad, nodes(a), nodes(b)))(c);
      // values = M X M^T: X = M^-1 values M^-T.
      const Eigen::MatrixXd x = lu.solve(lu.solve(values).transpose()).transpose();
      for (int a = 0; a <= n; ++a)
        for (int b = 0; b <= n; ++b) s.poles(space.index(a, b), c) = x(a, b);
    }
  }
  return out;
}

}  // namespace varsurf
