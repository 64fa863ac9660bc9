// SPDX-License-Identifier: LGPL-2.1-or-later
// The Bloor-Wilson energy against closed forms: its values on polynomial surfaces, its null space
// (surfaces with (d_ss + a^2 d_tt) P = 0), and the constrained minimum reproducing a solution of
// (d_ss + a^2 d_tt)^2 P = 0 from its Hermite data on the four sides.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/pde_energy.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

// Domain [0, 2] x [1, 4], non-uniform knots: the energy is measured in s = u / 2, t = (v - 1) / 3.
SplineSpace pde_space(int spans_u = 5, int spans_v = 4, int degree = 3) {
  SplineSpace sp = SplineSpace::uniform(degree, degree, spans_u, spans_v);
  for (double& k : sp.knots_u) k = 2.0 * k * k * (3.0 - 2.0 * k) * 0.5 + k;  // keeps 0 and 2
  for (double& k : sp.knots_v) k = 1.0 + 3.0 * k;
  sp.knots_u[static_cast<size_t>(degree + 1)] *= 0.8;
  return sp;
}

using Scalar2 = std::function<double(double, double)>;

// Poles of (u, v, z(s, t)): exact when z lies in the space.
Eigen::MatrixX3d graph_poles(const SplineSpace& sp, const Scalar2& z) {
  return test::fit_poles(
      sp, [&](double u, double v) { return Eigen::Vector3d(u, v, z(u / 2.0, (v - 1.0) / 3.0)); });
}

double z_energy(const Eigen::SparseMatrix<double>& h, const Eigen::MatrixX3d& p) {
  const Eigen::VectorXd z = p.col(2);
  return z.dot(h * z);
}

// int_[0,1]^2 f, by a 24-point tensor Gauss rule on each of cells x cells squares: independent of
// the spline machinery.
double integrate(const Scalar2& f, int cells = 4) {
  const GaussRule& g = gauss_legendre(24);
  double sum = 0.0;
  const double h = 0.5 / cells;
  for (int a = 0; a < cells; ++a)
    for (int b = 0; b < cells; ++b)
      for (size_t i = 0; i < g.nodes.size(); ++i)
        for (size_t j = 0; j < g.nodes.size(); ++j)
          sum += g.weights[i] * g.weights[j] * h * h *
                 f((2 * a + 1 + g.nodes[i]) * h, (2 * b + 1 + g.nodes[j]) * h);
  return sum;
}

// z = s^2 t^2: L z = 2 t^2 + 2 a^2 s^2.
double s2t2(double s, double t) {
  return s * s * t * t;
}

}  // namespace

TEST(PdeEnergy, ValuesOnPolynomialsMatchClosedForms) {
  const SplineSpace sp = pde_space();
  PdeCoefficient c;
  // z = s^3 t: L z = 6 s t for every a, so E = 36 / 9 = 4.
  const Eigen::MatrixX3d p1 = graph_poles(sp, [](double s, double t) { return s * s * s * t; });
  for (double a : {0.5, 1.0, 3.0}) {
    c.a = a;
    EXPECT_NEAR(z_energy(assemble_pde(sp, c), p1), 4.0, 1e-10);
  }
  // z = s^2 t^2: E = 4/5 + 8 a^2 / 9 + 4 a^4 / 5.
  const Eigen::MatrixX3d p2 = graph_poles(sp, s2t2);
  for (double a : {0.5, 1.0, 2.0}) {
    c.a = a;
    const double exact = 0.8 + 8.0 * a * a / 9.0 + 0.8 * a * a * a * a;
    EXPECT_NEAR(z_energy(assemble_pde(sp, c), p2), exact, 1e-10 * exact);
  }
  // x = u and y = v are linear: no energy.
  const Eigen::SparseMatrix<double> h = assemble_pde(sp, c);
  EXPECT_LT(std::abs(p2.col(0).dot(h * p2.col(0))) + std::abs(p2.col(1).dot(h * p2.col(1))), 1e-9);
}

