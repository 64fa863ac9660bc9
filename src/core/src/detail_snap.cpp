// SPDX-License-Identifier: LGPL-2.1-or-later
// The re-parameterization of Boier-Martin, Ronfard & Bernardini's Appendix on a multiresolution
// surface: vertices moved along the surface onto a curve lying on it, the finer levels they
// displace re-captured onto the surface before, so that point constraints at those vertices
// then hold points of the curve itself.
#include <Eigen/Geometry>
#include <limits>
#include <set>
#include <string>

#include "varsurf/core/detail_edit.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

Multiresolution DetailEditor::snap(
    const Multiresolution& surface, int level, const std::vector<int>& vertices,
    const Eigen::MatrixX3d& targets,
    const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& closest) const {
  check(surface);
  if (level < 0 || level > levels())
    throw InvalidInput("level " + std::to_string(level) + " does not exist (the surface has 0.." +
                       std::to_string(levels()) + "): give one of those");
  if (targets.rows() != static_cast<Eigen::Index>(vertices.size()))
    throw InvalidInput("a snap needs one target per vertex, not " + std::to_string(targets.rows()) +
                       " for " + std::to_string(vertices.size()));
  if (!targets.allFinite()) throw InvalidInput("a snap's targets are not finite");
  // Vertices keep their numbers on finer levels: a vertex of `level` is the same one there.
  std::vector<int> target_of(static_cast<size_t>(this->vertices(levels())), -1);
  for (size_t i = 0; i < vertices.size(); ++i) {
    const int v = vertices[i];
    if (v < 0 || v >= this->vertices(level))
      throw InvalidInput("level " + std::to_string(level) + " has vertices 0.." +
                         std::to_string(this->vertices(level) - 1) + ", not " + std::to_string(v) +
                         ": pick one of those");
    if (target_of[static_cast<size_t>(v)] >= 0)
      throw InvalidInput("vertex " + std::to_string(v) + " is snapped twice: give it once");
    target_of[static_cast<size_t>(v)] = static_cast<int>(i);
  }
  const std::vector<Eigen::MatrixX3d> before = points(surface);
  const Eigen::MatrixX3d& finest = before.back();
  const double size = (finest.colwise().maxCoeff() - finest.colwise().minCoeff()).norm();
  // A vertex moved less than this keeps its detail: the re-parameterization stays local.
  const double still = 1e-12 * size;
  // Where a vertex goes: onto the surface at `on`, keeping the old vertex's offset from it.
  const auto placed = [&](const Eigen::Vector3d& on, const Eigen::Vector3d& old) {
    const Eigen::Vector3d p = closest(on);
    if (!p.allFinite()) throw InvalidInput("the surface's closest point to a vertex is not finite");
    return Eigen::Vector3d(p + (old - closest(old)));
  };

  Multiresolution out = surface;
  Eigen::MatrixX3d current = before[static_cast<size_t>(level)];
  Eigen::MatrixX3d smooth, frames;  // the level subdivided, and its frames
  if (level > 0) {
    const SubdivisionStep& step = steps_[static_cast<size_t>(level - 1)];
    smooth = step.refine * before[static_cast<size_t>(level - 1)];
    frames = frames_of(step.limit_u * smooth, step.limit_v * smooth);
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    const int v = vertices[i];
    const Eigen::Vector3d to =
        placed(targets.row(static_cast<Eigen::Index>(i)).transpose(), current.row(v).transpose());
    current.row(v) = to.transpose();
    if (level > 0)  // the frame is orthonormal: it takes the move into its coordinates
      out.details[static_cast<size_t>(level - 1)].row(v) =
          (frames.middleRows(3 * v, 3) * (to - smooth.row(v).transpose())).transpose();
  }
  if (level == 0) out.base.points = current;

  for (size_t k = static_cast<size_t>(level); k < steps_.size(); ++k) {
    const SubdivisionStep& step = steps_[k];
    Eigen::MatrixX3d next = step.refine * current;
    frames = frames_of(step.limit_u * next, step.limit_v * next);
    const Eigen::MatrixX3d& old = before[k + 1];
    smooth = next;
    for (Eigen::Index v = 0; v < next.rows(); ++v) {
      const Eigen::Vector3d subdivided = next.row(v).transpose();
      const Eigen::Vector3d kept =
          subdivided + (surface.details[k].row(v) * frames.middleRows(3 * v, 3)).transpose();
      const int t = target_of[static_cast<size_t>(v)];
      Eigen::Vector3d to;
      if (t >= 0)
        to = placed(targets.row(t).transpose(), old.row(v).transpose());
      else if ((kept - old.row(v).transpose()).norm() <= still)
        to = kept;
      else  // displaced: re-captured where the subdivided point falls on the surface
        to = placed(subdivided, old.row(v).transpose());
      out.details[k].row(v) = (frames.middleRows(3 * v, 3) * (to - subdivided)).transpose();
      next.row(v) = to.transpose();
    }
    current = std::move(next);
  }
  // The snapped vertices' limit points onto the surface at their targets (their control points
  // put them there only as far as their unmoved neighbours let the limit follow): Jacobi sweeps
  // on the finest level's limit stencils, diagonally dominant along a chain (a regular vertex
  // weighs 4/9 of its own limit, its chain neighbours at most 2/9 together). A vertex moves at
  // most half its shortest edge so: further, its limit would come only by folding the faces
  // around it (measured on a scanned relief, where a coarse move left limits 0.9 finest edges
  // short), and the limit stays where it got to.
  {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> limit(steps_.back().limit);
    const size_t n = vertices.size();
    Eigen::MatrixX3d want(static_cast<Eigen::Index>(n), 3), start(static_cast<Eigen::Index>(n), 3);
    std::vector<double> own(n, 0.0), reach(n, std::numeric_limits<double>::infinity());
    std::vector<bool> moving(n, true);
    for (const std::vector<int>& face : meshes_.back().faces)
      for (size_t k = 0; k < face.size(); ++k) {
        const int a = face[k], b = face[(k + 1) % face.size()];
        const double e = (current.row(a) - current.row(b)).norm();
        for (const int v : {a, b})
          if (target_of[static_cast<size_t>(v)] >= 0) {
            double& r = reach[static_cast<size_t>(target_of[static_cast<size_t>(v)])];
            r = std::min(r, 0.5 * e);
          }
      }
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Index r = static_cast<Eigen::Index>(i);
      want.row(r) = closest(targets.row(r).transpose()).transpose();
      own[i] = limit.coeff(vertices[i], vertices[i]);
      start.row(r) = current.row(vertices[i]);
    }
    for (int sweep = 0; sweep < 200; ++sweep) {
      Eigen::MatrixX3d miss(want.rows(), 3);
      double worst = 0.0;
      for (size_t i = 0; i < n; ++i) {
        const Eigen::Index r = static_cast<Eigen::Index>(i);
        miss.row(r) = want.row(r) - limit.row(vertices[i]) * current;
        if (moving[i]) worst = std::max(worst, miss.row(r).norm());
      }
      if (worst <= still) break;
      for (size_t i = 0; i < n; ++i) {
        if (!moving[i]) continue;
        const Eigen::Index r = static_cast<Eigen::Index>(i);
        const Eigen::RowVector3d next = current.row(vertices[i]) + miss.row(r) / own[i];
        if ((next - start.row(r)).norm() > reach[i])
          moving[i] = false;
        else
          current.row(vertices[i]) = next;
      }
    }
    // The finest level's frames are its subdivided coarser level's, which this leaves alone.
    for (const int v : vertices)
      out.details.back().row(v) =
          (frames.middleRows(3 * v, 3) * (current.row(v) - smooth.row(v)).transpose()).transpose();
  }
  return out;
}

}  // namespace varsurf
