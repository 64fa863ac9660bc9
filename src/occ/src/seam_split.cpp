// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/seam_split.hpp"

#include <Geom_BSplineCurve.hxx>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/spline_space.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/point_projection.hpp"
#include "varsurf/occ/sheet_domain.hpp"

namespace varsurf::occ {

namespace {

// Which half of closed direction c the curve's foot at t is in (0: lower, 1: upper).
int half(const BSplineSurface& sheet, const SheetDomain& domain, const BSplineCurve& curve,
         double t, int c) {
  const PointOnSheet foot = project_point(sheet, curve.evaluate(t).head<3>());
  const double x = c == 0 ? foot.u : foot.v;
  return x - domain.lo()(c) > 0.5 * domain.width()(c) ? 1 : 0;
}

// The parameter in [a, b] where the foot passes from one half to the other: across the seam
// when the two halves meet there, found by bisection.
double crossing(const BSplineSurface& sheet, const SheetDomain& domain, const BSplineCurve& curve,
                double a, double b, int c) {
  const int start = half(sheet, domain, curve, a, c);
  const double resolution = 1e-12 * (curve.last() - curve.first());
  while (b - a > resolution) {
    const double m = 0.5 * (a + b);
    (half(sheet, domain, curve, m, c) == start ? a : b) = m;
  }
  return 0.5 * (a + b);
}

// The crossing to rounding: bisection on OCCT's feet (good to ~1e-8 of the range) leaves a piece
// that starts that far beside the seam, whose projection then jumps across it at once. Newton on
// (t, s), s along the seam: the curve point's offset from the seam point is normal to the sheet
// there (orthogonal to S_along and S_across), from the bisected t and its foot. Returns `t` when
// it does not converge inside [a, b].
double polished(const BSplineSurface& sheet, const SheetDomain& domain, const BSplineCurve& curve,
                double a, double b, double t, int c) {
  const PointOnSheet foot = project_point(sheet, curve.evaluate(t).head<3>());
  const double seam = domain.lo()(c);
  double s = c == 0 ? foot.v : foot.u, x = t;
  // Rows of evaluate_surface: S, S_u, S_v, S_uu, S_uv, S_vv; `across` is the closed direction.
  const int across = c == 0 ? 1 : 2, along = c == 0 ? 2 : 1, along2 = c == 0 ? 5 : 3;
  for (int it = 0; it < 30; ++it) {
    const Eigen::MatrixXd w = c == 0 ? evaluate_surface(sheet.space, sheet.poles, seam, s, 2)
                                     : evaluate_surface(sheet.space, sheet.poles, s, seam, 2);
    const Eigen::MatrixXd d = curve.derivatives(x, 1);
    const Eigen::Vector3d r = d.row(0).head<3>().transpose() - w.row(0).transpose();
    const Eigen::Vector3d dc = d.row(1).head<3>().transpose();
    const Eigen::Vector3d sa = w.row(across).transpose(), sl = w.row(along).transpose();
    const Eigen::Vector3d sal = w.row(4).transpose(), sll = w.row(along2).transpose();
    Eigen::Vector2d f(r.dot(sa), r.dot(sl));
    Eigen::Matrix2d j;
    j << dc.dot(sa), -sl.dot(sa) + r.dot(sal), dc.dot(sl), -sl.dot(sl) + r.dot(sll);
    if (!(std::abs(j.determinant()) > 0.0)) return t;
    const Eigen::Vector2d step = j.inverse() * f;
    x -= step(0);
    s -= step(1);
    if (!(x >= a && x <= b) || !std::isfinite(s)) return t;
    if (std::abs(step(0)) <= 1e-15 * (curve.last() - curve.first())) return x;
  }
  return t;
}

}  // namespace

std::vector<BSplineCurve> split_at_seams(const BSplineSurface& sheet, const BSplineCurve& curve,
                                         int samples) {
  sheet.validate();
  curve.validate("curve");
  if (curve.dim() != 3) throw InvalidInput("split_at_seams: expected a 3D curve");
  if (samples < 0 || samples > 100000)
    throw InvalidInput("split_at_seams takes 0 to 100,000 samples");
  const SheetDomain domain(sheet);
  if (samples == 0) samples = std::max(64, 8 * curve.pole_count());
  std::vector<double> cuts;
  const double t0 = curve.first(), t1 = curve.last();
  for (int c = 0; c < 2; ++c) {
    if (!domain.closed(c)) continue;
    const double lo = domain.lo()(c), hi = domain.hi()(c), quarter = 0.25 * domain.width()(c);
    const double on_seam = SheetDomain::snap_margin * domain.width()(c);
    bool seen = false;
    double previous_t = t0, previous = 0.0;
    for (int k = 0; k <= samples; ++k) {
      const double t = t0 + (t1 - t0) * k / samples;
      const PointOnSheet foot = project_point(sheet, curve.evaluate(t).head<3>());
      const double x = c == 0 ? foot.u : foot.v;
      // A foot on the seam is on both sides (a curve along the seam, or one touching it): only
      // feet off it tell a crossing.
      if (std::min(x - lo, hi - x) <= on_seam) continue;
      // A jump by more than half the range between neighbouring feet is the seam (the curve
      // cannot run that far along the sheet between them); both within a quarter of an end, so
      // a steep run across the middle is not taken for one.
      const bool near_ends =
          std::min(previous - lo, hi - previous) < quarter && std::min(x - lo, hi - x) < quarter;
      if (seen && near_ends && std::abs(x - previous) > 2.0 * quarter) {
        const double t_cut = polished(sheet, domain, curve, previous_t, t,
                                      crossing(sheet, domain, curve, previous_t, t, c), c);
        // A crossing at an end of the curve is its start or end on the seam: nothing to cut.
        const double margin = 1e-9 * (t1 - t0);
        if (t_cut - t0 > margin && t1 - t_cut > margin) cuts.push_back(t_cut);
      }
      seen = true;
      previous_t = t;
      previous = x;
    }
  }
  std::sort(cuts.begin(), cuts.end());
  if (cuts.empty()) return {curve};
  std::vector<double> ends{t0};
  ends.insert(ends.end(), cuts.begin(), cuts.end());
  ends.push_back(t1);
  return guarded("splitting a curve at a seam", [&] {
    std::vector<BSplineCurve> pieces;
    for (size_t i = 0; i + 1 < ends.size(); ++i) {
      Handle(Geom_BSplineCurve) piece = to_geom_curve(curve);
      piece->Segment(ends[i], ends[i + 1]);
      pieces.push_back(from_geom(piece));
    }
    return pieces;
  });
}

}  // namespace varsurf::occ
