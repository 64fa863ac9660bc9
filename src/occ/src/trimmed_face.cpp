// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/trimmed_face.hpp"

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepLib.hxx>
#include <BRepLib_CheckCurveOnSurface.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Precision.hxx>
#include <ShapeFix_Face.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "collapsed_sides.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/face_builder.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/shape_check.hpp"

namespace varsurf::occ {

namespace {

struct Box {
  double u1, u2, v1, v2;
  double span() const { return std::max(u2 - u1, v2 - v1); }
};

Box bounds_of(const Handle(Geom_Surface) & s) {
  Box b{};
  s->Bounds(b.u1, b.u2, b.v1, b.v2);
  return b;
}

Box face_box(const TopoDS_Face& face) {
  Box b{};
  BRepTools::UVBounds(face, b.u1, b.u2, b.v1, b.v2);
  return b;
}

// (u, v) of `s` nearest to p, starting from (u, v): Gauss-Newton (the point lies on the surface,
// so it converges quadratically), with OCCT's global projection when it stalls (at a pole or
// far from the start). Returns the distance left.
double invert(const Handle(Geom_Surface) & s, const Box& box, const gp_Pnt& p, double& u,
              double& v) {
  auto clamp = [](double x, double lo, double hi) { return std::min(std::max(x, lo), hi); };
  u = clamp(u, box.u1, box.u2);
  v = clamp(v, box.v1, box.v2);
  for (int it = 0; it < 40; ++it) {
    gp_Pnt q;
    gp_Vec su, sv;
    s->D1(u, v, q, su, sv);
    const gp_Vec r(q, p);
    const double a11 = su.Dot(su), a12 = su.Dot(sv), a22 = sv.Dot(sv);
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 1e-20 * a11 * a22)) break;  // singular (a pole): leave it to the projection
    const double du = (a22 * su.Dot(r) - a12 * sv.Dot(r)) / det;
    const double dv = (a11 * sv.Dot(r) - a12 * su.Dot(r)) / det;
    u = clamp(u + du, box.u1, box.u2);
    v = clamp(v + dv, box.v1, box.v2);
    if (std::abs(du) + std::abs(dv) < 1e-15 * box.span()) break;
  }
  double d = s->Value(u, v).Distance(p);
  if (d > 1e-9 * (1.0 + p.XYZ().Modulus())) {
    GeomAPI_ProjectPointOnSurf projection(p, s, box.u1, box.u2, box.v1, box.v2);
    if (projection.NbPoints() > 0 && projection.LowerDistance() < d) {
      projection.LowerDistanceParameters(u, v);
      d = projection.LowerDistance();
    }
  }
  return d;
}

// The sheet's (su, sv) of the base's (u, v): the sheet's point nearest to the base's. Where the
// base degenerates (at a pole one derivative vanishes and any su fits), that coordinate comes
// from a point just inside the face (`face`: its (u, v) box), where it is determined: the
// conversions reparametrize each direction on its own.
void carry_point(const Handle(Geom_Surface) & base, const Box& face,
                 const Handle(Geom_Surface) & sheet, const Box& box, double u, double v, double& su,
                 double& sv) {
  gp_Pnt p;
  gp_Vec du, dv;
  base->D1(u, v, p, du, dv);
  invert(sheet, box, p, su, sv);
  const double big = std::max(du.Magnitude(), dv.Magnitude());
  for (int axis = 0; axis < 2 && big > 0.0; ++axis) {
    if ((axis == 0 ? du : dv).Magnitude() > 1e-7 * big) continue;
    const double lo = axis == 0 ? face.v1 : face.u1, hi = axis == 0 ? face.v2 : face.u2;
    const double at = axis == 0 ? v : u;
    const double step = 1e-4 * (hi - lo) * (at < 0.5 * (lo + hi) ? 1.0 : -1.0);
    double a = su, b = sv;
    invert(sheet, box, axis == 0 ? base->Value(u, v + step) : base->Value(u + step, v), a, b);
    (axis == 0 ? su : sv) = axis == 0 ? a : b;
  }
}

