// SPDX-License-Identifier: LGPL-2.1-or-later
// Multiresolution Catmull-Clark surfaces (Boier-Martin, Ronfard & Bernardini sec. 3.1): a base
// mesh and, per level, detail vectors added to the subdivided coarser mesh, each in the local
// frame of the vertex it moves (the limit surface's two tangent directions and normal there), so
// that details ride along when the coarse shape moves, turns or bends.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "varsurf/core/subdivision.hpp"

namespace varsurf {

struct Multiresolution {
  SubdivisionMesh base;
  // details[k]: one row per vertex of level k + 1, (along t1, along t2, along n) of the frame at
  // that vertex of the subdivided level-k mesh.
  std::vector<Eigen::MatrixX3d> details;
};

// The local frames of a mesh's vertices from its limit tangents: t1 along the first tangent, n
// their cross product, t2 = n x t1; rows 3k .. 3k + 2 are vertex k's t1, t2, n. Where the
// tangents are degenerate (a corner, a dart), the frame falls back to the coordinate axes: the
// same mesh always gives the same frames, which is all reconstruction needs.
Eigen::MatrixX3d local_frames(const SubdivisionLevels& subdivided);
// The same frames from the two tangents at each vertex (one row each).
Eigen::MatrixX3d frames_of(const Eigen::MatrixX3d& tangent_u, const Eigen::MatrixX3d& tangent_v);

// Every level's mesh: level 0 the base, level k + 1 the subdivided level k plus its details.
// InvalidInput for details whose rows do not match their level's vertices, or a bad base mesh.
std::vector<SubdivisionMesh> reconstruct(const Multiresolution& surface);

// Detail captured from a target, level by level (sec. 3.1, "fit the hierarchy"): each level's
// subdivided vertices moved to `closest(point)` on the target, the moves stored as details.
// `levels` 1..8. InvalidInput for a bad base mesh, a closest point that is not finite, and a
// target so far from the cage that a first-level vertex would move more than the cage's size.
Multiresolution capture(const SubdivisionMesh& base, int levels,
                        const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& closest);

// How far the limit surface lies from the target: the distances at the finest level's limit
// points (the fit capture reports).
struct CaptureFit {
  double max_distance = 0.0, rms_distance = 0.0;
};
CaptureFit capture_fit(const Multiresolution& surface,
                       const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& closest);

}  // namespace varsurf
