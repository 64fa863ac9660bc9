// SPDX-License-Identifier: LGPL-2.1-or-later
// libFuzzer harness over the OpenCASCADE bridge: faces and edges of every kind a FreeCAD document
// may hand over (B-spline faces from random data, periodic cylinders and tori, spheres and cones
// with collapsed edges, zero-area faces; lines, full and partial circles, zero-length segments,
// random B-spline curves), through conversion, projection, face building, deviation, normal
// fields, BREP round trips and checks. The bridge may refuse (InvalidInput, GeometryError); a
// crash, a sanitizer report, an escaping OCCT exception or any other exception is a bug.
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Line.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Standard_Failure.hxx>
#include <TopoDS.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>

#include <cstdio>
#include <cstdlib>
#include <optional>

#include "fuzz_input.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/brep_io.hpp"
#include "varsurf/occ/curve_projection.hpp"
#include "varsurf/occ/deviation.hpp"
#include "varsurf/occ/face_builder.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/normal_field.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/point_projection.hpp"
#include "varsurf/occ/shape_check.hpp"
#include "varsurf/occ/surface_refinement.hpp"

using namespace varsurf;
using varsurf::fuzz::number;

namespace {

// Finite numbers only: these build the harness's own OCCT input, not the bridge's.
double finite(FuzzedDataProvider& in, double lo, double hi) {
  return in.ConsumeFloatingPointInRange<double>(lo, hi);
}

gp_Ax3 frame(FuzzedDataProvider& in) {
  const gp_Pnt origin(finite(in, -50, 50), finite(in, -50, 50), finite(in, -50, 50));
  gp_Dir axis(0, 0, 1);
  if (in.ConsumeBool()) axis = gp_Dir(finite(in, -1, 1), finite(in, -1, 1), 1.0);
  return gp_Ax3(origin, axis);
}

// A face as FreeCAD could hold it; nullopt when the harness's own construction is refused.
std::optional<TopoDS_Face> any_face(FuzzedDataProvider& in) {
  const int kind = in.ConsumeIntegralInRange<int>(0, 5);
  if (kind == 0) {  // a B-spline face from random data, through the bridge's own builder
    BSplineSurface s;
    s.space = fuzz::space(in);
    const int n = std::max(0, std::min(s.space.size(), 400));
    s.poles.resize(n, 3);
    for (int k = 0; k < n; ++k)
      for (int c = 0; c < 3; ++c) s.poles(k, c) = number(in, -20, 20);
    return occ::make_face(s);  // may throw InvalidInput / GeometryError: an answer, not a bug
  }
  Handle(Geom_Surface) surface;
  const double r = finite(in, 0.0, 30.0);
  switch (kind) {
    case 1:
      surface = new Geom_Plane(frame(in));
      break;
    case 2:
      surface = new Geom_CylindricalSurface(frame(in), r);
      break;
    case 3:
      surface = new Geom_SphericalSurface(frame(in), r);
      break;
    case 4:
      surface = new Geom_ConicalSurface(frame(in), finite(in, 0.05, 1.5), r);
      break;
    default:
      surface = new Geom_ToroidalSurface(frame(in), r + 5.0, r);
      break;
  }
  double u0 = finite(in, -7, 7), u1 = finite(in, -7, 7), v0 = finite(in, -7, 7),
         v1 = finite(in, -7, 7);
  if (in.ConsumeBool()) u1 = u0;  // zero area
  BRepBuilderAPI_MakeFace make(surface, std::min(u0, u1), std::max(u0, u1), std::min(v0, v1),
                               std::max(v0, v1), 1e-7);
  if (!make.IsDone()) return std::nullopt;
  return make.Face();
}

std::optional<TopoDS_Edge> any_edge(FuzzedDataProvider& in) {
  const int kind = in.ConsumeIntegralInRange<int>(0, 3);
  if (kind == 0) {  // random B-spline curve through the bridge's own conversion
    const BSplineCurve c = fuzz::curve(in, 3, -20, 20);
    return BRepBuilderAPI_MakeEdge(occ::to_geom_curve(c)).Edge();
  }
  const gp_Pnt a(finite(in, -20, 20), finite(in, -20, 20), finite(in, -20, 20));
  if (kind == 1) {  // a segment, maybe of zero length
    const gp_Pnt b = in.ConsumeBool() ? a : gp_Pnt(finite(in, -20, 20), 0, finite(in, -20, 20));
    BRepBuilderAPI_MakeEdge make(a, b);
    if (!make.IsDone()) return std::nullopt;
    return make.Edge();
  }
  const gp_Circ circle(gp_Ax2(a, gp_Dir(0, 0, 1)), finite(in, 0.0, 20.0));
  if (kind == 2) {  // full circle: closed and periodic
    BRepBuilderAPI_MakeEdge make(circle);
    if (!make.IsDone()) return std::nullopt;
    return make.Edge();
  }
  BRepBuilderAPI_MakeEdge make(circle, finite(in, -4, 4), finite(in, -4, 4));
  if (!make.IsDone()) return std::nullopt;
  return make.Edge();
}

void exercise(FuzzedDataProvider& in) {
  std::optional<TopoDS_Face> face;
  std::optional<TopoDS_Edge> edge;
  try {  // the harness's input: OCCT refusing to build it is not the bridge's business
    face = any_face(in);
    edge = any_edge(in);
  } catch (const Standard_Failure&) {
    return;
  } catch (const InvalidInput&) {
    return;
  } catch (const occ::GeometryError&) {
    return;
  }
  if (!face || !edge) return;
  const occ::ShapeCheck check = occ::check_shape(*face);
  (void)check;
  const TopoDS_Shape back = occ::read_brep(occ::write_brep(*face));
  (void)back;
  const BSplineSurface sheet = occ::surface_from_face(*face);
  const BSplineCurve target = occ::curve_from_edge(*edge);
  switch (in.ConsumeIntegralInRange<int>(0, 5)) {
    case 0: {
      occ::ProjectionOptions po;
      po.tolerance = number(in, 0.0, 50.0);
      po.fit_tolerance = number(in, 1e-9, 1e-2);
      po.max_poles = in.ConsumeIntegralInRange<int>(-1, 200);
      occ::project_curve(sheet, target, po);
      break;
    }
    case 1:
      occ::max_deviation(sheet, target, in.ConsumeIntegralInRange<int>(-1, 300));
      break;
    case 2:
      occ::project_point(sheet, fuzz::vector3(in, 50));
      break;
    case 3:
      occ::normal_field(*face, target, number(in, -360, 360), number(in, 0, 10),
                        in.ConsumeIntegralInRange<int>(-1, 100));
      break;
    case 4:
      occ::refine_surface(sheet, in.ConsumeIntegralInRange<int>(-1, 64),
                          in.ConsumeIntegralInRange<int>(-1, 64),
                          in.ConsumeIntegralInRange<int>(-1, 6));
      break;
    default:
      occ::make_face(sheet);
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  try {
    exercise(in);
  } catch (const InvalidInput&) {
  } catch (const SolveFailure&) {
  } catch (const occ::GeometryError&) {
  }
  return 0;
}
