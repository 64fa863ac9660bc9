// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/exchange_edges.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepTools_ReShape.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Line.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopTools_DataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_MapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <cmath>
#include <vector>

#include "varsurf/occ/curve_on_surface.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

constexpr double kConfusion = 1e-7;  // OCCT's smallest tolerance: deviations below it are safe
constexpr double kMargin = 1e-3;     // interior peaks must stay this far (relative) below the ends
constexpr int kMaxPieces = 64;       // per edge
constexpr double kShortest = 20.0;   // pieces stay this many times the largest deviation long:
                                     // 10 file uncertainties (step_io writes twice the deviation)

// The distance between an edge's 3D curve and its curves on its faces, at a parameter.
class EdgeDeviation {
 public:
  EdgeDeviation(const TopoDS_Edge& edge, const std::vector<TopoDS_Face>& faces) : curve_(edge) {
    for (const TopoDS_Face& f : faces) on_faces_.emplace_back(edge, f);
  }
  gp_Pnt point(double t) const { return curve_.Value(t); }
  double operator()(double t) const {
    const gp_Pnt p = curve_.Value(t);
    double d = 0.0;
    for (const BRepAdaptor_Curve& c : on_faces_) d = std::max(d, p.Distance(c.Value(t)));
    return d;
  }

 private:
  BRepAdaptor_Curve curve_;
  std::vector<BRepAdaptor_Curve> on_faces_;
};

struct Peak {
  double t = 0.0;
  double value = 0.0;
};

// The largest local maximum of d inside (a, b): dense samples, each local maximum refined by
// golden-section search between its neighbours. `samples` follows the curves' knot counts so
// that every span is visited several times.
Peak interior_peak(const EdgeDeviation& d, double a, double b, int samples) {
  std::vector<double> t(static_cast<size_t>(samples) + 1), v(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    t[i] = a + (b - a) * static_cast<double>(i) / samples;
    v[i] = d(t[i]);
  }
  Peak best;
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  for (size_t i = 1; i + 1 < t.size(); ++i) {
    if (v[i] < v[i - 1] || v[i] < v[i + 1]) continue;
    double lo = t[i - 1], hi = t[i + 1];
    double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
    double f1 = d(x1), f2 = d(x2);
    for (int k = 0; k < 60 && hi - lo > 1e-14 * (b - a); ++k) {
      if (f1 < f2) {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + phi * (hi - lo), f2 = d(x2);
      } else {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - phi * (hi - lo), f1 = d(x1);
      }
    }
    Peak p{f1 > f2 ? x1 : x2, std::max(f1, f2)};
    if (v[i] > p.value) p = {t[i], v[i]};
    if (p.value > best.value) best = p;
  }
  return best;
}

// Breaks (interior parameters, ascending) after which the deviation on every piece of [a, b]
// is largest at the piece's ends. No piece is shorter than `shortest` (a reader removes edges
// shorter than the file's uncertainty).
void peak_breaks(const EdgeDeviation& d, double a, double b, int samples, double shortest,
                 std::vector<double>& breaks) {
  if (static_cast<int>(breaks.size()) + 1 >= kMaxPieces) return;
  const Peak p = interior_peak(d, a, b, samples);
  const double ends = std::max(d(a), d(b));
  if (p.value <= kConfusion || p.value <= (1.0 - kMargin) * ends) return;
  const gp_Pnt at = d.point(p.t);
  if (at.Distance(d.point(a)) < shortest || at.Distance(d.point(b)) < shortest) return;
  peak_breaks(d, a, p.t, samples, shortest, breaks);
  breaks.push_back(p.t);
  peak_breaks(d, p.t, b, samples, shortest, breaks);
}

int knot_count(const Handle(Geom_Curve) & c) {
  Handle(Geom_BSplineCurve) b = Handle(Geom_BSplineCurve)::DownCast(c);
  return b.IsNull() ? 0 : b->NbKnots();
}

int knot_count(const Handle(Geom2d_Curve) & c) {
  Handle(Geom2d_BSplineCurve) b = Handle(Geom2d_BSplineCurve)::DownCast(c);
  return b.IsNull() ? 0 : b->NbKnots();
}

// The curve restricted to [a, b]: a B-spline cut exactly (Segment keeps its parametrization),
// any other curve (a line, a circle: parametrized on their own) shared as it is.
Handle(Geom_Curve) piece_of(const Handle(Geom_Curve) & c, double a, double b) {
  Handle(Geom_BSplineCurve) spline = Handle(Geom_BSplineCurve)::DownCast(c);
  if (spline.IsNull()) return c;
  spline = Handle(Geom_BSplineCurve)::DownCast(spline->Copy());
  spline->Segment(a, b);
  return spline;
}

