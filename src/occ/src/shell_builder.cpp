#include "varsurf/occ/shell_builder.hpp"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <ShapeFix_Face.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Wire.hxx>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/shape_check.hpp"

namespace varsurf::occ {

namespace {

// Signed area of the loop in (u, v), by the shoelace formula on samples of each curve.
double signed_area(const std::vector<BSplineCurve>& loop) {
  double area = 0.0;
  for (const BSplineCurve& c : loop) {
    const int n = 64;
    Eigen::VectorXd prev = c.evaluate(c.first());
    for (int k = 1; k <= n; ++k) {
      const Eigen::VectorXd p = c.evaluate(c.first() + (c.last() - c.first()) * k / n);
      area += 0.5 * (prev(0) * p(1) - p(0) * prev(1));
      prev = p;
    }
  }
  return area;
}

}  // namespace

TopoDS_Face make_trimmed_face(const TrimmedSheet& sheet, double tolerance) {
  sheet.surface.validate();
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw InvalidInput("trimming: the tolerance must be a positive length");
  if (sheet.loop.empty()) throw InvalidInput("trimming: the sheet has no boundary loop");
  const SplineSpace& sp = sheet.surface.space;
  const double du = sp.u_last() - sp.u_first(), dv = sp.v_last() - sp.v_first();
  const double ptol = 1e-7 * std::max(du, dv);
  for (size_t i = 0; i < sheet.loop.size(); ++i) {
    const BSplineCurve& c = sheet.loop[i];
    c.validate("boundary pre-image");
    if (c.dim() != 2) throw InvalidInput("trimming: boundary pre-images must be 2D (u, v) curves");
    const BSplineCurve& next = sheet.loop[(i + 1) % sheet.loop.size()];
    if ((c.evaluate(c.last()) - next.evaluate(next.first())).norm() > ptol)
      throw InvalidInput("trimming: the boundary loop does not close (curve " + std::to_string(i) +
                         " does not end where curve " +
                         std::to_string((i + 1) % sheet.loop.size()) + " starts)");
    for (int k = 0; k <= 32; ++k) {
      const Eigen::VectorXd p = c.evaluate(c.first() + (c.last() - c.first()) * k / 32);
      if (p(0) < sp.u_first() - ptol || p(0) > sp.u_last() + ptol || p(1) < sp.v_first() - ptol ||
          p(1) > sp.v_last() + ptol)
        throw InvalidInput("trimming: boundary pre-image " + std::to_string(i) +
                           " leaves the sheet's parameter domain");
    }
  }
  const bool reverse = signed_area(sheet.loop) < 0.0;
  return guarded("trimming the sheet", [&] {
    Handle(Geom_BSplineSurface) surface = to_geom(sheet.surface);
    BRepBuilderAPI_MakeWire wire;
    for (size_t k = 0; k < sheet.loop.size(); ++k) {
      const BSplineCurve& c = sheet.loop[reverse ? sheet.loop.size() - 1 - k : k];
      Handle(Geom2d_BSplineCurve) pcurve = to_geom2d_curve(c);
      if (reverse) pcurve->Reverse();
      BRepBuilderAPI_MakeEdge edge(pcurve, surface, pcurve->FirstParameter(),
                                   pcurve->LastParameter());
      if (!edge.IsDone()) throw GeometryError("trimming: an edge could not be built on the sheet");
      TopoDS_Edge e = edge.Edge();
      BRepLib::BuildCurves3d(e, std::min(tolerance, 1e-5));
      wire.Add(e);
      if (!wire.IsDone())
        throw GeometryError("trimming: the boundary edges do not chain into a wire");
    }
    TopoDS_Wire w = wire.Wire();
    if (!w.Closed()) {
      if (!BRep_Tool::IsClosed(w)) throw InvalidInput("trimming: the boundary wire is not closed");
    }
    BRepBuilderAPI_MakeFace face(surface, w, Standard_True);
    if (!face.IsDone()) throw GeometryError("trimming: the face could not be built");
    ShapeFix_Face fix(face.Face());
    fix.SetPrecision(std::min(tolerance, 1e-5));
    fix.Perform();
    TopoDS_Face out = fix.Face();
    BRepLib::SameParameter(out, std::min(tolerance, 1e-5));
    const ShapeCheck check = check_shape(out);
    if (!check.valid) throw GeometryError("trimming: the face is not valid: " + check.message);
    return out;
  });
}

ShellResult sew_faces(const std::vector<TopoDS_Face>& faces, double tolerance) {
  if (faces.empty()) throw InvalidInput("sewing: no faces");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw InvalidInput("sewing: the tolerance must be a positive length");
  return guarded("sewing the sheets", [&] {
    BRepBuilderAPI_Sewing sewing(tolerance);
    for (const TopoDS_Face& f : faces) {
      if (f.IsNull()) throw InvalidInput("sewing: a face is null");
      sewing.Add(f);
    }
    sewing.Perform();
    TopoDS_Shape sewn = sewing.SewedShape();
    if (sewn.IsNull()) throw GeometryError("sewing produced nothing");
    ShellResult out;
    out.free_edges = sewing.NbFreeEdges();
    TopoDS_Shell shell;
    int shells = 0;
    for (TopExp_Explorer ex(sewn, TopAbs_SHELL); ex.More(); ex.Next()) {
      shell = TopoDS::Shell(ex.Current());
      ++shells;
    }
    out.shape = sewn;
    if (shells == 1 && out.free_edges == 0 && BRep_Tool::IsClosed(shell)) {
      BRepBuilderAPI_MakeSolid solid(shell);
      if (!solid.IsDone()) throw GeometryError("sewing: the closed shell did not make a solid");
      TopoDS_Solid s = solid.Solid();
      BRepLib::OrientClosedSolid(s);
      out.shape = s;
      out.closed = true;
    }
    for (TopExp_Explorer ex(out.shape, TopAbs_FACE); ex.More(); ex.Next()) ++out.faces;
    const ShapeCheck check = check_shape(out.shape);
    out.valid = check.valid;
    out.message = check.message;
    out.max_tolerance = check.max_tolerance;
    return out;
  });
}

}  // namespace varsurf::occ
