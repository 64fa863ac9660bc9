// SPDX-License-Identifier: LGPL-2.1-or-later
// Triangle meshes for the triangular surface's tests: fans, planar grids, the Platonic solids
// with triangular faces, a torus.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

namespace varsurf::test {

struct Mesh {
  Eigen::MatrixX3d points;
  std::vector<std::array<int, 3>> triangles;
};

// k triangles around vertex 0 raised to `height` over a unit regular k-gon in z = 0 (open).
inline Mesh fan_mesh(int k, double height) {
  Mesh m;
  m.points.resize(k + 1, 3);
  m.points.row(0) << 0.0, 0.0, height;
  for (int i = 0; i < k; ++i) {
    const double a = 2.0 * M_PI * i / k;
    m.points.row(i + 1) << std::cos(a), std::sin(a), 0.1 * std::sin(3.0 * a);
  }
  for (int i = 0; i < k; ++i) m.triangles.push_back({0, 1 + i, 1 + (i + 1) % k});
  return m;
}

// An nx x ny grid of squares, each cut into two triangles, over [0, 1]^2 in z = 0, its inner
// points moved by up to `jitter` of a cell.
inline Mesh grid_mesh(int nx, int ny, double jitter) {
  Mesh m;
  m.points.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const bool inner = i > 0 && j > 0 && i < nx && j < ny;
      const double dx = inner ? jitter * std::sin(7.1 * i + 3.3 * j) : 0.0;
      const double dy = inner ? jitter * std::cos(5.7 * i - 2.9 * j) : 0.0;
      m.points.row(j * (nx + 1) + i) << (i + dx) / nx, (j + dy) / ny, 0.0;
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

inline Mesh tetrahedron() {
  Mesh m;
  m.points.resize(4, 3);
  m.points << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return m;
}

inline Mesh octahedron() {
  Mesh m;
  m.points.resize(6, 3);
  m.points << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

inline Mesh icosahedron() {
  Mesh m;
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  m.points.resize(12, 3);
  m.points << -1, p, 0, 1, p, 0, -1, -p, 0, 1, -p, 0, 0, -1, p, 0, 1, p, 0, -1, -p, 0, 1, -p, p, 0,
      -1, p, 0, 1, -p, 0, -1, -p, 0, 1;
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  return m;
}

// A torus (radii R = 2, r = 0.7) of nu x nv quads cut into triangles: every vertex of valence 6.
inline Mesh torus_mesh(int nu, int nv) {
  Mesh m;
  m.points.resize(nu * nv, 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2.0 * M_PI * i / nu, v = 2.0 * M_PI * j / nv;
      m.points.row(i * nv + j) << (2.0 + 0.7 * std::cos(v)) * std::cos(u),
          (2.0 + 0.7 * std::cos(v)) * std::sin(u), 0.7 * std::sin(v);
    }
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const int a = i * nv + j, b = ((i + 1) % nu) * nv + j, c = i * nv + (j + 1) % nv,
                d = ((i + 1) % nu) * nv + (j + 1) % nv;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

}  // namespace varsurf::test