Handle(Geom2d_Curve) piece_of(const Handle(Geom2d_Curve) & c, double a, double b) {
  Handle(Geom2d_BSplineCurve) spline = Handle(Geom2d_BSplineCurve)::DownCast(c);
  if (spline.IsNull()) return c;
  spline = Handle(Geom2d_BSplineCurve)::DownCast(spline->Copy());
  spline->Segment(a, b);
  return spline;
}

// The piece [a, b] of a (forward) edge, on the same curves and parameters, between the given
// vertices.
TopoDS_Edge edge_piece(const TopoDS_Edge& edge, const std::vector<TopoDS_Face>& faces, double a,
                       double b, const TopoDS_Vertex& first, const TopoDS_Vertex& last,
                       double tolerance) {
  BRep_Builder builder;
  TopLoc_Location loc;
  double f = 0.0, l = 0.0;
  TopoDS_Edge piece;
  builder.MakeEdge(piece, piece_of(BRep_Tool::Curve(edge, loc, f, l), a, b), loc, tolerance);
  for (const TopoDS_Face& face : faces)
    builder.UpdateEdge(piece, piece_of(BRep_Tool::CurveOnSurface(edge, face, f, l), a, b), face,
                       tolerance);
  builder.Range(piece, a, b);
  builder.Add(piece, first.Oriented(TopAbs_FORWARD));
  builder.Add(piece, last.Oriented(TopAbs_REVERSED));
  builder.SameRange(piece, Standard_True);
  builder.SameParameter(piece, Standard_True);
  return piece;
}

// Whether the edge can be cut: a 3D curve and pcurves, same range and parameter, not a seam.
// (Lines count: a part's straight edge sewn to a sheet has the sheet's B-spline pcurve, whose
// deviation peaks inside the edge.)
bool splittable(const TopoDS_Edge& edge, const std::vector<TopoDS_Face>& faces) {
  if (BRep_Tool::Degenerated(edge) || !BRep_Tool::SameParameter(edge) ||
      !BRep_Tool::SameRange(edge) || faces.empty())
    return false;
  double f = 0.0, l = 0.0;
  const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, f, l);
  if (curve.IsNull() || !(knot_count(curve) > 0 || curve->IsKind(STANDARD_TYPE(Geom_Line))))
    return false;
  for (const TopoDS_Face& face : faces) {
    if (BRep_Tool::IsClosed(edge, face)) return false;
    if (BRep_Tool::CurveOnSurface(edge, face, f, l).IsNull()) return false;
  }
  return true;
}

}  // namespace

