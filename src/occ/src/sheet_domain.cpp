// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/sheet_domain.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "varsurf/core/knot_vector.hpp"

namespace varsurf::occ {

namespace {

// Parameters along direction c at which two boundary curves are compared: each knot span's ends
// and interior points, enough to tell two B-spline curves of the span's degree apart.
std::vector<double> probes(const SplineSpace& space, int c) {
  std::vector<double> values;
  std::vector<int> mults;
  split_knots(c == 0 ? space.knots_u : space.knots_v, values, mults);
  const int per_span = (c == 0 ? space.degree_u : space.degree_v) + 2;
  std::vector<double> out;
  for (size_t k = 0; k + 1 < values.size(); ++k)
    for (int i = 0; i < per_span; ++i)
      out.push_back(values[k] + (values[k + 1] - values[k]) * i / per_span);
  out.push_back(values.back());
  return out;
}

}  // namespace

SheetDomain::SheetDomain(const BSplineSurface& sheet)
    : sheet_(sheet),
      lo_(sheet.space.u_first(), sheet.space.v_first()),
      hi_(sheet.space.u_last(), sheet.space.v_last()),
      scale_(std::max(
          1.0, (sheet.poles.colwise().maxCoeff() - sheet.poles.colwise().minCoeff()).norm())) {
  // Closed in u when the boundary curves u = lo and u = hi coincide (a cylinder's seam).
  for (int c = 0; c < 2; ++c) {
    bool same = true;
    for (double s : probes(sheet.space, 1 - c)) {
      const Eigen::Vector3d a = c == 0 ? sheet.evaluate(lo_(0), s) : sheet.evaluate(s, lo_(1));
      const Eigen::Vector3d b = c == 0 ? sheet.evaluate(hi_(0), s) : sheet.evaluate(s, hi_(1));
      if ((a - b).norm() > 1e-9 * scale_) {
        same = false;
        break;
      }
    }
    closed_[static_cast<size_t>(c)] = same;
  }
  for (int c = 0; c < 2; ++c) {
    for (int side = 0; side < 2; ++side) {
      const double at = side == 0 ? lo_(c) : hi_(c);
      auto point = [&](double s) { return c == 0 ? sheet.evaluate(at, s) : sheet.evaluate(s, at); };
      const Eigen::Vector3d first = point(c == 0 ? lo_(1) : lo_(0));
      bool collapsed = true;
      for (double s : probes(sheet.space, 1 - c))
        collapsed = collapsed && (point(s) - first).norm() <= 1e-9 * scale_;
      degenerate_[static_cast<size_t>(2 * c + side)] = collapsed;
    }
  }
}

int SheetDomain::side(const Eigen::Vector2d& uv, int c) const {
  const double margin = snap_margin * (hi_(c) - lo_(c));
  if (uv(c) <= lo_(c) + margin) return -1;
  if (uv(c) >= hi_(c) - margin) return 1;
  return 0;
}

Eigen::Vector2d SheetDomain::across_seam(const Eigen::Vector2d& uv, int c) const {
  Eigen::Vector2d out = uv;
  out(c) = side(uv, c) < 0 ? hi_(c) : lo_(c);
  return out;
}

Eigen::Vector2d SheetDomain::snapped(const Eigen::Vector2d& uv) const {
  Eigen::Vector2d out = uv.cwiseMax(lo_).cwiseMin(hi_);
  Eigen::Vector2d trial = out;
  for (int c = 0; c < 2; ++c) {
    const int s = side(out, c);
    if (s != 0) trial(c) = s < 0 ? lo_(c) : hi_(c);
  }
  if (trial == out) return out;
  const Eigen::Vector3d before = sheet_.evaluate(out(0), out(1));
  if ((sheet_.evaluate(trial(0), trial(1)) - before).norm() <= 1e-9 * scale_) return trial;
  // Each coordinate on its own (near a corner only one of them may be on its bound).
  for (int c = 0; c < 2; ++c) {
    Eigen::Vector2d one = out;
    one(c) = trial(c);
    if (one != out && (sheet_.evaluate(one(0), one(1)) - before).norm() <= 1e-9 * scale_)
      return one;
  }
  return out;
}

}  // namespace varsurf::occ