// An edge's pcurve on the sheet with the range it is used on.
struct Pcurve {
  Handle(Geom2d_Curve) curve;
  double first = 0.0, last = 0.0;
};

}  // namespace

BaseTrim::BaseTrim(const TopoDS_Face& base) {
  if (base.IsNull()) throw InvalidInput("face is null");
  nurbs_ = to_geom(surface_from_face(base));
  guarded("reading the base face's boundary", [&] {
    orientation_ = base.Orientation();
    base_ = TopoDS::Face(base.Oriented(TopAbs_FORWARD));
    surface_ = BRep_Tool::Surface(base_);
    Bnd_Box box;
    BRepBndLib::Add(base_, box);
    if (!box.IsVoid()) size_ = std::max(std::sqrt(box.SquareExtent()), Precision::Confusion());

    double u1, u2, v1, v2;
    BRepTools::UVBounds(base_, u1, u2, v1, v2);
    const Box sheet = bounds_of(nurbs_);
    // The conversion kept the parameters when the two surfaces agree point for point. The
    // samples avoid symmetric fractions: a rational arc meets the angle at its spans' middles.
    identity_ = true;
    for (int i = 0; i <= 7 && identity_; ++i) {
      for (int j = 0; j <= 7 && identity_; ++j) {
        const double u = u1 + (u2 - u1) * std::min(1.0, (i + 0.3183) / 7.3183);
        const double v = v1 + (v2 - v1) * std::min(1.0, (j + 0.2718) / 7.2718);
        identity_ = u >= sheet.u1 && u <= sheet.u2 && v >= sheet.v1 && v <= sheet.v2 &&
                    surface_->Value(u, v).Distance(nurbs_->Value(u, v)) <= 1e-9 * size_;
      }
    }

    BRep_Builder builder;
    builder.MakeCompound(edges_);
    int wires = 0;
    for (TopExp_Explorer ex(base_, TopAbs_WIRE); ex.More(); ex.Next()) ++wires;
    for (TopExp_Explorer ex(base_, TopAbs_EDGE); ex.More(); ex.Next())
      builder.Add(edges_, ex.Current());

    // Natural: one wire, all of it on the sheet's parameter rectangle.
    const double ptol = 1e-7 * sheet.span();
    natural_ = wires == 1;
    for (TopExp_Explorer ex(base_, TopAbs_EDGE); ex.More() && natural_; ex.Next()) {
      double f, l;
      Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), base_, f, l);
      if (c.IsNull()) throw GeometryError("the base face has an edge without a curve on it");
      for (int k = 0; k <= 8 && natural_; ++k) {
        const gp_Pnt2d p = c->Value(f + (l - f) * k / 8);
        double su = p.X(), sv = p.Y();
        to_sheet(p.X(), p.Y(), su, sv);
        natural_ = std::abs(su - sheet.u1) <= ptol || std::abs(su - sheet.u2) <= ptol ||
                   std::abs(sv - sheet.v1) <= ptol || std::abs(sv - sheet.v2) <= ptol;
      }
    }

    const double uv_tol = 1e-9 * std::max(u2 - u1, v2 - v1);
    whole_ = std::make_unique<BRepTopAdaptor_FClass2d>(base_, uv_tol);
    TopoDS_Face outer = TopoDS::Face(base_.EmptyCopied());
    builder.Add(outer, BRepTools::OuterWire(base_));
    outer_ = std::make_unique<BRepTopAdaptor_FClass2d>(outer, uv_tol);

    // The sheet's normal against the face's outward one, where the surfaces are least degenerate
    // (inside the face if any sample is).
    double best[2] = {-1.0, -1.0}, dot[2] = {1.0, 1.0};  // [outside, inside]
    for (int i = 1; i <= 7; ++i) {
      for (int j = 1; j <= 7; ++j) {
        const double u = u1 + (u2 - u1) * i / 8, v = v1 + (v2 - v1) * j / 8;
        gp_Pnt p, q;
        gp_Vec su, sv, tu, tv;
        surface_->D1(u, v, p, su, sv);
        double a = u, b = v;
        to_sheet(u, v, a, b);
        nurbs_->D1(a, b, q, tu, tv);
        const gp_Vec n = su.Crossed(sv), m = tu.Crossed(tv);
        const double weight = n.Magnitude() * m.Magnitude();
        const int in = whole_->Perform(gp_Pnt2d(u, v)) == TopAbs_IN ? 1 : 0;
        if (weight > best[in]) {
          best[in] = weight;
          dot[in] = n.Dot(m);
        }
      }
    }
    const double along = best[1] > 0.0 ? dot[1] : dot[0];
    normal_sign_ = (along >= 0.0) == (orientation_ != TopAbs_REVERSED) ? 1 : -1;
  });
}

