// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/revolved_surface.hpp"

#include <Geom2dConvert.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Ax22d.hxx>

#include <algorithm>
#include <cmath>

namespace varsurf::occ {

namespace {

// The arc [a1, a2] of the circle of `centre` and `radius` as an exact rational B-spline whose
// parameter is the angle at both ends. Of OCCT's exact parametrizations, TgtThetaOver2 is C0 by
// its knots; RationalC1 (degree 4, C1 knots every quarter turn) and QuasiAngular (degree 6, no
// interior knot) both pass the check. QuasiAngular is kept: its parameter is the angle to 3e-3
// rad over a whole turn (speed within 1.5 %, RationalC1: 11 %), so nothing creases a solved sheet
// and the pre-image of a circle around a cylinder fits with fewer poles (RationalC1 took 69 poles
// for an arc that now needs under 60); the price is degree 6 along the arc.
// The conversion of a trimmed periodic circle may report its parameters a period away (an arc
// from -pi/2 starts at 3 pi/2): its knots are shifted back.
Handle(Geom2d_BSplineCurve) arc(const gp_Pnt2d& centre, double radius, double a1, double a2) {
  Handle(Geom2d_Circle) circle = new Geom2d_Circle(gp_Ax22d(centre, gp_Dir2d(1.0, 0.0)), radius);
  Handle(Geom2d_BSplineCurve) b = Geom2dConvert::CurveToBSplineCurve(
      new Geom2d_TrimmedCurve(circle, a1, a2), Convert_QuasiAngular);
  if (b.IsNull() || b->IsPeriodic()) return nullptr;
  const double shift = a1 - b->FirstParameter();
  if (std::abs(shift) > 0.0) {
    TColStd_Array1OfReal knots(1, b->NbKnots());
    b->Knots(knots);
    for (int i = knots.Lower(); i <= knots.Upper(); ++i) knots(i) += shift;
    b->SetKnots(knots);
  }
  return b;
}

// The segment from (r1, z1) to (r2, z2) over [v1, v2].
Handle(Geom2d_BSplineCurve)
    segment(double r1, double z1, double r2, double z2, double v1, double v2) {
  TColgp_Array1OfPnt2d poles(1, 2);
  poles(1) = gp_Pnt2d(r1, z1);
  poles(2) = gp_Pnt2d(r2, z2);
  TColStd_Array1OfReal knots(1, 2);
  knots(1) = v1;
  knots(2) = v2;
  TColStd_Array1OfInteger mults(1, 2);
  mults.Init(2);
  return new Geom2d_BSplineCurve(poles, knots, mults, 1);
}

// A curve turned about the frame's z axis, (cos u, sin u) = `turn`: the profile's poles in the
// frame (x, y, z) turned by the arc's (cos, sin) poles, with weights w_i * w_j. Both curves are
// rational, and the turned point is bilinear in their homogeneous coordinates, so the tensor
// product is exact.
Handle(Geom_BSplineSurface)
    revolve_curve(const gp_Ax3& frame, const Handle(Geom2d_BSplineCurve) & turn,
                  const Handle(Geom_BSplineCurve) & profile) {
  if (turn.IsNull() || profile.IsNull()) return nullptr;
  const gp_XYZ o = frame.Location().XYZ(), x = frame.XDirection().XYZ(),
               y = frame.YDirection().XYZ(), z = frame.Direction().XYZ();
  const int nu = turn->NbPoles(), nv = profile->NbPoles();
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i) {
    const gp_Pnt2d c = turn->Pole(i);
    for (int j = 1; j <= nv; ++j) {
      const gp_XYZ d = profile->Pole(j).XYZ() - o;
      const double px = d.Dot(x), py = d.Dot(y), pz = d.Dot(z);
      poles(i, j) =
          gp_Pnt(o + (c.X() * px - c.Y() * py) * x + (c.Y() * px + c.X() * py) * y + pz * z);
      weights(i, j) = turn->Weight(i) * profile->Weight(j);
    }
  }
  TColStd_Array1OfReal ku(1, turn->NbKnots()), kv(1, profile->NbKnots());
  TColStd_Array1OfInteger mu(1, turn->NbKnots()), mv(1, profile->NbKnots());
  turn->Knots(ku);
  turn->Multiplicities(mu);
  profile->Knots(kv);
  profile->Multiplicities(mv);
  return new Geom_BSplineSurface(poles, weights, ku, kv, mu, mv, turn->Degree(), profile->Degree());
}

// O + R(v) (cos u X + sin u Y) + Z(v) Zdir, the form every elementary surface of revolution has
// in its own frame (ElSLib): the (R, Z) profile is the curve in the frame's xz plane, turned.
Handle(Geom_BSplineSurface) revolve(const gp_Ax3& frame, const Handle(Geom2d_BSplineCurve) & turn,
                                    const Handle(Geom2d_BSplineCurve) & profile) {
  if (profile.IsNull()) return nullptr;
  const gp_XYZ o = frame.Location().XYZ(), x = frame.XDirection().XYZ(),
               z = frame.Direction().XYZ();
  TColgp_Array1OfPnt poles(1, profile->NbPoles());
  TColStd_Array1OfReal weights(1, profile->NbPoles());
  for (int j = 1; j <= profile->NbPoles(); ++j) {
    poles(j) = gp_Pnt(o + profile->Pole(j).X() * x + profile->Pole(j).Y() * z);
    weights(j) = profile->Weight(j);
  }
  TColStd_Array1OfReal knots(1, profile->NbKnots());
  TColStd_Array1OfInteger mults(1, profile->NbKnots());
  profile->Knots(knots);
  profile->Multiplicities(mults);
  return revolve_curve(frame, turn,
                       new Geom_BSplineCurve(poles, weights, knots, mults, profile->Degree()));
}

// The basis curve of a surface of revolution over [v1, v2] as a B-spline with the curve's own
// parameter (B-splines, Béziers and lines keep it), else null: a conic's conversion would
// change it, and the face's pcurves would no longer fit.
Handle(Geom_BSplineCurve)
    profile_of(const Handle(Geom_SurfaceOfRevolution) & s, double v1, double v2) {
  const Handle(Geom_Curve) basis = s->BasisCurve();
  const Handle(Geom_BSplineCurve) b =
      GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(basis, v1, v2));
  if (b.IsNull() || b->IsPeriodic()) return nullptr;
  const double tol = Precision::PConfusion();
  if (std::abs(b->FirstParameter() - v1) > tol || std::abs(b->LastParameter() - v2) > tol)
    return nullptr;
  for (int k = 0; k <= 7; ++k) {  // not symmetric: a conic's conversion keeps its midpoint
    const double t = v1 + (v2 - v1) * k / 7;
    if (b->Value(t).Distance(basis->Value(t)) > Precision::Confusion()) return nullptr;
  }
  return b;
}

}  // namespace

