// SPDX-License-Identifier: LGPL-2.1-or-later
// Projection along a direction (a sketch's normal): where the line through a target point along
// the direction meets a base sheet. A curve drawn well above a curved sheet has an orthogonal
// projection that jumps between the sheet's valleys; seen along the sketch's normal it has a
// continuous shadow, which is what a designer drawing in plan means.
#pragma once

#include <Eigen/Core>
#include <Geom_BSplineSurface.hxx>

#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

class LineFoot {
 public:
  // InvalidInput for an invalid sheet or a zero or non-finite direction.
  LineFoot(const BSplineSurface& base, const Eigen::Vector3d& direction);

  // (u, v) where the line through p along the direction meets the sheet. From `near` (the foot of
  // a neighbouring point) Newton continues along the curve; without it, or where Newton leaves
  // the sheet, OCCT intersects the line with the whole sheet and the meeting closest to `near`
  // (else to p along the line) is taken. InvalidInput where the line misses the sheet (the curve
  // passes beyond the face in this view) or grazes it; GeometryError if OCCT fails.
  Eigen::Vector2d operator()(const Eigen::Vector3d& p, const Eigen::Vector2d* near) const;

  const Eigen::Vector3d& direction() const { return direction_; }

 private:
  bool newton(const Eigen::Vector3d& p, Eigen::Vector2d& uv) const;
  void check_incidence(const Eigen::Vector3d& p, const Eigen::Vector2d& uv) const;

  const BSplineSurface& base_;
  Eigen::Vector3d direction_;
  Eigen::Matrix<double, 2, 3> across_;  // two unit rows across the line
  Eigen::Vector2d lo_, hi_;
  double scale_;
  Handle(Geom_BSplineSurface) geom_;
};

}  // namespace varsurf::occ
