// SPDX-License-Identifier: LGPL-2.1-or-later
// The discrete stretch-and-bend energy of a mesh's deformation (Boier-Martin, Ronfard &
// Bernardini secs. 3.3-3.4): at each vertex a quadratic is fitted in least squares to the vertex
// and its one-ring (edge and face neighbours) in a local parameterization that spreads the ring's
// angles over the full turn; its coefficients are divided-difference operators D on the ring.
// Divided differences on the mesh itself rather than OpenSubdiv's limit derivatives: they exist
// at every level and every valence with the same rows, and a deformation's energy then needs no
// limit evaluation (the comparison is measured in the tests).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "varsurf/core/subdivision.hpp"

namespace varsurf {

struct DetailEnergyWeights {
  double stretch = 1.0;  // alpha: first derivatives
  double bend = 1.0;     // beta: second derivatives
};

// The operators of every vertex: rows 5i .. 5i + 4 give (Q_u, Q_v, Q_uu, Q_uv, Q_vv) at vertex i
// as combinations of the mesh's points (its ring minus itself), exact for quadratic fields over a
// flat regular ring. Only `vertices`' rows are filled when given (the others stay zero).
// InvalidInput when a vertex's faces do not make one fan (not manifold).
Eigen::SparseMatrix<double> divided_differences(const SubdivisionMesh& mesh,
                                                const std::vector<int>& vertices = {});

// H of E(dP) = sum over coordinates of dP^T H dP: per vertex, stretch/l^2 (Q_u^2 + Q_v^2) plus
// bend (Q_uu^2 + 2 Q_uv^2 + Q_vv^2), l being the mesh's mean edge length, so that scaling the mesh
// scales every term alike and the minimizer with it. Summed over `vertices` when given (a
// region's energy needs the region's vertices and their ring), else over all.
Eigen::SparseMatrix<double> detail_energy(const SubdivisionMesh& mesh,
                                          const DetailEnergyWeights& weights,
                                          const std::vector<int>& vertices = {});

// Each vertex's faces, after OpenSubdiv's checks of the mesh (InvalidInput as subdivide). The
// _checked functions below skip those checks, which took most of an edit's time with normal
// constraints (their tangents are taken again each round): for a mesh whose topology is checked.
using VertexFaces = std::vector<std::vector<int>>;
VertexFaces vertex_faces(const SubdivisionMesh& mesh);
Eigen::SparseMatrix<double> divided_differences_checked(const SubdivisionMesh& mesh,
                                                        const VertexFaces& incident,
                                                        const std::vector<int>& vertices = {});
Eigen::SparseMatrix<double> detail_energy_checked(const SubdivisionMesh& mesh,
                                                  const VertexFaces& incident,
                                                  const DetailEnergyWeights& weights,
                                                  const std::vector<int>& vertices = {});

}  // namespace varsurf
