// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/multiresolution.hpp"

#include <Eigen/Geometry>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

Eigen::MatrixX3d local_frames(const SubdivisionLevels& s) {
  return frames_of(s.limit_tangent_u, s.limit_tangent_v);
}

Eigen::MatrixX3d frames_of(const Eigen::MatrixX3d& tangent_u, const Eigen::MatrixX3d& tangent_v) {
  const Eigen::Index n = tangent_u.rows();
  Eigen::MatrixX3d frames(3 * n, 3);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector3d tu = tangent_u.row(k), tv = tangent_v.row(k);
    const Eigen::Vector3d normal = tu.cross(tv);
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    // A relative test: the tangents' lengths scale with the mesh.
    if (normal.norm() > 1e-12 * tu.norm() * tv.norm() && tu.norm() > 0.0) {
      f.row(0) = tu.normalized();
      f.row(2) = normal.normalized();
      f.row(1) = f.row(2).cross(f.row(0));
    }
    frames.middleRows(3 * k, 3) = f;
  }
  return frames;
}

namespace {

// One level up: the subdivided mesh with the details added in its frames.
SubdivisionMesh refined(const SubdivisionMesh& coarse, const Eigen::MatrixX3d& detail,
                        size_t level) {
  const SubdivisionLevels s = subdivide(coarse, 1);
  SubdivisionMesh fine = s.levels[1];
  if (detail.rows() != fine.points.rows())
    throw InvalidInput("level " + std::to_string(level + 1) + " has " +
                       std::to_string(detail.rows()) + " detail vectors for " +
                       std::to_string(fine.points.rows()) + " vertices");
  if (!detail.allFinite())
    throw InvalidInput("level " + std::to_string(level + 1) + " has details that are not finite");
  const Eigen::MatrixX3d frames = local_frames(s);
  for (Eigen::Index k = 0; k < fine.points.rows(); ++k)
    fine.points.row(k) += detail.row(k) * frames.middleRows(3 * k, 3);
  return fine;
}

}  // namespace

std::vector<SubdivisionMesh> reconstruct(const Multiresolution& surface) {
  if (surface.details.size() > 8)
    throw InvalidInput("a multiresolution surface has at most 8 levels");
  std::vector<SubdivisionMesh> out{surface.base};
  subdivide(surface.base, 0);  // checks the base mesh
  for (size_t level = 0; level < surface.details.size(); ++level)
    out.push_back(refined(out.back(), surface.details[level], level));
  return out;
}

Multiresolution capture(const SubdivisionMesh& base, int levels,
                        const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& closest) {
  if (levels < 1 || levels > 8) throw InvalidInput("capture levels must be in 1..8");
  Multiresolution out{base, {}};
  SubdivisionMesh current = base;
  for (int level = 0; level < levels; ++level) {
    const SubdivisionLevels s = subdivide(current, 1);
    const Eigen::MatrixX3d frames = local_frames(s);
    const SubdivisionMesh& fine = s.levels[1];
    Eigen::MatrixX3d detail(fine.points.rows(), 3);
    for (Eigen::Index k = 0; k < fine.points.rows(); ++k) {
      const Eigen::Vector3d p = fine.points.row(k).transpose();
      const Eigen::Vector3d target = closest(p);
      if (!target.allFinite())
        throw InvalidInput("the target's closest point to a level-" + std::to_string(level + 1) +
                           " vertex is not finite");
      // The frame is orthonormal: its transpose takes the move into it.
      detail.row(k) = (frames.middleRows(3 * k, 3) * (target - p)).transpose();
    }
    out.details.push_back(detail);
    current = refined(current, detail, static_cast<size_t>(level));
  }
  return out;
}

}  // namespace varsurf
