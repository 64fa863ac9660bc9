// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/region.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

using Point = Eigen::Vector2d;
using Polygon = std::vector<Point>;

double cross(const Point& a, const Point& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double signed_area(const Polygon& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

// The loop without repeated consecutive points (and without a repeated first point).
Polygon cleaned(const std::vector<Point>& loop) {
  Polygon out;
  for (const Point& q : loop)
    if (out.empty() || q != out.back()) out.push_back(q);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

// Orientation of c relative to the line a -> b: +1, -1 or 0.
int side(const Point& a, const Point& b, const Point& c) {
  const double s = cross(b - a, c - a);
  return (s > 0.0) - (s < 0.0);
}

bool on_segment(const Point& a, const Point& b, const Point& c) {  // c collinear with a, b
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

bool segments_meet(const Point& a, const Point& b, const Point& c, const Point& d) {
  const int s1 = side(a, b, c), s2 = side(a, b, d), s3 = side(c, d, a), s4 = side(c, d, b);
  // Strictly on both sides of each other: they cross. (Not s1 != s2: on a straight run of the
  // loop, one point exactly on the other's line and the next a rounding off it is no crossing;
  // exact pre-images of straight sketch lines made every such loop "cross itself".)
  if (s1 * s2 < 0 && s3 * s4 < 0) return true;
  return (s1 == 0 && on_segment(a, b, c)) || (s2 == 0 && on_segment(a, b, d)) ||
         (s3 == 0 && on_segment(c, d, a)) || (s4 == 0 && on_segment(c, d, b));
}

bool is_simple(const Polygon& p) {
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // neighbours through the closing edge
      if (segments_meet(p[i], p[i + 1], p[j], p[(j + 1) % n])) return false;
    }
  return true;
}

// Sutherland-Hodgman against the rectangle [u0, u1] x [v0, v1]. A concave loop may come out with
// zero-width bridges along the rectangle's sides; they enclose no area and add nothing below.
Polygon clip(const Polygon& subject, double u0, double u1, double v0, double v1) {
  Polygon poly = subject;
  auto clip_edge = [&](auto inside, auto cut) {
    Polygon out;
    for (size_t i = 0; i < poly.size(); ++i) {
      const Point& a = poly[i];
      const Point& b = poly[(i + 1) % poly.size()];
      const bool ia = inside(a), ib = inside(b);
      if (ia) out.push_back(a);
      if (ia != ib) out.push_back(cut(a, b));
    }
    poly = std::move(out);
  };
  auto at_u = [](double u) {
    return [u](const Point& a, const Point& b) {
      const double t = (u - a.x()) / (b.x() - a.x());
      return Point(u, a.y() + t * (b.y() - a.y()));
    };
  };
  auto at_v = [](double v) {
    return [v](const Point& a, const Point& b) {
      const double t = (v - a.y()) / (b.y() - a.y());
      return Point(a.x() + t * (b.x() - a.x()), v);
    };
  };
  clip_edge([&](const Point& q) { return q.x() >= u0; }, at_u(u0));
  if (!poly.empty()) clip_edge([&](const Point& q) { return q.x() <= u1; }, at_u(u1));
  if (!poly.empty()) clip_edge([&](const Point& q) { return q.y() >= v0; }, at_v(v0));
  if (!poly.empty()) clip_edge([&](const Point& q) { return q.y() <= v1; }, at_v(v1));
  return poly;
}

// Breakpoints of one direction inside [a, b], with a and b: the pieces where the basis is
// polynomial.
std::vector<double> pieces(const std::vector<double>& knots, int degree, double a, double b) {
  std::vector<double> out = {a};
  for (double t : breakpoints(knots, degree))
    if (t > a && t < b) out.push_back(t);
  out.push_back(b);
  return out;
}

// The loop's bounding box, clipped to the domain.
Eigen::Vector4d loop_box(const SplineSpace& s, const Polygon& p) {
  Eigen::Vector4d box(p[0].x(), p[0].x(), p[0].y(), p[0].y());
  for (const Point& q : p) {
    box(0) = std::min(box(0), q.x());
    box(1) = std::max(box(1), q.x());
    box(2) = std::min(box(2), q.y());
    box(3) = std::max(box(3), q.y());
  }
  box(0) = std::max(box(0), s.u_first());
  box(1) = std::min(box(1), s.u_last());
  box(2) = std::max(box(2), s.v_first());
  box(3) = std::min(box(3), s.v_last());
  return box;
}

}  // namespace

bool same_region(const Region& a, const Region& b) {
  return a.loop == b.loop && a.u0 == b.u0 && a.u1 == b.u1 && a.v0 == b.v0 && a.v1 == b.v1;
}

void check_region(const SplineSpace& space, const Region& r, const char* what) {
  const std::string w(what);
  const double du = space.u_last() - space.u_first(), dv = space.v_last() - space.v_first();
  if (r.is_loop()) {
    if (static_cast<int>(r.loop.size()) > max_loop_points)
      throw InvalidInput(w + ": the region's loop has " + std::to_string(r.loop.size()) +
                         " points, more than " + std::to_string(max_loop_points));
    for (const Point& q : r.loop) {
      if (!q.allFinite()) throw InvalidInput(w + ": the region's loop has non-finite points");
      if (q.x() < space.u_first() - 1e-9 * du || q.x() > space.u_last() + 1e-9 * du ||
          q.y() < space.v_first() - 1e-9 * dv || q.y() > space.v_last() + 1e-9 * dv)
        throw InvalidInput(w + ": the region's loop leaves the sheet's parameter domain");
    }
    const Polygon p = cleaned(r.loop);
    if (p.size() < 3) throw InvalidInput(w + ": the region's loop encloses no area");
    if (!is_simple(p)) throw InvalidInput(w + ": the region's loop crosses itself");
    if (!(std::abs(signed_area(p)) > 1e-14 * du * dv))
      throw InvalidInput(w + ": the region's loop encloses no area");
    return;
  }
  if (!std::isfinite(r.u0) || !std::isfinite(r.u1) || !std::isfinite(r.v0) || !std::isfinite(r.v1))
    throw InvalidInput(w + ": region bounds are not finite");
  if (!(r.u0 < r.u1) || !(r.v0 < r.v1)) throw InvalidInput(w + ": region is empty");
  if (r.u0 < space.u_first() || r.u1 > space.u_last() || r.v0 < space.v_first() ||
      r.v1 > space.v_last())
    throw InvalidInput(w + ": region lies outside the sheet's parameter domain");
}

std::vector<QuadraturePoint> region_quadrature(const SplineSpace& space, const Region& r) {
  const int extra = space.rational() ? 2 : 0;
  std::vector<QuadraturePoint> out;
  if (!r.is_loop()) {
    const GaussRule& gu = gauss_legendre(space.degree_u + 1 + extra);
    const GaussRule& gv = gauss_legendre(space.degree_v + 1 + extra);
    const std::vector<double> pu = pieces(space.knots_u, space.degree_u, r.u0, r.u1);
    const std::vector<double> pv = pieces(space.knots_v, space.degree_v, r.v0, r.v1);
    for (size_t a = 0; a + 1 < pu.size(); ++a) {
      const double hu = 0.5 * (pu[a + 1] - pu[a]);
      for (size_t b = 0; b + 1 < pv.size(); ++b) {
        const double hv = 0.5 * (pv[b + 1] - pv[b]);
        for (size_t i = 0; i < gu.nodes.size(); ++i)
          for (size_t j = 0; j < gv.nodes.size(); ++j)
            out.push_back({pu[a] + hu * (gu.nodes[i] + 1.0), pv[b] + hv * (gv.nodes[j] + 1.0),
                           gu.weights[i] * gv.weights[j] * hu * hv});
      }
    }
    return out;
  }
  Polygon loop = cleaned(r.loop);
  if (signed_area(loop) < 0.0) std::reverse(loop.begin(), loop.end());
  // A product of two basis functions has total degree <= 2 (p + q) on a piece; the collapsed map
  // adds one degree along s, so n points per direction with 2 n - 1 >= 2 (p + q) + 1 are exact.
  const GaussRule& g = gauss_legendre(space.degree_u + space.degree_v + 1 + extra);
  const GaussRule& gu = gauss_legendre(space.degree_u + 1 + extra);
  const GaussRule& gv = gauss_legendre(space.degree_v + 1 + extra);
  const Eigen::Vector4d box = loop_box(space, loop);
  const std::vector<double> pu = pieces(space.knots_u, space.degree_u, box(0), box(1));
  const std::vector<double> pv = pieces(space.knots_v, space.degree_v, box(2), box(3));
  for (size_t a = 0; a + 1 < pu.size(); ++a)
    for (size_t b = 0; b + 1 < pv.size(); ++b) {
      const Polygon cell = clip(loop, pu[a], pu[a + 1], pv[b], pv[b + 1]);
      const double hu = 0.5 * (pu[a + 1] - pu[a]), hv = 0.5 * (pv[b + 1] - pv[b]);
      if (cell.size() >= 3 && std::abs(signed_area(cell) - 4.0 * hu * hv) <= 1e-12 * hu * hv) {
        // The loop covers the whole piece: the tensor rule needs far fewer points.
        for (size_t i = 0; i < gu.nodes.size(); ++i)
          for (size_t j = 0; j < gv.nodes.size(); ++j)
            out.push_back({pu[a] + hu * (gu.nodes[i] + 1.0), pv[b] + hv * (gv.nodes[j] + 1.0),
                           gu.weights[i] * gv.weights[j] * hu * hv});
        continue;
      }
      for (size_t k = 1; k + 1 < cell.size(); ++k) {
        const Point &p0 = cell[0], &p1 = cell[k], &p2 = cell[k + 1];
        const double twice_area = cross(p1 - p0, p2 - p0);  // signed: bridges cancel
        if (twice_area == 0.0) continue;
        for (size_t i = 0; i < g.nodes.size(); ++i) {
          const double s = 0.5 * (g.nodes[i] + 1.0);
          for (size_t j = 0; j < g.nodes.size(); ++j) {
            const double t = 0.5 * (g.nodes[j] + 1.0);
            const Point q = p0 + s * (p1 - p0) + s * t * (p2 - p1);
            out.push_back({q.x(), q.y(), 0.25 * g.weights[i] * g.weights[j] * s * twice_area});
          }
        }
      }
    }
  return out;
}

std::vector<int> poles_in_region(const SplineSpace& space, const Region& r) {
  space.validate();
  check_region(space, r, "frozen region");
  std::vector<int> out;
  const auto& ku = space.knots_u;
  const auto& kv = space.knots_v;
  const int pu = space.degree_u, pv = space.degree_v;
  if (r.is_loop()) {
    // Pole (i, j) is supported on [ku_i, ku_{i+p+1}] x [kv_j, kv_{j+q+1}]: it acts on the region
    // if the loop covers part of that rectangle.
    const Polygon loop = cleaned(r.loop);
    const double tiny =
        1e-14 * (space.u_last() - space.u_first()) * (space.v_last() - space.v_first());
    for (int i = 0; i < space.nu(); ++i)
      for (int j = 0; j < space.nv(); ++j) {
        const Polygon part =
            clip(loop, ku[static_cast<size_t>(i)], ku[static_cast<size_t>(i + pu + 1)],
                 kv[static_cast<size_t>(j)], kv[static_cast<size_t>(j + pv + 1)]);
        if (part.size() >= 3 && std::abs(signed_area(part)) > tiny)
          out.push_back(space.index(i, j));
      }
    return out;
  }
  // A pole acts on the rectangle if its support overlaps it in more than a point.
  auto inside = [](const std::vector<double>& k, int p, int i, double a, double b) {
    return k[static_cast<size_t>(i)] < b && k[static_cast<size_t>(i + p + 1)] > a;
  };
  for (int i = 0; i < space.nu(); ++i)
    for (int j = 0; j < space.nv(); ++j)
      if (inside(ku, pu, i, r.u0, r.u1) && inside(kv, pv, j, r.v0, r.v1))
        out.push_back(space.index(i, j));
  return out;
}

}  // namespace varsurf
