// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/point_constraints.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "unit_vector.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

void check_point(const SplineSpace& space, double u, double v, double weight, const char* what) {
  const std::string w(what);
  if (!std::isfinite(u) || !std::isfinite(v)) throw InvalidInput(w + ": (u, v) is not finite");
  if (u < space.u_first() || u > space.u_last() || v < space.v_first() || v > space.v_last())
    throw InvalidInput(w + ": (u, v) lies outside the sheet's parameter domain");
  if (!std::isfinite(weight) || weight <= 0.0)
    throw InvalidInput(w + ": weight must be positive and finite");
}

// Appends the coupled row sqrt(w) * sum_k beta_k (a . p_k) = sqrt(w) * rhs.
void append_coupled(ConstraintSamples& out, const BasisSample& s, int derivative,
                    const Eigen::Vector3d& a, double rhs, double weight) {
  const double sw = std::sqrt(weight);
  std::vector<int> cols;
  Eigen::VectorXd coeff(3 * static_cast<Eigen::Index>(s.index.size()));
  for (size_t k = 0; k < s.index.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      cols.push_back(3 * s.index[k] + c);
      coeff(3 * static_cast<Eigen::Index>(k) + c) =
          sw * s.values(derivative, static_cast<Eigen::Index>(k)) * a(c);
    }
  out.index.push_back(std::move(cols));
  out.coeff.push_back(std::move(coeff));
  out.weight.push_back(weight);
  const Eigen::Index r = out.rhs.rows();
  out.rhs.conservativeResize(r + 1, 1);
  out.rhs(r, 0) = sw * rhs;
}

// Two unit vectors completing d to an orthonormal frame.
void frame(const Eigen::Vector3d& d, Eigen::Vector3d& e1, Eigen::Vector3d& e2) {
  const Eigen::Vector3d pick =
      std::abs(d.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  e1 = d.cross(pick).normalized();
  e2 = d.cross(e1);
}

}  // namespace

ConstraintSamples sample_tangent(const SplineSpace& space, const TangentConstraint& c) {
  check_point(space, c.u, c.v, c.weight, "tangent constraint");
  if (c.direction != 0 && c.direction != 1)
    throw InvalidInput("tangent constraint: direction must be 0 (u) or 1 (v)");
  if (!c.target.allFinite()) throw InvalidInput("tangent constraint: target is not finite");
  const BasisSample s = space.basis(c.u, c.v, 1);
  ConstraintSamples out;
  const double sw = std::sqrt(c.weight);
  out.index.push_back(s.index);
  out.coeff.push_back(sw * s.values.row(1 + c.direction).transpose());
  out.weight.push_back(c.weight);
  out.rhs = sw * c.target.transpose();
  return out;
}

ConstraintSamples sample_normal(const SplineSpace& space, const NormalConstraint& c) {
  check_point(space, c.u, c.v, c.weight, "normal constraint");
  const Eigen::Vector3d n = unit_vector(c.normal, "normal constraint: the normal");
  const BasisSample s = space.basis(c.u, c.v, 1);
  ConstraintSamples out;
  out.rhs.resize(0, 1);
  append_coupled(out, s, 1, n, 0.0, 0.5 * c.weight);
  append_coupled(out, s, 2, n, 0.0, 0.5 * c.weight);
  return out;
}

ConstraintSamples sample_plane_point(const SplineSpace& space, const PlanePointConstraint& c) {
  check_point(space, c.u, c.v, c.weight, "point-in-plane constraint");
  const Eigen::Vector3d n = unit_vector(c.normal, "point-in-plane constraint: the plane normal");
  if (!c.origin.allFinite()) throw InvalidInput("point-in-plane constraint: origin is not finite");
  ConstraintSamples out;
  out.rhs.resize(0, 1);
  append_coupled(out, space.basis(c.u, c.v, 0), 0, n, n.dot(c.origin), c.weight);
  return out;
}

ConstraintSamples sample_line_point(const SplineSpace& space, const LinePointConstraint& c) {
  check_point(space, c.u, c.v, c.weight, "point-on-line constraint");
  const Eigen::Vector3d d =
      unit_vector(c.direction, "point-on-line constraint: the line direction");
  if (!c.origin.allFinite()) throw InvalidInput("point-on-line constraint: origin is not finite");
  Eigen::Vector3d e1, e2;
  frame(d, e1, e2);
  const BasisSample s = space.basis(c.u, c.v, 0);
  ConstraintSamples out;
  out.rhs.resize(0, 1);
  append_coupled(out, s, 0, e1, e1.dot(c.origin), 0.5 * c.weight);
  append_coupled(out, s, 0, e2, e2.dot(c.origin), 0.5 * c.weight);
  return out;
}

}  // namespace varsurf