ExchangeShape prepare_for_exchange(const TopoDS_Shape& shape) {
  ExchangeShape out;
  out.shape = shape;
  if (shape.IsNull()) return out;
  return guarded("preparing edges for exchange", [&] {
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    TopTools_DataMapOfShapeListOfShape pieces;  // forward edge -> its pieces, in order
    TopTools_MapOfShape touched_faces;
    BRep_Builder builder;
    // First every edge's deviation: the largest sets the file's uncertainty, hence the shortest
    // piece allowed.
    std::vector<std::vector<TopoDS_Face>> faces_of(static_cast<size_t>(edge_faces.Extent()));
    std::vector<double> deviation_of(faces_of.size());
    for (int k = 1; k <= edge_faces.Extent(); ++k) {
      const TopoDS_Edge edge = TopoDS::Edge(edge_faces.FindKey(k).Oriented(TopAbs_FORWARD));
      std::vector<TopoDS_Face>& faces = faces_of[static_cast<size_t>(k - 1)];
      TopTools_MapOfShape seen;
      for (TopTools_ListIteratorOfListOfShape it(edge_faces(k)); it.More(); it.Next())
        if (seen.Add(it.Value())) faces.push_back(TopoDS::Face(it.Value()));
      deviation_of[static_cast<size_t>(k - 1)] = curve_on_surface_deviation(edge, faces);
      out.max_deviation = std::max(out.max_deviation, deviation_of[static_cast<size_t>(k - 1)]);
    }
    for (int k = 1; k <= edge_faces.Extent(); ++k) {
      const TopoDS_Edge edge = TopoDS::Edge(edge_faces.FindKey(k).Oriented(TopAbs_FORWARD));
      const std::vector<TopoDS_Face>& faces = faces_of[static_cast<size_t>(k - 1)];
      const double deviation = deviation_of[static_cast<size_t>(k - 1)];
      if (deviation <= kConfusion || !splittable(edge, faces)) continue;
      double f = 0.0, l = 0.0;
      BRep_Tool::Range(edge, f, l);
      int knots = knot_count(BRep_Tool::Curve(edge, f, l));
      for (const TopoDS_Face& face : faces) {
        double a = 0.0, b = 0.0;
        knots = std::max(knots, knot_count(BRep_Tool::CurveOnSurface(edge, face, a, b)));
      }
      const EdgeDeviation d(edge, faces);
      std::vector<double> breaks;
      peak_breaks(d, f, l, 64 + 8 * knots, kShortest * out.max_deviation, breaks);
      if (breaks.empty()) continue;
      // The pieces keep the edge's tolerance, raised to what OCCT measures if that is more.
      const double tolerance = std::max(BRep_Tool::Tolerance(edge), 1.0001 * deviation);
      TopoDS_Vertex first, last;
      TopExp::Vertices(edge, first, last);
      const BRepAdaptor_Curve curve(edge);
      TopTools_ListOfShape list;
      TopoDS_Vertex start = first;
      for (size_t i = 0; i <= breaks.size(); ++i) {
        const double a = i == 0 ? f : breaks[i - 1];
        const double b = i == breaks.size() ? l : breaks[i];
        TopoDS_Vertex end = last;
        if (i < breaks.size()) builder.MakeVertex(end, curve.Value(b), tolerance);
        list.Append(edge_piece(edge, faces, a, b, start, end, tolerance));
        start = end;
      }
      pieces.Bind(edge, list);
      for (const TopoDS_Face& face : faces) touched_faces.Add(face.Oriented(TopAbs_FORWARD));
      ++out.split_edges;
    }
    if (pieces.IsEmpty()) return out;
    // Each face with a split edge rebuilt on the same surface, its wires walking the pieces in
    // the edge's direction of use.
    BRepTools_ReShape reshape;
    reshape.ModeConsiderLocation() = Standard_True;  // faces of a placed shape carry locations
    for (TopTools_MapIteratorOfMapOfShape it(touched_faces); it.More(); it.Next()) {
      const TopoDS_Face face = TopoDS::Face(it.Key());
      TopoDS_Face rebuilt = TopoDS::Face(face.EmptyCopied());
      for (TopoDS_Iterator wires(face, Standard_False); wires.More(); wires.Next()) {
        const TopoDS_Shape& wire = wires.Value();
        TopoDS_Wire new_wire;
        builder.MakeWire(new_wire);
        for (TopoDS_Iterator edges(wire, Standard_False); edges.More(); edges.Next()) {
          const TopoDS_Shape& e = edges.Value();
          const TopoDS_Shape key = e.Oriented(TopAbs_FORWARD);
          if (!pieces.IsBound(key)) {
            builder.Add(new_wire, e);
            continue;
          }
          std::vector<TopoDS_Shape> run;
          for (TopTools_ListIteratorOfListOfShape p(pieces(key)); p.More(); p.Next())
            run.push_back(p.Value());
          if (e.Orientation() == TopAbs_REVERSED) {
            for (auto p = run.rbegin(); p != run.rend(); ++p) builder.Add(new_wire, p->Reversed());
          } else {
            for (const TopoDS_Shape& p : run) builder.Add(new_wire, p.Oriented(e.Orientation()));
          }
        }
        new_wire.Closed(wire.Closed());
        new_wire.Orientation(wire.Orientation());
        builder.Add(rebuilt, new_wire);
      }
      reshape.Replace(face, rebuilt);
    }
    out.shape = reshape.Apply(shape);
    return out;
  });
}

int cover_measured_deviations(const TopoDS_Shape& shape) {
  if (shape.IsNull()) return 0;
  return guarded("measuring edge deviations", [&] {
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    BRep_Builder builder;
    int raised = 0;
    for (int k = 1; k <= edge_faces.Extent(); ++k) {
      const TopoDS_Edge& edge = TopoDS::Edge(edge_faces.FindKey(k));
      if (BRep_Tool::Degenerated(edge)) continue;
      std::vector<TopoDS_Face> faces;
      for (TopTools_ListIteratorOfListOfShape it(edge_faces(k)); it.More(); it.Next())
        faces.push_back(TopoDS::Face(it.Value()));
      const double deviation = curve_on_surface_deviation(edge, faces);
      if (deviation <= BRep_Tool::Tolerance(edge)) continue;
      const double tolerance = 1.0001 * deviation;
      builder.UpdateEdge(edge, tolerance);
      for (TopoDS_Iterator v(edge); v.More(); v.Next())
        if (BRep_Tool::Tolerance(TopoDS::Vertex(v.Value())) < tolerance)
          builder.UpdateVertex(TopoDS::Vertex(v.Value()), tolerance);
      ++raised;
    }
    return raised;
  });
}

}  // namespace varsurf::occ
