// SPDX-License-Identifier: LGPL-2.1-or-later
// Regions of a sheet's parameter domain on which energy operators act: a rectangle, or the area
// enclosed by a closed loop (e.g. the pre-image of a closed sketch), with quadrature that
// integrates products of basis functions over them exactly.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "varsurf/core/spline_space.hpp"

namespace varsurf {

struct Region {
  Region() = default;
  Region(double u0_, double u1_, double v0_, double v1_) : u0(u0_), u1(u1_), v0(v0_), v1(v1_) {}
  explicit Region(std::vector<Eigen::Vector2d> loop_) : loop(std::move(loop_)) {}

  double u0 = 0.0, u1 = 1.0, v0 = 0.0, v1 = 1.0;  // the rectangle [u0, u1] x [v0, v1]
  // A simple closed polygon in (u, v), first point not repeated, either orientation. When it has
  // points, the region is the area it encloses and the rectangle is ignored.
  std::vector<Eigen::Vector2d> loop;
  bool is_loop() const { return !loop.empty(); }
};

// The same rectangle or the same loop, point for point.
bool same_region(const Region& a, const Region& b);

// Throws InvalidInput (prefixed by `what`) for non-finite, empty or self-intersecting regions and
// for regions outside the domain. Loop points within 1e-9 of the domain (relative) count as on it.
void check_region(const SplineSpace& space, const Region& region, const char* what);

// Most loop points accepted (the simplicity check is quadratic in their number).
constexpr int max_loop_points = 5000;

struct QuadraturePoint {
  double u, v, weight;
};

// Points and weights on the region that integrate every product of two basis functions of the
// space, or of their first derivatives, exactly (non-rational spaces; rational ones get two extra
// points per direction). Rectangles use tensor Gauss rules per polynomial piece; loops are clipped
// to each piece and integrated over a fan of triangles with collapsed (Duffy) Gauss rules.
std::vector<QuadraturePoint> region_quadrature(const SplineSpace& space, const Region& region);

// Flat indices of the poles whose basis functions do not vanish on the region (on a set of
// positive area): holding them fixed keeps the surface over the region exactly as it is.
std::vector<int> poles_in_region(const SplineSpace& space, const Region& region);

}  // namespace varsurf
