// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

// A constant 3D field over [0, 1] as a degree-1 curve.
BSplineCurve constant_field(const Eigen::Vector3d& n) {
  return test::line_curve(n, n);
}

// Sheet over the unit square whose boundary poles lie on z = slope * x.
SheetProblem tilted_problem(int spans, double slope) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  pb.initial_poles = test::fit_poles(
      pb.space, [&](double u, double v) { return Eigen::Vector3d(u, v, slope * u); });
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  for (int k = 0; k < pb.space.size(); ++k)
    if (std::find(pb.fixed_poles.begin(), pb.fixed_poles.end(), k) == pb.fixed_poles.end())
      pb.initial_poles(k, 2) = 0.0;  // interior starts flat: the solve must tilt it
  return pb;
}

}  // namespace

TEST(Ribbon, ConsistentWithAPlaneIsMetExactly) {
  const double slope = 0.4;
  SheetProblem pb = tilted_problem(6, slope);
  RibbonConstraint r;
  r.preimage = test::line_curve(Eigen::Vector2d(0.2, 0.3), Eigen::Vector2d(0.8, 0.6));
  r.normals = constant_field(Eigen::Vector3d(-slope, 0.0, 1.0));
  pb.ribbons.push_back(r);
  const SolveResult res = solve_sheet(pb);
  EXPECT_TRUE(res.report.coupled);
  EXPECT_LT(ribbon_angle_error(pb.space, res.poles, r), 1e-9);
  for (int k = 0; k < pb.space.size(); ++k)
    EXPECT_NEAR(res.poles(k, 2), slope * res.poles(k, 0), 1e-9);
}

TEST(Ribbon, FoldAlongADiagonalConvergesUnderRefinement) {
  // A flat sheet held at its boundary and along a diagonal line, asked to turn its normal 20
  // degrees about that line: no finite sheet does it exactly; the angle error must fall with
  // refinement until it reaches round-off (from 16 spans on, the sheet meets it to ~1e-14).
  const Eigen::Vector2d a(0.25, 0.3), b(0.75, 0.7);
  const Eigen::Vector3d along = Eigen::Vector3d(b.x() - a.x(), b.y() - a.y(), 0.0).normalized();
  const Eigen::Vector3d tilted =
      Eigen::AngleAxisd(20.0 * M_PI / 180.0, along) * Eigen::Vector3d::UnitZ();
  double previous = 1e300;
  for (int spans : {8, 16, 32}) {
    SheetProblem pb = tilted_problem(spans, 0.0);
    CurveConstraint hold;
    hold.preimage = test::line_curve(a, b);
    hold.target =
        test::line_curve(Eigen::Vector3d(a.x(), a.y(), 0.0), Eigen::Vector3d(b.x(), b.y(), 0.0));
    pb.curves.push_back(hold);
    RibbonConstraint r;
    r.preimage = hold.preimage;
    r.normals = constant_field(tilted);
    pb.ribbons.push_back(r);
    const SolveResult res = solve_sheet(pb);
    const double err = ribbon_angle_error(pb.space, res.poles, r, 400);
    EXPECT_TRUE(err < previous || err < 1e-10) << spans << ": " << err << " after " << previous;
    EXPECT_LT(incidence_error(pb.space, res.poles, hold), 1e-9) << spans;
    previous = err;
  }
  EXPECT_LT(previous * 180.0 / M_PI, 0.5);  // degrees, at 32 spans
}

TEST(Ribbon, AcrossOnlyMeetsTheSameFoldWhereTheSheetHoldsTheCurve) {
  // The fold above at 16 spans, with the ribbon's rows across the line only: the sheet holds the
  // line, so the row along it says nothing new; the fold is met as well and the sheet is the same.
  const Eigen::Vector2d a(0.25, 0.3), b(0.75, 0.7);
  const Eigen::Vector3d along = Eigen::Vector3d(b.x() - a.x(), b.y() - a.y(), 0.0).normalized();
  SheetProblem pb = tilted_problem(16, 0.0);
  CurveConstraint hold;
  hold.preimage = test::line_curve(a, b);
  hold.target =
      test::line_curve(Eigen::Vector3d(a.x(), a.y(), 0.0), Eigen::Vector3d(b.x(), b.y(), 0.0));
  hold.exact = true;
  pb.curves.push_back(hold);
  RibbonConstraint r;
  r.preimage = hold.preimage;
  r.normals =
      constant_field(Eigen::AngleAxisd(20.0 * M_PI / 180.0, along) * Eigen::Vector3d::UnitZ());
  pb.ribbons.push_back(r);
  const SolveResult both = solve_sheet(pb);
  pb.ribbons[0].across_only = true;
  const SolveResult across = solve_sheet(pb);
  EXPECT_EQ(sample_ribbon(pb.space, pb.ribbons[0]).rows() * 2, sample_ribbon(pb.space, r).rows());
  EXPECT_LT(ribbon_angle_error(pb.space, across.poles, r, 400), 1e-9);
  EXPECT_LT(incidence_error(pb.space, across.poles, hold), 1e-9);
  EXPECT_LT((across.poles - both.poles).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(Ribbon, RejectsBadInput) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  RibbonConstraint r;
  r.preimage = test::line_curve(Eigen::Vector2d(0.2, 0.3), Eigen::Vector2d(0.8, 0.6));
  r.normals = constant_field(Eigen::Vector3d::Zero());
  EXPECT_THROW(sample_ribbon(sp, r), InvalidInput);
  r.normals = test::line_curve(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(), 0.0, 2.0);
  EXPECT_THROW(sample_ribbon(sp, r), InvalidInput);
  r.normals = constant_field(Eigen::Vector3d::UnitZ());
  r.preimage = test::line_curve(Eigen::Vector2d(0.2, 0.3), Eigen::Vector2d(1.8, 0.6));
  EXPECT_THROW(sample_ribbon(sp, r), InvalidInput);
}
