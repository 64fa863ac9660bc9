// SPDX-License-Identifier: LGPL-2.1-or-later
// Catmull-Clark subdivision of a control mesh of any topology (quads, with triangles and n-gons,
// boundaries and creased edges), by OpenSubdiv: the levels of uniform refinement and the limit
// surface's points and tangents at the finest level's vertices (Boier-Martin, Ronfard &
// Bernardini's multiresolution surfaces start here). OpenSubdiv rather than a hand-written
// subdivider: its rules at extraordinary vertices, boundaries and creases are the reference.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

namespace varsurf {

struct SubdivisionMesh {
  Eigen::MatrixX3d points;              // control vertices
  std::vector<std::vector<int>> faces;  // vertex indices, counterclockwise seen from outside
  // Creased edges: the two vertices of an edge of the mesh and its sharpness (0: smooth; 10 and
  // above: infinitely sharp, as OpenSubdiv's own scale).
  std::vector<std::pair<std::pair<int, int>, double>> creases;
};

struct SubdivisionLevels {
  // levels[0] is the control mesh; levels[k] the mesh after k uniform refinements, its creases
  // with the sharpness refinement left them. A vertex keeps its index in the next level (the
  // vertices' children come first), so a level's vertex i lies on the limit near its parent's.
  // The edge vertices follow OpenSubdiv's edge order, which is not the same for a refined level
  // and for that level's mesh refined again as a base: a multiresolution surface always refines
  // one level at a time.
  std::vector<SubdivisionMesh> levels;
  // The limit surface at the finest level's vertices: points and two tangents (along the first
  // and second edge directions OpenSubdiv chooses at each vertex).
  Eigen::MatrixX3d limit_points, limit_tangent_u, limit_tangent_v;
};

// Refines `mesh` `levels` times (0..8). InvalidInput for faces of fewer than three vertices,
// vertex indices out of range, points that are not finite, a crease that is not an edge of the
// mesh or has a negative sharpness, and topology OpenSubdiv refuses (non-manifold edges), with
// its message, a face running an edge the same way as another (inconsistent orientation) and an
// edge of more than two faces (not manifold), naming them.
SubdivisionLevels subdivide(const SubdivisionMesh& mesh, int levels);

// One refinement as linear maps, from OpenSubdiv's stencils: the next level's points are
// refine * points (rows: the refined vertices in subdivide's order), and the limit surface's
// points and tangents at them limit * (next points), limit_u * (next points),
// limit_v * (next points), as subdivide gives them.
// The same checks as subdivide.
struct SubdivisionStep {
  Eigen::SparseMatrix<double> refine, limit, limit_u, limit_v;
};
SubdivisionStep subdivision_step(const SubdivisionMesh& mesh);

}  // namespace varsurf
