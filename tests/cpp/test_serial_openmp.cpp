// SPDX-License-Identifier: LGPL-2.1-or-later
// The guard that holds the libraries' OpenMP regions to one thread during a factorization: it
// must put back what it found, and act on its own thread only.
#include <gtest/gtest.h>
#include <omp.h>

#include <optional>
#include <thread>

#include "serial_openmp.hpp"

using varsurf::SerialOpenMp;

TEST(SerialOpenMp, NoRegionIsActiveWhileItLivesAndTheSettingComesBack) {
  omp_set_max_active_levels(3);
  {
    const SerialOpenMp one_thread;
    EXPECT_EQ(omp_get_max_active_levels(), 0);
    {
      const SerialOpenMp nested;
      EXPECT_EQ(omp_get_max_active_levels(), 0);
    }
    EXPECT_EQ(omp_get_max_active_levels(), 0);
  }
  EXPECT_EQ(omp_get_max_active_levels(), 3);
}

TEST(SerialOpenMp, AGuardActsOnItsOwnThreadOnly) {
  // Solves run with the GIL released may overlap in two threads: each thread's guard holds that
  // thread's regions, and neither puts back the other's setting.
  omp_set_max_active_levels(2);
  std::optional<SerialOpenMp> first;
  first.emplace();
  std::thread other([] {
    const int before = omp_get_max_active_levels();
    EXPECT_GT(before, 0);  // the first guard does not reach this thread
    {
      const SerialOpenMp second;
      EXPECT_EQ(omp_get_max_active_levels(), 0);
    }
    EXPECT_EQ(omp_get_max_active_levels(), before);
  });
  other.join();
  EXPECT_EQ(omp_get_max_active_levels(), 0);
  first.reset();
  EXPECT_EQ(omp_get_max_active_levels(), 2);
}