BaseTrim::~BaseTrim() = default;

void BaseTrim::to_sheet(double u, double v, double& su, double& sv) const {
  if (identity_) {
    su = u;
    sv = v;
    return;
  }
  carry_point(surface_, face_box(base_), nurbs_, bounds_of(nurbs_), u, v, su, sv);
}

void BaseTrim::to_base(double su, double sv, double& u, double& v) const {
  if (identity_) {
    u = su;
    v = sv;
    return;
  }
  Box box{};
  BRepTools::UVBounds(base_, box.u1, box.u2, box.v1, box.v2);
  invert(surface_, box, nurbs_->Value(su, sv), u, v);
}

TopoDS_Face BaseTrim::face(const BSplineSurface& sheet) const {
  const Handle(Geom_BSplineSurface) geom = to_geom(sheet);
  const Box a = bounds_of(geom), b = bounds_of(nurbs_);
  const double tol = 1e-9 * b.span();
  if (std::abs(a.u1 - b.u1) > tol || std::abs(a.u2 - b.u2) > tol || std::abs(a.v1 - b.v1) > tol ||
      std::abs(a.v2 - b.v2) > tol)
    throw InvalidInput("the sheet does not share its base face's parameter domain");
  if (natural_) {
    TopoDS_Face out = make_face(sheet);
    out.Orientation(orientation_);
    return out;
  }
  return guarded("bounding the sheet by its base face's boundary", [&] {
    collapse_degenerate_sides(geom, Precision::Confusion());
    return bounded(geom);
  });
}

namespace {

// A curve given by its points as a cubic B-spline with the same parameter: interpolated within
// each piece between consecutive `breaks` (where it may be only C1 or C0: one interpolation
// across would converge slowly), with the piece's own end tangents (one-sided differences of
// fourth order), joined C0, each piece's points doubled until its midpoints are within
// `accuracy` as `error` measures.
template <class At, class Error>
Handle(Geom_BSplineCurve) interpolate_pieces(const At& at, const std::vector<double>& breaks,
                                             const Error& error, double accuracy) {
  auto tangent = [&](double t, double h) {  // h > 0: forward, h < 0: backward
    const gp_XYZ f0 = at(t).XYZ(), f1 = at(t + h).XYZ(), f2 = at(t + 2 * h).XYZ(),
                 f3 = at(t + 3 * h).XYZ(), f4 = at(t + 4 * h).XYZ();
    return gp_Vec((-25 * f0 + 48 * f1 - 36 * f2 + 16 * f3 - 3 * f4) / (12 * h));
  };
  std::vector<gp_Pnt> poles;
  std::vector<double> knots;
  std::vector<int> mults;
  for (size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i], b = breaks[i + 1];
    Handle(Geom_BSplineCurve) piece;
    for (int n = 4;; n *= 2) {
      Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, n + 1);
      Handle(TColStd_HArray1OfReal) params = new TColStd_HArray1OfReal(1, n + 1);
      for (int k = 0; k <= n; ++k) {
        const double t = k == n ? b : a + (b - a) * k / n;
        points->SetValue(k + 1, at(t));
        params->SetValue(k + 1, t);
      }
      GeomAPI_Interpolate interpolate(points, params, Standard_False, 0.0);
      interpolate.Load(tangent(a, 1e-3 * (b - a)), tangent(b, -1e-3 * (b - a)), Standard_False);
      interpolate.Perform();
      if (!interpolate.IsDone())
        throw GeometryError("a boundary edge of the base face could not be followed on the sheet");
      piece = interpolate.Curve();
      double worst = 0.0;
      for (int k = 0; k < n; ++k) {
        const double t = a + (b - a) * (k + 0.5) / n;
        worst = std::max(worst, error(at(t), piece->Value(t)));
      }
      if (worst <= accuracy || n >= 512) break;
    }
    for (int k = poles.empty() ? 1 : 2; k <= piece->NbPoles(); ++k) poles.push_back(piece->Pole(k));
    if (knots.empty()) {
      knots.push_back(piece->Knot(1));
      mults.push_back(4);
    } else {
      mults.back() = 3;  // the join: C0
    }
    for (int k = 2; k <= piece->NbKnots(); ++k) {
      knots.push_back(piece->Knot(k));
      mults.push_back(piece->Multiplicity(k));
    }
  }
  TColgp_Array1OfPnt p(1, static_cast<int>(poles.size()));
  TColStd_Array1OfReal k(1, static_cast<int>(knots.size()));
  TColStd_Array1OfInteger m(1, static_cast<int>(mults.size()));
  for (size_t i = 0; i < poles.size(); ++i) p(static_cast<int>(i) + 1) = poles[i];
  for (size_t i = 0; i < knots.size(); ++i) {
    k(static_cast<int>(i) + 1) = knots[i];
    m(static_cast<int>(i) + 1) = mults[i];
  }
  return new Geom_BSplineCurve(p, k, m, 3);
}

