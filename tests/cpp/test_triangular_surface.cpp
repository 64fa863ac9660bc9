// SPDX-License-Identifier: LGPL-2.1-or-later
// Triangular Bezier surfaces over triangulations (Veltkamp & Wesselink secs. 4 and 6): the control
// numbering shares edges, the orientation is made consistent, bad meshes are refused by name; a
// planar mesh stays planar; fans of every valence and closed meshes (genus 0 and 1) meet G1,
// measured at 50 points along every inner edge; constraints are met exactly; rigid motion,
// scaling and renumbering move the result alike; direct and CG solves agree.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "expect_refused.hpp"
#include "triangle_meshes.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/triangle_net.hpp"
#include "varsurf/core/triangular_surface.hpp"

using namespace varsurf;
using varsurf::test::expect_refused;
using varsurf::test::Mesh;

namespace {

TriangularProblem problem_of(const Mesh& m, int degree) {
  TriangularProblem p;
  p.vertices = m.points;
  p.triangles = m.triangles;
  p.degree = degree;
  return p;
}

// The surface point of input triangle t at barycentric b given in the input's corner order (a
// flipped triangle's corners (c0, c1, c2) became (c0, c2, c1)).
Eigen::Vector3d point_of(const TriangularResult& r, int t, const Eigen::Vector3d& b) {
  const bool flipped = std::binary_search(r.report.flipped.begin(), r.report.flipped.end(), t);
  return r.patches[t].evaluate(flipped ? Eigen::Vector3d(b(0), b(2), b(1)) : b);
}

}  // namespace

TEST(TriangleNet, SharesEdgePointsAndCountsControlPoints) {
  const Mesh m = test::grid_mesh(3, 2, 0.1);
  for (int n = 3; n <= 6; ++n) {
    const TriangleNet net = make_triangle_net(m.points, m.triangles, n);
    const int v = 12, t = 12, e = 23;
    EXPECT_EQ(net.control_count, v + e * (n - 1) + t * (n - 1) * (n - 2) / 2);
    std::set<int> all;
    for (const auto& c : net.control) all.insert(c.begin(), c.end());
    EXPECT_EQ(static_cast<int>(all.size()), net.control_count);  // every point used
    for (int ei = 0; ei < static_cast<int>(net.edges.size()); ++ei) {
      const NetEdge& edge = net.edges[ei];
      const std::vector<int> along = net.edge_points(ei, edge.a);
      EXPECT_EQ(along.front(), edge.a);
      EXPECT_EQ(along.back(), edge.b);
      for (const int side : {edge.left, edge.right}) {
        if (side < 0) continue;
        const auto& corners = side == edge.left ? edge.left_corners : edge.right_corners;
        for (int s = 0; s <= n; ++s) {  // the triangle's own points along the edge
          std::array<int, 3> w{};
          w[corners[0]] = n - s;
          w[corners[1]] = s;
          EXPECT_EQ(net.control[side][triangle_index(n, w[0], w[1])], along[s]);
        }
        const std::vector<int> row = net.edge_row(ei, side, edge.a);
        for (const int p : row) EXPECT_EQ(std::count(along.begin(), along.end(), p), 0);
      }
      if (edge.right >= 0) {  // the inner edge runs a -> b in left, b -> a in right
        EXPECT_EQ((edge.left_corners[0] + 1) % 3, edge.left_corners[1]);
        EXPECT_EQ((edge.right_corners[1] + 1) % 3, edge.right_corners[0]);
      }
    }
  }
}

TEST(TriangleNet, OrientsTrianglesAlike) {
  Mesh m = test::icosahedron();
  const std::vector<int> reversed{2, 5, 11, 17};
  for (const int t : reversed) std::swap(m.triangles[t][1], m.triangles[t][2]);
  const TriangleNet net = make_triangle_net(m.points, m.triangles, 3);
  // The first triangle keeps its order, so exactly the reversed ones are flipped back.
  EXPECT_EQ(net.flipped, reversed);
  for (const NetEdge& e : net.edges) EXPECT_GE(e.right, 0);  // closed
}

