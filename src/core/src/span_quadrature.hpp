// SPDX-License-Identifier: LGPL-2.1-or-later
// Tensor Gauss points over a sheet's whole domain, piece by polynomial piece.
#pragma once

#include <vector>

#include "varsurf/core/region.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// `n` points per direction on every polynomial piece of the domain, the pieces cut into cells no
// longer than `step` (a fraction of the domain; 1: no cut) for integrands that are not polynomial.
std::vector<QuadraturePoint> span_points(const SplineSpace& space, int n, double step = 1.0);

}  // namespace varsurf
