// SPDX-License-Identifier: LGPL-2.1-or-later
// Triangular Bezier patches of any degree n >= 1 (Veltkamp & Wesselink sec. 2, their eq. 2):
// T(u, v, w) = sum over i + j + k = n of P_ijk B_ijk(u, v, w), u + v + w = 1, evaluated by de
// Casteljau's algorithm, with directional derivatives and the subdivisions into three triangles
// at an inner point and into two at a point of an edge.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace varsurf {

// The control points of degree n are numbered by (i, j, k), i + j + k = n, i from n down to 0
// and, within each i, j from n - i down to 0: index(n, i, j) = (n - i)(n - i + 1) / 2 + (n - i -
// j). P_n00 is corner 1 (u = 1), P_0n0 corner 2, P_00n corner 3.
int triangle_points(int degree);  // (n + 1)(n + 2) / 2
int triangle_index(int degree, int i, int j);

struct TriangularBezier {
  int degree = 3;
  Eigen::MatrixX3d points;  // triangle_points(degree) rows
  // InvalidInput for a degree below 1 or above 20, a row count that does not match, points that
  // are not finite.
  void validate() const;
  Eigen::Vector3d evaluate(const Eigen::Vector3d& barycentric) const;
  // The derivative along a direction of barycentric coordinates (its entries sum to 0), `order`
  // times (0 .. degree): the degree - order patch whose value is that derivative.
  TriangularBezier derivative(const Eigen::Vector3d& direction, int order = 1) const;
};

// The unit normal at barycentric b, (T_v - T_u) x (T_w - T_u) in the patch's corner order; not
// finite where the patch has no tangent plane.
Eigen::Vector3d patch_normal(const TriangularBezier& patch, const Eigen::Vector3d& b);

// The patch with its corners replaced by the three points `corners` of its own domain (each in
// barycentric coordinates): the same surface over the sub-triangle, a patch of the same degree
// (the blossom of T at the new corners). Sub-triangles need not lie inside the domain.
TriangularBezier sub_patch(const TriangularBezier& patch,
                           const std::array<Eigen::Vector3d, 3>& corners);

// De Casteljau's subdivision at an inner point p (barycentric; every entry > 0): the three
// patches over (p, V2, V3), (V1, p, V3) and (V1, V2, p), which join C0 and together are the patch.
std::array<TriangularBezier, 3> split_at_point(const TriangularBezier& patch,
                                               const Eigen::Vector3d& p);
// The split at the point of the edge opposite corner `corner` (0..2) that divides it at `t` in
// (0, 1) measured from the next corner: the two patches sharing the new edge from that point to
// `corner`.
std::array<TriangularBezier, 2> split_at_edge(const TriangularBezier& patch, int corner, double t);

}  // namespace varsurf
