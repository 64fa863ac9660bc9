// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/point_curvature.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

void validate(const SplineSpace& space, const PointCurvatureConstraint& c) {
  space.validate();
  if (!std::isfinite(c.u) || !std::isfinite(c.v) || c.u < space.u_first() || c.u > space.u_last() ||
      c.v < space.v_first() || c.v > space.v_last())
    throw InvalidInput("point curvature: (u, v) must lie in the sheet's domain");
  if (!c.along_u && !c.along_v)
    throw InvalidInput("point curvature: ask for the curvature along u, along v or both");
  if (!std::isfinite(c.kappa_u) || !std::isfinite(c.kappa_v))
    throw InvalidInput("point curvature: the curvatures must be finite");
  if (!std::isfinite(c.weight) || c.weight <= 0.0)
    throw InvalidInput("point curvature: weight must be positive and finite");
  if (space.degree_u < 2 || space.degree_v < 2)
    throw InvalidInput(
        "point curvature needs a sheet of degree 2 or more in u and v (this one has " +
        std::to_string(space.degree_u) + " x " + std::to_string(space.degree_v) + ")");
}

// The unit normal w_u x w_v / |w_u x w_v| from the rows of evaluate_surface (order >= 1).
Eigen::Vector3d unit_normal(const Eigen::MatrixXd& w) {
  const Eigen::Vector3d n = Eigen::Vector3d(w.row(1)).cross(Eigen::Vector3d(w.row(2)));
  const double len = n.norm();
  if (!(len > 1e-300) || !n.allFinite())
    throw InvalidInput(
        "point curvature: the sheet has no normal at the point (w_u x w_v = 0): move the point");
  return n / len;
}

}  // namespace

ConstraintSamples sample_point_curvature(const SplineSpace& space,
                                         const PointCurvatureConstraint& c,
                                         const Eigen::MatrixX3d& poles) {
  validate(space, c);
  BSplineSurface{space, poles}.validate();
  const Eigen::MatrixXd w = evaluate_surface(space, poles, c.u, c.v, 2);
  const Eigen::Vector3d n = unit_normal(w);
  const BasisSample s = space.basis(c.u, c.v, 2);
  const Eigen::Index m = static_cast<Eigen::Index>(s.index.size());
  ConstraintSamples out;
  std::vector<double> rhs;
  // Rows of basis derivatives: 1 = d/du, 2 = d/dv, 3 = d2/du2, 5 = d2/dv2.
  for (int dir = 0; dir < 2; ++dir) {
    if (!(dir == 0 ? c.along_u : c.along_v)) continue;
    const double kappa = dir == 0 ? c.kappa_u : c.kappa_v;
    const Eigen::Index first = 1 + dir, second = dir == 0 ? 3 : 5;
    const Eigen::Vector3d wd = w.row(first).transpose();
    const Eigen::VectorXd bd = s.values.row(first).transpose();
    const Eigen::VectorXd bdd = s.values.row(second).transpose();
    Eigen::VectorXd coeff(3 * m);
    for (Eigen::Index j = 0; j < m; ++j)
      for (int e = 0; e < 3; ++e) coeff(3 * j + e) = bdd(j) * n(e) - 2.0 * kappa * bd(j) * wd(e);
    const double scale = std::sqrt(c.weight) / std::max(coeff.norm(), 1e-300);
    std::vector<int> cols;
    for (Eigen::Index j = 0; j < m; ++j)
      for (int e = 0; e < 3; ++e) cols.push_back(3 * s.index[static_cast<size_t>(j)] + e);
    out.index.push_back(std::move(cols));
    out.coeff.push_back(scale * coeff);
    out.weight.push_back(c.weight);
    rhs.push_back(-scale * kappa * wd.squaredNorm());
  }
  out.rhs = Eigen::Map<Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  return out;
}

Eigen::Vector2d normal_curvatures(const SplineSpace& space, const Eigen::MatrixX3d& poles, double u,
                                  double v) {
  validate(space, PointCurvatureConstraint{u, v});
  BSplineSurface{space, poles}.validate();
  const Eigen::MatrixXd w = evaluate_surface(space, poles, u, v, 2);
  const Eigen::Vector3d n = unit_normal(w);
  return {n.dot(w.row(3)) / w.row(1).squaredNorm(), n.dot(w.row(5)) / w.row(2).squaredNorm()};
}

double point_curvature_error(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                             const PointCurvatureConstraint& c, double floor) {
  validate(space, c);
  BSplineSurface{space, poles}.validate();
  const Eigen::Vector2d k = normal_curvatures(space, poles, c.u, c.v);
  double worst = 0.0;
  if (c.along_u)
    worst = std::abs(k(0) - c.kappa_u) / std::max({std::abs(c.kappa_u), floor, 1e-300});
  if (c.along_v)
    worst = std::max(worst,
                     std::abs(k(1) - c.kappa_v) / std::max({std::abs(c.kappa_v), floor, 1e-300}));
  return worst;
}

}  // namespace varsurf
