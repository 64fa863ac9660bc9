// SPDX-License-Identifier: LGPL-2.1-or-later
// Catmull-Clark subdivision through OpenSubdiv against independent answers: on a regular grid the
// refined points follow the bicubic B-spline's subdivision and the limit surface is the bicubic
// B-spline of the control points; at extraordinary vertices the limit point is Catmull-Clark's
// closed-form limit mask; bad meshes are refused by name.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "bicubic_grid.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/subdivision.hpp"

using namespace varsurf;
using namespace varsurf::test;

namespace {

// Far enough inside that every mask involved sees regular interior points only.
bool interior(double s, double t) {
  return s >= 2.0 && s <= kGrid - 3.0 && t >= 2.0 && t <= kGrid - 3.0;
}

}  // namespace

TEST(Subdivision, RegularGridRefinesAsTheBicubicBSpline) {
  const SubdivisionLevels out = subdivide(grid(), 1);
  ASSERT_EQ(out.levels.size(), 2u);
  const SubdivisionMesh& fine = out.levels[1];
  EXPECT_EQ(fine.faces.size(), 4 * grid().faces.size());
  // B-spline subdivision masks: (1, 6, 1) / 8 at a vertex, (1, 1) / 2 at an edge's midpoint.
  auto mask = [](double x) {
    const double f = x - std::floor(x);
    return f == 0.0 ? std::vector<std::pair<int, double>>{{-1, 0.125}, {0, 0.75}, {1, 0.125}}
                    : std::vector<std::pair<int, double>>{{0, 0.5}, {1, 0.5}};
  };
  int checked = 0;
  for (Eigen::Index k = 0; k < fine.points.rows(); ++k) {
    const double s = fine.points(k, 0), t = fine.points(k, 1);
    if (!interior(s, t)) continue;
    double z = 0.0;
    for (const auto& [di, wi] : mask(s))
      for (const auto& [dj, wj] : mask(t))
        z += wi * wj *
             height(static_cast<int>(std::floor(s)) + di, static_cast<int>(std::floor(t)) + dj);
    EXPECT_NEAR(fine.points(k, 2), z, 1e-12) << s << " " << t;
    ++checked;
  }
  EXPECT_EQ(checked, 7 * 7);  // s and t in 2, 2.5, ..., 5
}

TEST(Subdivision, RegularGridsLimitIsTheBicubicBSpline) {
  for (int levels : {0, 2}) {
    const SubdivisionLevels out = subdivide(grid(), levels);
    int checked = 0;
    for (Eigen::Index k = 0; k < out.limit_points.rows(); ++k) {
      const double s = out.levels.back().points(k, 0), t = out.levels.back().points(k, 1);
      if (!interior(s, t)) continue;
      const Eigen::Vector3d p = out.limit_points.row(k);
      EXPECT_NEAR(p.x(), s, 1e-12);
      EXPECT_NEAR(p.y(), t, 1e-12);
      EXPECT_NEAR(p.z(), bicubic(s, t), 1e-12) << s << " " << t;
      // The tangent plane is the B-spline's: its normal along (-z_s, -z_t, 1).
      const double h = 1e-6;
      const Eigen::Vector3d n(-(bicubic(s + h, t) - bicubic(s - h, t)) / (2 * h),
                              -(bicubic(s, t + h) - bicubic(s, t - h)) / (2 * h), 1.0);
      const Eigen::Vector3d du = out.limit_tangent_u.row(k), dv = out.limit_tangent_v.row(k);
      EXPECT_LT(du.cross(dv).normalized().cross(n.normalized()).norm(), 1e-8);
      ++checked;
    }
    EXPECT_GT(checked, 0);
  }
}

