// SPDX-License-Identifier: LGPL-2.1-or-later
// Resource limits of a solve: max_unknowns, memory_limit (refused before allocating, by the
// estimate) and time_limit (stopped between steps), each with ResourceLimit and a message.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/hierarchical_solver.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

SheetProblem pinned_sheet(int spans) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  // Flat poles on a grid (the uniform space's Greville points are not needed: the sheet is flat).
  pb.initial_poles.resize(pb.space.size(), 3);
  for (int i = 0; i < pb.space.nu(); ++i)
    for (int j = 0; j < pb.space.nv(); ++j)
      pb.initial_poles.row(pb.space.index(i, j)) =
          Eigen::RowVector3d(i / (pb.space.nu() - 1.0), j / (pb.space.nv() - 1.0), 0.0);
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  PointConstraint p;
  p.u = p.v = 0.5;
  p.target = Eigen::Vector3d(0.5, 0.5, 0.2);
  pb.points.push_back(p);
  return pb;
}

std::string message_of(const SheetProblem& pb, const SolveOptions& opt) {
  try {
    solve_sheet(pb, opt);
  } catch (const ResourceLimit& e) {
    return e.what();
  }
  return "";
}

// The ResourceLimit message of a solve and how long the solve took before it.
std::pair<std::string, double> timed_message(const SheetProblem& pb, const SolveOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  std::string m = message_of(pb, opt);
  return {m, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace

TEST(SolveLimits, EstimateGrowsAsNLogNAndTheExactModeNeedsMost) {
  const double small = estimate_solve_bytes(1000, 49, SolveMode::exact);
  const double large = estimate_solve_bytes(100000, 49, SolveMode::exact);
  // n log n: 100x the unknowns cost between 100x and 100x * log ratio (plus the linear part).
  EXPECT_GT(large / small, 100.0);
  EXPECT_LT(large / small, 100.0 * std::log2(100002.0) / std::log2(1002.0) * 1.01);
  EXPECT_GT(estimate_solve_bytes(100000, 49, SolveMode::exact),
            4.0 * estimate_solve_bytes(100000, 49, SolveMode::penalty));
  EXPECT_EQ(estimate_solve_bytes(100000, 49, SolveMode::automatic),
            estimate_solve_bytes(100000, 49, SolveMode::exact));
  EXPECT_EQ(estimate_solve_bytes(0, 49, SolveMode::exact), 0.0);
}

TEST(SolveLimits, TooManyPolesAreRefusedWithTheLimitNamed) {
  SolveOptions opt;
  opt.max_unknowns = 100;
  const std::string m = message_of(pinned_sheet(16), opt);  // 361 poles
  EXPECT_NE(m.find("361 poles"), std::string::npos) << m;
  EXPECT_NE(m.find("limit of 100"), std::string::npos) << m;
}

TEST(SolveLimits, MemoryBeyondTheLimitIsRefusedBeforeAllocating) {
  const SheetProblem pb = pinned_sheet(256);  // 67081 poles
  SolveOptions opt;
  opt.memory_limit = 50e6;
  const auto [m, seconds] = timed_message(pb, opt);
  EXPECT_NE(m.find("memory limit of 50 MB"), std::string::npos) << m;
  EXPECT_NE(m.find("MaxSpans"), std::string::npos) << m;  // says what to do
  // Refused at the estimate, not after assembling: far quicker than the solve (~1 s).
  EXPECT_LT(seconds, 0.2);
  // Within the limit the same problem solves.
  opt.memory_limit = 0.0;
  opt.mode = SolveMode::penalty;
  opt.fit_tolerance = 1e-4;
  const SolveResult r = solve_sheet(pinned_sheet(32), opt);
  EXPECT_TRUE(r.poles.allFinite());
}

TEST(SolveLimits, ALongSolveStopsAtItsTimeLimit) {
  SheetProblem pb = pinned_sheet(24);
  Repeller r;  // iterated: many steps, each checking the clock
  r.origin = Eigen::Vector3d(0.5, 0.5, -0.2);
  r.strength = 1.0;
  pb.repellers.push_back(r);
  SolveOptions opt;
  opt.max_iterations = 100000;
  opt.nonlinear_tolerance = 1e-300;  // never converges by itself
  opt.time_limit = 0.3;
  const auto [m, seconds] = timed_message(pb, opt);
  EXPECT_NE(m.find("time limit of 0.3 s"), std::string::npos) << m;
  EXPECT_GT(seconds, 0.3);
  EXPECT_LT(seconds, 3.0);  // one step past the deadline at most
  // The budget ended with the solve: the next solve on this thread has its own.
  opt.time_limit = 0.0;
  opt.max_iterations = 3;
  EXPECT_NO_THROW(solve_sheet(pb, opt));
}

TEST(SolveLimits, NegativeOrNanLimitsAreInvalid) {
  SolveOptions opt;
  opt.time_limit = -1.0;
  EXPECT_THROW(solve_sheet(pinned_sheet(4), opt), InvalidInput);
  opt.time_limit = 0.0;
  opt.memory_limit = std::nan("");
  EXPECT_THROW(solve_sheet(pinned_sheet(4), opt), InvalidInput);
}

TEST(SolveLimits, TheHierarchicalFinestLevelIsCheckedToo) {
  const SheetProblem pb = pinned_sheet(8);
  HierarchicalOptions h;
  h.max_depth = 1;
  h.automatic = false;
  SolveOptions opt;
  opt.mode = SolveMode::penalty;
  opt.fit_tolerance = 1e-4;
  // 5 MB: the 8-span base fits (about 2.6 MB by the estimate), its 16-span finest level (about
  // 9 MB) does not.
  opt.memory_limit = 5e6;
  EXPECT_NO_THROW(solve_hierarchical(pb, h, opt));
  h.manual.push_back({0, 0.0, 1.0, 0.0, 1.0});  // refine everything: 16 spans
  EXPECT_THROW(solve_hierarchical(pb, h, opt), ResourceLimit);
}
