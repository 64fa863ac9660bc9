// SPDX-License-Identifier: LGPL-2.1-or-later
// Du & Qin's dynamic sheets: the motion settles on the static solution, the energy falls
// monotonically once released, bad parameters are refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/pde_energy.hpp"
#include "varsurf/core/sheet_dynamics.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

// A PDE sheet on [0, 1]^2 held by its two outer rings of poles (Hermite data on all sides), a
// saddle to start from.
SheetProblem held_sheet(int spans) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  pb.pde = PdeCoefficient();
  pb.pde->a = 1.5;
  const int nu = pb.space.nu(), nv = pb.space.nv();
  pb.initial_poles.resize(pb.space.size(), 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = static_cast<double>(i) / (nu - 1), v = static_cast<double>(j) / (nv - 1);
      pb.initial_poles.row(pb.space.index(i, j)) << 100 * u, 100 * v, 10 * (u - 0.5) * (v - 0.5);
      if (i < 2 || j < 2 || i >= nu - 2 || j >= nv - 2)
        pb.fixed_poles.push_back(pb.space.index(i, j));
    }
  return pb;
}

DynamicsParameters parameters(double damping) {
  DynamicsParameters d;
  d.mass.a = 1.0;
  d.damping.a = damping;
  d.stiffness = 1.0;
  d.time_step = 1.0 / 60.0;
  return d;
}

}  // namespace