// Catmull-Clark's limit point of a vertex of valence n whose faces are quads:
// (n^2 v + 4 sum e + sum f) / (n (n + 5)), e its edge neighbours, f the vertices across its faces.
TEST(Subdivision, ExtraordinaryVerticesMeetCatmullClarksLimitMask) {
  // A cube: valence 3 at every corner.
  SubdivisionMesh cube;
  cube.points.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    cube.points.row(k) << (k & 1 ? 1.0 : -1.0) * 2.0, (k & 2 ? 1.0 : -1.0),
        (k & 4 ? 1.0 : -1.0) * 1.5;
  cube.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  const SubdivisionLevels c = subdivide(cube, 0);
  for (int v = 0; v < 8; ++v) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero(), f = Eigen::Vector3d::Zero();
    for (int bit : {1, 2, 4}) e += cube.points.row(v ^ bit);
    for (int bits : {3, 5, 6}) f += cube.points.row(v ^ bits);
    const Eigen::Vector3d want = (9.0 * Eigen::Vector3d(cube.points.row(v)) + 4.0 * e + f) / 24.0;
    EXPECT_LT((Eigen::Vector3d(c.limit_points.row(v)) - want).norm(), 1e-12) << v;
  }
  // A valence-5 vertex: five quads around a raised centre.
  SubdivisionMesh fan;
  fan.points.resize(11, 3);
  fan.points.row(0) << 0.1, -0.2, 2.0;
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * M_PI * k / 5, b = 2 * M_PI * (k + 0.5) / 5;
    fan.points.row(1 + k) << std::cos(a), std::sin(a), 0.3 * k;
    fan.points.row(6 + k) << 1.8 * std::cos(b), 1.8 * std::sin(b), -0.2 * k;
  }
  for (int k = 0; k < 5; ++k) fan.faces.push_back({0, 1 + k, 6 + k, 1 + (k + 1) % 5});
  const SubdivisionLevels g = subdivide(fan, 0);
  const Eigen::Vector3d e = fan.points.middleRows(1, 5).colwise().sum();
  const Eigen::Vector3d f = fan.points.middleRows(6, 5).colwise().sum();
  const Eigen::Vector3d want = (25.0 * Eigen::Vector3d(fan.points.row(0)) + 4.0 * e + f) / 50.0;
  EXPECT_LT((Eigen::Vector3d(g.limit_points.row(0)) - want).norm(), 1e-12);
}

TEST(Subdivision, BadMeshesAreRefusedByName) {
  auto message = [](const SubdivisionMesh& m, int levels = 1) {
    try {
      subdivide(m, levels);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SubdivisionMesh m = grid();
  m.faces[3] = {1, 2};
  EXPECT_NE(message(m).find("face 3 of the control mesh has fewer than 3"), std::string::npos);
  m = grid();
  m.faces[5][2] = 999;
  EXPECT_NE(message(m).find("face 5 names vertex 999"), std::string::npos) << message(m);
  m = grid();
  m.points(7, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(m).find("not finite"), std::string::npos);
  m = grid();
  m.creases.push_back({{0, 9}, 2.0});  // a diagonal of a quad, not an edge
  EXPECT_NE(message(m).find("crease 0-9 is not an edge"), std::string::npos) << message(m);
  m = grid();
  EXPECT_NE(message(m, 9).find("levels must be in 0..8"), std::string::npos);
  EXPECT_NE(message(SubdivisionMesh()).find("no faces"), std::string::npos);
  // A face turned over runs its edges the same way as its neighbours.
  m = grid();
  std::reverse(m.faces[10].begin(), m.faces[10].end());
  EXPECT_NE(message(m).find("inconsistently oriented"), std::string::npos) << message(m);
  // A third face on an edge (a fin) makes the mesh non-manifold.
  m = grid();
  m.points.conservativeResize(m.points.rows() + 1, 3);
  m.points.row(m.points.rows() - 1) << 3.5, 3.5, 9.0;
  m.faces.push_back({3 * kGrid + 4, 3 * kGrid + 3, static_cast<int>(m.points.rows() - 1)});
  m.faces.push_back({3 * kGrid + 3, 3 * kGrid + 4, static_cast<int>(m.points.rows() - 1)});
  EXPECT_NE(message(m).find("not manifold"), std::string::npos) << message(m);
  // A creased edge is accepted and keeps the refined mesh on it sharper than without.
  m = grid();
  m.creases.push_back({{3 * kGrid + 3, 4 * kGrid + 3}, 10.0});
  EXPECT_NO_THROW(subdivide(m, 2));
}
