// SPDX-License-Identifier: LGPL-2.1-or-later
// A triangular Bezier patch of degree n as three tensor-product Bezier patches of degree n x n,
// exactly and without collapsed edges: the triangle is split at its centroid C into the quads
// (V_i, M_i, C, M_i-1) through its edges' midpoints; each quad is the image of the unit square
// under a bilinear map of the domain, and the patch composed with a bilinear map is a polynomial
// of degree n in each of the square's two parameters.
#pragma once

#include <array>

#include "varsurf/core/spline_space.hpp"
#include "varsurf/core/triangular_bezier.hpp"

namespace varsurf {

// Quad i (0..2) starts at corner i: u runs towards the midpoint of the edge to the next corner,
// v towards the midpoint of the edge to the previous one, so every quad is oriented as the
// triangle (V1, V2, V3). Its poles interpolate the composed polynomial at the (n + 1)^2
// Chebyshev-Lobatto points of the square: exact but for rounding. InvalidInput for a bad patch.
std::array<BSplineSurface, 3> triangle_quads(const TriangularBezier& patch);

// The barycentric point of quad `quad` at (u, v) of its square.
Eigen::Vector3d triangle_quad_point(int quad, double u, double v);

}  // namespace varsurf
