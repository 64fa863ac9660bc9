// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/geom_convert.hpp"

#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <GeomConvert.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/revolved_surface.hpp"

namespace varsurf::occ {

namespace {

struct OcctKnots {
  TColStd_Array1OfReal values;
  TColStd_Array1OfInteger mults;
};

// Distinct knots must be farther apart than OCCT's resolution, or its constructors raise.
OcctKnots to_occt_knots(const std::vector<double>& flat, const std::string& what) {
  std::vector<double> knots;
  std::vector<int> mults;
  split_knots(flat, knots, mults);
  OcctKnots out{TColStd_Array1OfReal(1, static_cast<int>(knots.size())),
                TColStd_Array1OfInteger(1, static_cast<int>(knots.size()))};
  for (size_t i = 0; i < knots.size(); ++i) {
    if (i > 0 && knots[i] - knots[i - 1] <= Epsilon(std::abs(knots[i - 1])))
      throw InvalidInput(what + ": distinct knots " + std::to_string(knots[i - 1]) + " and " +
                         std::to_string(knots[i]) + " are too close for OpenCASCADE");
    out.values(static_cast<int>(i) + 1) = knots[i];
    out.mults(static_cast<int>(i) + 1) = mults[i];
  }
  return out;
}

std::vector<double> from_occt(const TColStd_Array1OfReal& a) {
  return std::vector<double>(a.begin(), a.end());
}

void check_degree(int degree, int max_degree, const std::string& what) {
  if (degree > max_degree)
    throw InvalidInput(what + ": degree " + std::to_string(degree) +
                       " exceeds OpenCASCADE's maximum " + std::to_string(max_degree));
}

// OCCT's SetNotPeriodic leaves unclamped end knots (the domain sits inside the knot vector);
// segmenting to the domain clamps them.
void make_clamped(const Handle(Geom_BSplineSurface) & s) {
  if (s->IsUPeriodic()) s->SetUNotPeriodic();
  if (s->IsVPeriodic()) s->SetVNotPeriodic();
  const int pu = s->UDegree() + 1, pv = s->VDegree() + 1;
  if (s->UMultiplicity(1) < pu || s->UMultiplicity(s->NbUKnots()) < pu ||
      s->VMultiplicity(1) < pv || s->VMultiplicity(s->NbVKnots()) < pv) {
    double u1, u2, v1, v2;
    s->Bounds(u1, u2, v1, v2);
    s->Segment(u1, u2, v1, v2);
  }
}

template <class Curve>
void make_clamped(const Handle(Curve) & c) {
  if (c->IsPeriodic()) c->SetNotPeriodic();
  const int p = c->Degree() + 1;
  if (c->Multiplicity(1) < p || c->Multiplicity(c->NbKnots()) < p)
    c->Segment(c->FirstParameter(), c->LastParameter());
}

// OCCT stores the face's surface, possibly trimmed; the B-spline underneath or null.
Handle(Geom_BSplineSurface) bspline_under(const Handle(Geom_Surface) & s) {
  Handle(Geom_Surface) basis = s;
  while (auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(basis))
    basis = trimmed->BasisSurface();
  return Handle(Geom_BSplineSurface)::DownCast(basis);
}

// Restricts `s` to [u1, u2] x [v1, v2] where that is smaller than its domain (a periodic
// direction may be shifted), then removes periodicity.
void restrict_to(const Handle(Geom_BSplineSurface) & s, double u1, double u2, double v1,
                 double v2) {
  double su1, su2, sv1, sv2;
  s->Bounds(su1, su2, sv1, sv2);
  const double tol = Precision::PConfusion();
  auto range = [tol](bool periodic, double a, double b, double lo, double hi, double& ra,
                     double& rb) {
    if (periodic) {
      ra = a;
      rb = std::min(b, a + (hi - lo));
    } else {
      ra = std::max(a, lo);
      rb = std::min(b, hi);
    }
    return std::abs(ra - lo) > tol || std::abs(rb - hi) > tol;
  };
  double ru1, ru2, rv1, rv2;
  const bool cut_u = range(s->IsUPeriodic(), u1, u2, su1, su2, ru1, ru2);
  const bool cut_v = range(s->IsVPeriodic(), v1, v2, sv1, sv2, rv1, rv2);
  if (!(ru2 - ru1 > tol) || !(rv2 - rv1 > tol))
    throw InvalidInput("face: its UV bounds do not overlap its surface's domain");
  if (cut_u || cut_v) s->Segment(ru1, ru2, rv1, rv2);
  make_clamped(s);
}

// Whether [u1, u2] x [v1, v2] spans a whole period of `s` in both directions.
bool covers_both_periods(const Handle(Geom_Surface) & s, double u1, double u2, double v1,
                         double v2) {
  const double tol = Precision::PConfusion();
  return s->IsUPeriodic() && s->IsVPeriodic() && u2 - u1 >= s->UPeriod() - tol &&
         v2 - v1 >= s->VPeriod() - tol;
}

// The box on `bs` (all of `s`, converted to a doubly periodic B-spline) whose sides are the face's
// seams: u1 and v1 of `s` may be anywhere around it (Part's Torus starts v at pi), and the
// conversion's parameters are not the angles between its knots.
void seams_on(const Handle(Geom_Surface) & s, const Handle(Geom_BSplineSurface) & bs, double& u1,
              double& u2, double& v1, double& v2) {
  GeomAPI_ProjectPointOnSurf foot(s->Value(u1, v1), bs);
  if (!foot.IsDone() || foot.NbPoints() == 0 || !bs->IsUPeriodic() || !bs->IsVPeriodic())
    throw GeometryError("face: its seams could not be found on its converted surface");
  foot.LowerDistanceParameters(u1, v1);
  u2 = u1 + bs->UPeriod();
  v2 = v1 + bs->VPeriod();
}

}  // namespace

Handle(Geom_BSplineSurface) to_geom(const BSplineSurface& surface) {
  surface.validate();
  const SplineSpace& sp = surface.space;
  check_degree(sp.degree_u, Geom_BSplineSurface::MaxDegree(), "sheet");
  check_degree(sp.degree_v, Geom_BSplineSurface::MaxDegree(), "sheet");
  const OcctKnots ku = to_occt_knots(sp.knots_u, "sheet u knots");
  const OcctKnots kv = to_occt_knots(sp.knots_v, "sheet v knots");
  const int nu = sp.nu(), nv = sp.nv();
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const int k = sp.index(i, j);
      poles(i + 1, j + 1) = gp_Pnt(surface.poles(k, 0), surface.poles(k, 1), surface.poles(k, 2));
      weights(i + 1, j + 1) = sp.rational() ? sp.weights(k) : 1.0;
    }
  }
  return guarded("building a B-spline surface", [&]() -> Handle(Geom_BSplineSurface) {
    if (sp.rational())
      return new Geom_BSplineSurface(poles, weights, ku.values, kv.values, ku.mults, kv.mults,
                                     sp.degree_u, sp.degree_v);
    return new Geom_BSplineSurface(poles, ku.values, kv.values, ku.mults, kv.mults, sp.degree_u,
                                   sp.degree_v);
  });
}

