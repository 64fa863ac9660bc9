// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/triangular_bezier.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

int triangle_points(int degree) {
  return (degree + 1) * (degree + 2) / 2;
}

int triangle_index(int degree, int i, int j) {
  const int m = degree - i;
  return m * (m + 1) / 2 + (m - j);
}

namespace {

// One de Casteljau step: the degree m - 1 net of x's affine (or, for a direction, linear)
// combinations Q_ijk = x0 P_(i+1)jk + x1 P_i(j+1)k + x2 P_ij(k+1).
Eigen::MatrixX3d step(const Eigen::MatrixX3d& p, int m, const Eigen::Vector3d& x) {
  Eigen::MatrixX3d q(triangle_points(m - 1), 3);
  for (int i = 0; i <= m - 1; ++i)
    for (int j = 0; i + j <= m - 1; ++j)
      q.row(triangle_index(m - 1, i, j)) = x(0) * p.row(triangle_index(m, i + 1, j)) +
                                           x(1) * p.row(triangle_index(m, i, j + 1)) +
                                           x(2) * p.row(triangle_index(m, i, j));
  return q;
}

}  // namespace

void TriangularBezier::validate() const {
  if (degree < 1 || degree > 20)
    throw InvalidInput("a triangular patch has degree 1 to 20, not " + std::to_string(degree));
  if (points.rows() != triangle_points(degree))
    throw InvalidInput("a triangular patch of degree " + std::to_string(degree) + " has " +
                       std::to_string(triangle_points(degree)) + " control points, not " +
                       std::to_string(points.rows()));
  if (!points.allFinite()) throw InvalidInput("a triangular patch has points that are not finite");
}

Eigen::Vector3d TriangularBezier::evaluate(const Eigen::Vector3d& barycentric) const {
  validate();
  if (!barycentric.allFinite()) throw InvalidInput("barycentric coordinates are not finite");
  Eigen::MatrixX3d p = points;
  for (int m = degree; m > 0; --m) p = step(p, m, barycentric);
  return p.row(0).transpose();
}

TriangularBezier TriangularBezier::derivative(const Eigen::Vector3d& direction, int order) const {
  validate();
  if (order < 0 || order > degree)
    throw InvalidInput("a derivative's order must lie in 0.." + std::to_string(degree));
  if (!direction.allFinite()) throw InvalidInput("a derivative's direction is not finite");
  TriangularBezier out{degree - order, points};
  for (int m = degree; m > degree - order; --m) out.points = m * step(out.points, m, direction);
  return out;
}

TriangularBezier sub_patch(const TriangularBezier& patch,
                           const std::array<Eigen::Vector3d, 3>& corners) {
  patch.validate();
  for (const Eigen::Vector3d& c : corners)
    if (!c.allFinite()) throw InvalidInput("a sub-triangle's corner is not finite");
  const int n = patch.degree;
  TriangularBezier out{n, Eigen::MatrixX3d(triangle_points(n), 3)};
  // Control point ijk is the blossom of T at (c1 i times, c2 j times, c3 k times).
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      Eigen::MatrixX3d p = patch.points;
      int m = n;
      for (int s = 0; s < i; ++s, --m) p = step(p, m, corners[0]);
      for (int s = 0; s < j; ++s, --m) p = step(p, m, corners[1]);
      for (; m > 0; --m) p = step(p, m, corners[2]);
      out.points.row(triangle_index(n, i, j)) = p.row(0);
    }
  return out;
}

std::array<TriangularBezier, 3> split_at_point(const TriangularBezier& patch,
                                               const Eigen::Vector3d& p) {
  if (!p.allFinite() || !(p.minCoeff() > 0.0) || std::abs(p.sum() - 1.0) > 1e-12)
    throw InvalidInput("a split point must lie inside the triangle (barycentric, all > 0)");
  const Eigen::Vector3d v1 = Eigen::Vector3d::UnitX(), v2 = Eigen::Vector3d::UnitY(),
                        v3 = Eigen::Vector3d::UnitZ();
  return {sub_patch(patch, {p, v2, v3}), sub_patch(patch, {v1, p, v3}),
          sub_patch(patch, {v1, v2, p})};
}

std::array<TriangularBezier, 2> split_at_edge(const TriangularBezier& patch, int corner, double t) {
  if (corner < 0 || corner > 2) throw InvalidInput("a triangle's corners are 0, 1 and 2");
  if (!(t > 0.0 && t < 1.0)) throw InvalidInput("an edge is split at t in (0, 1)");
  const int a = (corner + 1) % 3, b = (corner + 2) % 3;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p(a) = 1.0 - t;
  p(b) = t;
  std::array<Eigen::Vector3d, 3> first, second;
  for (int k = 0; k < 3; ++k)
    first[static_cast<size_t>(k)] = second[static_cast<size_t>(k)] = Eigen::Vector3d::Unit(k);
  first[static_cast<size_t>(b)] = p;   // corner, next corner, p
  second[static_cast<size_t>(a)] = p;  // corner, p, the one after
  return {sub_patch(patch, first), sub_patch(patch, second)};
}

Eigen::Vector3d patch_normal(const TriangularBezier& p, const Eigen::Vector3d& b) {
  const Eigen::Vector3d du = p.derivative(Eigen::Vector3d(-1.0, 1.0, 0.0)).evaluate(b);
  const Eigen::Vector3d dv = p.derivative(Eigen::Vector3d(-1.0, 0.0, 1.0)).evaluate(b);
  return du.cross(dv).normalized();
}

}  // namespace varsurf
