// SPDX-License-Identifier: LGPL-2.1-or-later
// A regular control grid and the uniform bicubic B-spline of its heights: the independent answer
// that Catmull-Clark subdivision and its limit patches must reproduce on regular meshes.
#pragma once

#include <cmath>

#include "varsurf/core/subdivision.hpp"

namespace varsurf::test {

constexpr int kGrid = 8;  // control points per side

inline double height(int i, int j) {
  return 3.0 * std::sin(0.9 * i + 0.3 * j) + 0.5 * i * j - 0.1 * j * j;
}

// A kGrid x kGrid control net on the unit grid: x = i, y = j, z = height(i, j).
inline SubdivisionMesh grid() {
  SubdivisionMesh m;
  m.points.resize(kGrid * kGrid, 3);
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) m.points.row(i * kGrid + j) << i, j, height(i, j);
  for (int i = 0; i + 1 < kGrid; ++i)
    for (int j = 0; j + 1 < kGrid; ++j)
      m.faces.push_back(
          {i * kGrid + j, (i + 1) * kGrid + j, (i + 1) * kGrid + j + 1, i * kGrid + j + 1});
  return m;
}

// The centred uniform cubic B-spline: the weight of the control point at distance x.
inline double bspline(double x) {
  x = std::abs(x);
  if (x >= 2.0) return 0.0;
  if (x >= 1.0) return std::pow(2.0 - x, 3) / 6.0;
  return (4.0 - 6.0 * x * x + 3.0 * x * x * x) / 6.0;
}

// The bicubic B-spline surface of the grid's heights at (s, t) (x = s, y = t on it).
inline double bicubic(double s, double t) {
  double z = 0.0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) z += bspline(s - i) * bspline(t - j) * height(i, j);
  return z;
}

}  // namespace varsurf::test
