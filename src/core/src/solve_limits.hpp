// SPDX-License-Identifier: LGPL-2.1-or-later
// Resource limits of a solve (SolveOptions::time_limit, memory_limit): a deadline shared by every
// step of one solve, and a memory estimate checked before anything large is allocated.
#pragma once

#include "varsurf/core/sheet_solver.hpp"

namespace varsurf {

// Starts the clock of SolveOptions::time_limit for the solve on this thread, unless an enclosing
// solve already did (a hierarchical or hinge solve runs many inner solves on one budget).
class SolveBudget {
 public:
  explicit SolveBudget(const SolveOptions& options);
  ~SolveBudget();
  SolveBudget(const SolveBudget&) = delete;
  SolveBudget& operator=(const SolveBudget&) = delete;

 private:
  bool owner_ = false;
};

// Throws ResourceLimit when the current solve is past its deadline.
void check_deadline();

// Throws ResourceLimit when a problem of `unknowns` unknowns, each coupled to `row_nonzeros`
// others of its own coordinate, solved in `mode`, would need more than options.memory_limit
// (estimate_solve_bytes). Before assembly the mode is not known yet: the penalty mode's need is the
// least any takes.
void check_memory(long long unknowns, long long row_nonzeros, SolveMode mode,
                  const SolveOptions& options, const char* what);

}  // namespace varsurf
