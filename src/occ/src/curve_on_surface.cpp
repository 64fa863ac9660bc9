// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/curve_on_surface.hpp"

#include <BRepLib_CheckCurveOnSurface.hxx>
#include <algorithm>

namespace varsurf::occ {

double curve_on_surface_deviation(const TopoDS_Edge& edge, const TopoDS_Face& face) {
  BRepLib_CheckCurveOnSurface check(edge, face);
  check.Perform();
  return check.IsDone() ? check.MaxDistance() : -1.0;
}

double curve_on_surface_deviation(const TopoDS_Edge& edge, const std::vector<TopoDS_Face>& faces) {
  double worst = 0.0;
  for (const TopoDS_Face& face : faces)
    worst = std::max(worst, curve_on_surface_deviation(edge, face));
  return worst;
}

}  // namespace varsurf::occ
