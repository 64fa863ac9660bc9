// SPDX-License-Identifier: LGPL-2.1-or-later
// The closest point on a triangle mesh (a scan, a tessellated shape), through a bounding-volume
// tree (Eigen's KdBVH): what capturing a target's detail onto a subdivision surface asks at each
// vertex of each level.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

namespace varsurf {

class TriangleSurface {
 public:
  // InvalidInput for no triangles, indices out of range, points that are not finite.
  TriangleSurface(Eigen::MatrixX3d points, std::vector<std::array<int, 3>> triangles);
  ~TriangleSurface();
  TriangleSurface(const TriangleSurface&) = delete;
  TriangleSurface& operator=(const TriangleSurface&) = delete;
  Eigen::Vector3d closest(const Eigen::Vector3d& p) const;
  // The bounding box's diagonal: the target's size.
  double size() const;

 private:
  struct Tree;
  Eigen::MatrixX3d points_;
  std::vector<std::array<int, 3>> triangles_;
  std::unique_ptr<Tree> tree_;
};

// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection 5.1.5).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace varsurf
