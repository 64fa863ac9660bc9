// SPDX-License-Identifier: LGPL-2.1-or-later
// A sheet keeps its base face's trim and orientation: a plate with a hole, a disc, a cylinder
// patch with a hole (its NURBS conversion reparametrizes it), checked against analytic areas,
// OCCT's checker and the measured distance between each edge and the sheet.
#include <gtest/gtest.h>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepLib.hxx>
#include <BRepLib_CheckCurveOnSurface.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Geom2d_Circle.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2d.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>
#include <gp_Circ2d.hxx>
#include <gp_Pln.hxx>

#include <cmath>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/surface_refinement.hpp"
#include "varsurf/occ/trimmed_face.hpp"

using namespace varsurf;

namespace {

double area(const TopoDS_Shape& s) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(s, props, 1e-10);
  return props.Mass();
}

// A 100 x 80 plate at z = 40 with a hole of radius 10 at (50, 40), as Part's box minus a
// cylinder gives it (the hole's wire runs clockwise).
TopoDS_Face plate_with_hole() {
  const gp_Pln plane(gp_Pnt(0, 0, 40), gp_Dir(0, 0, 1));
  BRepBuilderAPI_MakePolygon outer(gp_Pnt(0, 0, 40), gp_Pnt(100, 0, 40), gp_Pnt(100, 80, 40),
                                   gp_Pnt(0, 80, 40), Standard_True);
  BRepBuilderAPI_MakeFace face(plane, outer.Wire());
  const gp_Circ circle(gp_Ax2(gp_Pnt(50, 40, 40), gp_Dir(0, 0, 1)), 10);
  TopoDS_Wire hole = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire();
  hole.Reverse();
  face.Add(hole);
  return face.Face();
}

TopoDS_Face disc(double radius) {
  const gp_Circ circle(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), radius);
  return BRepBuilderAPI_MakeFace(
             BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire())
      .Face();
}

// A quarter of a cylinder of radius 10 (u in [0, pi/2], v in [0, 60]) with a hole that is a
// circle of radius 0.3 about (pi/4, 30) in its (u, v): not an isoline, so mapping it through
// the conversion's reparametrization needs more than a coordinate change.
constexpr double kRadius = 10.0, kHole = 0.3;
TopoDS_Face cylinder_patch_with_hole() {
  Handle(Geom_CylindricalSurface) cyl = new Geom_CylindricalSurface(gp_Ax3(gp::XOY()), kRadius);
  BRepBuilderAPI_MakeFace face(cyl, 0.0, M_PI / 2, 0.0, 60.0, 1e-7);
  Handle(Geom2d_Circle) uv =
      new Geom2d_Circle(gp_Circ2d(gp_Ax2d(gp_Pnt2d(M_PI / 4, 30.0), gp_Dir2d(1, 0)), kHole));
  TopoDS_Edge edge = BRepBuilderAPI_MakeEdge(uv, cyl).Edge();
  BRepLib::BuildCurves3d(edge);
  TopoDS_Wire hole = BRepBuilderAPI_MakeWire(edge).Wire();
  hole.Reverse();
  face.Add(hole);
  return face.Face();
}

// The sheet a solve starts from: the base converted and refined (knot insertion and degree
// elevation keep its parametrization).
BSplineSurface start_sheet(const TopoDS_Face& base) {
  return occ::refine_surface(occ::surface_from_face(base), 8, 8, 3);
}

// Largest distance between an edge's 3D curve and its pcurve on the face, over the face's edges,
// relative to each edge's tolerance (<= 1 when the tolerances hold).
double worst_edge_ratio(const TopoDS_Face& face) {
  double worst = 0.0;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Degenerated(e)) continue;
    BRepLib_CheckCurveOnSurface check(e, face);
    check.Perform();
    EXPECT_TRUE(check.IsDone());
    worst = std::max(worst, check.MaxDistance() / BRep_Tool::Tolerance(e));
  }
  return worst;
}

// The face's normal at (u, v), with its orientation.
gp_Dir normal_at(const TopoDS_Face& face, double u, double v) {
  BRepAdaptor_Surface adaptor(face);
  BRepLProp_SLProps props(adaptor, u, v, 1, 1e-9);
  gp_Dir n = props.Normal();
  if (face.Orientation() == TopAbs_REVERSED) n.Reverse();
  return n;
}

}  // namespace