// Knots of a B-spline where it is less than C2 (multiplicity above degree - 2), ends excluded.
template <class Curve>
std::vector<double> kinks(const Handle(Curve) & c) {
  std::vector<double> out;
  for (int i = 2; i < c->NbKnots(); ++i)
    if (c->Multiplicity(i) > c->Degree() - 2) out.push_back(c->Knot(i));
  return out;
}

// The pcurve c on [f, l] of the base carried to the sheet's parameters through the conversion's
// reparametrization (the sheet's point nearest to the base's). An isoline stays an exact line
// (parametrized by its varying coordinate); any other curve is interpolated in pieces between
// its own kinks and where it crosses the sheet's kinked knot lines, to `accuracy` mm on the
// sheet.
Pcurve mapped(const Handle(Geom2d_Curve) & c, double f, double l, const Handle(Geom_Surface) & base,
              const Box& face, const Handle(Geom_BSplineSurface) & sheet, double accuracy) {
  const Box box = bounds_of(sheet);
  const double ptol = 1e-10 * box.span();
  double su = c->Value(f).X(), sv = c->Value(f).Y();  // the last image: the next one's start
  auto at = [&](double t) {
    const gp_Pnt2d p = c->Value(t);
    carry_point(base, face, sheet, box, p.X(), p.Y(), su, sv);
    return gp_Pnt(su, sv, 0.0);
  };
  const int n = 64;
  std::vector<gp_Pnt> pts;
  for (int k = 0; k <= n; ++k) pts.push_back(at(f + (l - f) * k / n));
  // A point on a side of the face's (u, v) box (along a seam, at a cut of constant angle, a seam's
  // end at a pole) lies on the same side of the sheet's box: the conversion maps the box's sides
  // onto the sheet's. Inverted, such a point may land on either side of a seam (near a pole at any
  // u), so that coordinate is taken from the base's pcurve.
  const double base_tol = 1e-10 * face.span();
  const double sides[4] = {face.u1, face.u2, face.v1, face.v2};
  const double sheet_sides[4] = {box.u1, box.u2, box.v1, box.v2};
  for (int k = 0; k <= n; ++k) {
    const gp_Pnt2d q = c->Value(f + (l - f) * k / n);
    for (int side = 0; side < 4; ++side)
      if (std::abs(q.Coord(side / 2 + 1) - sides[side]) <= base_tol)
        pts[static_cast<size_t>(k)].SetCoord(side / 2 + 1, sheet_sides[side]);
  }
  double umin = pts[0].X(), umax = umin, vmin = pts[0].Y(), vmax = vmin;
  for (const gp_Pnt& p : pts) {
    umin = std::min(umin, p.X());
    umax = std::max(umax, p.X());
    vmin = std::min(vmin, p.Y());
    vmax = std::max(vmax, p.Y());
  }
  for (int axis = 0; axis < 2; ++axis) {
    const bool iso = axis == 0 ? umax - umin <= ptol : vmax - vmin <= ptol;
    if (!iso) continue;
    const double fixed = axis == 0 ? pts[0].X() : pts[0].Y();
    const double a = axis == 0 ? pts.front().Y() : pts.front().X();
    const double z = axis == 0 ? pts.back().Y() : pts.back().X();
    if (!(std::abs(z - a) > ptol)) continue;
    const double dir = z > a ? 1.0 : -1.0;
    Handle(Geom2d_Line) line = axis == 0
                                   ? new Geom2d_Line(gp_Pnt2d(fixed, 0.0), gp_Dir2d(0.0, dir))
                                   : new Geom2d_Line(gp_Pnt2d(0.0, fixed), gp_Dir2d(dir, 0.0));
    return Pcurve{line, dir * a, dir * z};
  }

  std::vector<double> breaks = {f, l};
  if (auto bs = Handle(Geom2d_BSplineCurve)::DownCast(c)) {
    for (double t : kinks(bs))
      if (t > f && t < l) breaks.push_back(t);
  }
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> lines;
    for (int i = 2; i < (axis == 0 ? sheet->NbUKnots() : sheet->NbVKnots()); ++i) {
      const int mult = axis == 0 ? sheet->UMultiplicity(i) : sheet->VMultiplicity(i);
      if (mult > (axis == 0 ? sheet->UDegree() : sheet->VDegree()) - 2)
        lines.push_back(axis == 0 ? sheet->UKnot(i) : sheet->VKnot(i));
    }
    for (double knot : lines) {
      for (int k = 0; k < n; ++k) {
        const double c0 = pts[static_cast<size_t>(k)].Coord(axis + 1) - knot;
        const double c1 = pts[static_cast<size_t>(k) + 1].Coord(axis + 1) - knot;
        if (!(c0 * c1 < 0.0)) continue;
        double lo = f + (l - f) * k / n, hi = f + (l - f) * (k + 1) / n;
        su = pts[static_cast<size_t>(k)].X();
        sv = pts[static_cast<size_t>(k)].Y();
        for (int it = 0; it < 60 && hi - lo > 1e-15 * (l - f); ++it) {
          const double mid = 0.5 * (lo + hi);
          if ((at(mid).Coord(axis + 1) - knot) * c0 > 0.0)
            lo = mid;
          else
            hi = mid;
        }
        breaks.push_back(0.5 * (lo + hi));
      }
    }
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end(),
                           [&](double x, double y) { return y - x <= 1e-9 * (l - f); }),
               breaks.end());
  breaks.back() = l;

  auto error = [&](const gp_Pnt& x, const gp_Pnt& y) {
    return sheet->Value(x.X(), x.Y()).Distance(sheet->Value(y.X(), y.Y()));
  };
  const Handle(Geom_BSplineCurve) curve = interpolate_pieces(at, breaks, error, accuracy);
  TColgp_Array1OfPnt2d poles(1, curve->NbPoles());
  for (int i = 1; i <= curve->NbPoles(); ++i)
    poles(i) = gp_Pnt2d(curve->Pole(i).X(), curve->Pole(i).Y());
  TColStd_Array1OfReal knots(1, curve->NbKnots());
  TColStd_Array1OfInteger mults(1, curve->NbKnots());
  curve->Knots(knots);
  curve->Multiplicities(mults);
  return Pcurve{new Geom2d_BSplineCurve(poles, knots, mults, curve->Degree()), f, l};
}

