// SPDX-License-Identifier: LGPL-2.1-or-later
#include "solve_limits.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

using Clock = std::chrono::steady_clock;

// One solve per thread at a time: the Python binding releases no GIL during a solve, and FreeCAD
// recomputes on one thread.
thread_local bool budget_active = false;
thread_local Clock::time_point deadline;
thread_local double budget_seconds = 0.0;

std::string megabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f MB", bytes / 1e6);
  return text;
}

}  // namespace

SolveBudget::SolveBudget(const SolveOptions& options) {
  if (budget_active) return;
  if (!(options.time_limit >= 0.0) || !(options.memory_limit >= 0.0))
    throw InvalidInput("time_limit and memory_limit must be non-negative numbers (0: none)");
  if (options.time_limit == 0.0 || std::isinf(options.time_limit)) return;
  owner_ = true;
  budget_active = true;
  budget_seconds = options.time_limit;
  deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                std::chrono::duration<double>(options.time_limit));
}

SolveBudget::~SolveBudget() {
  if (owner_) budget_active = false;
}

void check_deadline() {
  if (budget_active && Clock::now() > deadline) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the solve took longer than its time limit of %.3g s; raise the limit, or "
                  "use fewer spans or a looser tolerance",
                  budget_seconds);
    throw ResourceLimit(text);
  }
}

double estimate_solve_bytes(long long unknowns, long long row_nonzeros, SolveMode mode) {
  const double n = static_cast<double>(unknowns), r = static_cast<double>(row_nonzeros);
  if (n <= 0.0) return 0.0;
  // Sparse factors of a 2D problem grow as n log n (nested dissection), with the energy's row
  // width r (per coordinate: a coupled solve's 3 coordinates a pole add to n, not to r). Peak
  // resident memory measured over solve_sheet on bicubic sheets (r = 49), separable and coupled,
  // of 64^2 to 256^2 poles: the exact mode's KKT LU took 2400-2950 bytes per n log2 n, the
  // penalty mode's Cholesky 410-470. The factors below bound both with a margin of 1.4 to 1.9;
  // automatic may pick the exact mode, so it counts as exact.
  const bool lu =
      mode == SolveMode::exact || mode == SolveMode::mtsvd || mode == SolveMode::automatic;
  const double per_entry = lu ? 80.0 : 16.0;
  return per_entry * r * n * std::log2(n + 2.0) + 512.0 * n;
}

void check_memory(long long unknowns, long long row_nonzeros, SolveMode mode,
                  const SolveOptions& options, const char* what) {
  if (options.memory_limit <= 0.0) return;
  const double need = estimate_solve_bytes(unknowns, row_nonzeros, mode);
  if (need > options.memory_limit)
    throw ResourceLimit(std::string(what) + " has " + std::to_string(unknowns) +
                        " unknowns and would need about " + megabytes(need) +
                        ", more than the memory limit of " + megabytes(options.memory_limit) +
                        "; use fewer spans (MaxSpans) or raise the limit");
}

}  // namespace varsurf
