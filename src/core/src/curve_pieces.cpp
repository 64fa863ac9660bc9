// SPDX-License-Identifier: LGPL-2.1-or-later
#include "curve_pieces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

// Whether a knot line of `knots` (interior ones) lies strictly between lo and hi.
bool line_between(const std::vector<double>& knots, double lo, double hi) {
  const auto it = std::upper_bound(knots.begin() + 1, knots.end() - 1, lo);
  return it != knots.end() - 1 && *it < hi;
}

// Parameters in (a, b) where the pre-image crosses an interior knot line of the sheet (ku, kv:
// its breakpoints): the integrand is a different polynomial on each side.
void add_knot_crossings(const std::vector<double>& ku, const std::vector<double>& kv,
                        const BSplineCurve& pre, double a, double b, std::vector<double>& cuts) {
  // The piece lies in one span of the pre-image, so in the box of that span's poles (positive
  // weights keep a rational span in its poles' hull too). A box that no knot line cuts needs no
  // search: most pieces of a projected edge (62 spans over a 16-span sheet) are such, and sampling
  // each was a third of sampling the curve.
  const int span = find_span(pre.knots, pre.degree, 0.5 * (a + b));
  const auto poles = pre.poles.middleRows(span - pre.degree, pre.degree + 1);
  const Eigen::Vector2d lo = poles.colwise().minCoeff(), hi = poles.colwise().maxCoeff();
  if (!line_between(ku, lo(0), hi(0)) && !line_between(kv, lo(1), hi(1))) return;
  const int m = 4 * (pre.degree + 1);
  Eigen::MatrixXd uv(m + 1, 2);
  for (int i = 0; i <= m; ++i) uv.row(i) = pre.evaluate(a + (b - a) * i / m).transpose();
  auto crossings = [&](int coord, const std::vector<double>& knots) {
    for (size_t k = 1; k + 1 < knots.size(); ++k) {
      const double line = knots[k];
      // A sample exactly on the line between samples on either side of it is a crossing there
      // (an exact pre-image, a straight line's, lands on knot lines at evenly spaced samples; the
      // sign test below skips zeros). A pre-image along the line crosses nothing.
      for (int i = 1; i < m; ++i)
        if (uv(i, coord) == line && (uv(i - 1, coord) - line) * (uv(i + 1, coord) - line) < 0.0)
          cuts.push_back(a + (b - a) * i / m);
      for (int i = 0; i < m; ++i) {
        double f0 = uv(i, coord) - line, f1 = uv(i + 1, coord) - line;
        if (f0 == 0.0 || f0 * f1 >= 0.0) continue;
        double lo = a + (b - a) * i / m, hi = a + (b - a) * (i + 1) / m;
        for (int it = 0; it < 60 && hi - lo > 1e-15 * (1.0 + std::abs(hi)); ++it) {
          const double mid = 0.5 * (lo + hi);
          const double fm = pre.evaluate(mid)(coord) - line;
          if ((fm < 0.0) == (f0 < 0.0)) {
            lo = mid;
            f0 = fm;
          } else {
            hi = mid;
          }
        }
        cuts.push_back(0.5 * (lo + hi));
      }
    }
  };
  crossings(0, ku);
  crossings(1, kv);
}

}  // namespace

// Keeps a pre-image point inside the sheet's domain; tiny overshoot from fitting is clipped, a
// real excursion is an input error.
Eigen::Vector2d clamp_to_domain(const SplineSpace& space, const Eigen::Vector2d& uv, double t) {
  const double tol_u = 1e-7 * (space.u_last() - space.u_first());
  const double tol_v = 1e-7 * (space.v_last() - space.v_first());
  if (!uv.allFinite() || uv(0) < space.u_first() - tol_u || uv(0) > space.u_last() + tol_u ||
      uv(1) < space.v_first() - tol_v || uv(1) > space.v_last() + tol_v) {
    std::ostringstream msg;
    msg << "the curve's pre-image leaves the sheet's parameter domain at t = " << t << " (u, v) = ("
        << uv(0) << ", " << uv(1) << "), domain [" << space.u_first() << ", " << space.u_last()
        << "] x [" << space.v_first() << ", " << space.v_last() << "]";
    throw InvalidInput(msg.str());
  }
  // A pre-image along the boundary has its poles exactly on it, but their sum evaluates an ulp or
  // so inside the upper bound; there, the sample's weights on interior poles would be ~1e-15 and
  // the solve would fit the data's rounding with them, throwing those poles far.
  auto onto = [](double x, double lo, double hi) {
    const double snap = 1e-12 * (hi - lo) + 16.0 * std::numeric_limits<double>::epsilon() *
                                                std::max(std::abs(lo), std::abs(hi));
    x = std::clamp(x, lo, hi);
    return x - lo <= snap ? lo : (hi - x <= snap ? hi : x);
  };
  return {onto(uv(0), space.u_first(), space.u_last()),
          onto(uv(1), space.v_first(), space.v_last())};
}

