// SPDX-License-Identifier: LGPL-2.1-or-later
// Finite-dimensional constraints beyond point position (Welch & Witkin 4.2.1): parametric
// derivatives, normals, and points held to a plane or a line. Tangents are separable in x, y, z;
// the others couple the coordinates and switch the solve to one 3n system.
#pragma once

#include <Eigen/Core>

#include "varsurf/core/constraints.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// The parametric derivative w_u (direction 0) or w_v (direction 1) at (u, v) is `target`.
struct TangentConstraint {
  double u = 0.0;
  double v = 0.0;
  int direction = 0;
  Eigen::Vector3d target = Eigen::Vector3d::UnitX();
  double weight = 1.0;
};

// The surface normal at (u, v) is parallel to `normal`: w_u . N = 0 and w_v . N = 0.
struct NormalConstraint {
  double u = 0.0;
  double v = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double weight = 1.0;
};

// The point w(u, v) lies in the plane through `origin` with normal `normal`.
struct PlanePointConstraint {
  double u = 0.0;
  double v = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double weight = 1.0;
};

// The point w(u, v) lies on the line through `origin` along `direction`.
struct LinePointConstraint {
  double u = 0.0;
  double v = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  double weight = 1.0;
};

ConstraintSamples sample_tangent(const SplineSpace& space,
                                 const TangentConstraint& c);                          // separable
ConstraintSamples sample_normal(const SplineSpace& space, const NormalConstraint& c);  // coupled
ConstraintSamples sample_plane_point(const SplineSpace& space, const PlanePointConstraint& c);
ConstraintSamples sample_line_point(const SplineSpace& space, const LinePointConstraint& c);

}  // namespace varsurf
