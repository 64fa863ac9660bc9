// SPDX-License-Identifier: LGPL-2.1-or-later
// Error types thrown by the core. The binding maps each to a distinct Python exception.
#pragma once

#include <stdexcept>
#include <string>

namespace varsurf {

// The caller gave something the model cannot represent (bad knots, NaN, a curve outside the
// domain).
struct InvalidInput : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The input was well formed but the numerical solve failed (singular system, no convergence).
struct SolveFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The caller's progress callback asked to stop (SolveOptions::keep_going returned false).
struct Cancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The solve would exceed SolveOptions::time_limit or memory_limit (or max_unknowns): refused or
// stopped with a message saying which limit and what to change.
struct ResourceLimit : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace varsurf
