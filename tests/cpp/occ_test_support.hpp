// SPDX-License-Identifier: LGPL-2.1-or-later
// Sheets the OpenCASCADE bridge's tests share: a flat square and a curved bicubic sheet, both
// fitted exactly.
#pragma once

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::test {

// A sheet over [0, 1]^2 whose image is the square [0, size]^2 in the plane z = height.
inline BSplineSurface plane_sheet(double size, double height = 0.0) {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 2, 2);
  s.poles = test::fit_poles(
      s.space, [&](double u, double v) { return Eigen::Vector3d(size * u, size * v, height); });
  return s;
}

// A curved bicubic sheet over [0, 1]^2 with 3 x 2 spans.
inline BSplineSurface curved_sheet() {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 3, 2);
  s.poles = test::fit_poles(s.space, [](double u, double v) {
    return Eigen::Vector3d(4.0 * u + 0.3 * v * v, 3.0 * v, std::sin(2.0 * u) * std::cos(1.5 * v));
  });
  return s;
}

}  // namespace varsurf::test
