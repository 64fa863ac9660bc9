// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/triangle_net.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <numeric>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/triangular_bezier.hpp"

namespace varsurf {

namespace {

std::string edge_name(int a, int b) {
  return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

int find(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

void check_triangles(const Eigen::MatrixX3d& vertices,
                     const std::vector<std::array<int, 3>>& triangles) {
  if (triangles.empty()) throw InvalidInput("a triangle net needs at least one triangle");
  if (!vertices.allFinite()) throw InvalidInput("a triangle net has points that are not finite");
  const int n = static_cast<int>(vertices.rows());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& c = triangles[t];
    const std::string name = "triangle " + std::to_string(t);
    for (const int v : c)
      if (v < 0 || v >= n)
        throw InvalidInput(name + " names vertex " + std::to_string(v) + " of " +
                           std::to_string(n) + "; give indices 0.." + std::to_string(n - 1));
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
      throw InvalidInput(name + " repeats a corner; remove it from the mesh");
    const Eigen::Vector3d p = vertices.row(c[0]), q = vertices.row(c[1]), r = vertices.row(c[2]);
    const double longest =
        std::max({(q - p).squaredNorm(), (r - q).squaredNorm(), (p - r).squaredNorm()});
    if (!((q - p).cross(r - p).norm() > 1e-12 * longest))
      throw InvalidInput(name + " has no area (its corners are collinear); remove or fix it");
  }
}

}  // namespace

int TriangleNet::edge(int a, int b) const {
  const int lo = std::min(a, b), hi = std::max(a, b);
  const auto it = std::lower_bound(
      edges.begin(), edges.end(), std::make_pair(lo, hi),
      [](const NetEdge& e, const std::pair<int, int>& k) { return std::make_pair(e.a, e.b) < k; });
  return it != edges.end() && it->a == lo && it->b == hi ? static_cast<int>(it - edges.begin())
                                                         : -1;
}

std::vector<int> TriangleNet::edge_points(int e, int from) const {
  const NetEdge& edge = edges.at(e);
  const int vcount = static_cast<int>(vertices.rows());
  std::vector<int> out(degree + 1);
  for (int s = 0; s <= degree; ++s) {
    if (s == 0 || s == degree) {
      out[s] = (s == 0) == (from == edge.a) ? edge.a : edge.b;
      continue;
    }
    const int along = from == edge.a ? s : degree - s;  // steps from a
    out[s] = vcount + e * (degree - 1) + along - 1;
  }
  return out;
}

std::vector<int> TriangleNet::edge_row(int e, int t, int from) const {
  const NetEdge& edge = edges.at(e);
  const auto& corners = t == edge.left ? edge.left_corners : edge.right_corners;
  if (t != edge.left && t != edge.right) throw InvalidInput("the triangle is not at the edge");
  const int cf = from == edge.a ? corners[0] : corners[1];
  const int co = from == edge.a ? corners[1] : corners[0];
  std::vector<int> out(degree);
  for (int i = 0; i < degree; ++i) {
    std::array<int, 3> w{};
    w[cf] = degree - 1 - i;
    w[co] = i;
    w[corners[2]] = 1;
    out[i] = control[t][triangle_index(degree, w[0], w[1])];
  }
  return out;
}

TriangleNet make_triangle_net(const Eigen::MatrixX3d& vertices,
                              const std::vector<std::array<int, 3>>& triangles, int degree) {
  if (degree < 3 || degree > 12)
    throw InvalidInput("a triangular surface has degree 3 to 12, not " + std::to_string(degree));
  check_triangles(vertices, triangles);
  const int vcount = static_cast<int>(vertices.rows());
  const int tcount = static_cast<int>(triangles.size());
  // Each undirected edge's triangles and whether each runs it low -> high.
  std::map<std::pair<int, int>, std::vector<std::pair<int, bool>>> uses;
  for (int t = 0; t < tcount; ++t)
    for (int c = 0; c < 3; ++c) {
      const int p = triangles[t][c], q = triangles[t][(c + 1) % 3];
      auto& u = uses[{std::min(p, q), std::max(p, q)}];
      u.push_back({t, p < q});
      if (u.size() > 2)
        throw InvalidInput(edge_name(std::min(p, q), std::max(p, q)) +
                           " is shared by more than two triangles (non-manifold); split the mesh "
                           "there");
    }
  // Orient every connected piece like its first triangle.
  std::vector<int> flip(tcount, -1);
  std::vector<std::vector<std::pair<int, bool>>> next(tcount);  // (neighbour, same direction)
  for (const auto& [key, u] : uses)
    if (u.size() == 2) {
      next[u[0].first].push_back({u[1].first, u[0].second == u[1].second});
      next[u[1].first].push_back({u[0].first, u[0].second == u[1].second});
    }
  for (int seed = 0; seed < tcount; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    std::deque<int> queue{seed};
    while (!queue.empty()) {
      const int t = queue.front();
      queue.pop_front();
      for (const auto& [o, same] : next[t]) {
        const int want = same ? 1 - flip[t] : flip[t];
        if (flip[o] < 0) {
          flip[o] = want;
          queue.push_back(o);
        } else if (flip[o] != want) {
          throw InvalidInput("triangles " + std::to_string(t) + " and " + std::to_string(o) +
                             " cannot be oriented alike (the surface is one-sided, like a "
                             "Moebius strip); cut it open");
        }
      }
    }
  }
  TriangleNet net;
  net.degree = degree;
  net.vertices = vertices;
  net.triangles = triangles;
  for (int t = 0; t < tcount; ++t)
    if (flip[t] == 1) {
      std::swap(net.triangles[t][1], net.triangles[t][2]);
      net.flipped.push_back(t);
    }
  for (const auto& [key, u] : uses) {
    NetEdge e;
    e.a = key.first;
    e.b = key.second;
    for (const auto& use : u) {
      const int t = use.first;
      const auto& c = net.triangles[t];
      int ca = 0, cb = 0;
      for (int k = 0; k < 3; ++k) {
        if (c[k] == e.a) ca = k;
        if (c[k] == e.b) cb = k;
      }
      const std::array<int, 3> corners{ca, cb, 3 - ca - cb};
      if ((ca + 1) % 3 == cb) {
        e.left = t;
        e.left_corners = corners;
      } else {
        e.right = t;
        e.right_corners = corners;
      }
    }
    if (e.left < 0) {  // a border edge runs b -> a in its triangle: keep it as `left`
      std::swap(e.left, e.right);
      std::swap(e.left_corners, e.right_corners);
    }
    net.edges.push_back(e);
  }
  // Per vertex: its triangles, border, angle, and a single fan.
  net.patches_at.assign(vcount, 0);
  net.border.assign(vcount, false);
  net.angle.assign(vcount, 0.0);
  std::vector<std::vector<int>> around(vcount);
  for (int t = 0; t < tcount; ++t)
    for (int c = 0; c < 3; ++c) {
      const int v = net.triangles[t][c];
      ++net.patches_at[v];
      around[v].push_back(t);
      const Eigen::Vector3d p = vertices.row(v);
      const Eigen::Vector3d x = vertices.row(net.triangles[t][(c + 1) % 3]).transpose() - p;
      const Eigen::Vector3d y = vertices.row(net.triangles[t][(c + 2) % 3]).transpose() - p;
      net.angle[v] += std::atan2(x.cross(y).norm(), x.dot(y));
    }
  for (const NetEdge& e : net.edges)
    if (e.right < 0) net.border[e.a] = net.border[e.b] = true;
  std::vector<int> parent(tcount);
  std::iota(parent.begin(), parent.end(), 0);
  for (const NetEdge& e : net.edges)
    if (e.right >= 0) parent[find(parent, e.left)] = find(parent, e.right);
  for (int v = 0; v < vcount; ++v) {
    if (around[v].empty())
      throw InvalidInput("vertex " + std::to_string(v) +
                         " belongs to no triangle; remove it from the mesh");
    // Triangles around v joined through the edges at v: one fan, or the vertex is pinched.
    std::vector<int> local(around[v].size());
    std::iota(local.begin(), local.end(), 0);
    for (std::size_t i = 0; i < around[v].size(); ++i)
      for (std::size_t j = i + 1; j < around[v].size(); ++j) {
        const auto& p = net.triangles[around[v][i]];
        const auto& q = net.triangles[around[v][j]];
        for (const int w : p)
          if (w != v && std::find(q.begin(), q.end(), w) != q.end())
            local[find(local, static_cast<int>(i))] = find(local, static_cast<int>(j));
      }
    for (std::size_t i = 0; i < local.size(); ++i)
      if (find(local, static_cast<int>(i)) != find(local, 0))
        throw InvalidInput("vertex " + std::to_string(v) +
                           " joins separate fans of triangles (non-manifold); split it into one "
                           "vertex per fan");
  }
  // Control points: vertices, then n - 1 per edge, then (n - 1)(n - 2) / 2 per triangle.
  const int ecount = static_cast<int>(net.edges.size());
  const int inner = (degree - 1) * (degree - 2) / 2;
  net.control_count = vcount + ecount * (degree - 1) + tcount * inner;
  net.control.assign(tcount, std::vector<int>(triangle_points(degree)));
  for (int t = 0; t < tcount; ++t) {
    const auto& c = net.triangles[t];
    int ordinal = 0;
    for (int i = degree; i >= 0; --i)
      for (int j = degree - i; j >= 0; --j) {
        const std::array<int, 3> w{i, j, degree - i - j};
        const int zeros = (w[0] == 0) + (w[1] == 0) + (w[2] == 0);
        int& slot = net.control[t][triangle_index(degree, i, j)];
        if (zeros == 2) {
          slot = c[w[0] ? 0 : (w[1] ? 1 : 2)];
        } else if (zeros == 1) {
          const int z = w[0] == 0 ? 0 : (w[1] == 0 ? 1 : 2);
          const int p = c[(z + 1) % 3], q = c[(z + 2) % 3];
          const int e = net.edge(p, q);
          const int at_b = p == net.edges[e].b ? w[(z + 1) % 3] : w[(z + 2) % 3];
          slot = vcount + e * (degree - 1) + at_b - 1;
        } else {
          slot = vcount + ecount * (degree - 1) + t * inner + ordinal++;
        }
      }
  }
  return net;
}

}  // namespace varsurf
