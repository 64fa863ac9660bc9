// SPDX-License-Identifier: LGPL-2.1-or-later
// Area and volume integrated to a stated precision: a pillow of two paraboloid domes has its
// analytic ones; a null shape and precisions outside (0, 0.1] are refused.
#include <gtest/gtest.h>
#include <TopoDS_Shape.hxx>

#include <cmath>

#include "occ_test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/mass_properties.hpp"

using namespace varsurf;

namespace {

using test::kArea;
using test::kVolume;
using test::pillow;

}  // namespace

TEST(MassProperties, PillowOfTwoDomesHasTheAnalyticAreaAndVolume) {
  const occ::MassProperties m = occ::mass_properties(pillow(0.0).shape);
  EXPECT_NEAR(m.volume, kVolume, 1e-8 * kVolume);
  EXPECT_NEAR(m.area, kArea, 1e-8 * kArea);
  EXPECT_THROW(occ::mass_properties(TopoDS_Shape()), InvalidInput);
  EXPECT_THROW(occ::mass_properties(pillow(0.0).shape, 0.0), InvalidInput);
  EXPECT_THROW(occ::mass_properties(pillow(0.0).shape, std::nan("")), InvalidInput);
}
