// SPDX-License-Identifier: LGPL-2.1-or-later
// The vertices of a mesh level that follow a curve lying on the surface (Boier-Martin, Ronfard &
// Bernardini sec. 4.2 and Appendix): the curve, a polyline, approximated by a chain of vertices
// in which consecutive ones share a face (along an edge or across a face diagonally: the
// Appendix's approximation property), each with the curve parameter of its closest point, so
// point constraints placed on the chain carry the curve's motion. Instead of re-parameterizing
// the surface until the curve runs through vertices exactly, the chain is taken at a level fine
// enough: its distance from the curve (reported) shrinks with the level's edge length, and the
// surface is not changed before the edit.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "varsurf/core/subdivision.hpp"

namespace varsurf {

struct CurveChain {
  std::vector<int> vertices;       // in the curve's order, each once (closed: first not repeated)
  std::vector<double> parameters;  // each vertex's closest curve point, as arc length in 0..1
  Eigen::MatrixX3d points;         // those closest curve points (one row per vertex)
  double max_distance = 0.0;       // the farthest chain vertex from the curve
  double max_gap = 0.0;            // the farthest curve point from the chain's polyline
  bool closed = false;
};

// The chain of `mesh`'s vertices along `curve` (points in order; closed when its ends coincide
// within a thousandth of its length). InvalidInput for fewer than two distinct points, points
// that are not finite, a mesh the checks of subdivide refuse, or a curve that leaves the mesh
// (a sample farther from every vertex than the mesh's largest edge).
CurveChain curve_chain(const SubdivisionMesh& mesh, const Eigen::MatrixX3d& curve);

}  // namespace varsurf