TEST(TrimmedFace, PlateWithAHoleKeepsTheHole) {
  const TopoDS_Face base = plate_with_hole();
  const occ::BaseTrim trim(base);
  EXPECT_FALSE(trim.natural());
  EXPECT_TRUE(trim.same_parameters());
  const TopoDS_Face out = trim.face(start_sheet(base));
  EXPECT_TRUE(BRepCheck_Analyzer(out).IsValid());
  const double expected = 100.0 * 80.0 - M_PI * 100.0;  // 7685.84, not the 8000 of the square
  EXPECT_NEAR(area(out), expected, 1e-9 * expected);
  int wires = 0;
  for (TopExp_Explorer ex(out, TopAbs_WIRE); ex.More(); ex.Next()) ++wires;
  EXPECT_EQ(wires, 2);
  EXPECT_LE(worst_edge_ratio(out), 1.0);
  // The hole's centre is off the result, a point of the plate on it.
  BRepTopAdaptor_FClass2d classify(out, 1e-9);
  EXPECT_EQ(classify.Perform(gp_Pnt2d(50, 40)), TopAbs_OUT);
  EXPECT_EQ(classify.Perform(gp_Pnt2d(20, 20)), TopAbs_IN);
}

TEST(TrimmedFace, DiscStaysADiscOnADisplacedSheet) {
  const TopoDS_Face base = disc(30.0);
  const occ::BaseTrim trim(base);
  EXPECT_FALSE(trim.natural());
  EXPECT_NEAR(area(trim.face(start_sheet(base))), M_PI * 900.0, 1e-9 * M_PI * 900.0);
  // A solved sheet moves its poles: the boundary follows the sheet (each edge measured on it).
  BSplineSurface sheet = start_sheet(base);
  for (int k = 0; k < sheet.poles.rows(); ++k) {
    const double x = sheet.poles(k, 0), y = sheet.poles(k, 1);
    sheet.poles(k, 2) = 5.0 * std::cos(x / 20.0) * std::cos(y / 20.0);
  }
  const TopoDS_Face out = trim.face(sheet);
  EXPECT_TRUE(BRepCheck_Analyzer(out).IsValid());
  EXPECT_LE(worst_edge_ratio(out), 1.0);
  const Handle(Geom_Surface) s = occ::to_geom(sheet);
  for (TopExp_Explorer ex(out, TopAbs_VERTEX); ex.More(); ex.Next()) {
    GeomAPI_ProjectPointOnSurf on(BRep_Tool::Pnt(TopoDS::Vertex(ex.Current())), s);
    ASSERT_GT(on.NbPoints(), 0);
    EXPECT_LT(on.LowerDistance(), 1e-9);
  }
  EXPECT_GT(area(out), M_PI * 900.0);  // lifted: more area over the same plan
}

TEST(TrimmedFace, CylinderPatchMapsItsHoleThroughTheReparametrization) {
  const TopoDS_Face base = cylinder_patch_with_hole();
  const occ::BaseTrim trim(base);
  EXPECT_FALSE(trim.natural());
  EXPECT_FALSE(trim.same_parameters());  // the rational arc is not parametrized by angle
  const TopoDS_Face out = trim.face(start_sheet(base));
  EXPECT_TRUE(BRepCheck_Analyzer(out).IsValid());
  EXPECT_LE(worst_edge_ratio(out), 1.0);
  // Developable: the area is the radius times the (u, v) area.
  const double expected = kRadius * (M_PI / 2 * 60.0 - M_PI * kHole * kHole);
  EXPECT_NEAR(area(out), expected, 1e-7 * expected);
  EXPECT_NEAR(area(out), area(base), 1e-7 * expected);
  // Each edge of the result lies on the base cylinder (r = 10) within 1e-7 mm.
  for (TopExp_Explorer ex(out, TopAbs_EDGE); ex.More(); ex.Next()) {
    double f, l;
    Handle(Geom_Curve) c = BRep_Tool::Curve(TopoDS::Edge(ex.Current()), f, l);
    for (int k = 0; k <= 50; ++k) {
      const gp_Pnt p = c->Value(f + (l - f) * k / 50);
      EXPECT_NEAR(std::hypot(p.X(), p.Y()), kRadius, 1e-7);
    }
  }
}

TEST(TrimmedFace, NaturalFacesKeepTheirNaturalBoundary) {
  Handle(Geom_CylindricalSurface) cyl = new Geom_CylindricalSurface(gp_Ax3(gp::XOY()), kRadius);
  const TopoDS_Face patch = BRepBuilderAPI_MakeFace(cyl, 0.0, M_PI / 2, 0.0, 60.0, 1e-7).Face();
  EXPECT_TRUE(occ::BaseTrim(patch).natural());
  const TopoDS_Face plane =
      BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), -10.0, 10.0, 0.0, 5.0).Face();
  const occ::BaseTrim trim(plane);
  EXPECT_TRUE(trim.natural());
  EXPECT_NEAR(area(trim.face(start_sheet(plane))), 100.0, 1e-9);
}

