// SPDX-License-Identifier: LGPL-2.1-or-later
// Splitting a curve's parameter range into the pieces on which integrands along its pre-image are
// polynomial, for exact Gauss quadrature of constraints along curves.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// Keeps a pre-image point inside the sheet's domain; tiny overshoot from fitting is clipped, a
// real excursion is an input error (InvalidInput naming t and the domain).
Eigen::Vector2d clamp_to_domain(const SplineSpace& space, const Eigen::Vector2d& uv, double t);

// Sorted parameters from preimage.first() to preimage.last(): breakpoints of the pre-image and of
// `other` (a curve sharing the parameter, or null), and where the pre-image crosses an interior
// knot line of the sheet.
std::vector<double> curve_pieces(const SplineSpace& space, const BSplineCurve& preimage,
                                 const BSplineCurve* other);

// Gauss points per piece: b(c(t)) has degree (p_u + p_v) k on a piece with a degree-k polynomial
// pre-image, and this many points integrate its square exactly and sample it at full rank.
int gauss_points_along(const SplineSpace& space, const BSplineCurve& preimage);

// Gauss points for each piece [pieces[i], pieces[i + 1]]: gauss_points_along's count, or a
// straight pre-image's (degree 1: p_u + p_v + 1 points) where the pre-image leaves the chord of
// the piece by at most 1e-3 of the sheet's shortest knot span (non-rational sheets and
// pre-images): b(c(t)) is there a polynomial of degree p_u + p_v up to terms of that relative size.
std::vector<int> gauss_points_per_piece(const SplineSpace& space, const BSplineCurve& preimage,
                                        const std::vector<double>& pieces);

}  // namespace varsurf
