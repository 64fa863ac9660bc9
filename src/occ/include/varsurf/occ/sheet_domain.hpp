// SPDX-License-Identifier: LGPL-2.1-or-later
// The (u, v) domain of a sheet as projections see it: its bounds, the directions in which the
// sheet closes on itself (a seam, as on a cylinder), and the placing of parameters that lie on
// the boundary exactly on it. A pre-image a rounding error inside the boundary gives the solver
// constraint rows with ~1e-15 weights on interior poles, which it then fits exactly; exactly on
// the boundary those weights are exactly zero.
#pragma once

#include <Eigen/Core>
#include <array>

#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

class SheetDomain {
 public:
  explicit SheetDomain(const BSplineSurface& sheet);

  const Eigen::Vector2d& lo() const { return lo_; }
  const Eigen::Vector2d& hi() const { return hi_; }
  Eigen::Vector2d width() const { return hi_ - lo_; }
  double model_size() const { return scale_; }
  // Whether the sheet's boundary at the lower and upper bound of direction c is one curve.
  bool closed(int c) const { return closed_[static_cast<size_t>(c)]; }
  // Whether the side of the domain where coordinate c is at its lower (side -1) or upper (+1)
  // bound collapses to a point (a sphere's pole, a cone's apex).
  bool degenerate(int c, int side) const {
    return degenerate_[static_cast<size_t>(2 * c + (side > 0 ? 1 : 0))];
  }

  // On a side that collapses to a point: the sheet point does not decide the other coordinate.
  bool at_degenerate_side(const Eigen::Vector2d& uv) const {
    for (int c = 0; c < 2; ++c) {
      const int s = side(uv, c);
      if (s != 0 && degenerate(c, s)) return true;
    }
    return false;
  }
  // -1 at the lower bound of direction c, +1 at the upper, 0 inside (within the snap margin).
  int side(const Eigen::Vector2d& uv, int c) const;
  // On the seam of a closed direction c.
  bool on_seam(const Eigen::Vector2d& uv, int c) const { return closed(c) && side(uv, c) != 0; }
  // The same sheet point on the other side of direction c's seam (uv must be on it).
  Eigen::Vector2d across_seam(const Eigen::Vector2d& uv, int c) const;

  // `uv` clamped to the domain, each coordinate within the snap margin of a bound moved onto
  // it where that moves the sheet's point by no more than 1e-9 of the model's size.
  Eigen::Vector2d snapped(const Eigen::Vector2d& uv) const;

  // How close (relative to the direction's width) a parameter must be to a bound to be on it:
  // far above the projections' rounding (~1e-13), far below any modelling tolerance.
  static constexpr double snap_margin = 1e-9;

 private:
  const BSplineSurface& sheet_;
  Eigen::Vector2d lo_, hi_;
  double scale_;
  std::array<bool, 2> closed_{false, false};
  std::array<bool, 4> degenerate_{false, false, false, false};
};

}  // namespace varsurf::occ
