#include "varsurf/occ/point_projection.hpp"

#include <ShapeAnalysis_Surface.hxx>
#include <gp_Pnt.hxx>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

PointOnSheet project_point(const BSplineSurface& sheet, const Eigen::Vector3d& point) {
  if (!point.allFinite()) throw InvalidInput("project_point: the point is not finite");
  sheet.validate();
  return guarded("project_point", [&] {
    Handle(Geom_BSplineSurface) geom = to_geom(sheet);
    ShapeAnalysis_Surface analysis(geom);
    const gp_Pnt p(point.x(), point.y(), point.z());
    const gp_Pnt2d uv = analysis.ValueOfUV(p, 1e-9);
    PointOnSheet out;
    out.u = uv.X();
    out.v = uv.Y();
    out.distance = analysis.Gap();
    return out;
  });
}

}  // namespace varsurf::occ
