#include "varsurf/occ/deviation.hpp"

#include <Extrema_GenLocateExtPS.hxx>
#include <Extrema_POnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <ShapeAnalysis_Surface.hxx>

#include <algorithm>
#include <cmath>

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
    // Newton on the normal projection from the last closest point (Extrema_GenLocateExtPS), with
    // ShapeAnalysis_Surface's global search (which also finds boundary points) for the first
    // sample and wherever Newton fails or does worse than the step between samples allows.
    // Measured per curve of 200 samples: 20 ms with a global extremum search and boundary
    // projections per sample, 13 ms marching with ShapeAnalysis_Surface::NextValueOfUV, 24 ms with
    // the distance criterion, about 1 ms this way.
    ShapeAnalysis_Surface analysis(geom);
    GeomAdaptor_Surface adaptor(geom);
    Extrema_GenLocateExtPS locate(adaptor, 1e-12, 1e-12);
    double worst = 0.0, last_gap = 0.0;
    gp_Pnt2d uv;
    gp_Pnt previous;
    const double t0 = target.first(), t1 = target.last();
    for (int i = 0; i < samples; ++i) {
      const double t = i == samples - 1 ? t1 : t0 + (t1 - t0) * i / (samples - 1);
      const Eigen::VectorXd p = target.evaluate(t);
      const gp_Pnt point(p(0), p(1), p(2));
      const double step = i > 0 ? point.Distance(previous) : 0.0;
      previous = point;
      double gap = 0.0;
      bool local = false;
      if (i > 0) {
        locate.Perform(point, uv.X(), uv.Y(), Standard_False);
        if (locate.IsDone()) {
          gap = std::sqrt(locate.SquareDistance());
          double u = 0.0, v = 0.0;
          locate.Point().Parameter(u, v);
          // The closest distance moves by at most the step between samples.
          local = gap <= last_gap + step + 1e-12;
          if (local) uv = gp_Pnt2d(u, v);
        }
      }
      if (!local) {
        uv = analysis.ValueOfUV(point, 1e-11);
        gap = analysis.Gap();
      }
      last_gap = gap;
      worst = std::max(worst, gap);
    }
    return worst;
  });
}

}  // namespace varsurf::occ
