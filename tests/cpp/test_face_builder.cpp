// SPDX-License-Identifier: LGPL-2.1-or-later
// make_face: a sheet becomes a face that OCCT's checker finds valid and that carries the sheet
// exactly; an invalid sheet is refused.
#include <gtest/gtest.h>

#include <cmath>

#include "occ_test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/face_builder.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/shape_check.hpp"

namespace varsurf {
namespace {

TEST(MakeFace, IsValidAndCarriesTheSheet) {
  const BSplineSurface sheet = test::curved_sheet();
  const TopoDS_Face face = occ::make_face(sheet);
  const occ::ShapeCheck check = occ::check_shape(face);
  EXPECT_TRUE(check.valid) << check.message;
  EXPECT_EQ(check.message, "valid");
  const BSplineSurface back = occ::surface_from_face(face);
  EXPECT_EQ(back.space.knots_u, sheet.space.knots_u);
  EXPECT_LT((back.poles - sheet.poles).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(MakeFace, RejectsInvalidSheet) {
  BSplineSurface sheet = test::curved_sheet();
  sheet.poles(2, 2) = std::nan("");
  EXPECT_THROW(occ::make_face(sheet), InvalidInput);
}

}  // namespace
}  // namespace varsurf
