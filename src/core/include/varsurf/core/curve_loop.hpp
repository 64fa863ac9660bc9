// SPDX-License-Identifier: LGPL-2.1-or-later
// Curves in a sheet's (u, v) domain chained into one closed loop: what trims a sheet.
#pragma once

#include <vector>

#include "varsurf/core/bspline_curve.hpp"

namespace varsurf {

struct LoopStep {
  int curve = 0;          // index into the given curves
  bool reversed = false;  // walked from its last parameter to its first
  // +1 if the region the loop encloses lies left of the curve's own direction (first to last
  // parameter), -1 if right: which side of the curve the trimmed sheet is on.
  int inside = 1;
};

struct CurveLoop {
  std::vector<LoopStep> steps;  // end to start, starting with curve 0 forward
  double signed_area = 0.0;     // positive: counter-clockwise (shoelace on samples)
};

// Orders 2D curves end to start into one closed loop, reversing those walked backwards; ends
// closer than `gap` count as joined. InvalidInput ("the boundary loop does not close ...") if
// they do not form one closed loop, or for curves that are not 2D.
CurveLoop chain_loop(const std::vector<BSplineCurve>& curves, double gap);

}  // namespace varsurf