Handle(Geom_BSplineCurve) to_geom_curve(const BSplineCurve& curve) {
  curve.validate("curve");
  if (curve.dim() != 3)
    throw InvalidInput("curve: expected a 3D curve, got dimension " + std::to_string(curve.dim()));
  check_degree(curve.degree, Geom_BSplineCurve::MaxDegree(), "curve");
  const OcctKnots k = to_occt_knots(curve.knots, "curve knots");
  const int n = curve.pole_count();
  TColgp_Array1OfPnt poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i) {
    poles(i + 1) = gp_Pnt(curve.poles(i, 0), curve.poles(i, 1), curve.poles(i, 2));
    weights(i + 1) = curve.rational() ? curve.weights(i) : 1.0;
  }
  return guarded("building a B-spline curve", [&]() -> Handle(Geom_BSplineCurve) {
    if (curve.rational())
      return new Geom_BSplineCurve(poles, weights, k.values, k.mults, curve.degree);
    return new Geom_BSplineCurve(poles, k.values, k.mults, curve.degree);
  });
}

Handle(Geom2d_BSplineCurve) to_geom2d_curve(const BSplineCurve& curve) {
  curve.validate("2D curve");
  if (curve.dim() != 2)
    throw InvalidInput("2D curve: expected a 2D curve, got dimension " +
                       std::to_string(curve.dim()));
  check_degree(curve.degree, Geom2d_BSplineCurve::MaxDegree(), "2D curve");
  const OcctKnots k = to_occt_knots(curve.knots, "2D curve knots");
  const int n = curve.pole_count();
  TColgp_Array1OfPnt2d poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i) {
    poles(i + 1) = gp_Pnt2d(curve.poles(i, 0), curve.poles(i, 1));
    weights(i + 1) = curve.rational() ? curve.weights(i) : 1.0;
  }
  return guarded("building a 2D B-spline curve", [&]() -> Handle(Geom2d_BSplineCurve) {
    if (curve.rational())
      return new Geom2d_BSplineCurve(poles, weights, k.values, k.mults, curve.degree);
    return new Geom2d_BSplineCurve(poles, k.values, k.mults, curve.degree);
  });
}

