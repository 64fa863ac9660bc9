// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/normal_field.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRep_Tool.hxx>
#include <Eigen/Geometry>
#include <GeomAPI_PointsToBSpline.hxx>
#include <ShapeAnalysis_Curve.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopAbs_Orientation.hxx>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

// Samples normal(t, point, tangent) along the curve, turns each by the angle about the tangent
// and fits the samples by a cubic B-spline at their own parameters.
template <class F>
BSplineCurve sample_field(const BSplineCurve& curve, double angle_deg, int samples, F&& normal) {
  curve.validate("ribbon curve");
  if (curve.dim() != 3) throw InvalidInput("ribbon curve must be 3D");
  if (!std::isfinite(angle_deg)) throw InvalidInput("ribbon: the angle must be finite");
  const int spans = static_cast<int>(breakpoints(curve.knots, curve.degree).size()) - 1;
  const int n = samples > 0 ? samples : std::max(32, 8 * spans);
  if (n < 4 || n > 100000) throw InvalidInput("ribbon: samples must be in 4..100000");
  const double angle = angle_deg * M_PI / 180.0;
  TColgp_Array1OfPnt normals(1, n);
  TColStd_Array1OfReal params(1, n);
  const double t0 = curve.first(), t1 = curve.last();
  for (int k = 0; k < n; ++k) {
    const double t = t0 + (t1 - t0) * k / (n - 1);
    const Eigen::MatrixXd d = curve.derivatives(t, 1);
    const Eigen::Vector3d point = d.row(0).transpose(), tangent = d.row(1).transpose();
    if (!(tangent.norm() > 0.0))
      throw InvalidInput("ribbon: the curve has a zero tangent at t = " + std::to_string(t));
    Eigen::Vector3d nv = normal(t, point, tangent);
    if (angle != 0.0) nv = Eigen::AngleAxisd(angle, tangent.normalized()) * nv;
    normals.SetValue(k + 1, gp_Pnt(nv.x(), nv.y(), nv.z()));
    params.SetValue(k + 1, t);
  }
  GeomAPI_PointsToBSpline fit(normals, params, 3, 3, GeomAbs_C2, 1e-7);
  if (!fit.IsDone()) throw GeometryError("ribbon: fitting the normal field failed");
  return from_geom(fit.Curve());
}

// In mm, as the user measures the scene, with what to do about it.
std::string off_face(double gap, double t) {
  std::ostringstream msg;
  msg << std::setprecision(4) << "ribbon: the curve passes " << gap
      << " mm from its reference face (at t = " << t
      << "): draw the curve on that face, or pick the face it lies on";
  return msg.str();
}

}  // namespace

BSplineCurve normal_field(const TopoDS_Face& reference, const BSplineCurve& curve, double angle_deg,
                          double max_distance, int samples) {
  if (reference.IsNull()) throw InvalidInput("ribbon: the reference face is null");
  if (!(max_distance > 0.0)) throw InvalidInput("ribbon: the distance tolerance must be positive");
  return guarded("normal_field", [&] {
    Handle(Geom_Surface) surface = BRep_Tool::Surface(reference);
    if (surface.IsNull()) throw InvalidInput("ribbon: the reference face has no surface");
    ShapeAnalysis_Surface analysis(surface);
    BRepAdaptor_Surface adaptor(reference);
    const bool reversed = reference.Orientation() == TopAbs_REVERSED;
    return sample_field(
        curve, angle_deg, samples, [&](double t, const Eigen::Vector3d& p, const Eigen::Vector3d&) {
          const gp_Pnt2d uv = analysis.ValueOfUV(gp_Pnt(p.x(), p.y(), p.z()), 1e-9);
          if (analysis.Gap() > max_distance) throw InvalidInput(off_face(analysis.Gap(), t));
          BRepLProp_SLProps props(adaptor, uv.X(), uv.Y(), 1, 1e-9);
          if (!props.IsNormalDefined())
            throw InvalidInput(
                "ribbon: the reference face has no normal at t = " + std::to_string(t) +
                " (a cone's apex, a collapsed edge): pick a face "
                "that is smooth along the curve");
          gp_Dir normal = props.Normal();
          if (reversed) normal.Reverse();
          return Eigen::Vector3d(normal.X(), normal.Y(), normal.Z());
        });
  });
}

BSplineCurve normal_field_between(const BSplineCurve& curve, const BSplineCurve& second,
                                  double angle_deg, int samples) {
  // Checked before the scale below is taken from its poles (an empty matrix has no maximum).
  curve.validate("ribbon curve");
  if (curve.dim() != 3) throw InvalidInput("ribbon curve must be 3D");
  second.validate("ribbon's second curve");
  if (second.dim() != 3) throw InvalidInput("ribbon's second curve must be 3D");
  return guarded("normal_field_between", [&] {
    Handle(Geom_Curve) other = to_geom_curve(second);
    const double scale = std::max(1.0, curve.poles.cwiseAbs().maxCoeff());
    return sample_field(
        curve, angle_deg, samples,
        [&](double t, const Eigen::Vector3d& p, const Eigen::Vector3d& tangent) {
          gp_Pnt q;
          double s = 0.0;
          ShapeAnalysis_Curve().Project(other, gp_Pnt(p.x(), p.y(), p.z()), 1e-9, q, s,
                                        second.first(), second.last(), false);
          const Eigen::Vector3d across = Eigen::Vector3d(q.X(), q.Y(), q.Z()) - p;
          const Eigen::Vector3d n = tangent.normalized().cross(across);
          if (!(n.norm() > 1e-9 * scale))
            throw InvalidInput(
                "ribbon: the second curve touches the curve or lies along its tangent "
                "at t = " +
                std::to_string(t));
          return Eigen::Vector3d(n.normalized());
        });
  });
}

}  // namespace varsurf::occ
