// SPDX-License-Identifier: LGPL-2.1-or-later
// project_point: the closest point of a sheet, checked on a point at a known distance along the
// normal of a curved sheet.
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/point_projection.hpp"

TEST(ProjectPoint, FindsTheParametersAndDistanceOfAPointAboveACurvedSheet) {
  varsurf::BSplineSurface s;
  s.space = varsurf::SplineSpace::uniform(3, 3, 3, 3);
  s.poles = varsurf::test::fit_poles(s.space, [](double u, double v) {
    return Eigen::Vector3d(10 * u, 8 * v, std::sin(u) + 0.5 * v * v);
  });
  const double u = 0.3, v = 0.7;
  const Eigen::MatrixXd d = varsurf::evaluate_surface(s.space, s.poles, u, v, 1);
  const Eigen::Vector3d n = Eigen::Vector3d(d.row(1)).cross(Eigen::Vector3d(d.row(2))).normalized();
  const varsurf::occ::PointOnSheet p =
      varsurf::occ::project_point(s, Eigen::Vector3d(d.row(0)) + 2.0 * n);
  EXPECT_NEAR(p.u, u, 1e-7);
  EXPECT_NEAR(p.v, v, 1e-7);
  EXPECT_NEAR(p.distance, 2.0, 1e-7);
  EXPECT_THROW(varsurf::occ::project_point(s, Eigen::Vector3d(NAN, 0, 0)), varsurf::InvalidInput);
}
