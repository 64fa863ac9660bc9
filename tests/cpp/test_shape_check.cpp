// SPDX-License-Identifier: LGPL-2.1-or-later
// check_shape: OCCT's checker summed up on one line; a face whose edges lie off its surface and a
// null shape are reported invalid.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Pln.hxx>

#include <string>

#include "varsurf/occ/shape_check.hpp"

namespace varsurf {
namespace {

TEST(ShapeCheck, ReportsProblems) {
  // A face on the plane z = 0 bounded by a wire lying in z = 1: its edges have no curves on the
  // face's surface.
  BRepBuilderAPI_MakeFace plane(gp_Pln(gp::XOY()), 0.0, 1.0, 0.0, 1.0);
  BRepBuilderAPI_MakeFace lifted(gp_Pln(gp_Ax3(gp_Pnt(0, 0, 1), gp::DZ())), 0.0, 1.0, 0.0, 1.0);
  TopoDS_Face face = TopoDS::Face(plane.Face().EmptyCopied());
  BRep_Builder b;
  for (TopExp_Explorer ex(lifted.Face(), TopAbs_WIRE); ex.More(); ex.Next())
    b.Add(face, ex.Current());
  const occ::ShapeCheck check = occ::check_shape(face);
  EXPECT_FALSE(check.valid);
  EXPECT_NE(check.message, "valid");
  EXPECT_NE(check.message.find("edge"), std::string::npos) << check.message;
  EXPECT_EQ(check.message.find('\n'), std::string::npos) << check.message;
}

TEST(ShapeCheck, NullShapeIsInvalid) {
  const occ::ShapeCheck check = occ::check_shape(TopoDS_Shape());
  EXPECT_FALSE(check.valid);
  EXPECT_EQ(check.message, "null shape");
}

}  // namespace
}  // namespace varsurf