// The edge's pcurve on the base face carried to the sheet's parameters (as it is when the
// conversion kept them), to `accuracy` mm.
Pcurve carry(const TopoDS_Edge& edge, const TopoDS_Face& base, bool identity,
             const Handle(Geom_Surface) & surface, const Handle(Geom_BSplineSurface) & nurbs,
             double accuracy) {
  double f, l;
  Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(edge, base, f, l);
  if (c.IsNull()) throw GeometryError("the base face has an edge without a curve on it");
  if (identity) return Pcurve{c, f, l};
  return mapped(c, f, l, surface, face_box(base), nurbs, accuracy);
}

}  // namespace

TopoDS_Face BaseTrim::bounded(const Handle(Geom_BSplineSurface) & sheet) const {
  BRep_Builder builder;
  const double tol = Precision::Confusion();
  const double accuracy = std::min(1e-8 * size_, 0.1 * tol);
  auto carried = [&](const TopoDS_Edge& edge) {
    return carry(edge, base_, identity_, surface_, nurbs_, accuracy);
  };

  TopoDS_Face out;
  builder.MakeFace(out, sheet, tol);
  TopTools_DataMapOfShapeShape edges, vertices;
  auto vertex_at = [&](const TopoDS_Vertex& old, const gp_Pnt2d& uv) -> TopoDS_Vertex {
    if (vertices.IsBound(old)) return TopoDS::Vertex(vertices(old));
    TopoDS_Vertex fresh;
    builder.MakeVertex(fresh, sheet->Value(uv.X(), uv.Y()), tol);
    vertices.Bind(old, fresh);
    return fresh;
  };
  auto new_edge = [&](const TopoDS_Edge& old) -> TopoDS_Edge {
    const TopoDS_Edge fwd = TopoDS::Edge(old.Oriented(TopAbs_FORWARD));
    Pcurve one = carried(fwd);
    TopoDS_Edge e;
    builder.MakeEdge(e);
    if (BRep_Tool::IsClosed(fwd, base_)) {  // a seam: one pcurve on each side
      Pcurve two = carried(TopoDS::Edge(old.Oriented(TopAbs_REVERSED)));
      if (std::abs(two.first - one.first) > 1e-12 * (1.0 + std::abs(one.first)) ||
          std::abs(two.last - one.last) > 1e-12 * (1.0 + std::abs(one.last)))
        throw GeometryError("a seam of the base face maps to two different ranges on the sheet");
      builder.UpdateEdge(e, one.curve, two.curve, sheet, TopLoc_Location(), tol);
    } else {
      builder.UpdateEdge(e, one.curve, sheet, TopLoc_Location(), tol);
    }
    builder.Range(e, one.first, one.last);
    if (BRep_Tool::Degenerated(fwd)) {
      // Still a point on the sheet unless the solve opened it up (a free boundary at a pole).
      double spread = 0.0;
      const gp_Pnt2d a = one.curve->Value(one.first);
      for (int k = 1; k <= 16; ++k) {
        const gp_Pnt2d q = one.curve->Value(one.first + (one.last - one.first) * k / 16);
        spread = std::max(spread, sheet->Value(a.X(), a.Y()).Distance(sheet->Value(q.X(), q.Y())));
      }
      builder.Degenerated(e, spread <= tol);
    }
    TopoDS_Vertex v1, v2;
    TopExp::Vertices(fwd, v1, v2);
    if (!v1.IsNull())
      builder.Add(e, vertex_at(v1, one.curve->Value(one.first)).Oriented(TopAbs_FORWARD));
    if (!v2.IsNull())
      builder.Add(e, vertex_at(v2, one.curve->Value(one.last)).Oriented(TopAbs_REVERSED));
    return e;
  };

  // Orientations are copied as stored (relative to their parents); locations are composed so
  // that each edge finds its pcurve on the base face.
  for (TopoDS_Iterator w(base_, Standard_False, Standard_True); w.More(); w.Next()) {
    if (w.Value().ShapeType() != TopAbs_WIRE) continue;
    TopoDS_Wire wire;
    builder.MakeWire(wire);
    for (TopoDS_Iterator it(w.Value(), Standard_False, Standard_True); it.More(); it.Next()) {
      const TopoDS_Edge old = TopoDS::Edge(it.Value());
      if (!edges.IsBound(old)) edges.Bind(old, new_edge(old));
      builder.Add(wire, edges(old).Oriented(old.Orientation()));
    }
    wire.Closed(w.Value().Closed());
    builder.Add(out, wire.Oriented(w.Value().Orientation()));
  }

  BRepLib::BuildCurves3d(out, std::min(1e-9 * size_, 1e-7), GeomAbs_C1, 14, 64);
  // Each edge's tolerance from the measured distance between its 3D curve and its pcurve on the
  // sheet (what OCCT's BOP check measures), vertices' from their edges.
  for (TopExp_Explorer ex(out, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Degenerated(e)) continue;
    BRepLib_CheckCurveOnSurface measure(e, out);
    measure.Perform();
    if (!measure.IsDone())
      throw GeometryError("the sheet's boundary edges could not be measured against it");
    builder.UpdateEdge(e, std::max(1.5 * measure.MaxDistance(), tol));
    builder.SameParameter(e, Standard_True);
    builder.SameRange(e, Standard_True);
  }
  BRepLib::UpdateTolerances(out, Standard_False);

  ShapeCheck check = check_shape(out);
  if (!check.valid) {
    ShapeFix_Face fix(out);
    fix.SetPrecision(tol);
    fix.Perform();
    out = fix.Face();
    check = check_shape(out);
    if (!check.valid)
      throw GeometryError(
          "the sheet bounded by its base face's boundary is not valid (does the solved sheet fold "
          "over itself or collapse?): " +
          check.message);
  }
  out.Orientation(orientation_);
  return out;
}