BSplineSurface from_geom(const Handle(Geom_BSplineSurface) & surface) {
  if (surface.IsNull()) throw InvalidInput("B-spline surface is null");
  BSplineSurface out = guarded("reading a B-spline surface", [&] {
    Handle(Geom_BSplineSurface) s = Handle(Geom_BSplineSurface)::DownCast(surface->Copy());
    make_clamped(s);
    BSplineSurface r;
    r.space.degree_u = s->UDegree();
    r.space.degree_v = s->VDegree();
    r.space.knots_u = from_occt(s->UKnotSequence());
    r.space.knots_v = from_occt(s->VKnotSequence());
    const int nu = s->NbUPoles(), nv = s->NbVPoles();
    const bool rational = s->IsURational() || s->IsVRational();
    r.poles.resize(nu * nv, 3);
    if (rational) r.space.weights.resize(nu * nv);
    for (int i = 1; i <= nu; ++i) {
      for (int j = 1; j <= nv; ++j) {
        const int k = (i - 1) * nv + (j - 1);
        const gp_Pnt& p = s->Pole(i, j);
        r.poles.row(k) << p.X(), p.Y(), p.Z();
        if (rational) r.space.weights(k) = s->Weight(i, j);
      }
    }
    return r;
  });
  out.validate();
  return out;
}

BSplineCurve from_geom(const Handle(Geom_BSplineCurve) & curve) {
  if (curve.IsNull()) throw InvalidInput("B-spline curve is null");
  BSplineCurve out = guarded("reading a B-spline curve", [&] {
    Handle(Geom_BSplineCurve) c = Handle(Geom_BSplineCurve)::DownCast(curve->Copy());
    make_clamped(c);
    BSplineCurve r;
    r.degree = c->Degree();
    r.knots = from_occt(c->KnotSequence());
    const int n = c->NbPoles();
    r.poles.resize(n, 3);
    if (c->IsRational()) r.weights.resize(n);
    for (int i = 1; i <= n; ++i) {
      const gp_Pnt& p = c->Pole(i);
      r.poles.row(i - 1) << p.X(), p.Y(), p.Z();
      if (c->IsRational()) r.weights(i - 1) = c->Weight(i);
    }
    return r;
  });
  out.validate("curve");
  return out;
}

BSplineCurve from_geom(const Handle(Geom2d_BSplineCurve) & curve) {
  if (curve.IsNull()) throw InvalidInput("2D B-spline curve is null");
  BSplineCurve out = guarded("reading a 2D B-spline curve", [&] {
    Handle(Geom2d_BSplineCurve) c = Handle(Geom2d_BSplineCurve)::DownCast(curve->Copy());
    make_clamped(c);
    BSplineCurve r;
    r.degree = c->Degree();
    r.knots = from_occt(c->KnotSequence());
    const int n = c->NbPoles();
    r.poles.resize(n, 2);
    if (c->IsRational()) r.weights.resize(n);
    for (int i = 1; i <= n; ++i) {
      const gp_Pnt2d& p = c->Pole(i);
      r.poles.row(i - 1) << p.X(), p.Y();
      if (c->IsRational()) r.weights(i - 1) = c->Weight(i);
    }
    return r;
  });
  out.validate("2D curve");
  return out;
}