TEST(TriangleNet, RefusesBadMeshesByName) {
  const Mesh grid = test::grid_mesh(1, 1, 0.0);
  expect_refused([&] { make_triangle_net(grid.points, grid.triangles, 2); }, "degree 3 to 12");
  expect_refused([&] { make_triangle_net(grid.points, {}, 3); }, "at least one triangle");
  expect_refused([&] { make_triangle_net(grid.points, {{0, 1, 7}}, 3); }, "names vertex 7");
  expect_refused(
      [&] {
        make_triangle_net(grid.points, {{0, 1, 1}}, 3);
      },
      "triangle 0 repeats a corner");
  Eigen::MatrixX3d line(3, 3);
  line << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  expect_refused([&] { make_triangle_net(line, {{0, 1, 2}}, 3); }, "triangle 0 has no area");
  Eigen::MatrixX3d five(5, 3);
  five << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  expect_refused(
      [&] {
        make_triangle_net(five, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}, 3);
      },
      "edge (0, 1) is shared by more than two triangles");
  Eigen::MatrixX3d bow(5, 3);
  bow << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
  expect_refused(
      [&] {
        make_triangle_net(bow, {{0, 1, 2}, {0, 3, 4}}, 3);
      },
      "vertex 0 joins separate fans");
  expect_refused(
      [&] {
        make_triangle_net(five, {{0, 1, 2}}, 3);
      },
      "vertex 3 belongs to no triangle");
  // A Moebius strip of five triangles.
  Eigen::MatrixX3d strip(5, 3);
  for (int i = 0; i < 5; ++i) {
    const double a = 2.0 * M_PI * i / 5.0;
    strip.row(i) << std::cos(a), std::sin(a), (i % 2 ? 0.3 : -0.3);
  }
  expect_refused(
      [&] {
        make_triangle_net(strip, {{0, 1, 2}, {1, 2, 3}, {2, 3, 4}, {3, 4, 0}, {4, 0, 1}}, 3);
      },
      "cannot be oriented alike");
}

TEST(TriangularSurface, PlanarMeshStaysPlanar) {
  Mesh m = test::grid_mesh(4, 3, 0.25);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  m.points = (m.points * turn.transpose()).rowwise() + Eigen::RowVector3d(3.0, -1.0, 2.0);
  const Eigen::Vector3d normal = turn * Eigen::Vector3d::UnitZ();
  for (int n = 3; n <= 5; ++n) {
    const TriangularResult r = solve_triangular(problem_of(m, n));
    const Eigen::VectorXd off = (r.control.rowwise() - m.points.row(0)) * normal;
    // The G1 weight (1e6 over the energy's) costs accuracy: the solve's error is about 1e-9 of
    // the model's size (4 here).
    EXPECT_LT(off.cwiseAbs().maxCoeff(), 4 * 5e-9) << n;
    EXPECT_LT(r.report.worst_angle, 1e-5) << n;
    EXPECT_TRUE(r.report.overruled_edges.empty());
  }
}

TEST(TriangularSurface, FansOfEveryValenceMeetG1) {
  // A raised inner vertex over a wavy border: the mesh as drawn creases by tens of degrees.
  for (int k = 3; k <= 7; ++k)
    for (const int n : {3, 5}) {
      const TriangularResult r = solve_triangular(problem_of(test::fan_mesh(k, 0.6), n));
      EXPECT_EQ(r.report.edges_measured, k);
      EXPECT_LT(r.report.worst_angle, 0.01) << k << " " << n;
      EXPECT_TRUE(r.report.overruled_edges.empty()) << k << " " << n;
      if (k == 4) {
        // e = 0 at the centre: its conditions are met only by collapsing two opposite tangents
        // there (the vertex enclosure problem of even valences), which the report names.
        EXPECT_LT(r.report.shortest_tangent, 1e-6);
        EXPECT_EQ(r.report.singular_vertices, std::vector<int>{0});
      } else {
        EXPECT_GT(r.report.shortest_tangent, 0.1) << k << " " << n;
        EXPECT_TRUE(r.report.singular_vertices.empty()) << k << " " << n;
      }
      // Without G1 the same fan creases.
      TriangularProblem off = problem_of(test::fan_mesh(k, 0.6), n);
      off.g1 = false;
      EXPECT_GT(solve_triangular(off).report.worst_angle, 1.0) << k;
    }
}

TEST(TriangularSurface, ClosedMeshesBecomeSmoothClosedSurfaces) {
  const std::vector<Mesh> meshes{test::tetrahedron(), test::octahedron(), test::icosahedron(),
                                 test::torus_mesh(8, 6)};
  for (std::size_t i = 0; i < meshes.size(); ++i)
    for (int n = 3; n <= 4; ++n) {
      TriangularProblem p = problem_of(meshes[i], n);
      p.equilateral_domain = n == 3;  // both domains: their eq. 25, and the mesh's triangles
      const TriangularResult r = solve_triangular(p);
      EXPECT_EQ(r.report.edges_measured, static_cast<int>(meshes[i].triangles.size() * 3 / 2));
      EXPECT_LT(r.report.worst_angle, 0.01) << i << " " << n;
      EXPECT_GT(r.report.shortest_tangent, 0.1) << i << " " << n;
      for (int v = 0; v < meshes[i].points.rows(); ++v)  // the vertices interpolated
        EXPECT_EQ((r.control.row(v) - meshes[i].points.row(v)).norm(), 0.0);
    }
}

