// SPDX-License-Identifier: LGPL-2.1-or-later
// libFuzzer harness over the core solver: random spaces, degrees, knots, weights (NaN and inf
// included), constraint sets, operators, fixed poles and solve modes. A solve may refuse its input
// (InvalidInput), fail numerically (SolveFailure) or stop (Cancelled); anything else -- a crash, a
// sanitizer report, another exception, or a "successful" result that is not finite -- is a bug.
#include <cstdio>
#include <cstdlib>

#include "fuzz_input.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/hierarchical_solver.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;
using varsurf::fuzz::number;

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "fuzz_core_solver: %s\n", what);
  std::abort();
}

Region region(FuzzedDataProvider& in) {
  if (in.ConsumeIntegralInRange<int>(0, 4) == 0) {
    std::vector<Eigen::Vector2d> loop;
    const int n = in.ConsumeIntegralInRange<int>(0, 6);
    for (int k = 0; k < n; ++k) loop.emplace_back(number(in, -0.1, 1.1), number(in, -0.1, 1.1));
    return Region(loop);
  }
  return Region(number(in, -0.1, 1.0), number(in, 0.0, 1.1), number(in, -0.1, 1.0),
                number(in, 0.0, 1.1));
}

SheetProblem problem(FuzzedDataProvider& in) {
  SheetProblem pb;
  pb.space = fuzz::space(in);
  const int n = std::max(0, std::min(pb.space.size(), 4096));
  pb.initial_poles.resize(n, 3);
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) pb.initial_poles(k, c) = number(in, -10.0, 10.0);
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) {
    pb.energy.alpha << number(in, 0, 2), number(in, -1, 1), number(in, -1, 1), number(in, 0, 2);
    pb.energy.beta << number(in, 0, 2), number(in, 0, 2), number(in, 0, 2), number(in, 0, 2);
  } else {
    pb.energy = ThinPlateWeights::isotropic(number(in, 0.0, 2.0), number(in, 0.0, 2.0));
  }
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) pb.rest_poles = pb.initial_poles;
  for (int k = in.ConsumeIntegralInRange<int>(0, 3); k > 0; --k)
    pb.points.push_back({number(in, -0.1, 1.1), number(in, -0.1, 1.1), fuzz::vector3(in, 10),
                         number(in, 0.0, 2.0)});
  for (int k = in.ConsumeIntegralInRange<int>(0, 3); k > 0; --k) {
    CurveConstraint c;
    c.preimage = fuzz::curve(in, 2, -0.05, 1.05);
    c.target = fuzz::curve(in, 3, -10, 10);
    if (in.ConsumeBool()) c.target.knots = c.preimage.knots;  // share the parameter mostly
    c.weight = number(in, 0.0, 2.0);
    c.exact = in.ConsumeBool();
    pb.curves.push_back(c);
  }
  for (int k = in.ConsumeIntegralInRange<int>(0, 2); k > 0; --k)
    pb.tangents.push_back({number(in, 0, 1), number(in, 0, 1),
                           in.ConsumeIntegralInRange<int>(-1, 2), fuzz::vector3(in, 5),
                           number(in, 0, 2)});
  for (int k = in.ConsumeIntegralInRange<int>(0, 2); k > 0; --k)
    pb.normals.push_back({number(in, 0, 1), number(in, 0, 1), fuzz::vector3(in, 1), 1.0});
  for (int k = in.ConsumeIntegralInRange<int>(0, 1); k > 0; --k)
    pb.plane_points.push_back(
        {number(in, 0, 1), number(in, 0, 1), fuzz::vector3(in, 5), fuzz::vector3(in, 1), 1.0});
  for (int k = in.ConsumeIntegralInRange<int>(0, 1); k > 0; --k)
    pb.line_points.push_back(
        {number(in, 0, 1), number(in, 0, 1), fuzz::vector3(in, 5), fuzz::vector3(in, 1), 1.0});
  for (int k = in.ConsumeIntegralInRange<int>(0, 2); k > 0; --k) {
    Attractor a;
    a.kind = static_cast<AttractorKind>(in.ConsumeIntegralInRange<int>(0, 2));
    a.region = region(in);
    a.origin = fuzz::vector3(in, 10);
    a.direction = fuzz::vector3(in, 1);
    a.strength = number(in, 0, 5);
    pb.attractors.push_back(a);
  }
  if (in.ConsumeIntegralInRange<int>(0, 5) == 0)
    pb.directors.push_back({region(in), fuzz::vector3(in, 1), number(in, 0, 5)});
  if (in.ConsumeIntegralInRange<int>(0, 7) == 0)
    pb.repellers.push_back({region(in), fuzz::vector3(in, 10), number(in, 0, 5)});
  if (in.ConsumeIntegralInRange<int>(0, 7) == 0) pb.pressure = number(in, -1, 1);
  const int fixed = in.ConsumeIntegralInRange<int>(0, 3);
  if (fixed == 1) pb.fixed_poles = boundary_pole_indices(pb.space);
  for (int k = fixed == 2 ? in.ConsumeIntegralInRange<int>(1, 4) : 0; k > 0; --k)
    pb.fixed_poles.push_back(in.ConsumeIntegralInRange<int>(-2, n + 2));
  return pb;
}

