#include "varsurf/occ/normal_field.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRep_Tool.hxx>
#include <Eigen/Geometry>
#include <GeomAPI_PointsToBSpline.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopAbs_Orientation.hxx>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

BSplineCurve normal_field(const TopoDS_Face& reference, const BSplineCurve& curve, double angle_deg,
                          double max_distance, int samples) {
  curve.validate("ribbon curve");
  if (curve.dim() != 3) throw InvalidInput("ribbon curve must be 3D");
  if (reference.IsNull()) throw InvalidInput("ribbon: the reference face is null");
  if (!std::isfinite(angle_deg) || !(max_distance > 0.0))
    throw InvalidInput("ribbon: angle must be finite and the distance tolerance positive");
  const int spans = static_cast<int>(breakpoints(curve.knots, curve.degree).size()) - 1;
  const int n = samples > 0 ? samples : std::max(32, 8 * spans);
  if (n < 4 || n > 100000) throw InvalidInput("ribbon: samples must be in 4..100000");
  return guarded("normal_field", [&] {
    Handle(Geom_Surface) surface = BRep_Tool::Surface(reference);
    if (surface.IsNull()) throw InvalidInput("ribbon: the reference face has no surface");
    ShapeAnalysis_Surface analysis(surface);
    BRepAdaptor_Surface adaptor(reference);
    const bool reversed = reference.Orientation() == TopAbs_REVERSED;
    const double angle = angle_deg * M_PI / 180.0;
    TColgp_Array1OfPnt normals(1, n);
    TColStd_Array1OfReal params(1, n);
    const double t0 = curve.first(), t1 = curve.last();
    for (int k = 0; k < n; ++k) {
      const double t = t0 + (t1 - t0) * k / (n - 1);
      const Eigen::MatrixXd d = curve.derivatives(t, 1);
      const gp_Pnt p(d(0, 0), d(0, 1), d(0, 2));
      const gp_Pnt2d uv = analysis.ValueOfUV(p, 1e-9);
      if (analysis.Gap() > max_distance)
        throw InvalidInput("ribbon: the curve passes " + std::to_string(analysis.Gap()) +
                           " from its reference face (at t = " + std::to_string(t) + ")");
      BRepLProp_SLProps props(adaptor, uv.X(), uv.Y(), 1, 1e-9);
      if (!props.IsNormalDefined())
        throw InvalidInput("ribbon: the reference face has no normal at t = " + std::to_string(t));
      gp_Dir normal = props.Normal();
      if (reversed) normal.Reverse();
      Eigen::Vector3d nv(normal.X(), normal.Y(), normal.Z());
      const Eigen::Vector3d tangent = d.row(1).transpose();
      if (angle != 0.0) {
        if (!(tangent.norm() > 0.0)) throw InvalidInput("ribbon: the curve has a zero tangent");
        nv = Eigen::AngleAxisd(angle, tangent.normalized()) * nv;
      }
      normals.SetValue(k + 1, gp_Pnt(nv.x(), nv.y(), nv.z()));
      params.SetValue(k + 1, t);
    }
    GeomAPI_PointsToBSpline fit(normals, params, 3, 3, GeomAbs_C2, 1e-7);
    if (!fit.IsDone()) throw GeometryError("ribbon: fitting the normal field failed");
    return from_geom(fit.Curve());
  });
}

}  // namespace varsurf::occ
