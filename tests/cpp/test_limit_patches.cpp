// SPDX-License-Identifier: LGPL-2.1-or-later
// The limit surface as bicubic Bezier patches (OpenSubdiv's patch table) against independent
// answers: on a regular grid every interior patch is the bicubic B-spline of the control points
// to 1e-12; on a cube the patches meet with no gap, the regular ones are Catmull-Clark's limit at
// their corners, and the end caps at the valence-3 corners approach the limit as the isolation
// grows; meshes with other faces than quads are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bicubic_grid.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/limit_patches.hpp"

using namespace varsurf;
using namespace varsurf::test;

namespace {

SubdivisionMesh cube() {
  SubdivisionMesh m;
  m.points.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    m.points.row(k) << (k & 1 ? 3.0 : -3.0), (k & 2 ? 2.0 : -2.0), (k & 4 ? 4.0 : -4.0);
  m.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return subdivide(m, 1).levels[1];  // 24 quads, the corners still valence 3
}

}  // namespace

TEST(LimitPatches, RegularPatchesAreTheBicubicBSpline) {
  const SubdivisionMesh m = grid();
  const LimitPatches patches = limit_patches(m, 3);
  int checked = 0;
  for (const LimitPatch& p : patches.patches) {
    const std::vector<int>& face = m.faces[static_cast<size_t>(p.face)];
    const int i = face[0] / kGrid, j = face[0] % kGrid;
    if (i < 2 || j < 2 || i > kGrid - 4 || j > kGrid - 4) continue;  // interior masks only
    EXPECT_TRUE(p.regular);
    for (double a : {0.0, 0.3, 0.7, 1.0})
      for (double b : {0.0, 0.45, 1.0}) {
        const double s = i + p.u0 + p.size * a, t = j + p.v0 + p.size * b;
        const Eigen::Vector3d want(s, t, bicubic(s, t));
        EXPECT_LT((p.surface.evaluate(a, b) - want).norm(), 1e-12) << s << " " << t;
      }
    ++checked;
  }
  EXPECT_EQ(checked, (kGrid - 5) * (kGrid - 5));
  EXPECT_EQ(patches.end_caps,
            0);  // a grid with corners and boundaries, but no extraordinary vertex
}

TEST(LimitPatches, ACubesPatchesMeetAndItsEndCapsApproachTheLimit) {
  const SubdivisionMesh m = cube();
  const SubdivisionLevels limit = subdivide(m, 0);
  double previous = 1e300;
  for (const int isolation : {2, 3, 4, 5}) {
    const LimitPatches patches = limit_patches(m, isolation);
    EXPECT_EQ(patches.end_caps, 24);  // one per face corner at the 8 valence-3 vertices
    EXPECT_GT(patches.regular, 0);
    // No gaps: every patch corner is the corner of patches around it, or lies on their sides.
    // Measured on the faces' own corners: the limit points of the mesh's vertices.
    for (const LimitPatch& p : patches.patches)
      for (const auto& [a, b] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}}) {
        const double u = p.u0 + p.size * a, v = p.v0 + p.size * b;
        if ((u != 0.0 && u != 1.0) || (v != 0.0 && v != 1.0)) continue;
        const int corner = u == 0.0 ? (v == 0.0 ? 0 : 3) : (v == 0.0 ? 1 : 2);
        const int vertex = m.faces[static_cast<size_t>(p.face)][static_cast<size_t>(corner)];
        EXPECT_LT((p.surface.evaluate(a, b) - limit.limit_points.row(vertex).transpose()).norm(),
                  1e-12);
      }
    const double deviation = end_cap_deviation(m, patches, 10, 9);
    EXPECT_LT(deviation, previous / 1.5) << isolation;
    previous = deviation;
    std::printf("isolation %d: %d regular patches, %d end caps, end caps within %.3g\n", isolation,
                patches.regular, patches.end_caps, deviation);
  }
}

TEST(LimitPatches, MeshesOtherThanQuadsAreRefused) {
  SubdivisionMesh m = grid();
  m.faces.push_back({0, 1, kGrid});  // a triangle (overlapping: refused first for its edges)
  EXPECT_THROW(limit_patches(m, 2), InvalidInput);
  SubdivisionMesh tri;
  tri.points.resize(3, 3);
  tri.points << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  tri.faces = {{0, 1, 2}};
  try {
    limit_patches(tri, 2);
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("refine it once"), std::string::npos) << e.what();
  }
  EXPECT_THROW(limit_patches(grid(), 0), InvalidInput);
}
