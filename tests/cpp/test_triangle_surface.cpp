// SPDX-License-Identifier: LGPL-2.1-or-later
// The closest point on a triangle mesh against a brute-force search over every triangle, and a
// scan-like capture: a sphere tessellated coarsely captured onto a cube's cage comes within the
// tessellation's own sagitta of it; a target far from the cage is refused.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/multiresolution.hpp"
#include "varsurf/core/triangle_surface.hpp"

using namespace varsurf;

namespace {

// A UV sphere of radius r: `rings` x `segments` quads split into triangles.
void uv_sphere(double r, int rings, int segments, Eigen::MatrixX3d& points,
               std::vector<std::array<int, 3>>& triangles) {
  points.resize((rings - 1) * segments + 2, 3);
  points.row(0) << 0, 0, r;
  points.row(1) << 0, 0, -r;
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double t = M_PI * i / rings, p = 2 * M_PI * j / segments;
      points.row(2 + (i - 1) * segments + j) << r * std::sin(t) * std::cos(p),
          r * std::sin(t) * std::sin(p), r * std::cos(t);
    }
  auto at = [&](int i, int j) { return 2 + (i - 1) * segments + (j % segments); };
  triangles.clear();
  for (int j = 0; j < segments; ++j) {
    triangles.push_back({0, at(1, j), at(1, j + 1)});
    triangles.push_back({1, at(rings - 1, j + 1), at(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
}

}  // namespace

TEST(TriangleSurface, ClosestPointsMatchABruteForceSearch) {
  Eigen::MatrixX3d points;
  std::vector<std::array<int, 3>> triangles;
  uv_sphere(5.0, 17, 23, points, triangles);
  const TriangleSurface surface(points, triangles);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-9.0, 9.0);
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3d p(coord(rng), coord(rng), coord(rng));
    double best = 1e300;
    for (const auto& t : triangles)
      best = std::min(
          best, (closest_on_triangle(p, points.row(t[0]), points.row(t[1]), points.row(t[2])) - p)
                    .norm());
    EXPECT_NEAR((surface.closest(p) - p).norm(), best, 1e-12);
  }
  // The triangle's own regions: a vertex, an edge, the inside.
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_LT((closest_on_triangle({-1, -1, 3}, a, b, c) - a).norm(), 1e-15);
  EXPECT_LT((closest_on_triangle({1, -1, 3}, a, b, c) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((closest_on_triangle({0.5, 0.5, 3}, a, b, c) - Eigen::Vector3d(0.5, 0.5, 0)).norm(),
            1e-15);
  EXPECT_LT((closest_on_triangle({2, 2, 0}, a, b, c) - Eigen::Vector3d(1, 1, 0)).norm(), 1e-15);
  EXPECT_THROW(TriangleSurface(points, {}), InvalidInput);
  EXPECT_THROW(TriangleSurface(points, {{0, 1, 99999}}), InvalidInput);
}

TEST(TriangleSurface, ACoarseScanCapturesOntoACageWithinItsSagitta) {
  Eigen::MatrixX3d points;
  std::vector<std::array<int, 3>> triangles;
  const double r = 7.0;
  uv_sphere(r, 40, 80, points, triangles);
  const TriangleSurface scan(points, triangles);
  SubdivisionMesh cube;
  cube.points.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    cube.points.row(k) << (k & 1 ? 3.0 : -3.0), (k & 2 ? 3.0 : -3.0), (k & 4 ? 3.0 : -3.0);
  cube.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  auto closest = [&](const Eigen::Vector3d& p) { return scan.closest(p); };
  const Multiresolution m = capture(cube, 4, closest);
  const CaptureFit fit = capture_fit(m, closest);
  // The scan's chords lie within r (1 - cos(pi / 40)) = 0.0216 of the sphere; the limit surface
  // of the captured levels within two of those of the scan, and on the mean within one.
  const double sagitta = r * (1.0 - std::cos(M_PI / 40));
  EXPECT_LT(fit.max_distance, 2.0 * sagitta);
  EXPECT_LT(fit.rms_distance, sagitta);
  std::printf("capture fit: max %.4f rms %.4f\n", fit.max_distance, fit.rms_distance);
  // A cage far away from the scan is refused.
  SubdivisionMesh far = cube;
  far.points.col(0).array() += 100.0;
  try {
    capture(far, 2, closest);
    ADD_FAILURE() << "a far cage was captured";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("too far from the cage"), std::string::npos) << e.what();
  }
}

TEST(TriangleSurface, CapturesScaleWithTheScene) {
  // A cube cage whose face centres lie inside a tessellated sphere, on its axes: several facets
  // are nearest there. The same scene at 0.05x and 500x captures the same details scaled.
  Eigen::MatrixX3d points;
  std::vector<std::array<int, 3>> triangles;
  uv_sphere(6.5, 40, 80, points, triangles);
  SubdivisionMesh cube;
  cube.points.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    cube.points.row(k) << (k & 1 ? 5.0 : -5.0), (k & 2 ? 5.0 : -5.0), (k & 4 ? 5.0 : -5.0);
  cube.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  const auto details = [&](double scale) {
    const TriangleSurface scan(points * scale, triangles);
    SubdivisionMesh cage = cube;
    cage.points *= scale;
    return capture(cage, 3, [&](const Eigen::Vector3d& p) { return scan.closest(p); }).details;
  };
  const std::vector<Eigen::MatrixX3d> one = details(1.0);
  for (const double scale : {0.05, 500.0}) {
    const std::vector<Eigen::MatrixX3d> scaled = details(scale);
    for (size_t k = 0; k < one.size(); ++k)
      EXPECT_LT((scaled[k] / scale - one[k]).cwiseAbs().maxCoeff(), 1e-9) << scale << " " << k;
  }
}
