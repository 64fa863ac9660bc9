// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/shell_builder.hpp"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRepLib_CheckCurveOnSurface.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Precision.hxx>
#include <ShapeFix_Face.hxx>
#include <ShapeFix_Shell.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <cmath>
#include <string>

#include "varsurf/core/curve_loop.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/exchange_edges.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/pcurve_refit.hpp"
#include "varsurf/occ/shape_check.hpp"

namespace varsurf::occ {

namespace {

// A closed shell as a solid whose faces point outward.
TopoDS_Solid outward_solid(const TopoDS_Shell& shell) {
  BRepBuilderAPI_MakeSolid solid(shell);
  if (!solid.IsDone()) throw GeometryError("the closed shell did not make a solid");
  TopoDS_Solid out = solid.Solid();
  BRepLib::OrientClosedSolid(out);
  return out;
}

// The result's face count and validity (BRepCheck), filled in.
ShellResult finished(ShellResult out) {
  for (TopExp_Explorer ex(out.shape, TopAbs_FACE); ex.More(); ex.Next()) ++out.faces;
  const ShapeCheck check = check_shape(out.shape);
  out.valid = check.valid;
  out.message = check.message;
  out.max_tolerance = check.max_tolerance;
  return out;
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
  const CurveLoop order = chain_loop(sheet.loop, ptol);
  for (size_t i = 0; i < sheet.loop.size(); ++i) {
    const BSplineCurve& c = sheet.loop[i];
    for (int k = 0; k <= 32; ++k) {
      const Eigen::VectorXd p = c.evaluate(c.first() + (c.last() - c.first()) * k / 32);
      if (p(0) < sp.u_first() - ptol || p(0) > sp.u_last() + ptol || p(1) < sp.v_first() - ptol ||
          p(1) > sp.v_last() + ptol)
        throw InvalidInput("trimming: boundary pre-image " + std::to_string(i) +
                           " leaves the sheet's parameter domain");
    }
  }
  // Counter-clockwise in (u, v) keeps the surface's normal for the face.
  std::vector<LoopStep> steps = order.steps;
  if (order.signed_area < 0.0) {
    std::reverse(steps.begin(), steps.end());
    for (LoopStep& step : steps) step.reversed = !step.reversed;
  }
  return guarded("trimming the sheet", [&] {
    Handle(Geom_BSplineSurface) surface = to_geom(sheet.surface);
    // A loop of one or two curves is split so that the wire has at least three edges: a face
    // bounded by a single closed edge (one vertex) loses its pcurves in a STEP round trip
    // (measured: the re-read pillow had half its volume, with the sign flipped).
    const int pieces = sheet.loop.size() >= 3 ? 1 : (sheet.loop.size() == 1 ? 3 : 2);
    BRepBuilderAPI_MakeWire wire;
    for (const LoopStep& step : steps) {
      Handle(Geom2d_BSplineCurve) whole =
          to_geom2d_curve(sheet.loop[static_cast<size_t>(step.curve)]);
      if (step.reversed) whole->Reverse();
      const double t0 = whole->FirstParameter(), t1 = whole->LastParameter();
      for (int piece = 0; piece < pieces; ++piece) {
        Handle(Geom2d_BSplineCurve) pcurve = Handle(Geom2d_BSplineCurve)::DownCast(whole->Copy());
        if (pieces > 1)
          pcurve->Segment(t0 + (t1 - t0) * piece / pieces, t0 + (t1 - t0) * (piece + 1) / pieces);
        BRepBuilderAPI_MakeEdge edge(pcurve, surface, pcurve->FirstParameter(),
                                     pcurve->LastParameter());
        if (!edge.IsDone())
          throw GeometryError("trimming: an edge could not be built on the sheet");
        TopoDS_Edge e = edge.Edge();
        BRepLib::BuildCurves3d(e, std::min(tolerance, 1e-5));
        wire.Add(e);
        if (!wire.IsDone())
          throw GeometryError("trimming: the boundary edges do not chain into a wire");
      }
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
    // Sewing sets an edge's tolerance from its own samples, which can fall short of the deviation
    // OCCT's Boolean check finds between them (a sheet sewn to a fillet's arcs: 3 of 4 radii
    // failed check(True)); cover what that check measures.
    refit_pcurves(sewn, Precision::Confusion());
    cover_measured_deviations(sewn);
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
      out.shape = outward_solid(shell);
      out.closed = true;
    }
    return finished(out);
  });
}

namespace {

struct CurveEdges {
  std::vector<TopoDS_Edge> edges;  // forward along the 3D curve
  std::vector<double> breaks;      // parameters of the pieces' ends
};

}  // namespace

ShellResult join_sheets(const std::vector<BSplineCurve>& curves,
                        const std::vector<JoinedSheet>& sheets, double tolerance) {
  if (curves.empty() || sheets.empty()) throw InvalidInput("joining: no curves or no sheets");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw InvalidInput("joining: the tolerance must be a positive length");
  std::vector<int> uses(curves.size(), 0);
  for (size_t s = 0; s < sheets.size(); ++s) {
    const JoinedSheet& sh = sheets[s];
    sh.surface.validate();
    if (sh.curves.empty())
      throw InvalidInput("joining: sheet " + std::to_string(s) + " has no join curve");
    if (sh.curves.size() != sh.preimages.size())
      throw InvalidInput("joining: sheet " + std::to_string(s) + " needs one pre-image per curve");
    for (size_t k = 0; k < sh.curves.size(); ++k) {
      const int c = sh.curves[k];
      if (c < 0 || c >= static_cast<int>(curves.size()))
        throw InvalidInput("joining: sheet " + std::to_string(s) +
                           " names a curve that does not exist");
      ++uses[static_cast<size_t>(c)];
      sh.preimages[k].validate("join pre-image");
      if (sh.preimages[k].dim() != 2) throw InvalidInput("joining: pre-images must be 2D");
    }
  }
  for (size_t c = 0; c < curves.size(); ++c) {
    curves[c].validate("join curve");
    if (curves[c].dim() != 3) throw InvalidInput("joining: join curves must be 3D");
    if (uses[c] == 0)
      throw InvalidInput("joining: curve " + std::to_string(c) + " bounds no sheet");
  }
  return guarded("joining the sheets", [&] {
    BRep_Builder builder;
    // 1. Each shared curve as edges built once from its 3D curve; a closed curve's last vertex
    //    is its first.
    std::vector<CurveEdges> shared(curves.size());
    for (size_t c = 0; c < curves.size(); ++c) {
      Handle(Geom_BSplineCurve) g = to_geom_curve(curves[c]);
      const double t0 = g->FirstParameter(), t1 = g->LastParameter();
      const bool closed = g->Value(t0).Distance(g->Value(t1)) <= Precision::Confusion();
      const int pieces = closed ? 3 : 1;
      CurveEdges& ce = shared[c];
      std::vector<TopoDS_Vertex> vertices;
      for (int k = 0; k <= pieces; ++k) {
        const double t = t0 + (t1 - t0) * k / pieces;
        ce.breaks.push_back(t);
        if (closed && k == pieces) {
          vertices.push_back(vertices.front());
        } else {
          TopoDS_Vertex v;
          builder.MakeVertex(v, g->Value(t), Precision::Confusion());
          vertices.push_back(v);
        }
      }
      for (int k = 0; k < pieces; ++k) {
        BRepBuilderAPI_MakeEdge edge(
            g, vertices[static_cast<size_t>(k)], vertices[static_cast<size_t>(k + 1)],
            ce.breaks[static_cast<size_t>(k)], ce.breaks[static_cast<size_t>(k + 1)]);
        if (!edge.IsDone())
          throw GeometryError("joining: an edge of a join curve could not be built");
        ce.edges.push_back(edge.Edge());
      }
    }
    // 2. Per sheet: pcurves on its surface, the loop of its edges, the face inside it.
    std::vector<TopoDS_Face> faces;
    for (size_t s = 0; s < sheets.size(); ++s) {
      const JoinedSheet& sh = sheets[s];
      Handle(Geom_BSplineSurface) surface = to_geom(sh.surface);
      // The sheet's pieces of each shared curve, with their pcurves on its surface.
      std::vector<std::vector<TopoDS_Edge>> edges_of(sh.curves.size());
      for (size_t k = 0; k < sh.curves.size(); ++k) {
        const CurveEdges& ce = shared[static_cast<size_t>(sh.curves[k])];
        Handle(Geom2d_BSplineCurve) pre = to_geom2d_curve(sh.preimages[k]);
        for (size_t e = 0; e < ce.edges.size(); ++e) {
          Handle(Geom2d_BSplineCurve) piece = Handle(Geom2d_BSplineCurve)::DownCast(pre->Copy());
          if (ce.edges.size() > 1) piece->Segment(ce.breaks[e], ce.breaks[e + 1]);
          builder.UpdateEdge(ce.edges[e], piece, surface, TopLoc_Location(),
                             Precision::Confusion());
          edges_of[k].push_back(ce.edges[e]);
        }
      }
      // The pre-images chained into the loop, walked counter-clockwise in (u, v) so the face
      // keeps the surface's normal.
      const SplineSpace& sp = sh.surface.space;
      CurveLoop order;
      try {
        order = chain_loop(sh.preimages,
                           1e-6 * std::max(sp.u_last() - sp.u_first(), sp.v_last() - sp.v_first()));
      } catch (const InvalidInput& e) {
        throw InvalidInput("joining: sheet " + std::to_string(s) + ": " + e.what());
      }
      std::vector<LoopStep> steps = order.steps;
      if (order.signed_area < 0.0) {
        std::reverse(steps.begin(), steps.end());
        for (LoopStep& step : steps) step.reversed = !step.reversed;
      }
      TopoDS_Wire wire;
      builder.MakeWire(wire);
      for (const LoopStep& step : steps) {
        const std::vector<TopoDS_Edge>& pieces = edges_of[static_cast<size_t>(step.curve)];
        if (!step.reversed) {
          for (const TopoDS_Edge& e : pieces) builder.Add(wire, e);
        } else {
          for (auto it = pieces.rbegin(); it != pieces.rend(); ++it)
            builder.Add(wire, it->Reversed());
        }
      }
      wire.Closed(Standard_True);
      TopoDS_Face face;
      builder.MakeFace(face, surface, Precision::Confusion());
      builder.Add(face, wire);
      faces.push_back(face);
    }
    // 3. Edge tolerances from the measured 3D-curve / pcurve deviation; then the shell.
    for (const CurveEdges& ce : shared)
      for (const TopoDS_Edge& e : ce.edges) BRepLib::SameParameter(e, tolerance);
    // SameParameter samples the deviation; OCCT's own curve-on-surface check (used by its
    // Boolean operations) searches it: the edge tolerance must cover what that check finds.
    for (const TopoDS_Face& f : faces)
      for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) {
        const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
        BRepLib_CheckCurveOnSurface check(e, f);
        check.Perform();
        if (check.IsDone() && check.MaxDistance() > BRep_Tool::Tolerance(e))
          builder.UpdateEdge(e, 1.01 * check.MaxDistance());
      }
    for (TopoDS_Face& f : faces) BRepLib::UpdateTolerances(f);
    TopoDS_Shell shell;
    builder.MakeShell(shell);
    for (const TopoDS_Face& f : faces) builder.Add(shell, f);
    ShellResult out;
    bool closed = true;
    for (size_t c = 0; c < curves.size(); ++c) closed = closed && uses[c] >= 2;
    // Sheets that share a curve may walk it the same way (their (u, v) normals agree); the
    // shell needs each shared edge walked both ways: ShapeFix_Shell reverses faces to match.
    ShapeFix_Shell fix_shell(shell);
    fix_shell.Perform();
    shell = fix_shell.Shell();
    shell.Closed(closed);
    out.shape = closed ? TopoDS_Shape(outward_solid(shell)) : TopoDS_Shape(shell);
    out.closed = closed;
    for (size_t c = 0; c < curves.size(); ++c)
      if (uses[c] < 2) out.free_edges += static_cast<int>(shared[c].edges.size());
    return finished(out);
  });
}

}  // namespace varsurf::occ