namespace {

// The surface along a pre-image, s(pre(t)), as a 3D B-spline with the pre-image's parameter,
// interpolated in pieces between the pre-image's kinks (a rational arc is only C1 at its knots).
Handle(Geom_BSplineCurve) follow(const Handle(Geom2d_BSplineCurve) & pre,
                                 const Handle(Geom_Surface) & s, double accuracy) {
  auto at = [&](double t) {
    const gp_Pnt2d uv = pre->Value(t);
    return s->Value(uv.X(), uv.Y());
  };
  auto error = [](const gp_Pnt& x, const gp_Pnt& y) { return x.Distance(y); };
  std::vector<double> breaks = {pre->FirstParameter()};
  for (double t : kinks(pre)) breaks.push_back(t);
  breaks.push_back(pre->LastParameter());
  return interpolate_pieces(at, breaks, error, accuracy);
}

// The image of a pre-image under an affine surface: the same rational B-spline with its poles
// mapped (an affine map commutes with the weighted sums).
Handle(Geom_BSplineCurve)
    image(const Handle(Geom2d_BSplineCurve) & pre, const Handle(Geom_BSplineSurface) & s) {
  TColgp_Array1OfPnt poles(1, pre->NbPoles());
  TColStd_Array1OfReal weights(1, pre->NbPoles());
  for (int i = 1; i <= pre->NbPoles(); ++i) {
    poles(i) = s->Value(pre->Pole(i).X(), pre->Pole(i).Y());
    weights(i) = pre->Weight(i);
  }
  TColStd_Array1OfReal knots(1, pre->NbKnots());
  TColStd_Array1OfInteger mults(1, pre->NbKnots());
  pre->Knots(knots);
  pre->Multiplicities(mults);
  return new Geom_BSplineCurve(poles, weights, knots, mults, pre->Degree(), pre->IsPeriodic());
}

}  // namespace

