// SPDX-License-Identifier: LGPL-2.1-or-later
// Revolved surfaces as B-splines smooth by their knots: of a cylinder's faces only the lateral one
// converts; its planes, and a box longer than a turn, are left to GeomConvert (null).
#include <gtest/gtest.h>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Tool.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include "occ_test_support.hpp"
#include "varsurf/occ/revolved_surface.hpp"

using namespace varsurf;

namespace {

using test::curved_face;

}  // namespace

TEST(GeomConvert, OtherSurfacesAreLeftToGeomConvert) {
  const TopoDS_Shape box = BRepPrimAPI_MakeCylinder(5.0, 10.0).Shape();
  for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face face = TopoDS::Face(ex.Current());
    const Handle(Geom_Surface) s = BRep_Tool::Surface(face);
    const bool plane = GeomAdaptor_Surface(s).GetType() == GeomAbs_Plane;
    EXPECT_EQ(occ::smooth_revolved_surface(s, 0.0, 1.0, 0.0, 1.0).IsNull(), plane);
  }
  // A box longer than a turn is not an arc.
  const Handle(Geom_Surface) cylinder =
      BRep_Tool::Surface(curved_face(BRepPrimAPI_MakeCylinder(5.0, 10.0).Shape()));
  EXPECT_TRUE(occ::smooth_revolved_surface(cylinder, 0.0, 7.0, 0.0, 1.0).IsNull());
}
