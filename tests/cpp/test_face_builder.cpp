// SPDX-License-Identifier: LGPL-2.1-or-later
// make_face: a sheet becomes a face that OCCT's checker finds valid and that carries the sheet
// exactly; an invalid sheet is refused.
#include <gtest/gtest.h>
#include <BRep_Tool.hxx>
#include <GeomConvert.hxx>
#include <Geom_SphericalSurface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax3.hxx>

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

TEST(MakeFace, SidesThatArePointsWithinToleranceBecomeExactPoints) {
  // OCCT's sphere as NURBS, one pole row spread by rounding (1e-12 mm) and the other by 1e-3
  // (a side the solve opened up): the first becomes one point, the second and the rest stay.
  const Handle(Geom_BSplineSurface) nurbs = GeomConvert::SurfaceToBSplineSurface(
      new Geom_SphericalSurface(gp_Ax3(gp::Origin(), gp::DZ()), 15.0));
  BSplineSurface sheet = occ::from_geom(nurbs);
  const SplineSpace& sp = sheet.space;
  for (int i = 0; i < sp.nu(); ++i) {
    sheet.poles(sp.index(i, 0), 0) += 1e-12 * std::sin(i);
    sheet.poles(sp.index(i, sp.nv() - 1), 1) += 1e-3 * std::cos(i);
  }
  const TopoDS_Face face = occ::make_face(sheet);
  const BSplineSurface back = occ::surface_from_face(face);
  double spread_first = 0.0, spread_last = 0.0;
  for (int i = 1; i < sp.nu(); ++i) {
    spread_first = std::max(
        spread_first, (back.poles.row(sp.index(i, 0)) - back.poles.row(sp.index(0, 0))).norm());
    spread_last = std::max(spread_last, (back.poles.row(sp.index(i, sp.nv() - 1)) -
                                         back.poles.row(sp.index(0, sp.nv() - 1)))
                                            .norm());
  }
  EXPECT_EQ(spread_first, 0.0);
  EXPECT_GT(spread_last, 1e-3);
  // Moved by no more than the rounding; every other pole kept exactly.
  EXPECT_LT((back.poles - sheet.poles).cwiseAbs().maxCoeff(), 1e-11);
  for (int i = 0; i < sp.nu(); ++i)
    for (int j = 1; j < sp.nv(); ++j)
      EXPECT_EQ(back.poles.row(sp.index(i, j)), sheet.poles.row(sp.index(i, j)));
  int degenerated = 0;
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next())
    degenerated += BRep_Tool::Degenerated(TopoDS::Edge(e.Current())) ? 1 : 0;
  EXPECT_EQ(degenerated, 1);  // the opened side is an edge now
  const occ::ShapeCheck check = occ::check_shape(face);
  EXPECT_TRUE(check.valid) << check.message;
}

}  // namespace
}  // namespace varsurf