TEST(TriangularSurface, ConstraintsAreMetExactly) {
  const Mesh m = test::icosahedron();
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(1.0 / 3.0);
  TriangularProblem p = problem_of(m, 4);
  TriangularConstraint pull;
  pull.triangle = 3;
  pull.at = centre;
  const Eigen::Vector3d flat =
      (m.points.row(0) + m.points.row(7) + m.points.row(10)).transpose() / 3.0;
  pull.target = 1.4 * flat;
  TriangularConstraint normal;
  normal.kind = TriangularConstraint::Kind::normal;
  normal.triangle = 12;
  normal.at = Eigen::Vector3d(0.2, 0.5, 0.3);
  normal.direction = Eigen::Vector3d(0.1, -1.0, 0.3);
  TriangularConstraint plane;
  plane.kind = TriangularConstraint::Kind::plane;
  plane.triangle = 15;
  plane.target = Eigen::Vector3d(0.0, 0.0, 1.5);
  plane.direction = Eigen::Vector3d(0.0, 0.2, 1.0);
  TriangularConstraint line;
  line.kind = TriangularConstraint::Kind::line;
  line.triangle = 8;
  line.at = Eigen::Vector3d(0.6, 0.2, 0.2);
  line.target = Eigen::Vector3d(0.0, -1.2, -1.2);
  line.direction = Eigen::Vector3d(1.0, 0.0, 0.0);
  p.constraints = {pull, normal, plane, line};
  const TriangularResult r = solve_triangular(p);
  EXPECT_EQ(r.report.constraint_rows, 3 + 2 + 1 + 2);
  EXPECT_LT((r.patches[3].evaluate(centre) - pull.target).norm(), 1e-9);
  const TriangularBezier& t12 = r.patches[12];
  const Eigen::Vector3d du = t12.derivative(Eigen::Vector3d(-1, 1, 0)).evaluate(normal.at);
  const Eigen::Vector3d dv = t12.derivative(Eigen::Vector3d(-1, 0, 1)).evaluate(normal.at);
  EXPECT_LT(du.cross(dv).normalized().cross(normal.direction.normalized()).norm(), 1e-9);
  EXPECT_LT(std::abs((r.patches[15].evaluate(centre) - plane.target).dot(plane.direction)), 1e-9);
  const Eigen::Vector3d on = r.patches[8].evaluate(line.at) - line.target;
  EXPECT_LT(on.cross(line.direction).norm(), 1e-9);
  EXPECT_LT(r.report.constraint_residual, 1e-9);
  // The pull moved the surface out there, and the vertices stayed.
  EXPECT_GT((solve_triangular(problem_of(m, 4)).patches[3].evaluate(centre) - pull.target).norm(),
            0.1);
  for (int v = 0; v < 12; ++v) EXPECT_EQ((r.control.row(v) - m.points.row(v)).norm(), 0.0);

  // Two targets for one point conflict: least squares puts it halfway and reports the rest.
  TriangularProblem both = problem_of(m, 4);
  TriangularConstraint other = pull;
  other.target = pull.target + Eigen::Vector3d(0.0, 0.0, 0.1);
  both.constraints = {pull, other};
  const TriangularResult split = solve_triangular(both);
  EXPECT_NEAR(split.report.constraint_residual, 0.05, 1e-8);
  EXPECT_LT((split.patches[3].evaluate(centre) - 0.5 * (pull.target + other.target)).norm(), 1e-8);
}

TEST(TriangularSurface, MovesRigidlyAndScalesWithTheScene) {
  const Mesh m = test::torus_mesh(8, 6);
  const TriangularResult base = solve_triangular(problem_of(m, 4));
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(-0.3, 0.8, 0.5).normalized()).toRotationMatrix();
  const Eigen::RowVector3d shift(12.0, -7.0, 3.0);
  for (const double scale : {1e-3, 1.0, 1e4}) {
    Mesh moved = m;
    moved.points = ((scale * m.points) * turn.transpose()).rowwise() + scale * shift;
    const TriangularResult r = solve_triangular(problem_of(moved, 4));
    const Eigen::MatrixX3d expected =
        ((scale * base.control) * turn.transpose()).rowwise() + scale * shift;
    // The size is 3 scale; the solve's error 1e-9 of it (see PlanarMeshStaysPlanar).
    EXPECT_LT((r.control - expected).cwiseAbs().maxCoeff(), 3 * scale * 2e-8) << scale;
    EXPECT_LT(r.report.worst_angle, 0.01);
  }
}

