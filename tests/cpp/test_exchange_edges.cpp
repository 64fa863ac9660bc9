// SPDX-License-Identifier: LGPL-2.1-or-later
// Edges prepared for STEP on a pillow whose top dome waves 1e-4 above the shared rim: every
// deviation peak ends on a vertex, nothing moves, exact edges are left alone; the file covers it.
#include <gtest/gtest.h>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
// (after the shapes it takes)
#include <BRepLib_CheckCurveOnSurface.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListIteratorOfListOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "occ_test_support.hpp"
#include "varsurf/occ/exchange_edges.hpp"
#include "varsurf/occ/mass_properties.hpp"
#include "varsurf/occ/shell_builder.hpp"
#include "varsurf/occ/step_io.hpp"

using namespace varsurf;

namespace {

using test::kWave;
using test::pillow;
using test::temp_path;

}  // namespace

TEST(StepExchange, PreparingForExchangeMovesEveryDeviationPeakOntoAVertex) {
  const occ::ShellResult r = pillow(kWave);
  const occ::ExchangeShape ready = occ::prepare_for_exchange(r.shape);
  EXPECT_NEAR(ready.max_deviation, kWave, 1e-3 * kWave);
  EXPECT_EQ(ready.split_edges, 3);  // the rim's three pieces, each with crests inside
  TopTools_IndexedDataMapOfShapeListOfShape edges;
  TopExp::MapShapesAndAncestors(ready.shape, TopAbs_EDGE, TopAbs_FACE, edges);
  EXPECT_GT(edges.Extent(), 3);
  for (int k = 1; k <= edges.Extent(); ++k) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges.FindKey(k));
    double f = 0.0, l = 0.0;
    const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, f, l);
    double peak = 0.0, ends = 0.0;
    for (TopTools_ListIteratorOfListOfShape it(edges(k)); it.More(); it.Next()) {
      const TopoDS_Face& face = TopoDS::Face(it.Value());
      BRepLib_CheckCurveOnSurface check(edge, face);
      check.Perform();
      peak = std::max(peak, check.MaxDistance());
      const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, f, l);
      const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
      for (double t : {f, l}) {
        const gp_Pnt2d uv = pcurve->Value(t);
        ends = std::max(ends, surface->Value(uv.X(), uv.Y()).Distance(curve->Value(t)));
      }
    }
    // Every piece's deviation is largest at its ends (0.1 % margin inside), where readers sample.
    EXPECT_LE(peak, (1 + 1e-6) * ends) << "edge " << k;
  }
  // Nothing moved: the same area and volume to the integration's precision.
  const occ::MassProperties a = occ::mass_properties(r.shape, 1e-10);
  const occ::MassProperties b = occ::mass_properties(ready.shape, 1e-10);
  EXPECT_NEAR(a.area, b.area, 1e-9 * a.area);
  EXPECT_NEAR(a.volume, b.volume, 1e-9 * a.volume);
}

TEST(StepExchange, ExactEdgesAreLeftAloneAndTheUncertaintyCoversTheDeviation) {
  // Without the wave the domes meet exactly on the rim: nothing to split.
  const occ::ShellResult exact = pillow(0.0);
  const occ::ExchangeShape ready = occ::prepare_for_exchange(exact.shape);
  EXPECT_EQ(ready.split_edges, 0);
  EXPECT_LT(ready.max_deviation, 1e-7);
  EXPECT_TRUE(ready.shape.IsSame(exact.shape));
  // With it, the file's uncertainty is at least the deviation (OCCT's reader drops pcurves whose
  // ends lie farther than that from their vertices).
  const std::string path = temp_path("uncertainty");
  occ::write_step(pillow(kWave).shape, path);
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  std::remove(path.c_str());
  const std::string key = "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(";
  const size_t at = text.str().find(key);
  ASSERT_NE(at, std::string::npos);
  EXPECT_GE(std::stod(text.str().substr(at + key.size())), kWave);
}
