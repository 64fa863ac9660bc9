// SPDX-License-Identifier: LGPL-2.1-or-later
// The chain of mesh vertices that follows a curve on the surface (Boier-Martin et al.'s curve
// constraints): on a regular grid, against the grid's own geometry: consecutive vertices share a
// face, every vertex lies within half a face diagonal of the curve and the curve within that of
// the chain, the parameters follow the curve, a closed curve closes, a reversed curve gives the
// reversed chain, a rigid motion of the scene gives the same chain, and a curve off the surface
// is refused.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "flat_grid.hpp"
#include "varsurf/core/curve_chain.hpp"
#include "varsurf/core/detail_edit.hpp"
#include "varsurf/core/errors.hpp"

using namespace varsurf;

namespace {

constexpr double kEdge = 2.0;
constexpr int kCells = 30;

SubdivisionMesh grid() {
  return test::flat_grid(kCells, kEdge);
}

bool share_a_face(const SubdivisionMesh& m, int a, int b) {
  return std::any_of(m.faces.begin(), m.faces.end(), [&](const std::vector<int>& f) {
    return std::count(f.begin(), f.end(), a) && std::count(f.begin(), f.end(), b);
  });
}

Eigen::MatrixX3d circle(double cx, double cy, double r, int samples, bool reversed = false) {
  Eigen::MatrixX3d c(samples + 1, 3);
  for (int k = 0; k <= samples; ++k) {
    const double t = (reversed ? -2.0 : 2.0) * M_PI * k / samples;
    c.row(k) << cx + r * std::cos(t), cy + r * std::sin(t), 0.0;
  }
  return c;
}

}  // namespace

TEST(CurveChain, ACircleOnAGridClosesThroughVerticesThatShareFaces) {
  const SubdivisionMesh m = grid();
  const CurveChain chain = curve_chain(m, circle(30.0, 30.0, 17.0, 90));
  ASSERT_TRUE(chain.closed);
  const size_t n = chain.vertices.size();
  // About the circle's length over the mean step (an edge or a diagonal).
  EXPECT_GT(n, static_cast<size_t>(2 * M_PI * 17.0 / (kEdge * std::sqrt(2.0))));
  for (size_t k = 0; k < n; ++k)
    EXPECT_TRUE(share_a_face(m, chain.vertices[k], chain.vertices[(k + 1) % n])) << k;
  const double half_diagonal = kEdge * std::sqrt(0.5);
  EXPECT_LE(chain.max_distance, half_diagonal);
  EXPECT_LE(chain.max_gap, half_diagonal);
  for (size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d p = m.points.row(chain.vertices[k]).transpose();
    EXPECT_NEAR(std::hypot(p.x() - 30.0, p.y() - 30.0), 17.0, half_diagonal + 1e-12);
  }
  // The parameters run once around.
  int descents = 0;
  for (size_t k = 1; k < n; ++k) descents += chain.parameters[k] < chain.parameters[k - 1];
  EXPECT_LE(descents, 1);
  // The reversed circle: the same vertices in the other direction.
  const CurveChain back = curve_chain(m, circle(30.0, 30.0, 17.0, 90, true));
  EXPECT_EQ(std::set<int>(back.vertices.begin(), back.vertices.end()),
            std::set<int>(chain.vertices.begin(), chain.vertices.end()));
  const auto at = std::find(chain.vertices.begin(), chain.vertices.end(), back.vertices[1]);
  ASSERT_NE(at, chain.vertices.end());
  const size_t i = static_cast<size_t>(at - chain.vertices.begin());
  EXPECT_EQ(chain.vertices[(i + 1) % n], back.vertices[0]);
}

TEST(CurveChain, RigidMotionsGiveTheSameChainWhereTheCurvePassesVerticesAtEqualDistances) {
  // A circle centred on a vertex, of a radius an odd number of half edges: its samples pass
  // pairs of vertices at equal distances, which rounding in a moved scene told apart.
  const SubdivisionMesh m = grid();
  const Eigen::MatrixX3d curve = circle(30.0, 30.0, 5.0 * kEdge / 2.0, 64);
  const CurveChain reference = curve_chain(m, curve);
  std::srand(7);
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI * (std::rand() / double(RAND_MAX)),
                                                   Eigen::Vector3d::Random().normalized())
                                     .toRotationMatrix();
    const Eigen::RowVector3d move = 1000.0 * Eigen::RowVector3d::Random();
    SubdivisionMesh moved = m;
    moved.points = (m.points * turn.transpose()).rowwise() + move;
    const Eigen::MatrixX3d moved_curve = (curve * turn.transpose()).rowwise() + move;
    EXPECT_EQ(curve_chain(moved, moved_curve).vertices, reference.vertices) << "trial " << trial;
  }
}

