// SPDX-License-Identifier: LGPL-2.1-or-later
// External energy operators on triangular surfaces (Veltkamp & Wesselink sec. 5) through the
// terms sheets use: the patches' quadrature integrates products of Bernstein polynomials exactly
// (the point attractor's matrix is the Gram matrix); attractors, a director, a repeller and a
// shape attractor move a fan as they should, a shape attractor onto a plane is the plane
// attractor, and bad operators are refused by name.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numeric>

#include "expect_refused.hpp"
#include "triangle_meshes.hpp"
#include "varsurf/core/operator_terms.hpp"
#include "varsurf/core/triangle_domain.hpp"
#include "varsurf/core/triangular_energy.hpp"
#include "varsurf/core/triangular_surface.hpp"

using namespace varsurf;
using varsurf::test::expect_refused;

namespace {

// A flat hexagonal fan in z = 0 (no G1 needed to see the operators; kept on).
TriangularProblem flat_fan(int degree = 4) {
  TriangularProblem p;
  const test::Mesh m = test::fan_mesh(6, 0.0);
  p.vertices = m.points;
  p.vertices.col(2).setZero();
  p.triangles = m.triangles;
  p.degree = degree;
  return p;
}

// The height of patch 0 near the fan's middle vertex (which is held at z = 0).
double centre_height(const TriangularResult& r) {
  return r.patches[0].evaluate(Eigen::Vector3d(0.4, 0.3, 0.3)).z();
}

// The mean over points of every patch of what an attractor measures: the squared distance to
// `origin` across `metric` (I: a point, n n^T: a plane).
double mean_pull(const TriangularResult& r, const Eigen::Vector3d& origin,
                 const Eigen::Matrix3d& metric) {
  double sum = 0.0;
  int count = 0;
  for (const auto& patch : r.patches)
    for (int i = 0; i <= 6; ++i)
      for (int j = 0; i + j <= 6; ++j, ++count) {
        const Eigen::Vector3d d = patch.evaluate(Eigen::Vector3d(i, j, 6 - i - j) / 6.0) - origin;
        sum += d.dot(metric * d);
      }
  return sum / count;
}

}  // namespace

TEST(TriangularOperators, PatchQuadratureIsExactForTheGramMatrix) {
  const test::Mesh m = test::fan_mesh(5, 0.4);
  for (const int n : {3, 5})
    for (const bool equilateral : {true, false}) {
      const TriangleNet net = make_triangle_net(m.points, m.triangles, n);
      QuadraticTerms terms(net.control_count);
      attractor_terms(triangles_domain(net, {2}, equilateral), AttractorKind::point,
                      Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0, terms);
      Eigen::SparseMatrix<double> got(net.control_count, net.control_count);
      got.setFromTriplets(terms.separable.begin(), terms.separable.end());
      const auto [a, b, c] = domain_corners(net, 2, equilateral);
      const double area = 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
      const Eigen::MatrixXd gram = bernstein_gram(n, area);
      double worst = 0.0;
      for (int i = 0; i < gram.rows(); ++i)
        for (int j = 0; j < gram.cols(); ++j)
          worst = std::max(worst,
                           std::abs(got.coeff(net.control[2][i], net.control[2][j]) - gram(i, j)));
      EXPECT_LT(worst, 1e-14 * gram.maxCoeff() * 10) << n << " " << equilateral;
      // The derivative rows: the director's integrand of an affine patch is the domain's area
      // times |grad|^2, so the stretch matrix's quadratic form on x equals the director's on
      // (x, 0, 0) with d = (1, 0, 0).
      QuadraticTerms dir(net.control_count);
      director_terms(triangles_domain(net, {2}, equilateral), Eigen::Vector3d::UnitX(), 1.0, dir);
      Eigen::SparseMatrix<double> d(3 * net.control_count, 3 * net.control_count);
      d.setFromTriplets(dir.coupled.begin(), dir.coupled.end());
      const TriangleEnergy e = triangle_energy(n, a, b, c);
      double diff = 0.0;
      for (int i = 0; i < e.stretch.rows(); ++i)
        for (int j = 0; j < e.stretch.cols(); ++j)
          diff = std::max(diff, std::abs(d.coeff(3 * net.control[2][i], 3 * net.control[2][j]) -
                                         e.stretch(i, j)));
      EXPECT_LT(diff, 1e-12 * e.stretch.cwiseAbs().maxCoeff()) << n << " " << equilateral;
    }
}

