// SPDX-License-Identifier: LGPL-2.1-or-later
// Sheets and scenes the OpenCASCADE bridge's tests share: a flat square and a curved bicubic sheet,
// both fitted exactly; a pillow of two domes sewn along the unit circle, with its analytic area and
// volume; faces of primitives and of bare surfaces; random rational surfaces with non-uniform
// knots; temporary file paths.
#pragma once

#include <gtest/gtest.h>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomAbs_SurfaceType.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>
#include <gp_Ax2d.hxx>
#include <gp_Circ2d.hxx>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/shell_builder.hpp"

namespace varsurf::test {

// A sheet over [0, 1]^2 whose image is the square [0, size]^2 in the plane z = height.
inline BSplineSurface plane_sheet(double size, double height = 0.0) {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 2, 2);
  s.poles = test::fit_poles(
      s.space, [&](double u, double v) { return Eigen::Vector3d(size * u, size * v, height); });
  return s;
}

// A curved bicubic sheet over [0, 1]^2 with 3 x 2 spans.
inline BSplineSurface curved_sheet() {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 3, 2);
  s.poles = test::fit_poles(s.space, [](double u, double v) {
    return Eigen::Vector3d(4.0 * u + 0.3 * v * v, 3.0 * v, std::sin(2.0 * u) * std::cos(1.5 * v));
  });
  return s;
}

// ---------------------------------------------------------------------------------------------
// A pillow: two paraboloid domes, the top one waving above the shared rim, sewn into a solid.

inline constexpr double kHalf = 1.2;   // the sheets span [-1.2, 1.2]^2
inline constexpr double kWave = 1e-4;  // the top dome's height over the rim: kWave sin(3 theta)
inline const double kVolume = M_PI;    // twice the integral of 1 - r^2 over the unit disc; the
                                       // wave's term is odd in y and adds nothing
// Two paraboloid caps, without the wave.
inline const double kArea = 2 * M_PI / 6 * (5 * std::sqrt(5.0) - 1);

// z = sign (1 - x^2 - y^2) + wave (3 x^2 y - y^3): bicubic, so exactly a sheet (x = 2.4 u - 1.2).
// On the unit circle the wave term is wave sin(3 theta).
inline BSplineSurface dome(double sign, double wave = 0.0) {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 4, 4);
  s.poles = test::fit_poles(s.space, [sign, wave](double u, double v) {
    const double x = 2 * kHalf * u - kHalf, y = 2 * kHalf * v - kHalf;
    return Eigen::Vector3d(x, y, sign * (1.0 - x * x - y * y) + wave * (3 * x * x * y - y * y * y));
  });
  return s;
}

// The pillow's rim: the unit circle in z = 0 as a B-spline, and its pre-image on a dome (the
// circle of radius 1 / 2.4 about the domain's centre).
struct Rim {
  BSplineCurve curve, preimage;
};
inline Rim unit_circle_rim() {
  Handle(Geom_TrimmedCurve) circle3 = new Geom_TrimmedCurve(
      new Geom_Circle(gp_Ax2(gp::Origin(), gp::DZ(), gp::DX()), 1.0), 0.0, 2 * M_PI);
  Handle(Geom2d_TrimmedCurve) circle2 = new Geom2d_TrimmedCurve(
      new Geom2d_Circle(gp_Circ2d(gp_Ax2d(gp_Pnt2d(0.5, 0.5), gp_Dir2d(1, 0)), 0.5 / kHalf)), 0.0,
      2 * M_PI);
  return {occ::from_geom(GeomConvert::CurveToBSplineCurve(circle3)),
          occ::from_geom(Geom2dConvert::CurveToBSplineCurve(circle2))};
}

// Two domes joined along the unit circle.
inline occ::ShellResult pillow(double wave) {
  const Rim rim = unit_circle_rim();
  return occ::join_sheets(
      {rim.curve}, {{dome(1.0, wave), {0}, {rim.preimage}}, {dome(-1.0, 0.0), {0}, {rim.preimage}}},
      1e-3);
}

// ---------------------------------------------------------------------------------------------
// Faces

// The first face of `shape` whose surface is of `type` and whose middle lies at z >= min_z.
inline TopoDS_Face face_of(const TopoDS_Shape& shape, GeomAbs_SurfaceType type,
                           double min_z = -1e300) {
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face f = TopoDS::Face(ex.Current());
    BRepAdaptor_Surface a(f);
    if (a.GetType() != type) continue;
    const double u = 0.5 * (a.FirstUParameter() + a.LastUParameter());
    const double v = 0.5 * (a.FirstVParameter() + a.LastVParameter());
    if (a.Value(u, v).Z() >= min_z) return f;
  }
  return {};
}

// The face of a whole bounded surface.
inline TopoDS_Face face_of(const Handle(Geom_Surface) & surface) {
  return BRepBuilderAPI_MakeFace(surface, 1e-7);
}

// The primitive's curved (lateral) face: the first face whose surface is not a plane.
inline TopoDS_Face curved_face(const TopoDS_Shape& shape) {
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face face = TopoDS::Face(ex.Current());
    if (GeomAdaptor_Surface(BRep_Tool::Surface(face)).GetType() != GeomAbs_Plane) return face;
  }
  return TopoDS_Face();
}

// ---------------------------------------------------------------------------------------------
// Random surfaces

// A clamped knot vector over [0, length] with random interior knots (non-uniform on purpose).
inline void random_knots(std::mt19937& rng, int poles, int degree, double length,
                         TColStd_Array1OfReal& knots, TColStd_Array1OfInteger& mults) {
  std::uniform_real_distribution<double> inner(0.03, 0.97);
  std::vector<double> k{0.0, 1.0};
  while (static_cast<int>(k.size()) < poles - degree + 1) k.push_back(inner(rng));
  std::sort(k.begin(), k.end());
  knots.Resize(1, static_cast<int>(k.size()), false);
  mults.Resize(1, static_cast<int>(k.size()), false);
  for (int i = 0; i < static_cast<int>(k.size()); ++i) {
    knots(i + 1) = length * k[i];
    mults(i + 1) = i == 0 || i + 1 == static_cast<int>(k.size()) ? degree + 1 : 1;
  }
}

// A rational (weights 0.3 .. 3) surface of the given degree over about 100 x 80 mm with
// non-uniform knots and a bumpy height.
inline Handle(Geom_BSplineSurface)
    random_surface(std::mt19937& rng, int degree, int nu, int nv, double bump = 10.0) {
  std::uniform_real_distribution<double> jitter(-3.0, 3.0), height(-bump, bump), weight(0.3, 3.0);
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      poles(i, j) = gp_Pnt(100.0 * (i - 1) / (nu - 1) + jitter(rng),
                           80.0 * (j - 1) / (nv - 1) + jitter(rng), height(rng));
      weights(i, j) = weight(rng);
    }
  TColStd_Array1OfReal ku(1, 2), kv(1, 2);
  TColStd_Array1OfInteger mu(1, 2), mv(1, 2);
  random_knots(rng, nu, degree, 7.0, ku, mu);
  random_knots(rng, nv, degree, 0.4, kv, mv);
  return new Geom_BSplineSurface(poles, weights, ku, kv, mu, mv, degree, degree);
}

// ---------------------------------------------------------------------------------------------

// A STEP file path of this process in the test's temporary directory.
inline std::string temp_path(const std::string& stem) {
  return ::testing::TempDir() + "varsurf_" + stem + "_" + std::to_string(getpid()) + ".step";
}

}  // namespace varsurf::test
