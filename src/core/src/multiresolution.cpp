// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/multiresolution.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
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
  subdivide(base, 0);  // checks the base mesh
  const double size = (base.points.colwise().maxCoeff() - base.points.colwise().minCoeff()).norm();
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
      // A cage far from the target folds onto it: refuse rather than fit nonsense.
      if (level == 0 && (target - p).norm() > size)
        throw InvalidInput("the target lies too far from the cage: level-1 vertex " +
                           std::to_string(k) + " moves " + std::to_string((target - p).norm()) +
                           ", more than the cage's size " + std::to_string(size) +
                           ": move the cage around the target");
      // The frame is orthonormal: it takes the move into its coordinates.
      detail.row(k) = (frames.middleRows(3 * k, 3) * (target - p)).transpose();
    }
    out.details.push_back(detail);
    current = refined(current, detail, static_cast<size_t>(level));
  }
  return out;
}

CaptureFit capture_fit(const Multiresolution& surface,
                       const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& closest) {
  const std::vector<SubdivisionMesh> levels = reconstruct(surface);
  const SubdivisionLevels limit = subdivide(levels.back(), 0);
  CaptureFit fit;
  double sum = 0.0;
  const Eigen::Index n = limit.limit_points.rows();
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector3d p = limit.limit_points.row(k).transpose();
    const double d = (closest(p) - p).norm();
    fit.max_distance = std::max(fit.max_distance, d);
    sum += d * d;
  }
  fit.rms_distance = std::sqrt(sum / static_cast<double>(std::max<Eigen::Index>(n, 1)));
  return fit;
}

}  // namespace varsurf
