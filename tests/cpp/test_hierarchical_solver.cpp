// SPDX-License-Identifier: LGPL-2.1-or-later
// Sheets solved on locally refined spaces: the same answers as uniform spaces where they are the
// same space, and refinement driven by curve error (Welch & Witkin Figure 3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/hierarchical_solver.hpp"
#include "varsurf/core/knot_refinement.hpp"

using namespace varsurf;
using varsurf::test::fit_piecewise_curve;

namespace {

constexpr double pi = 3.14159265358979323846;

// A flat sheet over the unit square with its boundary kept and one curve across it: the pre-image
// runs from (0.15, 0.2) to (0.85, 0.75) (not along a knot line), the target rises in a wave.
SheetProblem wave_problem(int spans, double amplitude = 0.05, bool cubic = false) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  pb.initial_poles = varsurf::test::flat_poles(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  pb.fixed_poles = boundary_pole_indices(pb.space);
  const auto pre = [](double t) { return Eigen::Vector2d(0.15 + 0.7 * t, 0.2 + 0.55 * t); };
  CurveConstraint c;
  c.preimage = varsurf::test::line_curve(pre(0.0), pre(1.0));
  std::vector<double> breaks;
  for (int i = 0; i <= 16; ++i) breaks.push_back(i / 16.0);
  c.target = fit_piecewise_curve(breaks, 3, 3, [&](double t) {
    const Eigen::Vector2d uv = pre(t);
    Eigen::VectorXd p(3);
    // A cubic in t lies in the sheet's space along the straight pre-image: consistent constraints.
    const double z = cubic ? amplitude * t * (1 - t) * (1 + t)
                           : amplitude * std::sin(3 * pi * t) * std::sin(pi * t);
    p << uv(0), uv(1), z;
    return p;
  });
  pb.curves.push_back(c);
  return pb;
}

SolveOptions exact_options() {
  SolveOptions o;
  o.mode = SolveMode::exact;
  return o;
}

// Welch & Witkin Figure 3's scene: one bicubic span, the wave curve and a point on the sheet.
SheetProblem figure3_problem() {
  SheetProblem pb = wave_problem(1);
  pb.points.push_back({0.3, 0.7, Eigen::Vector3d(0.3, 0.7, 0.03)});
  return pb;
}

HierarchicalOptions refine_to(double tolerance, int max_depth) {
  HierarchicalOptions ho;
  ho.tolerance = tolerance;
  ho.max_depth = max_depth;
  return ho;
}

}  // namespace

TEST(HierarchicalSolver, UnrefinedEqualsTheUniformSolve) {
  const SheetProblem pb = wave_problem(4);
  SolveReport rep;
  const Eigen::MatrixX3d h =
      solve_on_hierarchy(pb, HierarchicalSpace(pb.space), exact_options(), rep);
  const SolveResult u = solve_sheet(pb, exact_options());
  EXPECT_LT((h - u.poles).cwiseAbs().maxCoeff(), 1e-8);  // (a displacement form: rounding apart)
}