TEST(PdeEnergy, NullSpaceIsTheOperatorsKernel) {
  const SplineSpace sp = pde_space();
  PdeCoefficient c;
  c.a = 1.7;
  const double a2 = c.a * c.a;
  const Eigen::SparseMatrix<double> h = assemble_pde(sp, c);
  // Harmonic for d_ss + a^2 d_tt: s^2 - t^2 / a^2, s^3 - 3 s t^2 / a^2, s t, 3 s^2 t - t^3 / a^2.
  for (const Scalar2& z :
       std::vector<Scalar2>{[&](double s, double t) { return s * s - t * t / a2; },
                            [&](double s, double t) { return s * s * s - 3.0 * s * t * t / a2; },
                            [](double s, double t) { return s * t; },
                            [&](double s, double t) { return 3.0 * s * s * t - t * t * t / a2; }}) {
    const Eigen::MatrixX3d p = graph_poles(sp, z);
    EXPECT_LT(std::abs(z_energy(h, p)), 1e-10 * p.col(2).squaredNorm());
  }
  // The thin plate does not vanish there: a different energy.
  const Eigen::MatrixX3d q =
      graph_poles(sp, [&](double s, double t) { return s * s - t * t / a2; });
  c.a = 1.0;
  EXPECT_GT(z_energy(assemble_pde(sp, c), q), 1e-3);
  // Positive semi-definite and symmetric.
  const Eigen::MatrixXd d(h);
  EXPECT_LT((d - d.transpose()).cwiseAbs().maxCoeff(), 1e-12 * d.cwiseAbs().maxCoeff());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(d);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-10 * eig.eigenvalues().maxCoeff());
}

TEST(PdeEnergy, FieldCoefficientIsIntegratedExactly) {
  const SplineSpace sp = pde_space();
  PdeCoefficient c;
  // a(s, t) = 1 + s + 0.5 t: a bilinear B-spline field over the sheet's domain.
  c.field_space = SplineSpace::uniform(1, 1, 1, 1);
  c.field_space.knots_u = {0.0, 0.0, 2.0, 2.0};
  c.field_space.knots_v = {1.0, 1.0, 4.0, 4.0};
  c.field_values.resize(4);
  c.field_values << 1.0, 1.5, 2.0, 2.5;  // (s, t) = (0,0), (0,1), (1,0), (1,1)
  const auto a = [](double s, double t) { return 1.0 + s + 0.5 * t; };
  EXPECT_NEAR(c.value(sp, 1.0, 2.5), a(0.5, 0.5), 1e-14);
  const Eigen::MatrixX3d p = graph_poles(sp, s2t2);
  const double exact = integrate([&](double s, double t) {
    const double l = 2.0 * t * t + 2.0 * a(s, t) * a(s, t) * s * s;
    return l * l;
  });
  EXPECT_NEAR(z_energy(assemble_pde(sp, c), p), exact, 1e-10 * exact);
}

TEST(PdeEnergy, SharpPaintedRegionsAddTheirDifference) {
  const SplineSpace sp = pde_space();
  const Eigen::MatrixX3d p = graph_poles(sp, s2t2);
  auto f = [](double a) {
    return [a](double s, double t) {
      const double l = 2.0 * t * t + 2.0 * a * a * s * s;
      return l * l;
    };
  };
  // a = 1, and 3 on s in [0.25, 0.75], t in [0.2, 0.6] (u in [0.5, 1.5], v in [1.6, 2.8]).
  PdeCoefficient c;
  c.painted.push_back({Region(0.5, 1.5, 1.6, 2.8), 3.0});
  // Integrals over the rectangle by the rule scaled onto it.
  auto over_rect = [](const Scalar2& g) {
    return 0.5 * 0.4 *
           integrate([&](double x, double y) { return g(0.25 + 0.5 * x, 0.2 + 0.4 * y); }, 1);
  };
  const double exact = integrate(f(1.0)) + over_rect(f(3.0)) - over_rect(f(1.0));
  EXPECT_NEAR(z_energy(assemble_pde(sp, c), p), exact, 1e-10 * exact);
  // The same rectangle as a loop: the same energy.
  PdeCoefficient loop;
  loop.painted.push_back(
      {Region(std::vector<Eigen::Vector2d>{{0.5, 1.6}, {1.5, 1.6}, {1.5, 2.8}, {0.5, 2.8}}), 3.0});
  EXPECT_NEAR(z_energy(assemble_pde(sp, loop), p), exact, 1e-10 * exact);
  // Two regions, the later one over the earlier: where they overlap the later value counts.
  PdeCoefficient two = c;
  two.painted.push_back({Region(0.0, 2.0, 2.8, 4.0), 2.0});  // t in [0.6, 1]: touches the first
  const double exact2 = exact + 0.4 * integrate([&](double x, double y) {
                                  return f(2.0)(x, 0.6 + 0.4 * y) - f(1.0)(x, 0.6 + 0.4 * y);
                                });
  EXPECT_NEAR(z_energy(assemble_pde(sp, two), p), exact2, 1e-10 * exact2);
}