TEST(TriangularSurface, RenumberingAndReversingChangeNothing) {
  const Mesh m = test::icosahedron();
  const TriangularResult base = solve_triangular(problem_of(m, 3));
  // Triangles listed backwards, each with its corners rotated, half of them reversed.
  Mesh other = m;
  std::reverse(other.triangles.begin(), other.triangles.end());
  for (std::size_t t = 0; t < other.triangles.size(); ++t) {
    auto& c = other.triangles[t];
    std::rotate(c.begin(), c.begin() + 1, c.end());
    if (t % 2) std::swap(c[1], c[2]);
  }
  const TriangularResult r = solve_triangular(problem_of(other, 3));
  const int tcount = static_cast<int>(m.triangles.size());
  for (int t = 0; t < tcount; ++t) {
    const int o = tcount - 1 - t;
    for (const Eigen::Vector3d& b :
         {Eigen::Vector3d(0.2, 0.3, 0.5), Eigen::Vector3d(0.6, 0.1, 0.3)}) {
      // Triangle t's corners (c0, c1, c2) are other's (c1, c2, c0), reversed for odd o.
      const Eigen::Vector3d rotated(b(1), b(2), b(0));
      const Eigen::Vector3d given =
          o % 2 ? Eigen::Vector3d(rotated(0), rotated(2), rotated(1)) : rotated;
      const Eigen::Vector3d ours = point_of(base, t, b);
      const Eigen::Vector3d theirs = point_of(r, o, given);
      EXPECT_LT((ours - theirs).norm(), 1e-9) << t;
    }
  }
}