Handle(Geom_BSplineSurface) smooth_revolved_surface(const Handle(Geom_Surface) & surface, double u1,
                                                    double u2, double v1, double v2) {
  Handle(Geom_Surface) s = surface;
  while (auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(s))
    s = trimmed->BasisSurface();
  const double period = 2.0 * M_PI, tol = Precision::PConfusion();
  if (s.IsNull() || !(u2 - u1 > tol) || !(v2 - v1 > tol) || u2 - u1 > period + tol) return nullptr;
  u2 = std::min(u2, u1 + period);
  const gp_Pnt2d origin(0.0, 0.0);
  if (auto cyl = Handle(Geom_CylindricalSurface)::DownCast(s)) {
    const double r = cyl->Radius();
    return revolve(cyl->Position(), arc(origin, 1.0, u1, u2), segment(r, v1, r, v2, v1, v2));
  }
  if (auto cone = Handle(Geom_ConicalSurface)::DownCast(s)) {
    const double r = cone->RefRadius(), a = cone->SemiAngle();
    auto radius = [&](double v) { return r + v * std::sin(a); };
    return revolve(cone->Position(), arc(origin, 1.0, u1, u2),
                   segment(radius(v1), v1 * std::cos(a), radius(v2), v2 * std::cos(a), v1, v2));
  }
  if (auto sphere = Handle(Geom_SphericalSurface)::DownCast(s)) {
    if (v1 < -0.5 * M_PI - tol || v2 > 0.5 * M_PI + tol) return nullptr;
    v1 = std::max(v1, -0.5 * M_PI);
    v2 = std::min(v2, 0.5 * M_PI);
    return revolve(sphere->Position(), arc(origin, 1.0, u1, u2),
                   arc(origin, sphere->Radius(), v1, v2));
  }
  if (auto torus = Handle(Geom_ToroidalSurface)::DownCast(s)) {
    if (v2 - v1 > period + tol) return nullptr;
    v2 = std::min(v2, v1 + period);
    return revolve(torus->Position(), arc(origin, 1.0, u1, u2),
                   arc(gp_Pnt2d(torus->MajorRadius(), 0.0), torus->MinorRadius(), v1, v2));
  }
  if (auto rev = Handle(Geom_SurfaceOfRevolution)::DownCast(s)) {
    // A revolved sketch: GeomConvert turns it with quadratic arcs, C0 at their double knots,
    // which OCCT's Boolean check refuses on the sheet built from it.
    const gp_Ax1 axis = rev->Axis();
    return revolve_curve(gp_Ax3(axis.Location(), axis.Direction()), arc(origin, 1.0, u1, u2),
                         profile_of(rev, v1, v2));
  }
  return nullptr;
}

}  // namespace varsurf::occ
