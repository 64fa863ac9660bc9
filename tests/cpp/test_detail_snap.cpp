// SPDX-License-Identifier: LGPL-2.1-or-later
// The re-parameterization along curves (Boier-Martin et al., Appendix) and pins held on the limit
// surface, against independent answers: vertices slid along a plane stay on it and the rest of
// the surface keeps its details bit for bit; on a captured relief the snapped surface lies on
// the relief as closely as the capture did; a pin on the limit surface puts the finished surface,
// finer details and all, through its target at every level and with every solve.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "flat_grid.hpp"
#include "varsurf/core/detail_edit.hpp"
#include "varsurf/core/errors.hpp"

using namespace varsurf;

namespace {

constexpr double kSpacing = 10.0;
constexpr int kCells = 8;
constexpr double kSize = kSpacing * kCells;

SubdivisionMesh plane() {
  return test::flat_grid(kCells, kSpacing);
}

double height(double x, double y) {
  const double k = 2.0 * M_PI / 20.0;
  return 1.5 * std::sin(k * x) * std::cos(k * y);
}

// The relief over the plane, reached vertically (the capture's and the snap's "closest").
Eigen::Vector3d relief(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), height(p.x(), p.y())};
}
Eigen::Vector3d flat(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), 0.0};
}

// The vertices of `level` within `reach` of the line y = c, with their feet on it at height h.
void near_line(const Eigen::MatrixX3d& points, double c, double reach, bool on_relief,
               std::vector<int>& vertices, Eigen::MatrixX3d& targets) {
  std::vector<Eigen::Vector3d> feet;
  for (Eigen::Index v = 0; v < points.rows(); ++v)
    if (std::abs(points(v, 1) - c) < reach && points(v, 0) > 5.0 && points(v, 0) < kSize - 5.0) {
      vertices.push_back(static_cast<int>(v));
      const double x = points(v, 0);
      feet.emplace_back(x, c, on_relief ? height(x, c) : 0.0);
    }
  targets.resize(static_cast<Eigen::Index>(feet.size()), 3);
  for (size_t k = 0; k < feet.size(); ++k)
    targets.row(static_cast<Eigen::Index>(k)) = feet[k].transpose();
}

}  // namespace

TEST(DetailSnap, VerticesSlidAlongAPlaneStayOnItAndTheRestKeepsItsDetails) {
  const int levels = 3;
  const Multiresolution m = capture(plane(), levels, flat);
  const DetailEditor editor(m.base, levels);
  const std::vector<Eigen::MatrixX3d> before = editor.points(m);
  const double c = 33.3;  // between the level-2 rows at 32.5 and 35
  std::vector<int> vertices;
  Eigen::MatrixX3d targets;
  near_line(before[2], c, 0.6 * kSpacing / 4, false, vertices, targets);
  ASSERT_GE(vertices.size(), 20u);
  const Multiresolution snapped = editor.snap(m, 2, vertices, targets, flat);
  const std::vector<Eigen::MatrixX3d> after = editor.points(snapped);
  // The snapped vertices sit on the line at their level and at every finer one but the finest,
  // where their limit points do.
  for (int level = 2; level < levels; ++level)
    for (size_t k = 0; k < vertices.size(); ++k)
      EXPECT_LT((after[static_cast<size_t>(level)].row(vertices[k]) -
                 targets.row(static_cast<Eigen::Index>(k)))
                    .norm(),
                1e-12 * kSize)
          << level;
  // (all but a row's two ends, which have a snapped neighbour on one side only and would have to
  // move more than half an edge: they stop there, nearer than before).
  const Eigen::MatrixX3d limit = editor.limit(snapped), old_limit = editor.limit(m);
  size_t met = 0;
  for (size_t k = 0; k < vertices.size(); ++k) {
    const Eigen::RowVector3d target = targets.row(static_cast<Eigen::Index>(k));
    const double now = (limit.row(vertices[k]) - target).norm();
    met += now < 1e-11 * kSize;
    EXPECT_LT(now, 0.5 * (old_limit.row(vertices[k]) - target).norm()) << vertices[k];
  }
  EXPECT_GE(met, vertices.size() - 2);
  // The shape stays: the plane's limit surface is still the plane.
  EXPECT_LT(editor.limit(snapped).col(2).cwiseAbs().maxCoeff(), 1e-12 * kSize);
  // Locality: vertices three level-2 edges from the line keep their finest points bit for bit.
  int far = 0;
  for (Eigen::Index v = 0; v < after.back().rows(); ++v)
    if (std::abs(before.back()(v, 1) - c) > 3.0 * kSpacing / 4) {
      EXPECT_EQ(after.back().row(v), before.back().row(v)) << v;
      ++far;
    }
  EXPECT_GT(far, after.back().rows() / 2);
}

