// SPDX-License-Identifier: LGPL-2.1-or-later
// Normal fields along a curve: a face's normal turned about the curve, and the normal of the strip
// between two curves, checked on planes whose normals are known.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <gp_Pln.hxx>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/normal_field.hpp"

TEST(NormalField, PlaneNormalTurnedAboutTheCurve) {
  // On the plane z = 0 the normal is +z; turned +30 degrees about the +x tangent of a line along
  // x it becomes (0, -sin 30, cos 30).
  const TopoDS_Face plane =
      BRepBuilderAPI_MakeFace(gp_Pln(gp::Origin(), gp::DZ()), -10, 10, -10, 10);
  const varsurf::BSplineCurve line =
      varsurf::test::line_curve(Eigen::Vector3d(-5, 1, 0), Eigen::Vector3d(5, 1, 0), 0.0, 3.0);
  const varsurf::BSplineCurve n = varsurf::occ::normal_field(plane, line, 30.0, 1e-6);
  EXPECT_DOUBLE_EQ(n.first(), 0.0);
  EXPECT_DOUBLE_EQ(n.last(), 3.0);
  for (double t : {0.0, 0.7, 1.9, 3.0}) {
    const Eigen::Vector3d v = n.evaluate(t);
    EXPECT_LT((v - Eigen::Vector3d(0.0, -0.5, std::sqrt(3.0) / 2.0)).norm(), 1e-7) << t;
  }
  const varsurf::BSplineCurve above =
      varsurf::test::line_curve(Eigen::Vector3d(-5, 1, 2), Eigen::Vector3d(5, 1, 2));
  EXPECT_THROW(varsurf::occ::normal_field(plane, above, 0.0, 1e-3), varsurf::InvalidInput);
}

TEST(NormalField, StripToASecondCurve) {
  // From a line along x at z = 0 to a parallel line at y = 1, z = 1: the strip's normal is
  // x cross (0, 1, 1) / sqrt 2 = (0, -1, 1) / sqrt 2 everywhere.
  const varsurf::BSplineCurve line =
      varsurf::test::line_curve(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 0, 0));
  const varsurf::BSplineCurve second =
      varsurf::test::line_curve(Eigen::Vector3d(-1, 1, 1), Eigen::Vector3d(5, 1, 1));
  const varsurf::BSplineCurve n = varsurf::occ::normal_field_between(line, second, 0.0);
  for (double t : {0.0, 0.3, 1.0}) {
    const Eigen::Vector3d v = n.evaluate(t);
    EXPECT_LT((v - Eigen::Vector3d(0, -1, 1) / std::sqrt(2.0)).norm(), 1e-7) << t;
  }
  // Turned by -45 degrees about x the strip's normal becomes (0, 0, 1).
  const Eigen::Vector3d turned =
      varsurf::occ::normal_field_between(line, second, -45.0).evaluate(0.5);
  EXPECT_LT((turned - Eigen::Vector3d(0, 0, 1)).norm(), 1e-7);
  // A second curve crossing the first has no strip there.
  const varsurf::BSplineCurve crossing =
      varsurf::test::line_curve(Eigen::Vector3d(2, -1, 0), Eigen::Vector3d(2, 1, 0));
  EXPECT_THROW(varsurf::occ::normal_field_between(line, crossing, 0.0), varsurf::InvalidInput);
}