TEST(TrimmedFace, ResultFollowsTheBaseFacesOrientation) {
  for (const TopAbs_Orientation o : {TopAbs_FORWARD, TopAbs_REVERSED}) {
    for (const TopoDS_Face& face :
         {plate_with_hole(), BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0, 1, 0, 1).Face()}) {
      const TopoDS_Face base = TopoDS::Face(face.Oriented(o));
      const occ::BaseTrim trim(base);
      EXPECT_EQ(trim.normal_sign(), o == TopAbs_REVERSED ? -1 : 1);
      const TopoDS_Face out = trim.face(start_sheet(base));
      EXPECT_EQ(out.Orientation(), o);
      double u1, u2, v1, v2;
      BRepTools::UVBounds(base, u1, u2, v1, v2);
      const double u = u1 + 0.1 * (u2 - u1), v = v1 + 0.1 * (v2 - v1);
      EXPECT_GT(normal_at(out, u, v).Dot(normal_at(base, u, v)), 1.0 - 1e-12);
    }
  }
}

TEST(TrimmedFace, PlacesPointsOverTheHoleAndOutsideTheBoundary) {
  const occ::BaseTrim plate(plate_with_hole());
  EXPECT_EQ(plate.place(20, 20, 0.01).place, occ::TrimPlace::inside);
  const occ::TrimHit hole = plate.place(50, 45, 0.01);
  EXPECT_EQ(hole.place, occ::TrimPlace::over_hole);
  EXPECT_NEAR(hole.distance, 5.0, 1e-7);
  // Within the tolerance of the hole's edge counts as on the face.
  EXPECT_EQ(plate.place(50, 49.995, 0.01).place, occ::TrimPlace::inside);
  EXPECT_EQ(plate.place(50, 49.98, 0.01).place, occ::TrimPlace::over_hole);

  const occ::BaseTrim round(disc(30.0));
  const occ::TrimHit corner = round.place(28, 28, 0.01);  // in the square, outside the disc
  EXPECT_EQ(corner.place, occ::TrimPlace::outside);
  EXPECT_NEAR(corner.distance, std::hypot(28.0, 28.0) - 30.0, 1e-7);

  // A pre-image across the hole: its farthest sample is the hole's centre line.
  BSplineCurve across;
  across.degree = 1;
  across.knots = {0, 0, 1, 1};
  across.poles.resize(2, 2);
  across.poles << 20, 40, 80, 40;
  const occ::TrimHit hit = plate.place(across, 0.01, 60);
  EXPECT_EQ(hit.place, occ::TrimPlace::over_hole);
  EXPECT_NEAR(hit.parameter, 0.5, 1e-12);
  EXPECT_NEAR(hit.distance, 10.0, 1e-7);
  across.poles << 10, 10, 90, 10;  // along the plate, clear of the hole
  EXPECT_EQ(plate.place(across, 0.01).place, occ::TrimPlace::inside);
}

TEST(TrimmedFace, BoundaryOffTheParameterRectangleIsHeldAlongTheBaseFacesEdges) {
  // The plate's outer edges run along its parameter rectangle (fixed poles hold them): only the
  // hole is returned; on the cylinder patch, through the reparametrization.
  struct Case {
    TopoDS_Face face;
    gp_Pnt centre;
    double radius;
  };
  for (const Case& c : {Case{plate_with_hole(), gp_Pnt(50, 40, 40), 10.0},
                        Case{disc(30.0), gp_Pnt(0, 0, 0), 30.0}}) {
    const occ::BaseTrim trim(c.face);
    const std::vector<occ::TrimCurve> held = trim.boundary();
    ASSERT_EQ(held.size(), 1u);
    const occ::TrimCurve& h = held[0];
    const BSplineSurface sheet = occ::surface_from_face(c.face);
    for (int k = 0; k <= 100; ++k) {
      const double t = h.preimage.first() + (h.preimage.last() - h.preimage.first()) * k / 100;
      const Eigen::VectorXd uv = h.preimage.evaluate(t);
      const Eigen::Vector3d on = sheet.evaluate(uv(0), uv(1));
      const Eigen::VectorXd target = h.target.evaluate(t);
      EXPECT_LT((on - target).norm(), 5e-8);  // interpolated to 1e-8 mm at midpoints
      EXPECT_NEAR(gp_Pnt(on(0), on(1), on(2)).Distance(c.centre), c.radius, 1e-9);
    }
  }
  const occ::BaseTrim patch(cylinder_patch_with_hole());
  const std::vector<occ::TrimCurve> hole = patch.boundary();
  ASSERT_EQ(hole.size(), 1u);
  for (int k = 0; k <= 100; ++k) {
    const Eigen::VectorXd p = hole[0].target.evaluate(
        hole[0].target.first() + (hole[0].target.last() - hole[0].target.first()) * k / 100);
    EXPECT_NEAR(std::hypot(p(0), p(1)), kRadius, 1e-8);
  }
  EXPECT_TRUE(occ::BaseTrim(BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0, 1, 0, 1).Face())
                  .boundary()
                  .empty());
}

TEST(TrimmedFace, RefusesASheetOnAnotherDomain) {
  const TopoDS_Face base = disc(30.0);
  BSplineSurface other = start_sheet(base);
  for (double& k : other.space.knots_u) k *= 2.0;
  EXPECT_THROW(occ::BaseTrim(base).face(other), InvalidInput);
}
