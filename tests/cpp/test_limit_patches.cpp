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
#include "varsurf/core/detail_energy.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/limit_patches.hpp"
#include "varsurf/core/multiresolution.hpp"

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

TEST(LimitPatches, DividedDifferencesMeasureTheShapeWhereLimitDerivativesMeasureTheScheme) {
  // Why the detail energy takes divided differences on the mesh (sec. 3.3) rather than the limit
  // surface's derivatives: a cube's cage captured onto a sphere of radius 7 at 4 levels puts
  // every vertex on the sphere. The divided differences' bend density (Q_uu^2 + 2 Q_uv^2 + Q_vv^2)
  // is the sphere's 2 / R^2 at regular and extraordinary vertices alike; the limit surface's own
  // curvature is the sphere's at a regular point but grows to over 3 times it approaching a
  // valence-3 corner (Catmull-Clark's limit is only C1 there): an energy of limit derivatives
  // would weigh every edit near an extraordinary vertex by the scheme, not by the shape.
  const double r = 7.0, sphere = 2.0 / (r * r);
  SubdivisionMesh cage;
  cage.points.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    cage.points.row(k) << (k & 1 ? 3.0 : -3.0), (k & 2 ? 3.0 : -3.0), (k & 4 ? 3.0 : -3.0);
  cage.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  const Multiresolution m = capture(
      cage, 4, [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(r * p.normalized()); });
  const SubdivisionMesh fine = reconstruct(m).back();
  const Eigen::MatrixXd q = divided_differences(fine) * fine.points;
  std::vector<int> valence(static_cast<size_t>(fine.points.rows()), 0);
  for (const auto& f : fine.faces)
    for (int v : f) ++valence[static_cast<size_t>(v)];
  double regular = 0.0, extraordinary = 0.0;
  for (Eigen::Index v = 0; v < fine.points.rows(); ++v) {
    const double bend = q.row(5 * v + 2).squaredNorm() + 2 * q.row(5 * v + 3).squaredNorm() +
                        q.row(5 * v + 4).squaredNorm();
    double& worst = valence[static_cast<size_t>(v)] == 4 ? regular : extraordinary;
    worst = std::max(worst, std::abs(bend / sphere - 1.0));
  }
  EXPECT_LT(regular, 1e-3);
  EXPECT_LT(extraordinary, 1e-3);
  // Vertex 0 is a cube corner (valence 3): the face with it as its first corner.
  int face = -1;
  for (size_t f = 0; f < fine.faces.size(); ++f)
    if (fine.faces[f][0] == 0) face = static_cast<int>(f);
  ASSERT_GE(face, 0);
  EXPECT_NEAR(limit_curvature(fine, 100, 0.5, 0.5, 10) / sphere, 1.0, 0.01);
  for (int k = 4; k <= 9; ++k) {
    const double t = std::pow(2.0, -k);
    EXPECT_GT(limit_curvature(fine, face, t, t, 10) / sphere, 2.5) << k;
  }
  std::printf(
      "divided differences within %.1e (regular) and %.1e (extraordinary) of 2/R^2; the "
      "limit's curvature %.2f x it at 2^-9 from a valence-3 corner\n",
      regular, extraordinary,
      limit_curvature(fine, face, std::pow(2.0, -9), std::pow(2.0, -9), 10) / sphere);
}
