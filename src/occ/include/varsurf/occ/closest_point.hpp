// SPDX-License-Identifier: LGPL-2.1-or-later
// Closest points on another shape's faces or edges: the targets of surface and curve attractors
// and the measure of their residuals.
#pragma once

#include <TopoDS_Shape.hxx>

#include <Eigen/Core>
#include <memory>

#include "varsurf/core/external_energy.hpp"

namespace varsurf::occ {

class ClosestPointTarget {
 public:
  // A shape with faces (the target is their surfaces, within each face's UV bounds) or, without
  // faces, with edges. InvalidInput for a null shape or one with neither.
  explicit ClosestPointTarget(const TopoDS_Shape& shape);
  ~ClosestPointTarget();
  ClosestPointTarget(const ClosestPointTarget&) = delete;
  ClosestPointTarget& operator=(const ClosestPointTarget&) = delete;

  // The closest point with its Gauss-Newton metric (n n^T inside a face, I - t t^T inside an
  // edge, I on a boundary). InvalidInput for a non-finite point; GeometryError if OCCT fails.
  ClosestPoint operator()(const Eigen::Vector3d& point) const;

  bool on_faces() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace varsurf::occ
