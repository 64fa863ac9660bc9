// SPDX-License-Identifier: LGPL-2.1-or-later
// Curves across the seam of a closed sheet cut where they cross it: each piece projects, and
// ends on the seam exactly.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <ElSLib.hxx>
#include <gp_Ax2.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>

#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/curve_projection.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/point_projection.hpp"
#include "varsurf/occ/seam_split.hpp"

using namespace varsurf;

namespace {

BSplineSurface cylinder_sheet() {
  BRepBuilderAPI_MakeFace maker(gp_Cylinder(gp::XOY(), 2.0), 0.0, 2 * M_PI, 0.0, 5.0);
  return occ::surface_from_face(maker.Face());
}

BSplineCurve arc(double radius, double from, double to) {
  return occ::curve_from_edge(
      BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, 2), gp::DZ()), radius), from, to).Edge());
}

}  // namespace

TEST(SeamSplit, AnArcAcrossACylindersSeamIsCutWhereItCrossesAndEachPieceProjects) {
  // From 3 rad to 8 rad around (crossing the seam once, at 2 pi), 1 mm outside the cylinder.
  const BSplineSurface sheet = cylinder_sheet();
  const BSplineCurve curve = arc(3.0, 3.0, 8.0);
  const std::vector<BSplineCurve> pieces = occ::split_at_seams(sheet, curve);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_DOUBLE_EQ(pieces.front().first(), curve.first());
  EXPECT_DOUBLE_EQ(pieces.back().last(), curve.last());
  EXPECT_NEAR(pieces[0].last(), pieces[1].first(), 1e-12);
  // The cut is on the seam: the plane y = 0, x > 0, to rounding.
  const Eigen::VectorXd cut = pieces[0].evaluate(pieces[0].last());
  EXPECT_NEAR(cut(1), 0.0, 1e-12);
  EXPECT_GT(cut(0), 0.0);
  for (const BSplineCurve& piece : pieces) {
    const occ::PreImage pre = occ::project_curve(sheet, piece);
    EXPECT_NEAR(pre.max_distance, 1.0, 1e-6);
    // The pieces are the curve: same points at the same parameters.
    for (int k = 0; k <= 10; ++k) {
      const double t = piece.first() + (piece.last() - piece.first()) * k / 10;
      EXPECT_LT((piece.evaluate(t) - curve.evaluate(t)).norm(), 1e-12);
    }
  }
}

TEST(SeamSplit, CurvesThatDoNotCrossStayWhole) {
  const BSplineSurface sheet = cylinder_sheet();
  // Within one turn, from the seam to the seam, and a curve of an open sheet.
  for (const BSplineCurve& curve : {arc(3.0, 0.5, 5.0), arc(3.0, 0.0, 2.0 * M_PI)})
    EXPECT_EQ(occ::split_at_seams(sheet, curve).size(), 1u);
  BRepBuilderAPI_MakeFace half(gp_Cylinder(gp::XOY(), 2.0), 0.0, M_PI, 0.0, 5.0);
  EXPECT_EQ(occ::split_at_seams(occ::surface_from_face(half.Face()), arc(3.0, 0.5, 2.5)).size(),
            1u);
  EXPECT_THROW(occ::split_at_seams(sheet, arc(3.0, 0.5, 5.0), -1), InvalidInput);
}

TEST(SeamSplit, AnEndRingOfANarrowingTubeAcrossTheSeamIsCutNotRefusedAsLeavingTheFace) {
  // A cone's face all the way round, narrowing upward; its top edge as a full circle that starts
  // 1 rad past the seam. Where the ring's foot is held at the seam, its offset runs along the
  // seam's other side, partly along the top's outward direction: that is the crossing, not the
  // ring passing beyond the top.
  const gp_Cone cone(gp_Ax3(gp::XOY()), -M_PI / 8, 10.0);
  const double top = 20.0;
  const BSplineSurface sheet =
      occ::surface_from_face(BRepBuilderAPI_MakeFace(cone, 0.0, 2 * M_PI, 0.0, top).Face());
  const gp_Pnt lip = ElSLib::Value(0.0, top, cone);
  const double radius = std::hypot(lip.X(), lip.Y());
  const BSplineCurve ring = occ::curve_from_edge(
      BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, lip.Z()), gp::DZ()), radius), 1.0,
                              1.0 + 2 * M_PI)
          .Edge());
  try {
    occ::project_curve(sheet, ring);
    FAIL() << "a ring across the seam has no single pre-image";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("crosses the seam"), std::string::npos)
        << error.what();
  }
  const std::vector<BSplineCurve> pieces = occ::split_at_seams(sheet, ring);
  ASSERT_EQ(pieces.size(), 2u);
  for (const BSplineCurve& piece : pieces) {
    const occ::PreImage pre = occ::project_curve(sheet, piece);
    EXPECT_LT(pre.max_distance, 1e-9);
    EXPECT_LT(pre.boundary_distance, 1e-9);
  }
}
