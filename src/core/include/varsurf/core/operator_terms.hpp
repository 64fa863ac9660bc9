// SPDX-License-Identifier: LGPL-2.1-or-later
// The external energy operators (Veltkamp & Wesselink sec. 5) over any surface kind: each is an
// integral over part of the surface, so it needs only quadrature points there, each with the
// basis functions that are non-zero at it (their values and first derivatives along two
// orthonormal directions of the parameter domain) and its area element. A B-spline sheet's region
// and a set of triangular Bezier patches both give those (an OperatorDomain), and the same terms
// serve both.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>

#include "varsurf/core/external_energy.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// Calls its argument with (sample, dA) at every quadrature point of part of a surface: the
// sample's index lists control points and its values rows are the basis functions' values and
// their derivatives along the domain's two directions. Points sharing one index list should come
// together (the terms are summed per run of them).
using SampleVisitor = std::function<void(const BasisSample&, double)>;
using OperatorDomain = std::function<void(const SampleVisitor&)>;

// weight * integral of |P (w - origin)|^2 dA (see Attractor); weight includes the strength.
void attractor_terms(const OperatorDomain& domain, AttractorKind kind,
                     const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
                     double weight, QuadraticTerms& terms);
// weight * integral of (d . w_x)^2 + (d . w_y)^2 dA.
void director_terms(const OperatorDomain& domain, const Eigen::Vector3d& unit_direction,
                    double weight, QuadraticTerms& terms);
// The Gauss-Newton model of weight * integral of 1 / |w - origin|^2 dA at `points` (control
// points, one row each), distances floored at min_distance (see add_repeller_model).
void repeller_terms(const OperatorDomain& domain, const Eigen::Vector3d& origin, double weight,
                    const Eigen::MatrixX3d& points, double min_distance, QuadraticTerms& terms);
// The Gauss-Newton model of weight * integral of dist(w, target)^2 dA at `points`. InvalidInput if
// the target gives a non-finite point or metric.
void shape_attractor_terms(const OperatorDomain& domain, const ClosestPointFunction& closest,
                           double weight, const Eigen::MatrixX3d& points, QuadraticTerms& terms);
// Strengths made relative (see OperatorScales) over the whole surface's domain, for an energy
// matrix of `size` control points.
OperatorScales operator_scales(const OperatorDomain& whole,
                               const Eigen::SparseMatrix<double>& energy);

}  // namespace varsurf
