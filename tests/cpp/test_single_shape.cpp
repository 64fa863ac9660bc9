// SPDX-License-Identifier: LGPL-2.1-or-later
// only_face and only_edge: the one face or edge a shape stands for; a shape with none or several
// is refused.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <gp_Pln.hxx>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/single_shape.hpp"

namespace varsurf {
namespace {

TEST(SingleShape, PicksTheOnlyFaceOrEdge) {
  BRepBuilderAPI_MakeFace maker(gp_Pln(gp::XOY()), 0.0, 1.0, 0.0, 1.0);
  EXPECT_NO_THROW(occ::only_face(maker.Face()));
  EXPECT_THROW(occ::only_edge(maker.Face()), InvalidInput);  // four edges
  EXPECT_THROW(occ::only_face(TopoDS_Shape()), InvalidInput);
}

}  // namespace
}  // namespace varsurf