TEST(SheetDynamics, SettlesOnTheStaticSolution) {
  const SheetProblem pb = held_sheet(8);
  DynamicSheet sheet(pb, parameters(20.0));
  // Without springs the equilibrium is the static constrained solve.
  EXPECT_LT((sheet.equilibrium() - solve_sheet(pb).poles).cwiseAbs().maxCoeff(), 1e-8);
  sheet.set_springs({{0.4, 0.6, Eigen::Vector3d(40, 60, 15), 50.0}});
  sheet.step(3000);
  EXPECT_LT((sheet.poles() - sheet.equilibrium()).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT(sheet.kinetic_energy(), 1e-16);
  // The spring pulled the sheet up toward its target.
  const BSplineSurface pulled{pb.space, sheet.poles()};
  EXPECT_GT(pulled.evaluate(0.4, 0.6).z(), 1.0);
  // Released, it settles back on the static solution.
  sheet.set_springs({});
  sheet.step(3000);
  EXPECT_LT((sheet.poles() - solve_sheet(pb).poles).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(SheetDynamics, EnergyFallsMonotonicallyOnceReleased) {
  for (double damping : {0.0, 5.0}) {
    DynamicSheet sheet(held_sheet(10), parameters(damping));
    sheet.set_springs({{0.5, 0.5, Eigen::Vector3d(50, 50, 30), 200.0}});
    sheet.step(20);  // pulled and moving
    sheet.set_springs({});
    double last = sheet.kinetic_energy() + sheet.potential_energy();
    double first = last;
    for (int k = 0; k < 300; ++k) {
      sheet.step();
      const double e = sheet.kinetic_energy() + sheet.potential_energy();
      EXPECT_LE(e, last + 1e-12 * std::abs(last)) << "step " << k << ", damping " << damping;
      last = e;
    }
    EXPECT_LT(last, first);  // it did lose energy (backward Euler dissipates even undamped)
  }
}

// A heavier sheet takes longer to rise to half its pulled height.
TEST(SheetDynamics, HeavierSheetsLag) {
  const SheetProblem pb = held_sheet(10);
  DynamicsParameters light = parameters(0.0), heavy = parameters(0.0);
  light.time_step = heavy.time_step = 2e-4;  // steps short beside the light sheet's rise
  heavy.mass.painted.push_back({Region(0.0, 1.0, 0.0, 1.0), 20.0});
  auto rise = [&](const DynamicsParameters& d) {
    DynamicSheet s(pb, d);
    s.set_springs({{0.5, 0.5, Eigen::Vector3d(50, 50, 30), 200.0}});
    const double half = 0.5 * BSplineSurface{pb.space, s.equilibrium()}.evaluate(0.5, 0.5).z();
    for (int k = 1; k <= 1000; ++k) {
      s.step();
      if (BSplineSurface{pb.space, s.poles()}.evaluate(0.5, 0.5).z() >= half) return k;
    }
    return 1001;
  };
  const int fast = rise(light), slow = rise(heavy);
  EXPECT_LT(fast, 1000);
  EXPECT_GT(slow, 3 * fast);  // 20 times the mass: sqrt(20) = 4.5 times the time, roughly
}

TEST(SheetDynamics, BadParametersAreRefused) {
  const SheetProblem pb = held_sheet(4);
  DynamicsParameters d = parameters(1.0);
  d.mass.a = 0.0;
  EXPECT_THROW(DynamicSheet(pb, d), InvalidInput);
  d = parameters(-1.0);
  EXPECT_THROW(DynamicSheet(pb, d), InvalidInput);
  d = parameters(1.0);
  d.time_step = 0.0;
  EXPECT_THROW(DynamicSheet(pb, d), InvalidInput);
  d.time_step = std::nan("");
  EXPECT_THROW(DynamicSheet(pb, d), InvalidInput);
  SheetProblem with_point = pb;
  with_point.points.push_back({0.5, 0.5, Eigen::Vector3d::Zero(), 1.0});
  EXPECT_THROW(DynamicSheet(with_point, parameters(1.0)), InvalidInput);
  DynamicSheet sheet(pb, parameters(1.0));
  EXPECT_THROW(sheet.set_springs({{2.0, 0.5, Eigen::Vector3d::Zero(), 1.0}}), InvalidInput);
  EXPECT_THROW(sheet.move_targets({Eigen::Vector3d::Zero()}), InvalidInput);
}

// Damping may be painted 0 (an undamped region): painted 0 over the whole domain moves the sheet
// as no damping does; painted below 0 it is refused.
TEST(SheetDynamics, DampingPaintedZeroIsNoDamping) {
  const SheetProblem pb = held_sheet(6);
  auto pulled = [&](DynamicsParameters d) {
    d.time_step = 2e-4;  // short beside the sheet's swing, so damping shows
    DynamicSheet sheet(pb, d);
    sheet.set_springs({{0.5, 0.5, Eigen::Vector3d(50, 50, 20), 5.0}});
    sheet.step(20);
    return Eigen::MatrixX3d(sheet.poles());
  };
  DynamicsParameters painted = parameters(50.0);
  painted.damping.painted.push_back({Region(0.0, 1.0, 0.0, 1.0), 0.0});
  const Eigen::MatrixX3d undamped = pulled(parameters(0.0)), damped = pulled(parameters(50.0));
  EXPECT_LT((pulled(painted) - undamped).cwiseAbs().maxCoeff(), 1e-12 * 50);
  EXPECT_GT((damped - undamped).cwiseAbs().maxCoeff(), 1e-3);
  painted.damping.painted.back().a = -1.0;
  EXPECT_THROW(DynamicSheet(pb, painted), InvalidInput);
  painted.damping.painted.back().a = 0.0;
  painted.damping.painted.back().region = Region(0.6, 0.4, 0.0, 1.0);
  EXPECT_THROW(DynamicSheet(pb, painted), InvalidInput);
}

// The pin's stiffness against the compliance of the free poles computed directly: a unit force
// at (u, v) moves the point by c = N^T A_FF^-1 N (each coordinate alike), so the stiffness is
// 1 / c, and the shape it deflects in is A_FF^-1 N / c, weighed by each pole's share of the
// domain (the integral of its basis function: knot differences over degree + 1 on uniform knots).
TEST(SheetDynamics, PinStiffnessIsTheInverseCompliance) {
  const SheetProblem pb = held_sheet(8);
  for (const auto& [u, v] : {std::pair{0.5, 0.5}, {0.3, 0.62}}) {
    const PinStiffness got = pin_stiffness(pb, u, v);
    const Eigen::SparseMatrix<double> a = assemble_pde(pb.space, *pb.pde);
    std::vector<int> free;
    std::vector<bool> fixed(static_cast<size_t>(pb.space.size()), false);
    for (int k : pb.fixed_poles) fixed[static_cast<size_t>(k)] = true;
    for (int k = 0; k < pb.space.size(); ++k)
      if (!fixed[static_cast<size_t>(k)]) free.push_back(k);
    const int n = static_cast<int>(free.size());
    Eigen::MatrixXd aff(n, n);
    const Eigen::MatrixXd dense(a);
    Eigen::VectorXd basis(n);
    const BasisSample s = pb.space.basis(u, v, 0);
    Eigen::VectorXd all = Eigen::VectorXd::Zero(pb.space.size());
    for (size_t k = 0; k < s.index.size(); ++k)
      all(s.index[k]) = s.values(0, static_cast<Eigen::Index>(k));
    for (int i = 0; i < n; ++i) {
      basis(i) = all(free[static_cast<size_t>(i)]);
      for (int j = 0; j < n; ++j)
        aff(i, j) = dense(free[static_cast<size_t>(i)], free[static_cast<size_t>(j)]);
    }
    const Eigen::VectorXd response = aff.ldlt().solve(basis);
    const double c = basis.dot(response);
    EXPECT_NEAR(got.stiffness, 1.0 / c, 1e-9 / c) << u << " " << v;
    auto share = [](const std::vector<double>& t, int i) { return (t[i + 4] - t[i]) / 4.0; };
    double shape = 0.0;
    for (int i = 0; i < n; ++i) {
      const int pole = free[static_cast<size_t>(i)];
      const int iu = pole / pb.space.nv(), iv = pole % pb.space.nv();
      ASSERT_EQ(pb.space.index(iu, iv), pole);
      shape +=
          share(pb.space.knots_u, iu) * share(pb.space.knots_v, iv) * std::pow(response(i) / c, 2);
    }
    EXPECT_NEAR(got.shape_mass, shape, 1e-9 * shape) << u << " " << v;
  }
  // Held where the pin is (every pole its basis reaches fixed): no give there.
  SheetProblem held = pb;
  const BasisSample s = pb.space.basis(0.5, 0.5, 0);
  for (int k : s.index) held.fixed_poles.push_back(k);
  std::sort(held.fixed_poles.begin(), held.fixed_poles.end());
  held.fixed_poles.erase(std::unique(held.fixed_poles.begin(), held.fixed_poles.end()),
                         held.fixed_poles.end());
  EXPECT_THROW(pin_stiffness(held, 0.5, 0.5), SolveFailure);
}
