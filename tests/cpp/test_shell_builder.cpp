// SPDX-License-Identifier: LGPL-2.1-or-later
// Sheets trimmed to pre-image loops and sewn into shells and solids: a pillow of two domes
// joined along a circle, checked against its analytic volume, and bad inputs.
#include <gtest/gtest.h>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <gp_Ax2d.hxx>
#include <gp_Circ2d.hxx>

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <string>

#include "occ_test_support.hpp"
#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/shell_builder.hpp"
#include "varsurf/occ/step_io.hpp"

using namespace varsurf;

namespace {

using test::dome;
using test::kHalf;

// The unit circle's pre-image (center (0.5, 0.5), radius 1 / 2.4), as an exact rational
// B-spline; `pieces` splits it into that many arcs.
std::vector<BSplineCurve> circle_loop(int pieces = 1) {
  Handle(Geom2d_Circle) circle =
      new Geom2d_Circle(gp_Circ2d(gp_Ax2d(gp_Pnt2d(0.5, 0.5), gp_Dir2d(1, 0)), 0.5 / kHalf));
  std::vector<BSplineCurve> loop;
  for (int k = 0; k < pieces; ++k) {
    Handle(Geom2d_TrimmedCurve) arc =
        new Geom2d_TrimmedCurve(circle, 2 * M_PI * k / pieces, 2 * M_PI * (k + 1) / pieces);
    loop.push_back(occ::from_geom(Geom2dConvert::CurveToBSplineCurve(arc)));
  }
  return loop;
}

double volume(const TopoDS_Shape& s) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(s, props);
  return props.Mass();
}

}  // namespace

TEST(ShellBuilder, PillowOfTwoDomesIsAClosedSolidWithTheAnalyticVolume) {
  // Both domes vanish on the unit circle, so the two trimmed faces share it. Volume: twice
  // the integral of 1 - r^2 over the unit disc, pi.
  const double tol = 1e-6;
  const TopoDS_Face top = occ::make_trimmed_face({dome(1.0), circle_loop(2)}, tol);
  const TopoDS_Face bottom = occ::make_trimmed_face({dome(-1.0), circle_loop(3)}, tol);
  const occ::ShellResult r = occ::sew_faces({top, bottom}, tol);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.faces, 2);
  EXPECT_EQ(r.free_edges, 0);
  EXPECT_LT(r.max_tolerance, 1e-5);
  EXPECT_EQ(r.shape.ShapeType(), TopAbs_SOLID);
  EXPECT_NEAR(volume(r.shape), M_PI, 1e-6 * M_PI) << volume(r.shape);  // positive: outward
  // A STEP round trip keeps it.
  const std::string path =
      ::testing::TempDir() + "varsurf_pillow_" + std::to_string(getpid()) + ".step";
  occ::write_step(r.shape, path);
  const TopoDS_Shape back = occ::read_step(path);
  std::remove(path.c_str());
  EXPECT_NEAR(volume(back), M_PI, 1e-6 * M_PI);
}

TEST(ShellBuilder, OneDomeIsAnOpenShell) {
  const TopoDS_Face top = occ::make_trimmed_face({dome(1.0), circle_loop()}, 1e-6);
  const occ::ShellResult r = occ::sew_faces({top}, 1e-6);
  EXPECT_FALSE(r.closed);
  EXPECT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.faces, 1);
  EXPECT_GT(r.free_edges, 0);
}

TEST(ShellBuilder, ClockwiseLoopsKeepTheSurfaceNormal) {
  // The same loop walked backwards gives the same face (the wire is re-oriented).
  std::vector<BSplineCurve> loop = circle_loop(1);
  Handle(Geom2d_BSplineCurve) reversed = occ::to_geom2d_curve(loop[0]);
  reversed->Reverse();
  const TopoDS_Face ccw = occ::make_trimmed_face({dome(1.0), loop}, 1e-6);
  const TopoDS_Face cw = occ::make_trimmed_face({dome(1.0), {occ::from_geom(reversed)}}, 1e-6);
  const occ::ShellResult a =
      occ::sew_faces({ccw, occ::make_trimmed_face({dome(-1.0), loop}, 1e-6)}, 1e-6);
  const occ::ShellResult b =
      occ::sew_faces({cw, occ::make_trimmed_face({dome(-1.0), loop}, 1e-6)}, 1e-6);
  EXPECT_NEAR(volume(a.shape), volume(b.shape), 1e-9);
}

TEST(ShellBuilder, RejectsOpenLoopsAndCurvesOffTheSheet) {
  std::vector<BSplineCurve> open = circle_loop(3);
  open.pop_back();
  EXPECT_THROW(occ::make_trimmed_face({dome(1.0), open}, 1e-6), InvalidInput);
  EXPECT_THROW(occ::make_trimmed_face({dome(1.0), {}}, 1e-6), InvalidInput);
  const BSplineCurve outside =
      test::line_curve(Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(1.5, 0.5));
  const BSplineCurve back = test::line_curve(Eigen::Vector2d(1.5, 0.5), Eigen::Vector2d(0.5, 0.5));
  EXPECT_THROW(occ::make_trimmed_face({dome(1.0), {outside, back}}, 1e-6), InvalidInput);
  EXPECT_THROW(occ::make_trimmed_face({dome(1.0), circle_loop()}, 0.0), InvalidInput);
  EXPECT_THROW(occ::sew_faces({}, 1e-6), InvalidInput);
}

TEST(JoinSheets, PillowSharesOneRimEdgeSetAndMatchesTheAnalyticVolume) {
  // The same pillow, its rim built once from the 3D unit circle with a pcurve on each dome.
  const test::Rim rim = test::unit_circle_rim();
  const occ::ShellResult r = occ::join_sheets(
      {rim.curve}, {{dome(1.0), {0}, {rim.preimage}}, {dome(-1.0), {0}, {rim.preimage}}}, 1e-6);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.faces, 2);
  EXPECT_LT(r.max_tolerance, 1e-5);
  EXPECT_NEAR(volume(r.shape), M_PI, 1e-6 * M_PI) << volume(r.shape);
  const std::string path =
      ::testing::TempDir() + "varsurf_joined_" + std::to_string(getpid()) + ".step";
  occ::write_step(r.shape, path);
  const TopoDS_Shape back = occ::read_step(path);
  std::remove(path.c_str());
  EXPECT_NEAR(volume(back), volume(r.shape), 1e-6 * M_PI);
  // One sheet alone: an open shell; a curve index that does not exist: refused.
  const occ::ShellResult open =
      occ::join_sheets({rim.curve}, {{dome(1.0), {0}, {rim.preimage}}}, 1e-6);
  EXPECT_FALSE(open.closed);
  EXPECT_THROW(occ::join_sheets({rim.curve}, {{dome(1.0), {1}, {rim.preimage}}}, 1e-6),
               InvalidInput);
}
