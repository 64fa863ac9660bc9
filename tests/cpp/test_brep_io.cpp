// SPDX-License-Identifier: LGPL-2.1-or-later
// BREP text and binary BREP: a face's round trip keeps its sheet, orientation and location
// exactly; empty, foreign and truncated text and a null shape are refused.
#include <gtest/gtest.h>
#include <TopoDS.hxx>
#include <gp_Trsf.hxx>

#include <string>

#include "occ_test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/brep_io.hpp"
#include "varsurf/occ/face_builder.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/single_shape.hpp"

namespace varsurf {
namespace {

TEST(BrepIo, RoundTripAndGarbage) {
  const TopoDS_Face face = occ::make_face(test::curved_sheet());
  const std::string text = occ::write_brep(face);
  const TopoDS_Shape back = occ::read_brep(text);
  ASSERT_FALSE(back.IsNull());
  const BSplineSurface s = occ::surface_from_face(occ::only_face(back));
  EXPECT_LT((s.poles - test::curved_sheet().poles).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_THROW(occ::read_brep(""), InvalidInput);
  EXPECT_THROW(occ::read_brep("hello world"), InvalidInput);
  EXPECT_THROW(occ::read_brep(text.substr(0, text.size() / 2)), InvalidInput);
  EXPECT_THROW(occ::read_brep(text.substr(0, text.size() - 8)), InvalidInput);
  EXPECT_THROW(occ::write_brep(TopoDS_Shape()), InvalidInput);
}

TEST(BrepIo, BinaryRoundTripKeepsTheFaceExactly) {
  TopoDS_Face face = occ::make_face(test::curved_sheet());
  face.Reverse();  // an orientation and a location that must survive too
  gp_Trsf move;
  move.SetTranslation(gp_Vec(1.0, -2.0, 3.0));
  face.Location(TopLoc_Location(move));
  const std::string data = occ::write_brep_binary(face);
  const TopoDS_Shape back = occ::read_brep_binary(data);
  ASSERT_FALSE(back.IsNull());
  EXPECT_EQ(back.ShapeType(), TopAbs_FACE);
  EXPECT_EQ(back.Orientation(), TopAbs_REVERSED);
  EXPECT_TRUE(back.Location().Transformation().TranslationPart().IsEqual(gp_XYZ(1, -2, 3), 0.0));
  const BSplineSurface s = occ::surface_from_face(TopoDS::Face(back.Located(TopLoc_Location())));
  EXPECT_EQ((s.poles - test::curved_sheet().poles).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_THROW(occ::read_brep_binary(""), InvalidInput);
  EXPECT_THROW(occ::write_brep_binary(TopoDS_Shape()), InvalidInput);
}

}  // namespace
}  // namespace varsurf
