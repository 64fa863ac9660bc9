// SPDX-License-Identifier: LGPL-2.1-or-later
// Wall-clock timing of solver phases (SolveReport's *_seconds).
#pragma once

#include <chrono>

namespace varsurf {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace varsurf
