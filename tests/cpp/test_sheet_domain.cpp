// SPDX-License-Identifier: LGPL-2.1-or-later
// A sheet's domain: a cylinder's lateral face closes in u only, a plane in neither direction;
// parameters within rounding of a bound snap onto it, those beyond are clamped, others kept.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <GeomAbs_SurfaceType.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pln.hxx>

#include <Eigen/Core>

#include "occ_test_support.hpp"
#include "varsurf/core/spline_space.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/sheet_domain.hpp"

namespace varsurf {
namespace {

using test::face_of;

TEST(SheetDomain, FindsTheSeamOfAClosedFaceOnly) {
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(20.0, 50.0).Shape();
  const BSplineSurface lateral = occ::surface_from_face(face_of(cylinder, GeomAbs_Cylinder));
  const occ::SheetDomain closed(lateral);
  EXPECT_TRUE(closed.closed(0));
  EXPECT_FALSE(closed.closed(1));
  const BSplineSurface plane = occ::surface_from_face(
      BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0.0, 100.0, 0.0, 60.0).Face());
  const occ::SheetDomain open(plane);
  EXPECT_FALSE(open.closed(0));
  EXPECT_FALSE(open.closed(1));
  // On the boundary within rounding: exactly on it; a visible distance inside: untouched.
  EXPECT_EQ(open.snapped({100.0 - 1e-13, 30.0}), Eigen::Vector2d(100.0, 30.0));
  EXPECT_EQ(open.snapped({3e-15, 1e-12}), Eigen::Vector2d(0.0, 0.0));
  EXPECT_EQ(open.snapped({1e-3, 30.0}), Eigen::Vector2d(1e-3, 30.0));
  EXPECT_EQ(open.snapped({-1.0, 61.0}), Eigen::Vector2d(0.0, 60.0));
}

}  // namespace
}  // namespace varsurf
