// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/point_projection.hpp"

#include <ShapeAnalysis_Surface.hxx>
#include <gp_Pnt.hxx>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/sheet_domain.hpp"

namespace varsurf::occ {

PointOnSheet project_point(const BSplineSurface& sheet, const Eigen::Vector3d& point) {
  if (!point.allFinite()) throw InvalidInput("project_point: the point is not finite");
  sheet.validate();
  return guarded("project_point", [&] {
    Handle(Geom_BSplineSurface) geom = to_geom(sheet);
    ShapeAnalysis_Surface analysis(geom);
    const gp_Pnt p(point.x(), point.y(), point.z());
    const gp_Pnt2d found = analysis.ValueOfUV(p, 1e-9);
    // A point on the boundary (a corner vertex, a point on a boundary edge) is placed exactly on
    // it, so that a constraint there weighs only the boundary poles (see SheetDomain).
    const Eigen::Vector2d uv = SheetDomain(sheet).snapped({found.X(), found.Y()});
    PointOnSheet out;
    out.u = uv(0);
    out.v = uv(1);
    out.distance = (sheet.evaluate(uv(0), uv(1)) - point).norm();
    return out;
  });
}

}  // namespace varsurf::occ
