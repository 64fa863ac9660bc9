// External energy operators (Veltkamp & Wesselink sec. 5): quadratic pulls on a region of the
// sheet, added to the thin-plate energy with a strength each. A point attractor is separable in
// x, y, z; plane and line attractors and the director couple the coordinates.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// A rectangle [u0, u1] x [v0, v1] of the parameter domain.
struct Region {
  double u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;
};

// Flat indices of the poles whose basis functions do not vanish on the region: holding them fixed
// keeps the surface over the region exactly as it is. InvalidInput for an empty or out-of-domain
// region.
std::vector<int> poles_in_region(const SplineSpace& space, const Region& region);

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

// Inflation by a pressure: the work pressure * volume, linearized at the current poles. Adds the
// force pressure * integral of b_k (w_u x w_v) du dv to every pole (positive: along the normal).
void add_pressure_force(const SplineSpace& space, double pressure, const Eigen::MatrixX3d& poles,
                        QuadraticTerms& terms);

}  // namespace varsurf
