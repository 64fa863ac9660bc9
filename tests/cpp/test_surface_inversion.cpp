// SPDX-License-Identifier: LGPL-2.1-or-later
// Point inversion on a rational surface with non-uniform knots: the closest point of points around
// it, started from a far one, is the global one OCCT's distance (BRepExtrema) finds.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>

#include <random>

#include "occ_test_support.hpp"
#include "varsurf/occ/surface_inversion.hpp"

namespace varsurf {
namespace {

using test::face_of;
using test::random_surface;

// The inversion alone: a point's closest point is global even when started from a far one.
TEST(SurfaceInversion, FindsTheGlobalClosestPointFromAnyStart) {
  std::mt19937 rng(5);
  const Handle(Geom_BSplineSurface) geom = random_surface(rng, 4, 9, 8);
  const TopoDS_Face face = face_of(geom);
  occ::SurfaceInversion inversion(geom);
  std::uniform_real_distribution<double> x(-20.0, 120.0), y(-20.0, 100.0), z(-30.0, 30.0);
  for (int k = 0; k < 200; ++k) {
    const gp_Pnt p(x(rng), y(rng), z(rng));
    occ::SurfacePoint far_start{0.0, 0.0, 0.0};
    const occ::SurfacePoint found = inversion.closest(p, &far_start);
    BRepExtrema_DistShapeShape reference(BRepBuilderAPI_MakeVertex(p).Vertex(), face);
    ASSERT_TRUE(reference.IsDone());
    EXPECT_NEAR(found.distance, reference.Value(), 1e-7) << k;
    EXPECT_NEAR(geom->Value(found.u, found.v).Distance(p), found.distance, 1e-9);
  }
}

}  // namespace
}  // namespace varsurf
