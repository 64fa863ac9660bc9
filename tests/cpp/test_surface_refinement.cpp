// SPDX-License-Identifier: LGPL-2.1-or-later
// refine_surface: raising the degree and inserting knots up to the requested span counts moves no
// point of a rational, non-uniform sheet; a sheet fine enough already comes back as it is.
#include <gtest/gtest.h>

#include <random>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/occ/surface_refinement.hpp"

TEST(RefineSurface, KeepsTheSurfaceAndReachesTheSpanCounts) {
  // A rational, non-uniform, bilinear-in-v sheet: degree raised to 3 and spans to 7 x 5 must not
  // move a single point.
  varsurf::BSplineSurface s;
  s.space = varsurf::SplineSpace::uniform(2, 1, 2, 1);
  s.space.knots_u = {0, 0, 0, 0.3, 1, 1, 1};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uni(0.5, 1.5);
  s.space.weights.resize(s.space.size());
  s.poles.resize(s.space.size(), 3);
  for (int k = 0; k < s.space.size(); ++k) {
    s.space.weights(k) = uni(rng);
    s.poles.row(k) = Eigen::RowVector3d(uni(rng), uni(rng), uni(rng)) * 10.0;
  }
  const varsurf::BSplineSurface r = varsurf::occ::refine_surface(s, 7, 5, 3);
  EXPECT_EQ(r.space.degree_u, 3);
  EXPECT_EQ(r.space.degree_v, 3);
  EXPECT_EQ(varsurf::breakpoints(r.space.knots_u, 3).size(), 8u);
  EXPECT_EQ(varsurf::breakpoints(r.space.knots_v, 3).size(), 6u);
  for (double u = 0.0; u <= 1.0; u += 0.0625)
    for (double v = 0.0; v <= 1.0; v += 0.125)
      EXPECT_LT((r.evaluate(u, v) - s.evaluate(u, v)).norm(), 1e-12) << u << " " << v;
  // Already fine enough: returned as is.
  const varsurf::BSplineSurface same = varsurf::occ::refine_surface(r, 2, 2, 2);
  EXPECT_EQ(same.space.knots_u, r.space.knots_u);
  EXPECT_THROW(varsurf::occ::refine_surface(s, 0, 4), varsurf::InvalidInput);
  EXPECT_THROW(varsurf::occ::refine_surface(s, 4, 4, 12), varsurf::InvalidInput);
}