TEST(PdeEnergy, BlendedBorderConvergesToItsIntegral) {
  const SplineSpace sp = pde_space();
  const Eigen::MatrixX3d p = graph_poles(sp, s2t2);
  PdeCoefficient c;
  c.a = 2.0;
  c.blend = 0.1;
  c.painted.push_back({Region(0.5, 1.5, 1.6, 2.8), 4.0});
  // Inside, beyond the band: the painted value; outside: the base; on the border: half way.
  EXPECT_DOUBLE_EQ(c.value(sp, 1.0, 2.2), 4.0);
  EXPECT_DOUBLE_EQ(c.value(sp, 1.9, 3.8), 2.0);
  EXPECT_NEAR(c.value(sp, 0.5, 2.2), 3.0, 1e-12);
  const double exact = integrate(
      [&](double s, double t) {
        const double a = c.value(sp, 2.0 * s, 1.0 + 3.0 * t);
        const double l = 2.0 * t * t + 2.0 * a * a * s * s;
        return l * l;
      },
      40);
  // Not polynomial: the assembly's cells a quarter of the band wide measured 7e-6 of the energy
  // off (1.4e-3 with one cell per span).
  EXPECT_NEAR(z_energy(assemble_pde(sp, c), p), exact, 2e-5 * exact);
}

TEST(PdeEnergy, BadCoefficientsAreRefusedByName) {
  const SplineSpace sp = pde_space();
  PdeCoefficient c;
  c.a = 0.0;
  EXPECT_THROW(assemble_pde(sp, c), InvalidInput);
  c.a = 1.0;
  c.painted.push_back({Region(0.5, 1.5, 1.6, 2.8), -2.0});
  try {
    assemble_pde(sp, c);
    FAIL() << "a negative painted value was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("painted PDE region 0"), std::string::npos) << e.what();
  }
  c.painted[0].a = 2.0;
  c.painted[0].region = Region(0.5, 2.5, 1.6, 2.8);  // beyond u = 2
  EXPECT_THROW(assemble_pde(sp, c), InvalidInput);
  c.painted.clear();
  c.field_space = SplineSpace::uniform(1, 1, 1, 1);  // [0, 1]^2 does not cover [0, 2] x [1, 4]
  c.field_values = Eigen::VectorXd::Ones(4);
  EXPECT_THROW(assemble_pde(sp, c), InvalidInput);
  c.field_space.knots_u = {0.0, 0.0, 2.0, 2.0};
  c.field_space.knots_v = {1.0, 1.0, 4.0, 4.0};
  c.field_values(2) = -0.1;
  EXPECT_THROW(assemble_pde(sp, c), InvalidInput);
  c.field_values(2) = 1.0;
  c.blend = 0.7;
  EXPECT_THROW(assemble_pde(sp, c), InvalidInput);
  EXPECT_THROW(assemble_pde(SplineSpace::uniform(1, 3, 2, 2), PdeCoefficient()), InvalidInput);
}