TEST(CurveChain, AnOpenLineRunsFromEndToEnd) {
  const SubdivisionMesh m = grid();
  Eigen::MatrixX3d line(2, 3);
  line << 3.1, 5.2, 0.0, 51.7, 40.3, 0.0;
  const CurveChain chain = curve_chain(m, line);
  EXPECT_FALSE(chain.closed);
  EXPECT_TRUE(std::is_sorted(chain.parameters.begin(), chain.parameters.end()));
  EXPECT_LT(chain.parameters.front(), 0.05);
  EXPECT_GT(chain.parameters.back(), 0.95);
  for (size_t k = 1; k < chain.vertices.size(); ++k)
    EXPECT_TRUE(share_a_face(m, chain.vertices[k - 1], chain.vertices[k]));
  EXPECT_LE(chain.max_distance, kEdge * std::sqrt(0.5));
}

TEST(CurveChain, BadCurvesAreRefused) {
  const SubdivisionMesh m = grid();
  Eigen::MatrixX3d off(2, 3);
  off << 10.0, 10.0, 0.0, 10.0, 10.0, 50.0;
  EXPECT_THROW(curve_chain(m, off), InvalidInput);
  Eigen::MatrixX3d point(2, 3);
  point << 1.0, 1.0, 0.0, 1.0, 1.0, 0.0;
  EXPECT_THROW(curve_chain(m, point), InvalidInput);
  Eigen::MatrixX3d nan(2, 3);
  nan << 1.0, NAN, 0.0, 3.0, 1.0, 0.0;
  EXPECT_THROW(curve_chain(m, nan), InvalidInput);
}

namespace {

// A single 100 x 100 quad refined 5 times, its corners given in `order`; the vertices of the
// finest level along a circle of radius 25 lifted by 15 and tilted 10 degrees about x, solved at
// influence 3 (where their masks are dependent). The limit surface.
Eigen::MatrixX3d lifted_circle(const std::vector<int>& order, DetailSolve solve) {
  SubdivisionMesh quad;
  quad.points.resize(4, 3);
  quad.points << -50, -50, 0, -50, 50, 0, 50, -50, 0, 50, 50, 0;
  quad.faces = {order};
  const int levels = 5;
  const Multiresolution m = capture(quad, levels, [](const Eigen::Vector3d& p) { return p; });
  const DetailEditor editor(m.base, levels);
  const Eigen::MatrixX3d finest = editor.points(m).back();
  SubdivisionMesh level = editor.topology(levels);
  level.points = finest;
  const CurveChain chain = curve_chain(level, [] {
    Eigen::MatrixX3d c(201, 3);
    for (int k = 0; k <= 200; ++k)
      c.row(k) << 25 * std::cos(2 * M_PI * k / 200), 25 * std::sin(2 * M_PI * k / 200), 0.0;
    return c;
  }());
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
  std::vector<DetailPin> pins;
  for (const int v : chain.vertices)
    pins.push_back({levels, v, turn * finest.row(v).transpose() + Eigen::Vector3d(0, 0, 15), 3});
  DetailEditOptions options;
  options.solve = solve;
  const DetailEditResult r = editor.edit(m, pins, options);
  EXPECT_LT(r.report.max_residual, 1e-6);
  return editor.limit(r.surface);
}

}  // namespace

TEST(CurveChain, PinsAlongACurveSolvedWhereTheirMasksAreDependentStayBounded) {
  // SparseLU factored this KKT system (64 pins' masks on level 3's 81 vertices, dependent)
  // without reporting it and swung the surface by 5e7 for one corner order of the same quad; the
  // probe solve now sends it to the least-squares path. Both corner orders give the same surface
  // (the points compared as sets: the numbering differs), within the lift's range.
  // Approximate and SOR take the masks' least-norm move: sparsely, or densely for dependent masks
  // as these are (the sparse factorization's probe sends them there).
  for (const DetailSolve solve :
       {DetailSolve::direct, DetailSolve::sor, DetailSolve::approximate}) {
    const Eigen::MatrixX3d a = lifted_circle({0, 2, 3, 1}, solve);
    const Eigen::MatrixX3d b = lifted_circle({1, 0, 2, 3}, solve);
    for (const Eigen::MatrixX3d* s : {&a, &b}) {
      EXPECT_GT(s->col(2).minCoeff(), -10.0);
      EXPECT_LT(s->col(2).maxCoeff(), 30.0);
    }
    double worst = 0.0;
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      worst =
          std::max(worst, std::sqrt((b.rowwise() - a.row(i)).rowwise().squaredNorm().minCoeff()));
    EXPECT_LT(worst, 1e-6) << static_cast<int>(solve);
  }
}