BSplineSurface surface_from_face(const TopoDS_Face& face) {
  if (face.IsNull()) throw InvalidInput("face is null");
  Handle(Geom_BSplineSurface) bs = guarded("reading a face", [&]() -> Handle(Geom_BSplineSurface) {
    TopoDS_Face f = face;
    Handle(Geom_Surface) geom = BRep_Tool::Surface(f);  // placed by the face's location
    if (geom.IsNull()) throw InvalidInput("face has no surface");
    double u1, u2, v1, v2;
    BRepTools::UVBounds(f, u1, u2, v1, v2);
    if (!std::isfinite(u1) || !std::isfinite(u2) || !std::isfinite(v1) || !std::isfinite(v2) ||
        Precision::IsInfinite(u1) || Precision::IsInfinite(u2) || Precision::IsInfinite(v1) ||
        Precision::IsInfinite(v2))
      throw InvalidInput("face is unbounded: give a face with boundary edges");
    if (!(u2 - u1 > Precision::PConfusion()) || !(v2 - v1 > Precision::PConfusion()))
      throw InvalidInput("face is degenerate: its parameter range is empty");

    Handle(Geom_BSplineSurface) basis = bspline_under(geom);
    // GeomConvert's circles are C0 by their knots, which OCCT's Boolean check refuses.
    if (basis.IsNull()) basis = smooth_revolved_surface(geom, u1, u2, v1, v2);
    if (basis.IsNull()) {
      // Only the surface over the face's UV box is needed, not the face: converting the trimmed
      // surface skips BRepBuilderAPI_NurbsConvert's re-projection of every pcurve, which took
      // up to 12 s on a sphere face cut near its pole (found by the OCCT bridge fuzzer). A box
      // over whole periods both ways (a full torus) is the whole surface, and OCCT's trimmed
      // torus conversion refuses it (Standard_DomainError): the untrimmed surface converts to
      // a doubly periodic B-spline, which restrict_to opens at the face's seams.
      const bool whole = covers_both_periods(geom, u1, u2, v1, v2);
      basis = GeomConvert::SurfaceToBSplineSurface(
          whole ? geom : new Geom_RectangularTrimmedSurface(geom, u1, u2, v1, v2));
      if (basis.IsNull()) throw GeometryError("face: conversion to NURBS gave no B-spline surface");
      if (whole)
        seams_on(geom, basis, u1, u2, v1, v2);
      else
        basis->Bounds(u1, u2, v1, v2);
    }
    Handle(Geom_BSplineSurface) s = Handle(Geom_BSplineSurface)::DownCast(basis->Copy());
    restrict_to(s, u1, u2, v1, v2);
    return s;
  });
  BSplineSurface out = from_geom(bs);
  const Eigen::Vector3d extent = out.poles.colwise().maxCoeff() - out.poles.colwise().minCoeff();
  if (!(extent.norm() > Precision::Confusion()))
    throw InvalidInput("face is degenerate: all its poles coincide");
  return out;
}

BSplineCurve curve_from_edge(const TopoDS_Edge& edge) {
  if (edge.IsNull()) throw InvalidInput("edge is null");
  Handle(Geom_BSplineCurve) bc = guarded("reading an edge", [&]() -> Handle(Geom_BSplineCurve) {
    if (BRep_Tool::Degenerated(edge)) throw InvalidInput("edge is degenerated (a point)");
    double first = 0.0, last = 0.0;
    Handle(Geom_Curve) c = BRep_Tool::Curve(edge, first, last);  // placed by the edge's location
    if (c.IsNull()) throw InvalidInput("edge has no 3D curve");
    if (!std::isfinite(first) || !std::isfinite(last) || Precision::IsInfinite(first) ||
        Precision::IsInfinite(last))
      throw InvalidInput("edge is unbounded");
    if (!(last - first > Precision::PConfusion()))
      throw InvalidInput("edge is degenerate: its parameter range is empty");
    GeomAdaptor_Curve adaptor(c, first, last);
    if (!(GCPnts_AbscissaPoint::Length(adaptor, first, last) > Precision::Confusion()))
      throw InvalidInput("edge has zero length");
    // Circles and ellipses as one knot-free rational span (as the faces' arcs): OCCT's default
    // joins quadratic arcs at double knots, and an edge built on such a C0 curve (a Solid's
    // join along a circle) fails its Boolean argument check. Other curves ignore the type.
    Handle(Geom_BSplineCurve) b = GeomConvert::CurveToBSplineCurve(
        new Geom_TrimmedCurve(c, first, last), Convert_QuasiAngular);
    if (b.IsNull()) throw GeometryError("edge: conversion to a B-spline curve failed");
    return b;
  });
  return from_geom(bc);
}

}  // namespace varsurf::occ