TEST(HierarchicalSolver, RefiningEverySpanEqualsTheHalvedUniformSpace) {
  const SheetProblem pb = wave_problem(3, 0.2, true);
  HierarchicalSpace h(pb.space);
  EXPECT_EQ(h.refine_box(0, 0.0, 1.0, 0.0, 1.0), 9);
  SolveReport rep;
  const Eigen::MatrixX3d hp = solve_on_hierarchy(pb, h, exact_options(), rep);
  SheetProblem fine = wave_problem(6, 0.2, true);  // the same surface space as level 1
  for (size_t k = 0; k < fine.space.knots_u.size(); ++k)
    ASSERT_NEAR(fine.space.knots_u[k], h.finest().knots_u[k], 1e-15);
  const SolveResult u = solve_sheet(fine, exact_options());
  // The same problem in two bases of one space: they agree to what the curve's rows resolve (the
  // reduction drops directions below rank_tolerance in each basis; measured 1e-8).
  EXPECT_LT((hp - u.poles).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_NEAR(incidence_error(fine.space, hp, fine.curves[0], 200),
              incidence_error(fine.space, u.poles, fine.curves[0], 200), 1e-7);
}

TEST(HierarchicalSolver, RefinesWhereTheCurveIsOffUntilItIsMet) {
  // Welch & Witkin Figure 3: one bicubic span, a point and a curve constraint; the curve cannot
  // be met until the spans under it are refined, and only those are.
  const HierarchicalResult r =
      solve_hierarchical(figure3_problem(), refine_to(2e-6, 8), exact_options());
  const HierarchicalReport& rep = r.report;
  ASSERT_TRUE(rep.met) << rep.round_error.back();
  EXPECT_LE(rep.max_deviation[0], 2e-6);
  EXPECT_GT(rep.round_error.front(), 1e-2);  // one span: far off at first
  for (size_t k = 1; k < rep.round_error.size(); ++k)
    EXPECT_LT(rep.round_error[k], rep.round_error[k - 1]) << k;  // falls with each refinement
  // Only near the curve: several times fewer than the uniform space of the same depth (the
  // benchmark compares with the uniform refinement that meets the tolerance).
  EXPECT_LT(3 * rep.dofs, rep.export_poles) << rep.dofs << " vs " << rep.export_poles;
  EXPECT_EQ(rep.export_poles, r.space.size());
  // The point constraint stays met in the exported sheet.
  const Eigen::Vector3d p = evaluate_surface(r.space, r.poles, 0.3, 0.7, 0).row(0).transpose();
  EXPECT_LT((p - Eigen::Vector3d(0.3, 0.7, 0.03)).norm(), 1e-9);
}

TEST(HierarchicalSolver, SeparableAndCoupledSystemsGiveTheSameSheet) {
  // Curves and points couple no coordinates: the hierarchical system is solved once for x, y and
  // z on one factorization; forced into one coupled 3n system it must give the same sheet. A
  // normal constraint couples them, and is then met.
  SheetProblem pb = figure3_problem();
  const HierarchicalOptions ho = refine_to(1e-5, 5);
  const HierarchicalResult separable = solve_hierarchical(pb, ho, exact_options());
  SolveOptions forced = exact_options();
  forced.force_coupled = true;
  const HierarchicalResult coupled = solve_hierarchical(pb, ho, forced);
  EXPECT_FALSE(separable.report.solve.coupled);
  EXPECT_TRUE(coupled.report.solve.coupled);
  EXPECT_EQ(coupled.report.solve.unknowns, 3 * separable.report.solve.unknowns);
  ASSERT_EQ(separable.report.dofs, coupled.report.dofs);
  EXPECT_LT((separable.poles - coupled.poles).cwiseAbs().maxCoeff(), 1e-9);

  NormalConstraint n;
  n.u = 0.6;
  n.v = 0.3;
  n.normal = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  pb.normals.push_back(n);
  const HierarchicalResult tilted = solve_hierarchical(pb, ho, exact_options());
  EXPECT_TRUE(tilted.report.solve.coupled);
  const Eigen::MatrixXd d = evaluate_surface(tilted.space, tilted.poles, n.u, n.v, 1);
  const Eigen::Vector3d normal =
      Eigen::Vector3d(d.row(1).transpose()).cross(Eigen::Vector3d(d.row(2).transpose()));
  EXPECT_LT(normal.normalized().cross(n.normal).norm(), 1e-8);
}

TEST(HierarchicalSolver, ACurvedPreimageIsMetToo) {
  // A quarter-circle pre-image (not along any knot line) carrying a wave, two crossing curves'
  // worth of detail on a 2 x 2-span sheet.
  SheetProblem pb = wave_problem(2);
  CurveConstraint& c = pb.curves[0];
  std::vector<double> breaks;
  for (int i = 0; i <= 12; ++i) breaks.push_back(i / 12.0);
  const auto arc = [](double t) {
    return Eigen::Vector2d(0.5 + 0.35 * std::cos(0.5 * pi * t),
                           0.15 + 0.35 * std::sin(0.5 * pi * t) + 0.2 * t);
  };
  c.preimage = fit_piecewise_curve(breaks, 3, 2, [&](double t) { return Eigen::VectorXd(arc(t)); });
  c.target = fit_piecewise_curve(breaks, 3, 3, [&](double t) {
    Eigen::VectorXd p(3);
    p << arc(t)(0), arc(t)(1), 0.03 * std::sin(4 * pi * t);
    return p;
  });
  HierarchicalOptions ho;
  ho.tolerance = 1e-5;
  ho.max_depth = 7;
  const HierarchicalResult r = solve_hierarchical(pb, ho, exact_options());
  ASSERT_TRUE(r.report.met) << r.report.round_error.back();
  for (size_t k = 1; k < r.report.round_error.size(); ++k)
    EXPECT_LT(r.report.round_error[k], r.report.round_error[k - 1]) << k;
  EXPECT_LE(incidence_error(r.space, r.poles, c, 1000),
            1.5e-5);  // between the measured samples too
  EXPECT_LT(r.report.dofs, r.report.export_poles);
}

TEST(HierarchicalSolver, AManualRegionAddsDetailWhereNoCurveAsks) {
  HierarchicalOptions ho;
  ho.tolerance = 1.0;  // met at once: nothing refined automatically
  const HierarchicalResult plain = solve_hierarchical(wave_problem(4), ho, exact_options());
  EXPECT_EQ(plain.report.depth, 0);
  ho.manual = {{1, 0.0, 0.2, 0.8, 1.0}};  // a corner, down to level 2
  const HierarchicalResult r = solve_hierarchical(wave_problem(4), ho, exact_options());
  EXPECT_EQ(r.report.depth, 2);
  EXPECT_GT(r.report.dofs, plain.report.dofs);
  for (const RefineBox& b : r.report.refined) {  // all in the corner (with its ring)
    EXPECT_LE(b.u0, 0.5) << b.level;
    EXPECT_GE(b.v1, 0.5) << b.level;
  }
  EXPECT_TRUE(plain.report.refined.empty());
  EXPECT_LT(r.report.dofs, r.report.export_poles / 2);  // only there
}

TEST(HierarchicalSolver, TheInfluenceLevelKeepsAnEditLocal) {
  // A point pulled up in the middle of a flat sheet with its boundary kept (Boier-Martin et al.
  // 4.2): with every level free the whole sheet bends; with the coarse levels held, refinement
  // around the point meets it and the sheet away from it does not move.
  SheetProblem pb = wave_problem(4);
  pb.curves.clear();
  pb.points.push_back({0.5, 0.5, Eigen::Vector3d(0.5, 0.5, 0.3)});
  HierarchicalOptions ho;
  ho.tolerance = 1e-6;
  ho.max_depth = 4;
  const HierarchicalResult global = solve_hierarchical(pb, ho, exact_options());
  ho.influence_level = 2;
  const HierarchicalResult local = solve_hierarchical(pb, ho, exact_options());
  ASSERT_TRUE(global.report.met && local.report.met);
  EXPECT_EQ(global.report.depth, 0);
  EXPECT_GE(local.report.depth, 2);
  const auto z = [](const HierarchicalResult& r, double u, double v) {
    return evaluate_surface(r.space, r.poles, u, v, 0)(0, 2);
  };
  for (const HierarchicalResult* r : {&global, &local}) EXPECT_NEAR(z(*r, 0.5, 0.5), 0.3, 1e-9);
  EXPECT_GT(z(global, 0.2, 0.5), 0.01);            // global: far from the point it moves
  EXPECT_LT(std::abs(z(local, 0.2, 0.5)), 1e-12);  // local: it keeps the start shape there
  EXPECT_GT(z(local, 0.45, 0.5), 0.01);            // but not right beside the point
}

TEST(HierarchicalSolver, RefusesWhatItCannotRepresent) {
  SheetProblem pb = wave_problem(4);
  pb.fixed_poles = {0, 1, 2};  // not the whole boundary
  SolveReport rep;
  EXPECT_THROW(solve_on_hierarchy(pb, HierarchicalSpace(pb.space), exact_options(), rep),
               InvalidInput);
  HierarchicalOptions ho;
  ho.tolerance = 0.0;
  EXPECT_THROW(solve_hierarchical(wave_problem(2), ho, exact_options()), InvalidInput);
  ho.tolerance = 1e-3;
  ho.manual = {{4, 0.0, 1.0, 0.0, 1.0}};  // the depth limit is 4: levels 0..3 can be refined
  EXPECT_THROW(solve_hierarchical(wave_problem(2), ho, exact_options()), InvalidInput);
  ho.manual = {{0, 0.6, 0.2, 0.0, 1.0}};  // u0 > u1
  EXPECT_THROW(solve_hierarchical(wave_problem(2), ho, exact_options()), InvalidInput);
}

namespace {

// Half a unit cylinder (rational, like a Part cylinder's face) with its boundary kept and as its
// rest shape, and a generator of it as a curve: a curve the base already contains.
SheetProblem half_cylinder_problem() {
  SheetProblem pb;
  pb.space = test::half_cylinder_space();
  pb.initial_poles = test::half_cylinder_poles(pb.space);
  pb.rest_poles = pb.initial_poles;
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  pb.fixed_poles = boundary_pole_indices(pb.space);
  const Eigen::Vector3d a = evaluate_surface(pb.space, pb.initial_poles, 0.25, 0.1, 0).row(0);
  const Eigen::Vector3d b = evaluate_surface(pb.space, pb.initial_poles, 0.25, 0.9, 0).row(0);
  CurveConstraint c;
  c.preimage = test::line_curve(Eigen::Vector2d(0.25, 0.1), Eigen::Vector2d(0.25, 0.9));
  c.target = test::line_curve(a, b);  // a straight line on the cylinder
  pb.curves.push_back(c);
  return pb;
}

// A curve along v at u = 0.75, pushed out of the cylinder by up to `bump`.
CurveConstraint bump_curve(const SheetProblem& pb, double bump) {
  const auto pre = [](double t) { return Eigen::Vector2d(0.75, 0.2 + 0.6 * t); };
  CurveConstraint c;
  c.preimage = test::line_curve(pre(0.0), pre(1.0));
  std::vector<double> breaks;
  for (int i = 0; i <= 24; ++i) breaks.push_back(i / 24.0);
  c.target = fit_piecewise_curve(breaks, 3, 3, [&](double t) {
    const Eigen::Vector2d uv = pre(t);
    const Eigen::Vector3d p = evaluate_surface(pb.space, pb.initial_poles, uv(0), uv(1), 0).row(0);
    const double s = 1.0 + bump * std::pow(std::sin(pi * t), 2);
    Eigen::VectorXd q(3);
    q << s * p(0), s * p(1), p(2);
    return q;
  });
  return c;
}

}  // namespace

TEST(HierarchicalSolver, ARationalBaseThatMeetsItsCurvesComesBackItself) {
  // Curves lying on a cylinder reproduce the cylinder, with refined layers too.
  const SheetProblem pb = half_cylinder_problem();
  HierarchicalSpace h(pb.space);
  h.refine_box(0, 0.0, 0.5, 0.3, 0.7);
  h.refine_box(1, 0.1, 0.3, 0.4, 0.6);
  ASSERT_EQ(h.levels(), 3);
  SolveReport rep;
  const Eigen::MatrixX3d p = solve_on_hierarchy(pb, h, exact_options(), rep);
  EXPECT_LT((p - h.base_to_finest(pb.initial_poles)).cwiseAbs().maxCoeff(), 1e-12);
  for (double u : {0.1, 0.3, 0.6, 0.9})
    for (double v : {0.2, 0.5, 0.8}) {
      const Eigen::Vector3d x = evaluate_surface(h.finest(), p, u, v, 0).row(0);
      EXPECT_NEAR(std::hypot(x(0), x(1)), 1.0, 1e-12);
    }
}

TEST(HierarchicalSolver, ARationalBaseRefinedEverywhereEqualsTheUniformSolve) {
  SheetProblem pb = half_cylinder_problem();
  pb.curves.push_back(bump_curve(pb, 0.05));
  HierarchicalSpace h(pb.space);
  EXPECT_EQ(h.refine_box(0, 0.0, 1.0, 0.0, 1.0), 6);
  SolveReport rep;
  const Eigen::MatrixX3d hp = solve_on_hierarchy(pb, h, exact_options(), rep);
  // The same problem posed on the halved rational space itself (every base span refined: the
  // hierarchy's functions are that space's), solved by the uniform solver.
  SheetProblem fine = pb;
  fine.space = h.finest();
  fine.initial_poles = h.base_to_finest(pb.initial_poles);
  fine.rest_poles = fine.initial_poles;
  fine.fixed_poles = boundary_pole_indices(fine.space);
  const SolveResult u = solve_sheet(fine, exact_options());
  EXPECT_LT((hp - u.poles).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(HierarchicalSolver, ARationalBaseIsRefinedWhereItsCurveIsOff) {
  SheetProblem pb = half_cylinder_problem();
  pb.curves.push_back(bump_curve(pb, 0.05));
  HierarchicalOptions ho;
  ho.tolerance = 1e-5;
  ho.max_depth = 6;
  const HierarchicalResult r = solve_hierarchical(pb, ho, exact_options());
  ASSERT_TRUE(r.report.met) << r.report.round_error.back();
  ASSERT_TRUE(r.space.rational());
  EXPECT_GT(r.report.depth, 0);
  EXPECT_GT(r.report.round_error.front(), 1e-3);  // the coarse cylinder cannot hold the bump
  EXPECT_LT(r.report.dofs, r.report.export_poles);
  for (const CurveConstraint& c : pb.curves)
    EXPECT_LE(incidence_error(r.space, r.poles, c, 1000), 1.5e-5);  // between the samples too
  // The boundary is kept: the half circles at the ends are still circles.
  for (double u : {0.1, 0.4, 0.7})
    for (double v : {0.0, 1.0}) {
      const Eigen::Vector3d x = evaluate_surface(r.space, r.poles, u, v, 0).row(0);
      EXPECT_NEAR(std::hypot(x(0), x(1)), 1.0, 1e-12);
    }
}
