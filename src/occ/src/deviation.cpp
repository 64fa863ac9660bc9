#include "varsurf/occ/deviation.hpp"

#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

double max_deviation(const BSplineSurface& surface, const BSplineCurve& target, int samples) {
  surface.validate();
  target.validate("target curve");
  if (target.dim() != 3) throw InvalidInput("target curve must be a 3D curve");
  if (samples < 2 || samples > 10000000)
    throw InvalidInput("max_deviation needs between 2 and 10^7 samples");
  const Handle(Geom_BSplineSurface) geom = to_geom(surface);
  return guarded("measuring the deviation", [&] {
    double u1, u2, v1, v2;
    geom->Bounds(u1, u2, v1, v2);
    GeomAPI_ProjectPointOnSurf on_surface;
    on_surface.Init(geom, u1, u2, v1, v2);
    // Interior extrema miss points whose closest sheet point is on the boundary.
    std::array<GeomAPI_ProjectPointOnCurve, 4> on_boundary;
    on_boundary[0].Init(geom->UIso(u1), v1, v2);
    on_boundary[1].Init(geom->UIso(u2), v1, v2);
    on_boundary[2].Init(geom->VIso(v1), u1, u2);
    on_boundary[3].Init(geom->VIso(v2), u1, u2);
    const std::array<gp_Pnt, 4> corners = {geom->Value(u1, v1), geom->Value(u1, v2),
                                           geom->Value(u2, v1), geom->Value(u2, v2)};
    double worst = 0.0;
    const double t0 = target.first(), t1 = target.last();
    for (int i = 0; i < samples; ++i) {
      const double t = i == samples - 1 ? t1 : t0 + (t1 - t0) * i / (samples - 1);
      const Eigen::VectorXd p = target.evaluate(t);
      const gp_Pnt point(p(0), p(1), p(2));
      double best = std::numeric_limits<double>::infinity();
      on_surface.Perform(point);
      if (on_surface.NbPoints() > 0) best = on_surface.LowerDistance();
      for (GeomAPI_ProjectPointOnCurve& b : on_boundary) {
        b.Perform(point);
        if (b.NbPoints() > 0) best = std::min(best, b.LowerDistance());
      }
      for (const gp_Pnt& c : corners) best = std::min(best, c.Distance(point));
      worst = std::max(worst, best);
    }
    return worst;
  });
}

}  // namespace varsurf::occ