// Du & Qin eq. 1 with Hermite data on the four sides (the two outer rows of poles on each side
// hold position and cross derivative): the constrained minimum is the closed-form solution.
TEST(PdeSolve, HermiteDataReproducesAClosedFormSolution) {
  for (double a : {0.6, 1.0, 1.7}) {
    const double a2 = a * a;
    // L^2 = d_ssss + 2 a^2 d_sstt + a^4 d_tttt. z = s^4 - 3 s^2 t^2 / a^2 solves L^2 z = 0 for
    // this a only (24 - 24 = 0); s^3 t + 2 s t^3 and s^2 - t^2 / a^2 have L z bilinear or zero.
    const Scalar2 z = [&](double s, double t) {
      return s * s * s * s - 3.0 * s * s * t * t / a2 + s * s * s * t + 2.0 * s * t * t * t -
             0.5 * (s * s - t * t / a2) + 0.3 * s * t;
    };
    const SplineSpace sp = pde_space(6, 5, 4);
    const Eigen::MatrixX3d exact = graph_poles(sp, z);
    SheetProblem pb;
    pb.space = sp;
    pb.pde = PdeCoefficient();
    pb.pde->a = a;
    pb.initial_poles = exact;
    for (int i = 0; i < sp.nu(); ++i)
      for (int j = 0; j < sp.nv(); ++j) {
        if (i < 2 || j < 2 || i >= sp.nu() - 2 || j >= sp.nv() - 2)
          pb.fixed_poles.push_back(sp.index(i, j));
        else
          pb.initial_poles.row(sp.index(i, j)) += Eigen::RowVector3d(0.1, -0.2, 0.3);
      }
    const SolveResult r = solve_sheet(pb);
    EXPECT_LT((r.poles - exact).cwiseAbs().maxCoeff(), 1e-8) << "a = " << a;
    // The thin plate's minimum is another surface (its operator in s, t is the Laplacian with
    // a = 2/3): the test can tell the energies apart.
    SheetProblem tp = pb;
    tp.pde.reset();
    tp.energy = ThinPlateWeights::isotropic(0.0, 1.0);
    EXPECT_GT((solve_sheet(tp).poles - exact).cwiseAbs().maxCoeff(), 1e-4) << "a = " << a;
  }
}

// Du & Qin Fig. 11: a = 3 everywhere, a = 5 on a region, a = 5 everywhere. Painting a region
// changes the shape near it; far from it the sheet stays where a = 3 put it. (Along v, whose
// length scale a lengthens, the change reaches further than along u: measured 0.18 of the
// region's own change 0.2 beyond its border, 0.05 at 0.35.)
TEST(PdeSolve, PaintedCoefficientActsLocally) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 16, 16);
  // Hermite data from a saddle-and-bump surface; the interior is left to the PDE.
  const Eigen::MatrixX3d start = test::fit_poles(sp, [](double u, double v) {
    return Eigen::Vector3d(u, v, 0.3 * std::sin(3.0 * u) * std::cos(2.0 * v) + 0.2 * u * v);
  });
  auto solve = [&](const PdeCoefficient& c) {
    SheetProblem pb;
    pb.space = sp;
    pb.pde = c;
    pb.initial_poles = start;
    for (int i = 0; i < sp.nu(); ++i)
      for (int j = 0; j < sp.nv(); ++j)
        if (i < 2 || j < 2 || i >= sp.nu() - 2 || j >= sp.nv() - 2)
          pb.fixed_poles.push_back(sp.index(i, j));
    return solve_sheet(pb).poles;
  };
  PdeCoefficient three, painted, five;
  three.a = 3.0;
  five.a = 5.0;
  painted.a = 3.0;
  painted.blend = 0.05;
  painted.painted.push_back({Region(0.55, 0.9, 0.55, 0.9), 5.0});
  const Eigen::MatrixX3d p3 = solve(three), pp = solve(painted), p5 = solve(five);
  double near = 0.0, far = 0.0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const double u = i / 40.0, v = j / 40.0;
      const double d = std::abs(BSplineSurface{sp, pp}.evaluate(u, v).z() -
                                BSplineSurface{sp, p3}.evaluate(u, v).z());
      const bool inside = u > 0.55 && u < 0.9 && v > 0.55 && v < 0.9;
      const bool away = u < 0.25 || v < 0.25;  // 0.3 or more from the region
      if (inside) near = std::max(near, d);
      if (away) far = std::max(far, d);
    }
  const double whole = (p5 - p3).col(2).cwiseAbs().maxCoeff();
  EXPECT_GT(near, 0.2 * whole);  // the region took a good part of the global change
  EXPECT_LT(far, 0.1 * near);    // and away from it the shape hardly moved
}