std::vector<TrimCurve> BaseTrim::boundary() const {
  return guarded("reading the base face's boundary", [&] {
    std::vector<TrimCurve> out;
    const Box box = bounds_of(nurbs_);
    const double ptol = 1e-7 * box.span();
    const double accuracy = std::min(1e-8 * size_, 0.1 * Precision::Confusion());
    // A plane's sheet is affine in (u, v): the image of a pre-image is exact, pole by pole.
    bool affine = nurbs_->UDegree() == 1 && nurbs_->VDegree() == 1 && nurbs_->NbUPoles() == 2 &&
                  nurbs_->NbVPoles() == 2 && !nurbs_->IsURational() && !nurbs_->IsVRational();
    if (affine) {
      const gp_XYZ twist = nurbs_->Pole(2, 2).XYZ() - nurbs_->Pole(2, 1).XYZ() -
                           nurbs_->Pole(1, 2).XYZ() + nurbs_->Pole(1, 1).XYZ();
      affine = twist.Modulus() <= 1e-12 * size_;
    }
    TopTools_IndexedMapOfShape edges;
    TopExp::MapShapes(base_, TopAbs_EDGE, edges);
    for (int i = 1; i <= edges.Extent(); ++i) {
      const TopoDS_Edge& edge = TopoDS::Edge(edges(i));
      if (BRep_Tool::Degenerated(edge)) continue;
      const Pcurve pc = carry(edge, base_, identity_, surface_, nurbs_, accuracy);
      // Along one side of the parameter rectangle: held by the fixed boundary poles already.
      bool side[4] = {true, true, true, true};
      for (int k = 0; k <= 16; ++k) {
        const gp_Pnt2d p = pc.curve->Value(pc.first + (pc.last - pc.first) * k / 16);
        side[0] = side[0] && std::abs(p.X() - box.u1) <= ptol;
        side[1] = side[1] && std::abs(p.X() - box.u2) <= ptol;
        side[2] = side[2] && std::abs(p.Y() - box.v1) <= ptol;
        side[3] = side[3] && std::abs(p.Y() - box.v2) <= ptol;
      }
      if (side[0] || side[1] || side[2] || side[3]) continue;
      Handle(Geom2d_BSplineCurve) pre =
          Geom2dConvert::CurveToBSplineCurve(new Geom2d_TrimmedCurve(pc.curve, pc.first, pc.last));
      const Handle(Geom_BSplineCurve) target =
          affine ? image(pre, nurbs_) : follow(pre, nurbs_, accuracy);
      out.push_back(TrimCurve{from_geom(pre), from_geom(target)});
    }
    return out;
  });
}