SolveOptions options(FuzzedDataProvider& in) {
  SolveOptions o;
  o.mode = static_cast<SolveMode>(in.ConsumeIntegralInRange<int>(0, 5));
  o.fit_tolerance = in.ConsumeBool() ? 0.0 : number(in, 0.0, 0.1);
  o.max_iterations = in.ConsumeIntegralInRange<int>(0, 8);  // bounded work per input
  o.penalty_steps = in.ConsumeIntegralInRange<int>(0, 30);
  o.max_weight_gain = in.ConsumeBool() ? 1.0 : number(in, 0.5, 1e4);
  o.drag_responses = in.ConsumeBool();
  o.max_unknowns = 20000;
  if (in.ConsumeIntegralInRange<int>(0, 9) == 0) o.time_limit = 1e-9;    // times out at once
  if (in.ConsumeIntegralInRange<int>(0, 9) == 0) o.memory_limit = 1024;  // far too little
  return o;
}

void check(const Eigen::MatrixX3d& poles, int expected) {
  if (poles.rows() != expected) fail("result has the wrong number of poles");
  if (!poles.allFinite()) fail("a solve returned non-finite poles instead of an error");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  const int entry = in.ConsumeIntegralInRange<int>(0, 3);
  try {
    const SheetProblem pb = problem(in);
    const SolveOptions opt = options(in);
    if (entry <= 1) {
      check(solve_sheet(pb, opt).poles, pb.space.size());
    } else if (entry == 2) {
      PreparedSheet prepared(pb, opt);
      check(prepared.result().poles, pb.space.size());
      SheetProblem moved = pb;
      for (auto& p : moved.points) p.target += fuzz::vector3(in, 1);
      check(prepared.update(moved).poles, pb.space.size());
      // Again: after a one-step solve, the penalty mode's drag responses take over.
      for (auto& p : moved.points) p.target += fuzz::vector3(in, 1);
      check(prepared.update(moved).poles, pb.space.size());
    } else {
      HierarchicalOptions h;
      h.tolerance = number(in, 1e-6, 1.0);
      h.max_depth = in.ConsumeIntegralInRange<int>(0, 2);
      h.samples = in.ConsumeIntegralInRange<int>(0, 40);
      h.influence_level = in.ConsumeIntegralInRange<int>(-1, 2);
      const HierarchicalResult r = solve_hierarchical(pb, h, opt);
      check(r.poles, r.space.size());
    }
  } catch (const InvalidInput&) {
  } catch (const SolveFailure&) {
  } catch (const Cancelled&) {
  } catch (const ResourceLimit&) {
  }
  return 0;
}
