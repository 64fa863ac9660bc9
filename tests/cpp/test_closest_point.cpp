// SPDX-License-Identifier: LGPL-2.1-or-later
// ClosestPointTarget: closest points and their Gauss-Newton metrics on a face (inside and beyond
// its boundary) and on an edge; null shapes, vertices and non-finite points are refused.
#include <gtest/gtest.h>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <gp_Pln.hxx>

#include <cmath>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/closest_point.hpp"

TEST(ClosestPointTarget, FaceInteriorBoundaryAndEdges) {
  using varsurf::occ::ClosestPointTarget;
  const ClosestPointTarget face(
      BRepBuilderAPI_MakeFace(gp_Pln(gp::Origin(), gp::DZ()), 0, 2, 0, 1));
  EXPECT_TRUE(face.on_faces());
  // Above the interior: straight down, metric z z^T.
  varsurf::ClosestPoint c = face(Eigen::Vector3d(0.5, 0.25, 3.0));
  EXPECT_LT((c.point - Eigen::Vector3d(0.5, 0.25, 0.0)).norm(), 1e-9);
  EXPECT_LT((c.metric - Eigen::Vector3d::UnitZ() * Eigen::Vector3d::UnitZ().transpose()).norm(),
            1e-9);
  // Beyond the edge x = 2: the closest point is on that edge, with the full metric.
  c = face(Eigen::Vector3d(3.0, 0.5, 1.0));
  EXPECT_LT((c.point - Eigen::Vector3d(2.0, 0.5, 0.0)).norm(), 1e-7);
  EXPECT_LT((c.metric - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  // An edge along x: across it, metric I - x x^T; beyond its end, the end.
  const ClosestPointTarget edge(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(1, 0, 0)).Edge());
  EXPECT_FALSE(edge.on_faces());
  c = edge(Eigen::Vector3d(0.3, 2.0, -1.0));
  EXPECT_LT((c.point - Eigen::Vector3d(0.3, 0, 0)).norm(), 1e-9);
  EXPECT_LT((c.metric - Eigen::Vector3d(0, 1, 1).asDiagonal().toDenseMatrix()).norm(), 1e-9);
  c = edge(Eigen::Vector3d(4.0, 1.0, 0.0));
  EXPECT_LT((c.point - Eigen::Vector3d(1, 0, 0)).norm(), 1e-9);
  EXPECT_THROW(edge(Eigen::Vector3d(NAN, 0, 0)), varsurf::InvalidInput);
  EXPECT_THROW(ClosestPointTarget{TopoDS_Shape()}, varsurf::InvalidInput);
  EXPECT_THROW(ClosestPointTarget{BRepBuilderAPI_MakeVertex(gp_Pnt(0, 0, 0)).Vertex()},
               varsurf::InvalidInput);
}
