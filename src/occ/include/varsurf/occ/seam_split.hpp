// SPDX-License-Identifier: LGPL-2.1-or-later
// A curve that runs across the seam of a closed sheet (around a cylinder) has no single pre-image:
// its foot jumps from one end of the parameter range to the other. Cut where it crosses, each
// piece has one, ending on the seam.
#pragma once

#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

// The target curve's pieces between the parameters where its closest points on `sheet` cross a
// seam of a closed direction, found among `samples` points (0: from the curve's poles) and
// bisected to 1e-12 of the parameter range; the whole curve when it crosses none. Each piece is
// the curve itself between two parameters (OCCT's exact segment). InvalidInput for an invalid
// sheet or curve.
std::vector<BSplineCurve> split_at_seams(const BSplineSurface& sheet, const BSplineCurve& curve,
                                         int samples = 0);

}  // namespace varsurf::occ
