// SPDX-License-Identifier: LGPL-2.1-or-later
// A triangulation as the control structure of a surface of triangular Bezier patches (Veltkamp &
// Wesselink sec. 4.3): the triangles oriented alike, each edge's one or two triangles, each
// vertex's patches and the angle its triangles span, and one numbering of all control points of
// degree n in which patches share the points of their common edges and vertices (C0 by
// construction).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace varsurf {

struct NetEdge {
  int a = 0, b = 0;  // vertices, a < b
  // The triangle that runs a -> b in its (oriented) corner order, and the one that runs b -> a
  // (-1 on the border, where `left` is the one triangle whichever way it runs); each with the
  // corners of a, b and the third vertex.
  int left = -1, right = -1;
  std::array<int, 3> left_corners{}, right_corners{};
};

struct TriangleNet {
  int degree = 3;
  Eigen::MatrixX3d vertices;
  // Oriented alike: input triangles whose corners were reversed to agree with their neighbours
  // are listed in `flipped`.
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> flipped;
  std::vector<NetEdge> edges;
  std::vector<int> patches_at;  // per vertex: triangles around it
  std::vector<bool> border;     // per vertex: on the surface's border
  std::vector<double> angle;    // per vertex: the angles of its triangles there, summed
  int control_count = 0;
  // Per triangle, the global control point of each local one (triangle_index order).
  std::vector<std::vector<int>> control;

  // The edge joining vertices a and b, or -1.
  int edge(int a, int b) const;
  // The control points along edge e from vertex `from` (its a or b) to the other.
  std::vector<int> edge_points(int e, int from) const;
  // The control points of triangle t's row next to edge e (those one step from it towards the
  // third corner), from the end at `from` on.
  std::vector<int> edge_row(int e, int t, int from) const;
};

// InvalidInput naming the triangle, edge or vertex at fault: a degree outside 3..12, no
// triangles, indices out of range, points that are not finite, a degenerate triangle (a repeated
// corner or no area), an edge of more than two triangles, a vertex where separate fans of
// triangles meet, a surface that cannot be oriented (a Moebius strip), a vertex of no triangle.
TriangleNet make_triangle_net(const Eigen::MatrixX3d& vertices,
                              const std::vector<std::array<int, 3>>& triangles, int degree);

}  // namespace varsurf