TEST(TriangularOperators, AttractorsDirectorAndRepellerMoveTheSurfaceTheirWay) {
  const double flat = centre_height(solve_triangular(flat_fan()));
  EXPECT_NEAR(flat, 0.0, 1e-12);
  // A point above pulls the middle up and the surface nearer to it, more with more strength.
  double last = 0.0, pull = mean_pull(solve_triangular(flat_fan()), Eigen::Vector3d::UnitZ(),
                                      Eigen::Matrix3d::Identity());
  for (const double strength : {0.1, 1.0, 10.0}) {
    TriangularProblem p = flat_fan();
    TriangularOperator op;
    op.origin = Eigen::Vector3d(0.0, 0.0, 1.0);
    op.strength = strength;
    p.operators = {op};
    const TriangularResult r = solve_triangular(p);
    const double z = centre_height(r);
    const double nearer = mean_pull(r, op.origin, Eigen::Matrix3d::Identity());
    EXPECT_GT(z, last) << strength;
    EXPECT_LT(nearer, pull) << strength;
    EXPECT_LT(r.report.worst_angle, 0.01);
    last = z;
    pull = nearer;
  }
  // A plane attractor z = 0.5 (normal z) lifts it as well; a line attractor along x at z = 0.5
  // lifts the middle too.
  for (const auto kind :
       {TriangularOperator::Kind::plane_attractor, TriangularOperator::Kind::line_attractor}) {
    TriangularProblem p = flat_fan();
    TriangularOperator op;
    op.kind = kind;
    op.origin = Eigen::Vector3d(0.0, 0.0, 0.5);
    op.direction = kind == TriangularOperator::Kind::plane_attractor ? Eigen::Vector3d::UnitZ()
                                                                     : Eigen::Vector3d::UnitX();
    op.strength = 5.0;
    p.operators = {op};
    const TriangularResult r = solve_triangular(p);
    EXPECT_GT(centre_height(r), 0.05);
    const Eigen::Matrix3d metric =
        kind == TriangularOperator::Kind::plane_attractor
            ? Eigen::Matrix3d(Eigen::Vector3d::UnitZ() * Eigen::RowVector3d::UnitZ())
            : Eigen::Matrix3d(Eigen::Matrix3d::Identity() -
                              Eigen::Vector3d::UnitX() * Eigen::RowVector3d::UnitX());
    EXPECT_LT(mean_pull(r, op.origin, metric),
              mean_pull(solve_triangular(flat_fan()), op.origin, metric));
  }
  // A repeller below pushes the middle up, in several Gauss-Newton steps.
  TriangularProblem p = flat_fan();
  TriangularOperator rep;
  rep.kind = TriangularOperator::Kind::repeller;
  rep.origin = Eigen::Vector3d(0.0, 0.0, -0.3);
  rep.strength = 0.05;
  p.operators = {rep};
  const TriangularResult pushed = solve_triangular(p);
  EXPECT_GT(centre_height(pushed), 0.01);
  EXPECT_GT(pushed.report.operator_iterations, 1);
  // A director toward a tilted direction on a raised fan turns its normals that way.
  TriangularProblem raised = flat_fan(3);
  raised.vertices(0, 2) = 0.6;
  raised.g1 = false;
  const Eigen::Vector3d tilt = Eigen::Vector3d(0.5, 0.0, 1.0).normalized();
  const auto mean_angle = [&](const TriangularResult& r) {
    double sum = 0.0;
    for (const auto& patch : r.patches) {
      const Eigen::Vector3d b = Eigen::Vector3d::Constant(1.0 / 3.0);
      const Eigen::Vector3d du = patch.derivative(Eigen::Vector3d(-1, 1, 0)).evaluate(b);
      const Eigen::Vector3d dv = patch.derivative(Eigen::Vector3d(-1, 0, 1)).evaluate(b);
      sum += std::acos(std::abs(du.cross(dv).normalized().dot(tilt)));
    }
    return sum / r.patches.size();
  };
  const double before = mean_angle(solve_triangular(raised));
  TriangularOperator dir;
  dir.kind = TriangularOperator::Kind::director;
  dir.direction = tilt;
  dir.strength = 20.0;
  raised.operators = {dir};
  EXPECT_LT(mean_angle(solve_triangular(raised)), 0.5 * before);
}

