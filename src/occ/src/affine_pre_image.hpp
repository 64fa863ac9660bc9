// SPDX-License-Identifier: LGPL-2.1-or-later
// Exact pre-images on flat sheets whose parametrization is affine, S(u, v) = A + u B + v C (a
// sheet from curves alone starts from one, and so does every Part plane, box face or sketch
// face converted to a B-spline): projecting along a fixed direction (the normal, or a chosen
// one) is then an affine map of space, and the pre-image of a (rational) B-spline target is the
// B-spline with the same knots and weights whose poles are the mapped poles. No sampling, no
// Newton steps, no fit: a sheet's projection stage in microseconds instead of milliseconds a
// curve, and with no fit error.
#pragma once

#include <optional>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"
#include "varsurf/occ/curve_projection.hpp"
#include "varsurf/occ/sheet_domain.hpp"

namespace varsurf::occ {

// The exact pre-image of `target`, or nothing where this does not apply and the general
// projection decides: a rational or curved base, a direction along the sheet, a target that
// leaves the domain (that one reports how far) or that runs along the projection direction.
// `ts` are the parameters at which the general projection would sample the target: the
// distances it reports (max_distance, boundary_distance) are taken there, as it takes them. The
// pre-image has at least `degree` (raised exactly where the target's is lower).
std::optional<PreImage> affine_pre_image(const BSplineSurface& base, const SheetDomain& domain,
                                         const BSplineCurve& target,
                                         const Eigen::Vector3d& direction,
                                         const std::vector<double>& ts, int degree);

}  // namespace varsurf::occ
