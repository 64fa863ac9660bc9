// SPDX-License-Identifier: LGPL-2.1-or-later
// Detail-preserving editing of a multiresolution Catmull-Clark surface (Boier-Martin, Ronfard &
// Bernardini sec. 4): pins on vertices of any level, each propagated through the Catmull-Clark
// masks (their Table 1, composed over levels) to a coarser level, its region of influence. The
// deformation is solved there, on the pins' masks grown by a few rings, and the finer levels
// follow by subdivision with their details riding in the turned local frames: coarse = global,
// fine = local, and the fine detail is kept either way.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "varsurf/core/detail_energy.hpp"
#include "varsurf/core/multiresolution.hpp"

namespace varsurf {

struct DetailPin {
  int level = 0;   // the level of the pinned vertex (0: the base)
  int vertex = 0;  // its index at that level
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  int influence = 0;  // the level it is propagated to, 0 .. level: its region of influence
  // Whether the target holds the vertex's point on the finished limit surface (where the finer
  // levels' details ride along) rather than its control point at `level`: a curve's vertices
  // then carry the surface itself through the curve's points.
  bool on_limit = false;
};

// A normal prescribed at a vertex (sec. 4.2): the vertex's tangents Q_u, Q_v, from the divided
// differences of the shape before the edit, made perpendicular to `normal` (its sign is free:
// the constraint is linear). Couples the three coordinates, so a level with normals is solved as
// one system (sec. 5).
struct DetailNormal {
  int level = 0;
  int vertex = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  int influence = 0;
};

enum class DetailSolve {
  approximate,  // the pins' masks moved by least norm, the rest by subdivision (during drags)
  direct,       // the energy's minimum on the region, by a sparse direct solve of its KKT system
  sor,          // the paper's: masks fixed by least norm, the region relaxed by SOR sweeps
};

struct DetailEditOptions {
  DetailEnergyWeights weights;
  int rings = 1;  // the region: the pins' masks grown by this many rings of faces
  DetailSolve solve = DetailSolve::direct;
  double omega = 1.7;  // SOR's relaxation, in (0, 2)
  int max_sweeps = 20000;
  int max_rounds = 12;      // re-solves while the details' frames turn with the edit
  double tolerance = 1e-9;  // on the pins, relative to the model's size
};

struct DetailEditReport {
  double max_residual = 0.0;  // the worst pin's distance from its target after the edit
  // The worst angle (radians) between a constrained vertex's normal after the edit, from fresh
  // divided differences, and its prescribed line.
  double max_normal_angle = 0.0;
  int rounds = 0;
  int sweeps = 0;                  // SOR's, over all rounds
  std::vector<int> region_sizes;   // the vertices free at each influence level solved
  std::vector<int> region_levels;  // those levels
};

struct DetailEditResult {
  Multiresolution surface;
  DetailEditReport report;
};

// The operators of a multiresolution surface's topology (each level's refinement and limit
// tangents, from OpenSubdiv's stencils), built once and shared by every edit of surfaces with
// this base topology and number of levels.
class DetailEditor {
 public:
  // InvalidInput for a bad base mesh or levels outside 1..8.
  DetailEditor(const SubdivisionMesh& base, int levels);
  int levels() const { return static_cast<int>(steps_.size()); }
  int vertices(int level) const;
  const SubdivisionMesh& topology(int level) const;  // faces and creases of a level
  // Every level's points, level 0 the base (the same as reconstruct's, without OpenSubdiv's
  // topology analysis on each call).
  std::vector<Eigen::MatrixX3d> points(const Multiresolution& surface) const;
  // The limit surface at the finest level's vertices (a cached stencil: what a drag draws).
  Eigen::MatrixX3d limit(const Multiresolution& surface) const;
  // The unit normal at a vertex of a level from its divided differences (Q_u x Q_v): what a
  // DetailNormal there holds. InvalidInput for a vertex that does not exist or has no tangent
  // plane.
  Eigen::Vector3d normal(const Multiresolution& surface, int level, int vertex) const;
  // The surface edited by the pins. InvalidInput for a surface of another topology, pins on
  // vertices or levels that do not exist (naming them), an influence coarser than 0 or finer
  // than the pin's level, targets not finite, two pins on one vertex, bad options; for normals
  // the same, a zero normal, and a vertex without a tangent plane.
  DetailEditResult edit(const Multiresolution& surface, const std::vector<DetailPin>& pins,
                        const std::vector<DetailNormal>& normals,
                        const DetailEditOptions& options) const;
  DetailEditResult edit(const Multiresolution& surface, const std::vector<DetailPin>& pins,
                        const DetailEditOptions& options) const {
    return edit(surface, pins, {}, options);
  }
  // The Appendix's re-parameterization at `level`: the surface re-expressed so that `vertices`
  // of that level (and the same vertices of every finer level) lie at `targets`, points on or
  // near the surface such as a curve lying on it, while the shape stays: each such vertex goes to
  // closest(target), keeping its offset from the surface (a control point's natural distance
  // from its limit), every finer vertex the move displaces is re-captured onto `closest` (the
  // surface before) the same way, and last the vertices' limit points are put at
  // closest(target) exactly. Defined in detail_snap.cpp. InvalidInput for a surface of another
  // topology, a level or vertices that do not exist, a vertex given twice, targets not finite or
  // not one per vertex.
  Multiresolution snap(const Multiresolution& surface, int level, const std::vector<int>& vertices,
                       const Eigen::MatrixX3d& targets,
                       const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& closest) const;

 private:
  void check(const Multiresolution& surface) const;
  // The vertices sharing a face with any of `seed` at `level`, `rings` times over.
  std::vector<int> grown(int level, const std::vector<int>& seed, int rings) const;
  std::vector<SubdivisionMesh> meshes_;  // topology and creases per level 0 .. L
  std::vector<SubdivisionStep> steps_;   // level k to k + 1
  std::vector<VertexFaces> incident_;    // per level, each vertex's faces
};

}  // namespace varsurf