TrimHit BaseTrim::place(double su, double sv, double tolerance) const {
  return guarded("placing a point on the base face", [&] {
    TrimHit hit;
    if (!(tolerance >= 0.0) || !std::isfinite(su) || !std::isfinite(sv))
      throw InvalidInput("placing on the base face: (u, v) must be finite and the tolerance >= 0");
    double u = su, v = sv;
    to_base(su, sv, u, v);
    if (whole_->Perform(gp_Pnt2d(u, v)) != TopAbs_OUT) return hit;
    BRepExtrema_DistShapeShape distance(BRepBuilderAPI_MakeVertex(surface_->Value(u, v)).Vertex(),
                                        edges_);
    if (!distance.IsDone()) throw GeometryError("placing on the base face: no distance");
    hit.distance = distance.Value();
    if (hit.distance <= tolerance) return hit;
    hit.place =
        outer_->Perform(gp_Pnt2d(u, v)) == TopAbs_OUT ? TrimPlace::outside : TrimPlace::over_hole;
    return hit;
  });
}

TrimHit BaseTrim::place(const BSplineCurve& preimage, double tolerance, int samples) const {
  preimage.validate("pre-image");
  if (preimage.dim() != 2) throw InvalidInput("placing on the base face: the pre-image is not 2D");
  if (samples < 0 || samples > 1000000)
    throw InvalidInput("placing on the base face takes 0 (automatic) to 1,000,000 samples");
  const int n = samples > 0 ? samples : std::max(64, 8 * static_cast<int>(preimage.knots.size()));
  TrimHit worst;
  for (int k = 0; k <= n; ++k) {
    const double t = preimage.first() + (preimage.last() - preimage.first()) * k / n;
    const Eigen::VectorXd p = preimage.evaluate(t);
    TrimHit hit = place(p(0), p(1), tolerance);
    if (hit.place != TrimPlace::inside && hit.distance > worst.distance) {
      hit.parameter = t;
      worst = hit;
    }
  }
  return worst;
}

}  // namespace varsurf::occ