TEST(TriangularSurface, ConjugateGradientsAgreeWithTheDirectSolve) {
  TriangularProblem p = problem_of(test::torus_mesh(8, 6), 4);
  p.solver = TriangularSolver::direct;
  const TriangularResult direct = solve_triangular(p);
  p.solver = TriangularSolver::cg;
  const TriangularResult cg = solve_triangular(p);
  EXPECT_EQ(direct.report.solver, "direct");
  EXPECT_EQ(cg.report.solver, "cg");
  EXPECT_GT(cg.report.cg_iterations, 0);
  EXPECT_LT((direct.control - cg.control).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(TriangularSurface, RefusesBadInputByName) {
  const Mesh m = test::icosahedron();
  TriangularProblem p = problem_of(m, 3);
  TriangularConstraint c;
  c.triangle = 20;
  p.constraints = {c};
  expect_refused([&] { solve_triangular(p); }, "constraint 0 names triangle 20");
  p.constraints[0].triangle = 0;
  p.constraints[0].at = Eigen::Vector3d(1.2, -0.1, -0.1);
  expect_refused([&] { solve_triangular(p); }, "constraint 0 lies outside its triangle");
  p.constraints[0].at = Eigen::Vector3d::Constant(1.0 / 3.0);
  p.constraints[0].kind = TriangularConstraint::Kind::normal;
  p.constraints[0].direction.setZero();
  expect_refused([&] { solve_triangular(p); }, "constraint 0 has a zero direction");
  // A pillow of two triangles: every vertex has two patches inside the surface.
  Eigen::MatrixX3d three(3, 3);
  three << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  TriangularProblem pillow;
  pillow.vertices = three;
  pillow.triangles = {{0, 1, 2}, {0, 2, 1}};
  expect_refused([&] { solve_triangular(pillow); }, "vertex 0 cannot be made G1");
  TriangularProblem weights = problem_of(m, 3);
  weights.stretch = weights.bend = 0.0;
  expect_refused([&] { solve_triangular(weights); }, "not both 0");
  TriangularProblem loose = problem_of(m, 3);
  loose.interpolate_vertices = false;
  expect_refused([&] { solve_triangular(loose); }, "nothing holds the triangular surface");
}

TEST(TriangularSurface, FixedEdgesCarryTheirCurvesExactly) {
  // Their sec. 4.2: a cubic curve set as the control points of a chain of edges is contained by
  // the surface exactly; the surface stays G1 across it (the curve is one of its inner edges).
  const test::Mesh m = test::grid_mesh(4, 2, 0.0);  // edges along y = 0.5 from (0, .5) to (1, .5)
  TriangularProblem p = problem_of(m, 4);
  const auto curve = [](double x) {
    return Eigen::Vector3d(x, 0.5, 0.3 * x * (1.0 - x) * (1.0 + x));  // a cubic in x
  };
  for (int i = 0; i < 4; ++i) {
    // Vertices 5 + i and 6 + i lie on y = 0.5; the piece of the cubic between them, as a quartic
    // Bezier: its points are the blossom at (a^(4-k), b^k) of the cubic elevated, here by sampling
    // and solving (exact for a polynomial of degree <= 4).
    const double a = i / 4.0, b = (i + 1) / 4.0;
    Eigen::MatrixXd basis(5, 5);
    Eigen::MatrixX3d values(5, 3);
    for (int s = 0; s <= 4; ++s) {
      const double t = s / 4.0;
      for (int k = 0; k <= 4; ++k)
        basis(s, k) = std::tgamma(5.0) / (std::tgamma(k + 1.0) * std::tgamma(5.0 - k)) *
                      std::pow(t, k) * std::pow(1 - t, 4 - k);
      values.row(s) = curve(a + t * (b - a)).transpose();
    }
    p.fixed_edges.push_back({5 + i, 6 + i, basis.partialPivLu().solve(values)});
  }
  p.interpolate_vertices = true;
  // The vertices on the curve move to it (the fixed edges overrule the mesh's positions).
  const TriangularResult r = solve_triangular(p);
  const TriangleNet net = make_triangle_net(m.points, m.triangles, 4);
  double worst = 0.0;
  for (int i = 0; i < 4; ++i) {
    const int e = net.edge(5 + i, 6 + i);
    const NetEdge& edge = net.edges[e];
    TriangularBezier patch = r.patches[edge.left];
    for (int s = 0; s <= 20; ++s) {
      const double t = s / 20.0;
      Eigen::Vector3d bary = Eigen::Vector3d::Zero();
      const int from = edge.a == 5 + i ? edge.left_corners[0] : edge.left_corners[1];
      const int to = edge.a == 5 + i ? edge.left_corners[1] : edge.left_corners[0];
      bary(from) = 1.0 - t;
      bary(to) = t;
      worst = std::max(worst, (patch.evaluate(bary) - curve((i + t) / 4.0)).norm());
    }
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(r.report.worst_angle, 0.01);
  // Bad fixed edges are named.
  TriangularProblem bad = problem_of(m, 4);
  bad.fixed_edges = {{0, 14, Eigen::MatrixX3d::Zero(5, 3)}};
  expect_refused([&] { solve_triangular(bad); }, "fixed edge 0 joins vertices 0 and 14");
  bad.fixed_edges = {{0, 1, Eigen::MatrixX3d::Zero(3, 3)}};
  expect_refused([&] { solve_triangular(bad); }, "fixed edge 0 has 3 points");
  // The first edge ends at vertex 1 at the origin, the second starts there at (5, 5, 5).
  const Eigen::MatrixX3d first = Eigen::MatrixX3d::Zero(5, 3);
  Eigen::MatrixX3d second = Eigen::MatrixX3d::Zero(5, 3);
  second.row(0) << 5.0, 5.0, 5.0;
  bad.fixed_edges = {{0, 1, first}, {1, 2, second}};
  expect_refused([&] { solve_triangular(bad); }, "put vertex 1 at different places");
}

TEST(TriangularSurface, FreeVerticesAreLeftToTheEnergy) {
  // A vertex a split added off the curves shapes only the control structure: raised above a
  // flat hexagon, it is not interpolated, and the fairest surface through the ring is the plane.
  Mesh m = test::fan_mesh(6, 0.7);
  for (int i = 1; i <= 6; ++i) m.points(i, 2) = 0.0;
  TriangularProblem p = problem_of(m, 4);
  p.free_vertices = {0};
  const TriangularResult r = solve_triangular(p);
  EXPECT_LT(r.control.col(2).cwiseAbs().maxCoeff(), 2 * 5e-9);
  EXPECT_LT(r.report.worst_angle, 1e-5);
  // Interpolated, it stays where it is.
  p.free_vertices.clear();
  EXPECT_NEAR(solve_triangular(p).control(0, 2), 0.7, 1e-12);
  p.free_vertices = {7};
  expect_refused([&] { solve_triangular(p); }, "free vertex 7 is not a vertex of the mesh");
}
