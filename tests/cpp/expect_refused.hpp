// SPDX-License-Identifier: LGPL-2.1-or-later
// The core's refusals: a call that must throw InvalidInput whose message names the problem.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf::test {

template <class Call>
void expect_refused(Call call, const std::string& words) {
  try {
    call();
    ADD_FAILURE() << "accepted: " << words;
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

}  // namespace varsurf::test