TEST(TriangularOperators, AShapeAttractorOntoAPlaneIsThePlaneAttractor) {
  TriangularProblem plane = flat_fan();
  TriangularOperator op;
  op.kind = TriangularOperator::Kind::plane_attractor;
  op.origin = Eigen::Vector3d(0.0, 0.0, 0.4);
  op.direction = Eigen::Vector3d::UnitZ();
  op.strength = 3.0;
  op.triangles = {0, 1, 2};
  plane.operators = {op};
  TriangularProblem shape = flat_fan();
  TriangularOperator onto = op;
  onto.kind = TriangularOperator::Kind::shape_attractor;
  onto.closest = [](const Eigen::Vector3d& w) {
    return ClosestPoint{Eigen::Vector3d(w.x(), w.y(), 0.4),
                        Eigen::Vector3d::UnitZ() * Eigen::RowVector3d::UnitZ()};
  };
  shape.operators = {onto};
  const TriangularResult a = solve_triangular(plane), b = solve_triangular(shape);
  EXPECT_GT(centre_height(a), 0.05);
  EXPECT_LT((a.control - b.control).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE(b.report.operator_iterations, 2);  // quadratic: the second step moves nothing
}

TEST(TriangularOperators, BadOperatorsAreRefusedByName) {
  TriangularProblem p = flat_fan();
  TriangularOperator op;
  op.triangles = {6};
  p.operators = {op};
  expect_refused([&] { solve_triangular(p); }, "operator 0 names triangle 6 of 6");
  p.operators[0].triangles.clear();
  p.operators[0].strength = -1.0;
  expect_refused([&] { solve_triangular(p); }, "operator 0 has a strength");
  p.operators[0].strength = 1.0;
  p.operators[0].kind = TriangularOperator::Kind::director;
  p.operators[0].direction.setZero();
  expect_refused([&] { solve_triangular(p); }, "operator 0 has a zero direction");
  p.operators[0].kind = TriangularOperator::Kind::shape_attractor;
  expect_refused([&] { solve_triangular(p); }, "operator 0 attracts to no shape");
  p.operators[0].kind = TriangularOperator::Kind::point_attractor;
  p.operators[0].origin(0) = NAN;
  expect_refused([&] { solve_triangular(p); }, "not finite");
}

TEST(TriangularOperators, TheEnergyOfTheDisplacementKeepsWhatNothingPulls) {
  // Sculpting: the vertices free, the energy of the displacement from the mesh's flat patches.
  // With nothing pulling, a flat mesh (already G1) comes back as it is; a point attractor moves
  // its own triangles' points most.
  TriangularProblem p = flat_fan();
  p.interpolate_vertices = false;
  p.energy_of_displacement = true;
  p.stretch = 1.0;
  for (int k = 0; k < 6; ++k) {  // the border vertices held, the middle one free
    TriangularConstraint hold;
    hold.triangle = k;
    hold.at = Eigen::Vector3d(0.0, 1.0, 0.0);
    hold.target = p.vertices.row(k + 1).transpose();
    p.constraints.push_back(hold);
  }
  const TriangularResult still = solve_triangular(p);
  TriangularProblem flat = flat_fan();
  const TriangularResult start = solve_triangular(flat);  // interpolating: the flat patches
  // To the solve's accuracy, about 1e-8 of the model's size (2) with the G1 weight.
  EXPECT_LT((still.control - start.control).cwiseAbs().maxCoeff(), 2 * 5e-8);
  TriangularOperator op;
  op.origin = Eigen::Vector3d(0.5, 0.3, 1.0);
  op.triangles = {0};
  op.strength = 0.5;
  p.operators = {op};
  const TriangularResult pulled = solve_triangular(p);
  EXPECT_GT(pulled.patches[0].evaluate(Eigen::Vector3d::Constant(1.0 / 3.0)).z(),
            2.0 * std::abs(pulled.patches[3].evaluate(Eigen::Vector3d::Constant(1.0 / 3.0)).z()));
  EXPECT_LT(pulled.report.worst_angle, 0.01);
}
