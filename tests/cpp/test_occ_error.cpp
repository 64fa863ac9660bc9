// SPDX-License-Identifier: LGPL-2.1-or-later
// guarded: an OCCT exception escaping a bridge call becomes a GeometryError that names the call,
// the exception's type and its message.
#include <gtest/gtest.h>
#include <Standard_DomainError.hxx>

#include <string>

#include "varsurf/occ/occ_error.hpp"

namespace varsurf {
namespace {

using occ::GeometryError;

TEST(OccError, StandardFailureBecomesGeometryError) {
  try {
    occ::guarded("testing", []() -> int { throw Standard_DomainError("boom"); });
    FAIL() << "no exception";
  } catch (const GeometryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("testing"), std::string::npos) << what;
    EXPECT_NE(what.find("Standard_DomainError"), std::string::npos) << what;
    EXPECT_NE(what.find("boom"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace varsurf
