// SPDX-License-Identifier: LGPL-2.1-or-later
// Rest shape, derivative/normal/plane/line point constraints, attractors and the director, and the
// coupled 3n solve they need.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

using test::flat_poles;

Eigen::MatrixX3d wavy_poles(const SplineSpace& sp) {
  return test::fit_poles(sp, [](double u, double v) {
    return Eigen::Vector3d(u, v, 0.1 * std::sin(7 * u) * std::cos(5 * v) + 0.05 * u * v);
  });
}

// A flat unit sheet with its boundary held, thin plate with a little tension.
SheetProblem flat_problem(int spans = 8) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  pb.initial_poles = flat_poles(pb.space);
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  return pb;
}

Eigen::RowVector3d point_at(const SheetProblem& pb, const Eigen::MatrixX3d& poles, double u,
                            double v, int d = 0) {
  return evaluate_surface(pb.space, poles, u, v, 1).row(d);
}

PointConstraint pull(double u, double v, const Eigen::Vector3d& target) {
  PointConstraint p;
  p.u = u;
  p.v = v;
  p.target = target;
  return p;
}

}  // namespace

TEST(CoupledSolve, AgreesWithTheSeparableSolve) {
  SheetProblem pb = flat_problem();
  pb.points.push_back(pull(0.4, 0.55, {0.4, 0.55, 0.3}));
  TangentConstraint t;
  t.u = 0.7;
  t.v = 0.3;
  t.target = Eigen::Vector3d(1.0, 0.2, 0.5);
  pb.tangents.push_back(t);
  SolveOptions coupled;
  coupled.force_coupled = true;
  const SolveResult a = solve_sheet(pb), b = solve_sheet(pb, coupled);
  EXPECT_FALSE(a.report.coupled);
  EXPECT_TRUE(b.report.coupled);
  EXPECT_EQ(3 * a.report.constraint_rank, b.report.constraint_rank);
  EXPECT_LT((a.poles - b.poles).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(RestShape, IsReproducedWithoutConstraints) {
  SheetProblem pb = flat_problem();
  pb.rest_poles = wavy_poles(pb.space);
  for (int k : pb.fixed_poles) pb.initial_poles.row(k) = pb.rest_poles.row(k);
  const SolveResult r = solve_sheet(pb);
  EXPECT_LT((r.poles - pb.rest_poles).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(RestShape, EditMovesTheDisplacementOnlyAndKeepsDetail) {
  // Minimizing (p - p^)^T H (p - p^) under a pull is the plain problem for the displacement
  // d = p - p^ (Boier-Martin et al. 4.1): solve that independently and compare.
  SheetProblem edit = flat_problem();
  edit.rest_poles = wavy_poles(edit.space);
  edit.initial_poles = edit.rest_poles;
  const Eigen::RowVector3d at = point_at(edit, edit.rest_poles, 0.5, 0.45);
  edit.points.push_back(pull(0.5, 0.45, (at + Eigen::RowVector3d(0, 0, 0.4)).transpose()));
  const SolveResult r = solve_sheet(edit);

  SheetProblem displacement = flat_problem();
  displacement.initial_poles.setZero();
  displacement.points.push_back(pull(0.5, 0.45, {0.0, 0.0, 0.4}));
  const SolveResult d = solve_sheet(displacement);
  EXPECT_LT((r.poles - (edit.rest_poles + d.poles)).cwiseAbs().maxCoeff(), 1e-10);
  // Without the rest shape the same pull gives another sheet: the identity above is not trivial.
  SheetProblem fair = edit;
  fair.rest_poles.resize(0, 3);
  EXPECT_GT((solve_sheet(fair).poles - r.poles).cwiseAbs().maxCoeff(), 0.05);
}

TEST(PointConstraints, TangentIsMetExactly) {
  SheetProblem pb = flat_problem();
  TangentConstraint t;
  t.u = 0.3;
  t.v = 0.6;
  t.direction = 1;
  t.target = Eigen::Vector3d(0.2, 1.5, -0.8);
  pb.tangents.push_back(t);
  const SolveResult r = solve_sheet(pb);
  EXPECT_LT((point_at(pb, r.poles, 0.3, 0.6, 2).transpose() - t.target).norm(), 1e-10);
}

TEST(PointConstraints, NormalIsMetToANanoradian) {
  SheetProblem pb = flat_problem();
  pb.points.push_back(pull(0.45, 0.5, {0.45, 0.5, 0.2}));
  NormalConstraint n;
  n.u = 0.45;
  n.v = 0.5;
  n.normal = Eigen::Vector3d(0.3, -0.4, 1.0);
  pb.normals.push_back(n);
  const SolveResult r = solve_sheet(pb);
  EXPECT_TRUE(r.report.coupled);
  const Eigen::Vector3d wu = point_at(pb, r.poles, n.u, n.v, 1).transpose();
  const Eigen::Vector3d wv = point_at(pb, r.poles, n.u, n.v, 2).transpose();
  const double angle = std::atan2(wu.cross(wv).cross(n.normal).norm(), wu.cross(wv).dot(n.normal));
  EXPECT_LT(std::abs(angle), 1e-9);
  EXPECT_LT((point_at(pb, r.poles, 0.45, 0.5) - Eigen::RowVector3d(0.45, 0.5, 0.2)).norm(), 1e-10);
}

TEST(PointConstraints, PointInPlaneAndOnLine) {
  SheetProblem pb = flat_problem();
  PlanePointConstraint pl;
  pl.u = 0.3;
  pl.v = 0.3;
  pl.origin = Eigen::Vector3d(0.0, 0.0, 0.25);
  pl.normal = Eigen::Vector3d(0.2, 0.1, 1.0);
  pb.plane_points.push_back(pl);
  LinePointConstraint ln;
  ln.u = 0.7;
  ln.v = 0.6;
  ln.origin = Eigen::Vector3d(0.7, 0.6, 0.0);
  ln.direction = Eigen::Vector3d(0.3, 0.0, 1.0);
  pb.line_points.push_back(ln);
  const SolveResult r = solve_sheet(pb);
  const Eigen::Vector3d a = point_at(pb, r.poles, 0.3, 0.3).transpose();
  EXPECT_LT(std::abs(pl.normal.normalized().dot(a - pl.origin)), 1e-10);
  EXPECT_GT(a.z(), 0.1);  // it really moved to the plane
  const Eigen::Vector3d b = point_at(pb, r.poles, 0.7, 0.6).transpose();
  EXPECT_LT((b - ln.origin).cross(ln.direction.normalized()).norm(), 1e-10);
}

TEST(Attractors, PointPullGrowsWithStrengthAndInterpolatesInTheLimit) {
  // Strengths are relative to the sheet's stiffness: 1 is comparable, 1e3 dominates.
  const Eigen::Vector3d target(0.5, 0.5, 1.0);
  double previous = 1e300;
  for (double strength : {1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3}) {
    SheetProblem pb = flat_problem();
    Attractor a;
    a.region = Region{0.45, 0.55, 0.45, 0.55};
    a.origin = target;
    a.strength = strength;
    pb.attractors.push_back(a);
    const SolveResult r = solve_sheet(pb);
    EXPECT_FALSE(r.report.coupled);
    const double gap = (point_at(pb, r.poles, 0.5, 0.5).transpose() - target).norm();
    EXPECT_LT(gap, previous) << "strength " << strength;
    previous = gap;
  }
  EXPECT_LT(previous, 1e-3);  // from a gap of 1 with no pull
}

TEST(Attractors, PlaneAndLinePullTheRegionOntoThem) {
  for (AttractorKind kind : {AttractorKind::plane, AttractorKind::line}) {
    SheetProblem pb = flat_problem();
    Attractor a;
    a.kind = kind;
    a.region = Region{0.3, 0.7, 0.4, 0.6};
    a.origin = Eigen::Vector3d(0.5, 0.5, 0.3);
    a.direction = kind == AttractorKind::plane ? Eigen::Vector3d(0.0, 0.3, 1.0)
                                               : Eigen::Vector3d(1.0, 0.0, 0.0);
    a.strength = 1e3;
    pb.attractors.push_back(a);
    const SolveResult r = solve_sheet(pb);
    EXPECT_TRUE(r.report.coupled);
    const Eigen::Vector3d d = a.direction.normalized();
    for (double u : {0.35, 0.5, 0.65}) {
      const Eigen::Vector3d w = point_at(pb, r.poles, u, 0.5).transpose() - a.origin;
      const double dist = kind == AttractorKind::plane ? std::abs(d.dot(w)) : w.cross(d).norm();
      EXPECT_LT(dist, 1e-3) << "kind " << static_cast<int>(kind) << " u " << u;
    }
  }
}

TEST(Attractors, DirectorTurnsTheRegionsNormalsTowardIt) {
  // A pulled point makes a bump; a director along z over the bump flattens its slopes.
  double previous = 1e300;
  for (double strength : {0.0, 1e-1, 1e1, 1e3}) {
    SheetProblem pb = flat_problem();
    pb.points.push_back(pull(0.5, 0.5, {0.5, 0.5, 0.3}));
    Director d;
    d.region = Region{0.3, 0.7, 0.3, 0.7};
    d.strength = strength;
    pb.directors.push_back(d);
    const SolveResult r = solve_sheet(pb);
    double slope = 0.0;
    for (double u : {0.35, 0.45, 0.55, 0.65})
      for (double v : {0.35, 0.45, 0.55, 0.65})
        slope = std::max(slope, std::abs(point_at(pb, r.poles, u, v, 1)(2)) +
                                    std::abs(point_at(pb, r.poles, u, v, 2)(2)));
    EXPECT_LT(slope, previous) << "strength " << strength;
    previous = slope;
  }
  EXPECT_LT(previous, 0.05);
}

TEST(FrozenRegion, HoldsExactlyTheRegionAndLetsTheRestMove) {
  SheetProblem pb = flat_problem();
  pb.rest_poles = wavy_poles(pb.space);
  pb.initial_poles = pb.rest_poles;
  const Region frozen{0.0, 0.5, 0.0, 1.0};
  const std::vector<int> held = poles_in_region(pb.space, frozen);
  // Uniform 8 spans, cubic: supports [k_i, k_i+4] overlap u < 0.5 for i = 0..6 (k_7 = 0.5).
  EXPECT_EQ(static_cast<int>(held.size()), 7 * pb.space.nv());
  pb.fixed_poles.insert(pb.fixed_poles.end(), held.begin(), held.end());
  pb.points.push_back(pull(0.75, 0.5, {0.75, 0.5, 0.5}));
  const SolveResult r = solve_sheet(pb);
  for (double u : {0.0, 0.2, 0.45, 0.5})
    for (double v : {0.1, 0.5, 0.9})
      EXPECT_LT((point_at(pb, r.poles, u, v) - point_at(pb, pb.rest_poles, u, v)).norm(), 1e-12);
  EXPECT_NEAR(point_at(pb, r.poles, 0.75, 0.5)(2), 0.5, 1e-10);
  EXPECT_THROW(poles_in_region(pb.space, Region{0.5, 0.4, 0.0, 1.0}), InvalidInput);
}

TEST(Operators, RejectBadInput) {
  auto fails = [](const std::function<void(SheetProblem&)>& edit, const char* text) {
    SheetProblem pb = flat_problem(4);
    edit(pb);
    try {
      solve_sheet(pb);
      ADD_FAILURE() << "expected InvalidInput for " << text;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  fails(
      [](SheetProblem& pb) {
        pb.normals.push_back({0.5, 0.5, Eigen::Vector3d::Zero(), 1.0});
      },
      "normal constraint 0");
  fails(
      [](SheetProblem& pb) {
        pb.line_points.push_back({0.5, 0.5, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1.0});
      },
      "non-zero");
  fails(
      [](SheetProblem& pb) {
        pb.plane_points.push_back(
            {1.5, 0.5, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0});
      },
      "outside");
  fails(
      [](SheetProblem& pb) {
        pb.tangents.push_back({0.5, 0.5, 2, Eigen::Vector3d::UnitX(), 1.0});
      },
      "direction");
  fails(
      [](SheetProblem& pb) {
        Attractor a;
        a.region = Region{0.6, 0.4, 0.0, 1.0};
        pb.attractors.push_back(a);
      },
      "empty");
  fails(
      [](SheetProblem& pb) {
        Attractor a;
        a.region = Region{0.0, 1.2, 0.0, 1.0};
        pb.attractors.push_back(a);
      },
      "outside");
  fails(
      [](SheetProblem& pb) {
        Attractor a;
        a.strength = NAN;
        pb.attractors.push_back(a);
      },
      "strength");
  fails(
      [](SheetProblem& pb) {
        Director d;
        d.direction = Eigen::Vector3d::Zero();
        pb.directors.push_back(d);
      },
      "director 0");
  fails([](SheetProblem& pb) { pb.rest_poles = Eigen::MatrixX3d::Zero(3, 3); }, "rest shape");
}
