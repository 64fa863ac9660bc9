// SPDX-License-Identifier: LGPL-2.1-or-later
// Tangent-plane continuity between triangular Bezier patches (Veltkamp & Wesselink sec. 4.3, eqs.
// 9-12), as linear conditions on their control points: along a shared edge M_0 .. M_n, with the
// rows next to it L_0 .. L_n-1 in one patch and R_0 .. R_n-1 in the other,
//   e(t) dM(t) + f(t) dL(t) + g(t) dR(t) = 0,
// dM the edge's derivative net (M_i+1 - M_i), dL and dR the cross-boundary ones (L_i - M_i,
// R_i - M_i), and e, f, g linear from their values at the edge's two vertices, which the number of
// patches around each vertex sets. Met, the three derivatives are coplanar all along the edge.
#pragma once

#include <Eigen/Core>

#include "varsurf/core/triangular_bezier.hpp"

namespace varsurf {

struct G1Weights {
  double e = 1.0, f = -1.0, g = -1.0;
};

// The weights at a vertex with `patches` patches around it: inside the surface e = 1, f = g =
// -1 / (2 cos(2 pi / k)); on its border, where the surface turns through `angle` (pi: flat),
// -1 / (2 cos(angle / k)); where that cosine vanishes (four patches inside, two on a flat border)
// e = 0, f = g = 1. InvalidInput for fewer than 3 patches inside or 1 on the border, or an angle
// outside (0, 2 pi).
G1Weights g1_weights(int patches, bool border, double angle = M_PI);

// The conditions across one edge of two degree-n patches as rows over the points [M_0 .. M_n,
// L_0 .. L_n-1, R_0 .. R_n-1] (each applies to x, y and z alike); `start` and `end` are the
// weights at M_0 and M_n for the vectors leaving each vertex (along the edge, to L's and R's
// points next to it). Full: the n + 1 Bernstein coefficients of the identity above (for n = 3
// their eqs. 9, 11, 12 and 10, eq. 11 less eq. 9; their eq. 10 writes M_n's vectors from M_n-1).
// Approximate: the two vertex rows and, between them, the n - 2 rows
// e (M_i+1 - M_i) + f (L_i - M_i) + g (R_i - M_i) = 0 with the two ends' mean weights (their
// weaker variant).
Eigen::MatrixXd g1_edge_equations(int degree, const G1Weights& start, const G1Weights& end,
                                  bool approximate = false);

// The largest angle (radians) between the normals of two patches along their shared edge, at
// `samples` points: the edge runs from corner `a_from` to `a_to` of patch a and from `b_from` to
// `b_to` of patch b (the same points in the same order), normals from each patch's own corner
// order (two patches oriented alike meet with equal normals); pi where a patch has no normal (a
// collapsed tangent). InvalidInput for bad corners or
// samples outside 2..100000.
double shared_edge_angle(const TriangularBezier& a, int a_from, int a_to, const TriangularBezier& b,
                         int b_from, int b_to, int samples = 50);

}  // namespace varsurf
