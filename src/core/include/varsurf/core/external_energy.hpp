// SPDX-License-Identifier: LGPL-2.1-or-later
// External energy operators (Veltkamp & Wesselink sec. 5): quadratic pulls on a region of the
// sheet, added to the thin-plate energy with a strength each. A point attractor is separable in
// x, y, z; plane and line attractors and the director couple the coordinates.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <optional>
#include <vector>

#include "varsurf/core/region.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

enum class AttractorKind { point, plane, line };

// strength (relative, see OperatorScales) * integral over the region of |P (w - origin)|^2 dA,
// with P = I (point), the
// projection onto `direction` taken as the plane's normal (plane), or the projection across the
// line along `direction` (line).
struct Attractor {
  AttractorKind kind = AttractorKind::point;
  Region region;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  double strength = 1.0;
};

// strength (relative) * integral over the region of (d . w_u)^2 + (d . w_v)^2 dA: tangents pushed
// perpendicular to d, i.e. the region's normals toward d.
struct Director {
  Region region;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  double strength = 1.0;
};

// strength (relative) * integral over the region of 1 / |w - origin|^2 dA: pushes the region away
// from a point. Not quadratic: the solve iterates Gauss-Newton steps (see SolveOptions).
struct Repeller {
  Region region;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double strength = 1.0;
};

// The point of another shape (a face, a curve) closest to a point in space, and the metric of the
// squared distance's Gauss-Newton model there: n n^T inside a surface, I - t t^T along a curve,
// I at an end, edge or corner.
struct ClosestPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Matrix3d metric = Eigen::Matrix3d::Identity();
};
using ClosestPointFunction = std::function<ClosestPoint(const Eigen::Vector3d&)>;

// strength (relative) * integral over the region of dist(w, target)^2 dA: the region pulled onto
// another surface or curve (Veltkamp & Wesselink's surface and curve attractors). Not quadratic:
// the solve iterates, pulling each quadrature point toward its current closest point.
struct ShapeAttractor {
  Region region;
  ClosestPointFunction closest;
  double strength = 1.0;
};

// Quadratic energy pieces beyond the thin plate, as E = x^T Q x - 2 f^T x (plus a constant).
struct QuadraticTerms {
  explicit QuadraticTerms(int poles);
  std::vector<Eigen::Triplet<double>> separable;  // poles x poles, the same for x, y and z
  Eigen::MatrixX3d separable_f;                   // poles x 3
  std::vector<Eigen::Triplet<double>> coupled;    // 3 poles x 3 poles, column 3 k + c
  Eigen::VectorXd coupled_f;                      // 3 poles
  bool uses_coupled() const { return !coupled.empty(); }
};

// Factors that make strengths relative to the sheet: mean diagonal of the sheet's energy matrix
// over the mean diagonal of the mass matrix (integral of b_k^2, for attractors) or of the
// gradient matrix (integral of |grad b_k|^2, for directors). Strength 1 then pulls about as hard
// as the sheet resists, whatever its size, units or spans.
struct OperatorScales {
  double value = 1.0;
  double gradient = 1.0;
};
OperatorScales operator_scales(const SplineSpace& space, const Eigen::SparseMatrix<double>& energy);

// Add strength * scale * (the operator's integral). Throw InvalidInput for empty or out-of-domain
// regions, zero directions, non-finite or negative strengths.
void add_attractor(const SplineSpace& space, const Attractor& a, double scale,
                   QuadraticTerms& terms);
void add_director(const SplineSpace& space, const Director& d, double scale, QuadraticTerms& terms);

// The Gauss-Newton model of a repeller at the current poles (size() x 3): its gradient and the
// radial part of its Hessian (d^2/dr^2 r^-2 = 6 r^-4 along w - origin; the tangential part is
// negative and left out so the model stays convex). Distances are floored at `min_distance`.
void add_repeller_model(const SplineSpace& space, const Repeller& r, double scale,
                        const Eigen::MatrixX3d& poles, double min_distance, QuadraticTerms& terms);

// The Gauss-Newton model of a shape attractor at the current poles: each quadrature point w0 adds
// (w - c)^T M (w - c) for its closest point c and metric M. InvalidInput if the target gives a
// non-finite point or metric.
void add_shape_attractor_model(const SplineSpace& space, const ShapeAttractor& a, double scale,
                               const Eigen::MatrixX3d& poles, QuadraticTerms& terms);

// Inflation by a pressure: the work pressure * volume, linearized at the current poles. Adds the
// force pressure * integral of b_k (w_u x w_v) du dv to every pole (positive: along the normal),
// over the region (a trimmed sheet's kept part) or, without one, the whole domain.
void add_pressure_force(const SplineSpace& space, double pressure, const Eigen::MatrixX3d& poles,
                        QuadraticTerms& terms, const std::optional<Region>& region = std::nullopt);

}  // namespace varsurf
