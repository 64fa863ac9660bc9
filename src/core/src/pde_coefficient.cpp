// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/pde_coefficient.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

using Point = Eigen::Vector2d;

// (u, v) in the sheet's domain mapped to [0, 1]^2: Du & Qin's parameters, in which a and the
// blend band are measured.
Point normalized(const SplineSpace& s, double u, double v) {
  return {(u - s.u_first()) / (s.u_last() - s.u_first()),
          (v - s.v_first()) / (s.v_last() - s.v_first())};
}

double segment_distance(const Point& p, const Point& a, const Point& b) {
  const Point d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

// Distance from p to the region's border, positive inside, in normalized parameters.
double signed_distance(const SplineSpace& s, const Region& r, const Point& p) {
  if (!r.is_loop()) {
    const Point lo = normalized(s, r.u0, r.v0), hi = normalized(s, r.u1, r.v1);
    const double inside =
        std::min({p.x() - lo.x(), hi.x() - p.x(), p.y() - lo.y(), hi.y() - p.y()});
    if (inside >= 0.0) return inside;
    const double dx = std::max({lo.x() - p.x(), 0.0, p.x() - hi.x()});
    const double dy = std::max({lo.y() - p.y(), 0.0, p.y() - hi.y()});
    return -std::hypot(dx, dy);
  }
  double dist = std::numeric_limits<double>::infinity();
  bool in = false;
  const size_t n = r.loop.size();
  for (size_t i = 0; i < n; ++i) {
    const Point a = normalized(s, r.loop[i].x(), r.loop[i].y());
    const Point b = normalized(s, r.loop[(i + 1) % n].x(), r.loop[(i + 1) % n].y());
    dist = std::min(dist, segment_distance(p, a, b));
    // Crossing number: the edge straddles p's horizontal line to p's right.
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in ? dist : -dist;
}

// 0 outside the band, 1 inside it, C2 (quintic smoothstep) across it.
double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * t * (10.0 + t * (-15.0 + 6.0 * t));
}

}  // namespace

void PdeCoefficient::validate(const SplineSpace& sheet) const {
  sheet.validate();  // before its domain is read (empty knots have none)
  if (!(std::isfinite(a) && a > 0.0))
    throw InvalidInput("PDE coefficient a = " + std::to_string(a) +
                       " must be a finite number greater than 0");
  if (!(std::isfinite(blend) && blend >= 0.0 && blend <= 0.5))
    throw InvalidInput("PDE coefficient blend " + std::to_string(blend) +
                       " must be in [0, 0.5] (a fraction of the domain)");
  for (size_t k = 0; k < painted.size(); ++k) {
    const std::string what = "painted PDE region " + std::to_string(k);
    if (!(std::isfinite(painted[k].a) && painted[k].a > 0.0))
      throw InvalidInput(what + ": a = " + std::to_string(painted[k].a) +
                         " must be a finite number greater than 0");
    check_region(sheet, painted[k].region, what.c_str());
  }
  if (!has_field()) return;
  field_space.validate();
  if (field_space.rational())
    throw InvalidInput("the PDE coefficient field must be a non-rational B-spline");
  if (field_values.size() != field_space.size())
    throw InvalidInput("the PDE coefficient field has " + std::to_string(field_values.size()) +
                       " values for " + std::to_string(field_space.size()) + " basis functions");
  const double tol = 1e-9 * std::max(sheet.u_last() - sheet.u_first(), 1.0);
  if (field_space.u_first() > sheet.u_first() + tol ||
      field_space.u_last() < sheet.u_last() - tol ||
      field_space.v_first() > sheet.v_first() + tol || field_space.v_last() < sheet.v_last() - tol)
    throw InvalidInput("the PDE coefficient field does not cover the sheet's domain");
  // The basis is non-negative and sums to one: positive values keep a(u, v) positive everywhere.
  for (Eigen::Index k = 0; k < field_values.size(); ++k)
    if (!(std::isfinite(field_values(k)) && field_values(k) > 0.0))
      throw InvalidInput("the PDE coefficient field's value " + std::to_string(k) + " is " +
                         std::to_string(field_values(k)) +
                         ": every value must be a finite number greater than 0");
}

double PdeCoefficient::base_value(double u, double v) const {
  if (!has_field()) return a;
  const double fu = std::clamp(u, field_space.u_first(), field_space.u_last());
  const double fv = std::clamp(v, field_space.v_first(), field_space.v_last());
  const BasisSample s = field_space.basis(fu, fv, 0);
  double out = 0.0;
  for (size_t k = 0; k < s.index.size(); ++k)
    out += s.values(0, static_cast<Eigen::Index>(k)) * field_values(s.index[k]);
  return out;
}

int PdeCoefficient::top_region(const SplineSpace& sheet, double u, double v) const {
  const Point p = normalized(sheet, u, v);
  for (size_t k = painted.size(); k-- > 0;)
    if (signed_distance(sheet, painted[k].region, p) >= 0.0) return static_cast<int>(k);
  return -1;
}

double PdeCoefficient::value(const SplineSpace& sheet, double u, double v) const {
  double out = base_value(u, v);
  if (painted.empty()) return out;
  if (blend == 0.0) {
    const int top = top_region(sheet, u, v);
    return top < 0 ? out : painted[static_cast<size_t>(top)].a;
  }
  const Point p = normalized(sheet, u, v);
  for (const PaintedCoefficient& r : painted)
    out += smoothstep(signed_distance(sheet, r.region, p) / blend + 0.5) * (r.a - out);
  return out;
}

int PdeCoefficient::field_degree() const {
  return has_field() ? std::max(field_space.degree_u, field_space.degree_v) : 0;
}

bool operator==(const PdeCoefficient& x, const PdeCoefficient& y) {
  if (x.a != y.a || x.blend != y.blend || x.plate_form != y.plate_form ||
      x.painted.size() != y.painted.size() || x.has_field() != y.has_field())
    return false;
  for (size_t k = 0; k < x.painted.size(); ++k)
    if (x.painted[k].a != y.painted[k].a || !same_region(x.painted[k].region, y.painted[k].region))
      return false;
  if (!x.has_field()) return true;
  const SplineSpace &s = x.field_space, &t = y.field_space;
  return s.degree_u == t.degree_u && s.degree_v == t.degree_v && s.knots_u == t.knots_u &&
         s.knots_v == t.knots_v && x.field_values == y.field_values;
}

}  // namespace varsurf