std::vector<double> curve_pieces(const SplineSpace& space, const BSplineCurve& pre,
                                 const BSplineCurve* other) {
  const double t0 = pre.first(), t1 = pre.last();
  const double tol = 1e-9 * (t1 - t0);
  std::vector<double> cuts = breakpoints(pre.knots, pre.degree);
  if (other != nullptr)
    for (double t : breakpoints(other->knots, other->degree)) cuts.push_back(t);
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> pieces;
  for (double t : cuts) {
    if (t < t0 || t > t1) continue;
    if (pieces.empty() || t - pieces.back() > tol) pieces.push_back(t);
  }
  pieces.front() = t0;
  pieces.back() = t1;
  std::vector<double> all = pieces;
  const std::vector<double> ku = breakpoints(space.knots_u, space.degree_u);
  const std::vector<double> kv = breakpoints(space.knots_v, space.degree_v);
  for (size_t i = 0; i + 1 < pieces.size(); ++i)
    add_knot_crossings(ku, kv, pre, pieces[i], pieces[i + 1], all);
  std::sort(all.begin(), all.end());
  pieces.clear();
  for (double t : all)
    if (pieces.empty() || t - pieces.back() > tol) pieces.push_back(t);
  pieces.back() = t1;
  return pieces;
}

int gauss_points_along(const SplineSpace& space, const BSplineCurve& pre) {
  const int extra = (space.rational() || pre.rational()) ? 2 : 0;
  return std::min(40, (space.degree_u + space.degree_v) * pre.degree + 1 + extra);
}

std::vector<int> gauss_points_per_piece(const SplineSpace& space, const BSplineCurve& pre,
                                        const std::vector<double>& pieces) {
  // A curve through many short pieces (a projected edge has as many spans as the edge: 62 for an
  // interpolation of 65 points) is nearly straight on each of them, and the exact count for a
  // cubic pre-image, 19 points a piece, made 13 300 samples for benchmark 2's 10 curves on a
  // 19 x 19 sheet: half of the solve was assembling them. Their pieces leave the chord by up to
  // 2.4e-4 of a span (the parametrization's non-uniformity counts too); with straight counts up to
  // 1e-3 there, the samples fell from 13 300 to 4 900 and the default-tolerance sheets' poles moved
  // 1e-8 mm.
  constexpr double kStraightPiece = 1e-3;
  const int full = gauss_points_along(space, pre);
  std::vector<int> out(pieces.size() > 0 ? pieces.size() - 1 : 0, full);
  if (space.rational() || pre.rational() || pre.degree <= 1) return out;
  const auto shortest = [](const std::vector<double>& b) {
    double h = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i + 1 < b.size(); ++i) h = std::min(h, b[i + 1] - b[i]);
    return h;
  };
  const double hu = shortest(breakpoints(space.knots_u, space.degree_u));
  const double hv = shortest(breakpoints(space.knots_v, space.degree_v));
  const int straight = space.degree_u + space.degree_v + 1;
  // The pre-image's distance from the chord is a polynomial of degree <= k vanishing at both ends:
  // 2k interior samples bound it closely (its largest value within a few per cent).
  const int checks = 2 * pre.degree;
  for (size_t i = 0; i < out.size(); ++i) {
    const double a = pieces[i], b = pieces[i + 1];
    const Eigen::Vector2d ca = pre.evaluate(a), cb = pre.evaluate(b);
    double bent = 0.0;
    for (int j = 1; j <= checks; ++j) {
      const double s = static_cast<double>(j) / (checks + 1);
      const Eigen::Vector2d off = pre.evaluate(a + s * (b - a)) - ((1.0 - s) * ca + s * cb);
      bent = std::max({bent, std::abs(off(0)) / hu, std::abs(off(1)) / hv});
    }
    if (bent <= kStraightPiece) out[i] = straight;
  }
  return out;
}

}  // namespace varsurf