TEST(DetailSnap, ASnapOnACapturedReliefLiesOnItAsCloselyAsTheCapture) {
  const int levels = 4;
  const Multiresolution m = capture(plane(), levels, relief);
  const DetailEditor editor(m.base, levels);
  const auto off_relief = [&](const Multiresolution& s) {
    const Eigen::MatrixX3d limit = editor.limit(s);
    double worst = 0.0;
    for (Eigen::Index v = 0; v < limit.rows(); ++v)
      worst = std::max(worst, std::abs(limit(v, 2) - height(limit(v, 0), limit(v, 1))));
    return worst;
  };
  std::vector<int> vertices;
  Eigen::MatrixX3d targets;
  near_line(editor.points(m)[3], 41.1, 0.6 * kSpacing / 8, true, vertices, targets);
  ASSERT_GE(vertices.size(), 40u);
  const Multiresolution snapped = editor.snap(m, 3, vertices, targets, relief);
  const double captured = off_relief(m), now = off_relief(snapped);
  std::printf("limit off the relief: captured %.3g, snapped %.3g\n", captured, now);
  EXPECT_LT(now, 1.5 * captured);
  // The snapped limit points lie on the relief at their targets.
  const Eigen::MatrixX3d limit = editor.limit(snapped);
  for (size_t k = 0; k < vertices.size(); ++k)
    EXPECT_LT((limit.row(vertices[k]) - targets.row(static_cast<Eigen::Index>(k))).norm(),
              1e-11 * kSize);
}

TEST(DetailSnap, APinOnTheLimitPutsTheFinishedSurfaceThroughItsTarget) {
  const int levels = 3;
  const Multiresolution m = capture(plane(), levels, relief);
  const DetailEditor editor(m.base, levels);
  const Eigen::MatrixX3d limit = editor.limit(m);
  const Eigen::MatrixX3d finest = editor.points(m).back();
  // Vertices of the base (0), of level 2 and of the finest level, each held on the limit.
  const int base_vertex = 4 * (kCells + 1) + 4;  // the base's (40, 40)
  int fine = 0, middle = 0;
  (finest.leftCols(2).rowwise() - Eigen::RowVector2d(21.25, 57.5))
      .rowwise()
      .squaredNorm()
      .minCoeff(&fine);
  (editor.points(m)[2].leftCols(2).rowwise() - Eigen::RowVector2d(62.5, 25.0))
      .rowwise()
      .squaredNorm()
      .minCoeff(&middle);
  const std::vector<DetailPin> pins{
      {0, base_vertex, limit.row(base_vertex).transpose() + Eigen::Vector3d(0, 0, 9.0), 0, true},
      {2, middle, limit.row(middle).transpose() + Eigen::Vector3d(1.0, -2.0, 4.0), 1, true},
      {3, fine, limit.row(fine).transpose() + Eigen::Vector3d(0.5, 0.5, -3.0), 2, true}};
  for (const DetailSolve solve :
       {DetailSolve::approximate, DetailSolve::direct, DetailSolve::sor}) {
    DetailEditOptions options;
    options.solve = solve;
    const DetailEditResult r = editor.edit(m, pins, options);
    const Eigen::MatrixX3d after = editor.limit(r.surface);
    for (const DetailPin& pin : pins)
      EXPECT_LT((after.row(pin.vertex).transpose() - pin.target).norm(), 2e-9 * kSize)
          << pin.level << " " << static_cast<int>(solve);
    EXPECT_LT(r.report.max_residual, 2e-9 * kSize);
    // The same pins on control points put the control points there, and the limit elsewhere.
    std::vector<DetailPin> control = pins;
    for (DetailPin& pin : control) pin.on_limit = false;
    const DetailEditResult c = editor.edit(m, control, options);
    EXPECT_GT((editor.limit(c.surface).row(fine).transpose() - pins[2].target).norm(), 1e-3);
  }
}

TEST(DetailSnap, BadSnapsAreRefusedByName) {
  const Multiresolution m = capture(plane(), 2, flat);
  const DetailEditor editor(m.base, 2);
  const Eigen::MatrixX3d one = Eigen::RowVector3d(1.0, 2.0, 0.0);
  const auto refused = [&](int level, std::vector<int> vertices, const Eigen::MatrixX3d& targets,
                           const std::string& words) {
    try {
      editor.snap(m, level, vertices, targets, flat);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused(3, {0}, one, "level 3 does not exist");
  refused(1, {100000}, one, "not 100000");
  refused(1, {5, 5}, Eigen::MatrixX3d::Zero(2, 3), "vertex 5 is snapped twice");
  refused(1, {5, 6}, one, "one target per vertex");
  refused(1, {5}, Eigen::RowVector3d(NAN, 0.0, 0.0), "not finite");
}
