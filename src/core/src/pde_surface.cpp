// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/pde_surface.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include "varsurf/core/curve_fit.hpp"
#include "varsurf/core/curve_orientation.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/core/seam_ties.hpp"

namespace varsurf {

namespace {

using Vec3 = Eigen::Vector3d;

// Samples of a curve for searches (closest points, lengths): enough for the few-span curves
// sketches and edges give; the searches refine from the best sample.
constexpr int kSearchSamples = 128;

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// The curve at its normalized parameter s in [0, 1].
Vec3 at(const BSplineCurve& c, double s) {
  return c.evaluate(c.first() + std::clamp(s, 0.0, 1.0) * (c.last() - c.first()));
}

// The poles of the straight blend between two rows of poles along v, placed at the Greville
// abscissae in u: where the energy starts, before it moves the free poles.
Eigen::MatrixX3d straight_blend(const SplineSpace& sp, const BSplineCurve& row0,
                                const BSplineCurve& row1) {
  const std::vector<double> gu = greville(sp.knots_u, sp.degree_u);
  Eigen::MatrixX3d out(sp.size(), 3);
  for (int i = 0; i < sp.nu(); ++i)
    for (int j = 0; j < sp.nv(); ++j)
      out.row(sp.index(i, j)) = (1.0 - gu[static_cast<size_t>(i)]) * row0.poles.row(j) +
                                gu[static_cast<size_t>(i)] * row1.poles.row(j);
  return out;
}

double length(const BSplineCurve& c) {
  double sum = 0.0;
  Vec3 prev = at(c, 0.0);
  for (int k = 1; k <= kSearchSamples; ++k) {
    const Vec3 p = at(c, static_cast<double>(k) / kSearchSamples);
    sum += (p - prev).norm();
    prev = p;
  }
  return sum;
}

// Normalized parameter of c's point closest to p: the best sample, refined by golden sections
// between its neighbours.
double closest(const BSplineCurve& c, const Vec3& p) {
  int best = 0;
  double dist = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= kSearchSamples; ++k) {
    const double d = (at(c, static_cast<double>(k) / kSearchSamples) - p).squaredNorm();
    if (d < dist) dist = d, best = k;
  }
  double lo = std::max(0, best - 1) / static_cast<double>(kSearchSamples);
  double hi = std::min(kSearchSamples, best + 1) / static_cast<double>(kSearchSamples);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 60; ++it) {
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    if ((at(c, a) - p).squaredNorm() < (at(c, b) - p).squaredNorm())
      hi = b;
    else
      lo = a;
  }
  return 0.5 * (lo + hi);
}

// Where two curves come closest: normalized parameters (on a, on b) and the distance, by
// alternating projections from the closest pair of samples.
struct Crossing {
  double sa, sb, gap;
};
Crossing crossing(const BSplineCurve& a, const BSplineCurve& b) {
  Crossing best{0.0, 0.0, std::numeric_limits<double>::infinity()};
  for (int i = 0; i <= kSearchSamples; ++i) {
    const double sa = static_cast<double>(i) / kSearchSamples;
    const double sb = closest(b, at(a, sa));
    const double gap = (at(a, sa) - at(b, sb)).norm();
    if (gap < best.gap) best = {sa, sb, gap};
  }
  for (int it = 0; it < 20; ++it) {
    best.sa = closest(a, at(b, best.sb));
    best.sb = closest(b, at(a, best.sa));
  }
  best.gap = (at(a, best.sa) - at(b, best.sb)).norm();
  return best;
}

BSplineCurve normalized_3d(const BSplineCurve& c, const std::string& name) {
  c.validate(name.c_str());
  if (c.dim() != 3) throw InvalidInput(name + ": a 3D curve is needed");
  if (!(length(c) > 0.0))
    throw InvalidInput(name + " has no length: give a curve that is not a point");
  return c;
}

// A monotone piecewise-linear map from the surface's parameter (0..1 along the curve) to the
// curve's normalized parameter: through its crossings with the curves across it.
struct ParameterMap {
  std::vector<double> s{0.0, 1.0}, t{0.0, 1.0};
  void add(double surface, double curve) {
    const auto it = std::upper_bound(s.begin(), s.end(), surface);
    const auto k = it - s.begin();
    s.insert(it, surface);
    t.insert(t.begin() + k, curve);
  }
  bool monotone() const {
    for (size_t k = 0; k + 1 < t.size(); ++k)
      if (!(t[k + 1] > t[k])) return false;
    return true;
  }
  double operator()(double x) const {
    const auto it = std::upper_bound(s.begin(), s.end(), x);
    const size_t k = std::clamp<size_t>(static_cast<size_t>(it - s.begin()), 1, s.size() - 1);
    const double w = (x - s[k - 1]) / (s[k] - s[k - 1]);
    return t[k - 1] + w * (t[k] - t[k - 1]);
  }
};

// A curve's data as a row of poles on `knots`: least squares through samples at the mapped
// parameters, ends interpolated. `value(s)` is the data at surface parameter s.
template <class Value>
BSplineCurve fit_row(const Value& value, int degree, const std::vector<double>& knots,
                     double* error) {
  const int spans = static_cast<int>(knots.size()) - 2 * degree - 1;
  const int count = spans * (2 * degree + 2) + 1;
  std::vector<double> s(static_cast<size_t>(count));
  Eigen::MatrixXd points(count, 3);
  for (int k = 0; k < count; ++k) {
    s[static_cast<size_t>(k)] = static_cast<double>(k) / (count - 1);
    points.row(k) = value(s[static_cast<size_t>(k)]).transpose();
  }
  BSplineCurve fit = fit_clamped_curve(s, points, degree, knots);
  for (int k = 0; k <= 4 * count; ++k) {
    const double x = static_cast<double>(k) / (4 * count);
    *error = std::max(*error, (fit.evaluate(x) - value(x)).norm());
  }
  return fit;
}

// How a closed curve's normalized parameter runs against the surface's v: t = frac(shift + dir s).
struct Alignment {
  double shift = 0.0, dir = 1.0;
  double operator()(double s) const {
    const double t = shift + dir * s;
    return t - std::floor(t);
  }
};

// The alignment of closed curve c whose points best match ref(s) (after removing both centroids
// when `centred`: two boundary circles of different radii and heights pair by direction).
template <class Ref>
Alignment align(const BSplineCurve& c, const Ref& ref, bool centred) {
  constexpr int kCandidates = 256, kSamples = 64;
  std::vector<Vec3> ring(kCandidates), target(kSamples);
  Vec3 cc = Vec3::Zero(), rc = Vec3::Zero();
  for (int j = 0; j < kCandidates; ++j)
    cc += (ring[static_cast<size_t>(j)] = at(c, static_cast<double>(j) / kCandidates));
  for (int k = 0; k < kSamples; ++k)
    rc += (target[static_cast<size_t>(k)] = ref(static_cast<double>(k) / kSamples));
  cc /= kCandidates;
  rc /= kSamples;
  if (!centred) cc.setZero(), rc.setZero();
  auto cost = [&](const Alignment& al) {
    double sum = 0.0;
    for (int k = 0; k < kSamples; ++k)
      sum += ((at(c, al(static_cast<double>(k) / kSamples)) - cc) -
              (target[static_cast<size_t>(k)] - rc))
                 .squaredNorm();
    return sum;
  };
  Alignment best;
  double lowest = std::numeric_limits<double>::infinity();
  const int step = kCandidates / kSamples;
  for (double dir : {1.0, -1.0})
    for (int j = 0; j < kCandidates; ++j) {
      double sum = 0.0;
      for (int k = 0; k < kSamples; ++k) {
        const int idx =
            ((j + static_cast<int>(dir) * k * step) % kCandidates + kCandidates) % kCandidates;
        sum += ((ring[static_cast<size_t>(idx)] - cc) - (target[static_cast<size_t>(k)] - rc))
                   .squaredNorm();
      }
      if (sum < lowest) lowest = sum, best = {static_cast<double>(j) / kCandidates, dir};
    }
  // Refined between the neighbouring candidates by golden sections.
  double lo = best.shift - 1.0 / kCandidates, hi = best.shift + 1.0 / kCandidates;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 40; ++it) {
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    if (cost({a, best.dir}) < cost({b, best.dir}))
      hi = b;
    else
      lo = a;
  }
  best.shift = 0.5 * (lo + hi);
  return best;
}

// fit_row for a closed curve: the row closed on itself with its derivatives up to degree - 1
// equal across the seam (closure_rows), so a closed sheet's seam is as smooth as its knot lines.
template <class Value>
BSplineCurve fit_closed_row(const Value& value, int degree, const std::vector<double>& knots,
                            double* error) {
  const int n = static_cast<int>(knots.size()) - degree - 1;
  const int spans = n - degree;
  const int count = spans * (2 * degree + 2) + 1;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(count, n), y(count, 3);
  Eigen::MatrixXd d(1, degree + 1);
  for (int k = 0; k < count; ++k) {
    const double s = static_cast<double>(k) / (count - 1);
    const int span = find_span(knots, degree, s);
    basis_derivatives(knots, degree, span, s, 0, d);
    for (int i = 0; i <= degree; ++i) a(k, span - degree + i) = d(0, i);
    y.row(k) = value(s).transpose();
  }
  const std::vector<std::map<int, double>> rows = closure_rows(knots, degree, degree - 1);
  const int m = static_cast<int>(rows.size());
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + m, n + m), rhs = Eigen::MatrixXd::Zero(n + m, 3);
  kkt.topLeftCorner(n, n) = a.transpose() * a;
  rhs.topRows(n) = a.transpose() * y;
  for (int r = 0; r < m; ++r)
    for (const auto& [col, x] : rows[static_cast<size_t>(r)]) kkt(n + r, col) = kkt(col, n + r) = x;
  BSplineCurve fit;
  fit.degree = degree;
  fit.knots = knots;
  fit.poles = kkt.fullPivLu().solve(rhs).topRows(n);
  for (int k = 0; k <= 4 * count; ++k) {
    const double x = static_cast<double>(k) / (4 * count);
    *error = std::max(*error, (fit.evaluate(x) - value(x)).norm());
  }
  return fit;
}

void check_iso(const std::vector<IsoCurve>& curves, const char* kind) {
  for (size_t k = 0; k < curves.size(); ++k)
    if (!(curves[k].at > 0.0 && curves[k].at < 1.0))
      throw InvalidInput(std::string(kind) + " " + std::to_string(k + 1) + " lies at " +
                         fmt(curves[k].at) + ": give a value strictly between 0 and 1");
}

// A curve of a network: its isoparametric value, its name in messages, and the map of the
// surface's parameter along it to its own normalized parameter.
struct Line {
  const BSplineCurve* curve;
  double at;
  std::string name;
  ParameterMap map;
};

// Checks that every u-direction curve meets every v-direction one; the crossings inside the
// surface place the curves across (their maps pass through them). Returns, per u-direction
// curve, its crossings (the v-direction curve's value, its own normalized parameter).
std::vector<std::vector<std::pair<double, double>>> cross(std::vector<Line>& along_v,
                                                          std::vector<Line>& along_u,
                                                          double gap_tolerance) {
  std::vector<std::vector<std::pair<double, double>>> out(along_v.size());
  for (size_t i = 0; i < along_v.size(); ++i)
    for (Line& y : along_u) {
      Line& x = along_v[i];
      const Crossing c = crossing(*x.curve, *y.curve);
      if (c.gap > gap_tolerance)
        throw InvalidInput(x.name + " and " + y.name + " do not meet (they come " + fmt(c.gap) +
                           " close): the curves of a network must cross; move one onto the other");
      out[i].emplace_back(y.at, c.sa);
      if (x.at > 0.0 && x.at < 1.0) y.map.add(x.at, c.sb);
    }
  return out;
}

void check_order(const std::vector<Line>& lines) {
  for (const Line& x : lines)
    if (!x.map.monotone())
      throw InvalidInput(x.name + " crosses the curves across it out of their order: order the " +
                         "isoparametric values as the curves lie");
}

// Gordon curves inside: curve constraints whose pre-images run along their isoparametric line
// through the crossings (degree 1, the crossings' parameters as knots). A closed curve's map may
// run across its own seam (its parameter unwrapped beyond 1): it is held as one piece per turn.
void add_curve_constraints(SheetProblem& pb, const Line& line, bool along_v_dir) {
  std::vector<double> s, t;
  for (size_t k = 0; k < line.map.s.size(); ++k) {
    s.push_back(line.map.s[k]);
    t.push_back(line.map.t[k]);
    if (k + 1 == line.map.s.size()) break;
    const double t1 = line.map.t[k + 1], s1 = line.map.s[k + 1];
    for (double n = std::floor(t.back()) + 1.0; n < t1; n += 1.0) {
      if (n <= t.back()) continue;
      s.push_back(s.back() + (n - t.back()) / (t1 - t.back()) * (s1 - s.back()));
      t.push_back(n);
    }
  }
  const BSplineCurve& curve = *line.curve;
  const double t0 = curve.first(), dt = curve.last() - curve.first();
  auto turn = [&](size_t k) { return std::floor(0.5 * (t[k] + t[k + 1])); };
  for (size_t start = 0; start + 1 < s.size();) {
    const double n = turn(start);
    size_t end = start + 1;
    while (end + 1 < s.size() && turn(end) == n) ++end;
    const double a = std::clamp(t[start] - n, 0.0, 1.0), b = std::clamp(t[end] - n, 0.0, 1.0);
    if (b - a > 1e-12) {
      CurveConstraint c;
      c.target = a == 0.0 && b == 1.0 ? curve : piece(curve, t0 + dt * a, t0 + dt * b);
      c.preimage.degree = 1;
      c.preimage.poles.resize(static_cast<Eigen::Index>(end - start + 1), 2);
      c.preimage.knots.push_back(c.target.first());
      for (size_t k = start; k <= end; ++k) {
        const double x = k == start ? a : k == end ? b : std::clamp(t[k] - n, a, b);
        c.preimage.knots.push_back(k == start ? c.target.first()
                                   : k == end ? c.target.last()
                                              : t0 + dt * x);
        c.preimage.poles.row(static_cast<Eigen::Index>(k - start)) =
            along_v_dir ? Eigen::RowVector2d(line.at, s[k]) : Eigen::RowVector2d(s[k], line.at);
      }
      c.preimage.knots.push_back(c.target.last());
      pb.curves.push_back(std::move(c));
    }
    start = end;
  }
}

// A closed curve's map through its crossings (v_k, t_k): sorted by v, each t the previous one plus
// the forward distance around the curve (unwrapped), repeated with the period of one turn.
// False when the crossings do not lie in the curve's cyclic order.
bool periodic_map(std::vector<std::pair<double, double>> pts, ParameterMap* out) {
  std::sort(pts.begin(), pts.end());
  std::vector<double> v, t;
  for (const auto& [vk, tk] : pts) {
    if (t.empty()) {
      v.push_back(vk), t.push_back(tk);
      continue;
    }
    const double step = tk - t.back() - std::floor(tk - t.back());
    if (!(vk > v.back() && step > 0.0)) return false;
    v.push_back(vk), t.push_back(t.back() + step);
  }
  if (!(t.back() - t.front() < 1.0)) return false;
  // Between the last crossing and the first one a turn later lies the surface's seam (v = 0 = 1).
  const double before = v.back() - 1.0, t_before = t.back() - 1.0;
  const double t_zero =
      v.front() == 0.0 ? t.front()
                       : t_before + (0.0 - before) / (v.front() - before) * (t.front() - t_before);
  out->s.clear(), out->t.clear();
  if (v.front() > 0.0) out->s.push_back(0.0), out->t.push_back(t_zero);
  out->s.insert(out->s.end(), v.begin(), v.end());
  out->t.insert(out->t.end(), t.begin(), t.end());
  out->s.push_back(1.0), out->t.push_back(t_zero + 1.0);
  return true;
}

// A closed curve read through its (possibly unwrapped) map.
Vec3 around(const Line& line, double s) {
  const double t = line.map(s);
  return at(*line.curve, t - std::floor(t));
}

// A surface closed along v: both boundary curves (and their derivative curves) closed. Without
// v-curves, the curves are paired by the seam shift and direction that best match u0's shape and
// v = 0 lies at u0's start; v-curves (from u0 to u1, at v in [0, 1)) place every closed curve by
// their crossings instead. The rows fitted closed and held, u-curves and v-curves as curve
// constraints, the seam tied.
SheetProblem closed_problem(const PdeBoundary& b, const PdeSurfaceOptions& o, double gap_tolerance,
                            double* fit_error) {
  if (b.v0.poles.size() != 0 || b.v1.poles.size() != 0)
    throw InvalidInput("a surface closed along v has no sides: clear v0 and v1");
  for (size_t k = 0; k < b.v_curves.size(); ++k)
    if (!(b.v_curves[k].at >= 0.0 && b.v_curves[k].at < 1.0))
      throw InvalidInput(
          "v-curve " + std::to_string(k + 1) + " lies at " + fmt(b.v_curves[k].at) +
          ": on a surface closed along v give a value from 0 up to (not including) 1");
  // Closed curves along v, each turned to run like u0 (by the shapes' best match).
  std::vector<BSplineCurve> closed{b.u0, b.u1};
  std::vector<std::string> names{"u0", "u1"};
  std::vector<double> ats{0.0, 1.0};
  for (size_t i = 0; i < b.u_curves.size(); ++i) {
    names.push_back("u-curve " + std::to_string(i + 1));
    closed.push_back(normalized_3d(b.u_curves[i].curve, names.back()));
    ats.push_back(b.u_curves[i].at);
  }
  std::vector<Line> along_v;
  for (size_t i = 0; i < closed.size(); ++i) {
    BSplineCurve& c = closed[i];
    const double gap = (at(c, 0.0) - at(c, 1.0)).norm();
    if (gap > gap_tolerance)
      throw InvalidInput(
          names[i] + " is open (its ends are " + fmt(gap) +
          " apart) on a surface closed along v: close it, or open the boundary curves");
    Line line{&c, ats[i], names[i], {}};
    if (i > 0) {
      const Alignment al = align(
          c, [&](double s) { return at(b.u0, s); }, true);
      if (al.dir < 0.0) c = reversed(c);
      // Without v-curves the best match places it: t = shift + s on the curve turned forward.
      const double shift = al.dir < 0.0 ? 1.0 - al.shift : al.shift;
      line.map.t = {shift, shift + 1.0};
    }
    along_v.push_back(std::move(line));
  }
  std::vector<BSplineCurve> profiles;
  profiles.reserve(b.v_curves.size());
  std::vector<Line> along_u;
  for (size_t j = 0; j < b.v_curves.size(); ++j) {
    const std::string name = "v-curve " + std::to_string(j + 1);
    BSplineCurve c = normalized_3d(b.v_curves[j].curve, name);
    // From u0 to u1: the end nearer u0 first.
    auto gap = [&](const BSplineCurve& to, double s) {
      return (at(to, closest(to, at(c, s))) - at(c, s)).norm();
    };
    if (gap(b.u0, 1.0) + gap(b.u1, 0.0) < gap(b.u0, 0.0) + gap(b.u1, 1.0)) c = reversed(c);
    profiles.push_back(std::move(c));
    along_u.push_back({&profiles.back(), b.v_curves[j].at, name, {}});
  }
  const auto crossings = cross(along_v, along_u, gap_tolerance);
  if (!along_u.empty())
    for (size_t i = 0; i < along_v.size(); ++i)
      if (!periodic_map(crossings[i], &along_v[i].map))
        throw InvalidInput(along_v[i].name +
                           " crosses the v-curves out of their order: order their values as the "
                           "curves lie around it (v runs the way u0 does)");
  check_order(along_u);

  const int p = o.degree;
  SheetProblem pb;
  pb.space = SplineSpace::uniform(p, p, o.spans_u, o.spans_v);
  pb.closed_v = true;
  pb.pde = b.a;
  pb.pde->plate_form = false;  // no free side: u = 0 and u = 1 are held, v closes
  const SplineSpace& sp = pb.space;
  const int nu = sp.nu(), nv = sp.nv();
  auto u0 = [&](double s) { return around(along_v[0], s); };
  auto u1 = [&](double s) { return around(along_v[1], s); };
  double error = 0.0;
  const BSplineCurve row0 = fit_closed_row(u0, p, sp.knots_v, &error);
  const BSplineCurve row1 = fit_closed_row(u1, p, sp.knots_v, &error);
  pb.initial_poles = straight_blend(sp, row0, row1);
  std::vector<int> rows{0, nu - 1};
  auto hold_row = [&](int i, const Eigen::MatrixXd& poles) {
    for (int j = 0; j < nv; ++j) pb.initial_poles.row(sp.index(i, j)) = poles.row(j);
  };
  hold_row(0, row0.poles);
  hold_row(nu - 1, row1.poles);
  auto hermite = [&](const BSplineCurve& d, const char* name, const auto& c, double magnitude,
                     const BSplineCurve& row, int i, double step) {
    const double gap = (at(d, 0.0) - at(d, 1.0)).norm();
    if (gap > std::max(o.tolerance, 1e-9 * length(d)))
      throw InvalidInput(std::string(name) + " is open (its ends are " + fmt(gap) +
                         " apart) beside a closed boundary curve: close it");
    const Alignment ad = align(d, c, true);
    const BSplineCurve dv = fit_closed_row(
        [&](double s) -> Vec3 { return magnitude * (at(d, ad(s)) - c(s)); }, p, sp.knots_v, &error);
    hold_row(i, row.poles + step * dv.poles);
    rows.push_back(i);
  };
  if (b.d0.poles.size() != 0)
    hermite(b.d0, "d0", u0, b.magnitude0, row0, 1, sp.knots_u[static_cast<size_t>(p + 1)] / p);
  if (b.d1.poles.size() != 0)
    hermite(b.d1, "d1", u1, b.magnitude1, row1, nu - 2,
            -(1.0 - sp.knots_u[static_cast<size_t>(nu - 1)]) / p);
  for (int i : rows)
    for (int j = 0; j < nv; ++j) pb.fixed_poles.push_back(sp.index(i, j));
  std::sort(pb.fixed_poles.begin(), pb.fixed_poles.end());
  pb.fixed_poles.erase(std::unique(pb.fixed_poles.begin(), pb.fixed_poles.end()),
                       pb.fixed_poles.end());
  for (size_t k = 2; k < along_v.size(); ++k) add_curve_constraints(pb, along_v[k], true);
  for (const Line& line : along_u) add_curve_constraints(pb, line, false);
  if (fit_error) *fit_error = error;
  return pb;
}

}  // namespace

SheetProblem pde_surface_problem(const PdeBoundary& in, const PdeSurfaceOptions& o,
                                 double* fit_error) {
  const int p = o.degree;
  if (p < 2 || p > 9) throw InvalidInput("PDE surface degree must be in 2..9");
  if (!(std::isfinite(o.tolerance) && o.tolerance >= 0.0))
    throw InvalidInput("PDE surface tolerance must be a finite distance >= 0");
  if (o.spans_u < 1 || o.spans_v < 1 || o.spans_u > 512 || o.spans_v > 512)
    throw InvalidInput("PDE surface spans must be in 1..512");
  const bool hermite0 = in.d0.poles.size() != 0, hermite1 = in.d1.poles.size() != 0;
  if ((hermite0 || hermite1) && p < 3)
    throw InvalidInput("Hermite boundary conditions need degree 3 or more");
  for (double m : {in.magnitude0, in.magnitude1})
    if (!std::isfinite(m)) throw InvalidInput("derivative magnitude must be finite");
  check_iso(in.u_curves, "u-curve");

  PdeBoundary b = in;
  b.u0 = normalized_3d(in.u0, "u0");
  b.u1 = oriented(normalized_3d(in.u1, "u1"), at(b.u0, 0.0), at(b.u0, 1.0));
  const double size = std::max(length(b.u0), length(b.u1));
  const double gap_tolerance = std::max(o.tolerance, 1e-9 * size);
  const double open0 = (at(b.u0, 0.0) - at(b.u0, 1.0)).norm();
  const double open1 = (at(b.u1, 0.0) - at(b.u1, 1.0)).norm();
  if ((open0 <= gap_tolerance) != (open1 <= gap_tolerance))
    throw InvalidInput(std::string(open0 <= gap_tolerance
                                       ? "u0 is closed but u1 is open (its ends are "
                                       : "u1 is closed but u0 is open (its ends are ") +
                       fmt(std::max(open0, open1)) +
                       " apart): a surface closed along v needs both boundary curves closed; close "
                       "the open one, or use two open curves");
  if (open0 <= gap_tolerance) return closed_problem(b, o, gap_tolerance, fit_error);
  check_iso(in.v_curves, "v-curve");
  auto derivative = [&](const BSplineCurve& d, const BSplineCurve& c, const char* name,
                        const char* of) {
    const BSplineCurve out = oriented(normalized_3d(d, name), at(c, 0.0), at(c, 1.0));
    const double e0 = (at(out, 0.0) - at(c, 0.0)).norm(), e1 = (at(out, 1.0) - at(c, 1.0)).norm();
    // Tangents may be long and skewed: only a curve far beyond any tangent the two curves'
    // sizes suggest is taken for a mistake (another curve picked, or a wrong role).
    const double reach = 5.0 * std::max(length(c), length(out));
    if (std::max(e0, e1) > reach)
      throw InvalidInput(
          std::string(name) + " does not run beside " + of + ": its ends are " + fmt(e0) + " and " +
          fmt(e1) + " from " + of + "'s ends, more than five times the curves' length (" +
          fmt(reach) + "); draw it alongside " + of + ", from beside its start to beside its end");
    return out;
  };
  if (hermite0) b.d0 = derivative(in.d0, b.u0, "d0", "u0");
  if (hermite1) b.d1 = derivative(in.d1, b.u1, "d1", "u1");
  const bool coons0 = in.v0.poles.size() != 0, coons1 = in.v1.poles.size() != 0;
  // A v-side curve runs from the u0 curve's end at that side to the u1 curve's.
  auto side = [&](const BSplineCurve& c, const char* name, double v) {
    const BSplineCurve out = oriented(normalized_3d(c, name), at(b.u0, v), at(b.u1, v));
    for (int end = 0; end < 2; ++end) {
      const Vec3 corner = at(end == 0 ? b.u0 : b.u1, v);
      const double gap = (at(out, end) - corner).norm();
      if (gap > gap_tolerance)
        throw InvalidInput(std::string(name) + "'s " + (end == 0 ? "start" : "end") + " is " +
                           fmt(gap) + " from the corner (u = " + std::to_string(end) +
                           ", v = " + fmt(v) + ") where " + (end == 0 ? "u0" : "u1") +
                           " ends: the boundary curves must meet at their corners (within " +
                           fmt(gap_tolerance) + ")");
    }
    return out;
  };
  if (coons0) b.v0 = side(in.v0, "v0", 0.0);
  if (coons1) b.v1 = side(in.v1, "v1", 1.0);

  // Gordon curves: oriented like the boundary curves they run beside; every u-curve must cross
  // every v-curve, and their crossings place them (their parameters are mapped through them).
  for (size_t i = 0; i < b.u_curves.size(); ++i) {
    const std::string name = "u-curve " + std::to_string(i + 1);
    b.u_curves[i].curve =
        oriented(normalized_3d(in.u_curves[i].curve, name), at(b.u0, 0.0), at(b.u0, 1.0));
  }
  for (size_t j = 0; j < b.v_curves.size(); ++j) {
    const std::string name = "v-curve " + std::to_string(j + 1);
    const double v = b.v_curves[j].at;
    b.v_curves[j].curve =
        oriented(normalized_3d(in.v_curves[j].curve, name), at(b.u0, v), at(b.u1, v));
  }
  // u-direction curves (u0, u1, u-curves) cross the v-direction ones (v0, v1, v-curves).
  std::vector<Line> along_v{{&b.u0, 0.0, "u0", {}}, {&b.u1, 1.0, "u1", {}}};
  for (size_t i = 0; i < b.u_curves.size(); ++i)
    along_v.push_back(
        {&b.u_curves[i].curve, b.u_curves[i].at, "u-curve " + std::to_string(i + 1), {}});
  std::vector<Line> along_u;
  if (coons0) along_u.push_back({&b.v0, 0.0, "v0", {}});
  if (coons1) along_u.push_back({&b.v1, 1.0, "v1", {}});
  for (size_t j = 0; j < b.v_curves.size(); ++j)
    along_u.push_back(
        {&b.v_curves[j].curve, b.v_curves[j].at, "v-curve " + std::to_string(j + 1), {}});
  const auto crossings = cross(along_v, along_u, gap_tolerance);
  // Crossings at the curves' ends are the corners, already at 0 and 1.
  for (size_t i = 0; i < along_v.size(); ++i)
    for (const auto& [v, t] : crossings[i])
      if (v > 0.0 && v < 1.0) along_v[i].map.add(v, t);
  check_order(along_v);
  check_order(along_u);

  SheetProblem pb;
  pb.space = SplineSpace::uniform(p, p, o.spans_u, o.spans_v);
  pb.pde = in.a;
  // A side no curve holds needs the energy's plate form (PdeCoefficient::plate_form).
  pb.pde->plate_form = !(coons0 && coons1);
  const SplineSpace& sp = pb.space;
  const int nu = sp.nu(), nv = sp.nv();
  double error = 0.0;
  auto row_of = [&](const Line& line) {
    return fit_row([&](double s) { return at(*line.curve, line.map(s)); }, p, sp.knots_v, &error);
  };
  const BSplineCurve row0 = row_of(along_v[0]), row1 = row_of(along_v[1]);
  // Start: the straight blend of the two boundary rows (the energy moves the free poles from it).
  pb.initial_poles = straight_blend(sp, row0, row1);
  std::vector<bool> fixed(static_cast<size_t>(sp.size()), false);
  auto hold = [&](int i, int j, const Eigen::RowVector3d& x) {
    pb.initial_poles.row(sp.index(i, j)) = x;
    fixed[static_cast<size_t>(sp.index(i, j))] = true;
  };
  // Coons sides first: the u rows overwrite their ends (the corners and the Hermite rows).
  for (const Line& line : along_u) {
    if (line.at != 0.0 && line.at != 1.0) continue;
    const BSplineCurve col =
        fit_row([&](double s) { return at(*line.curve, line.map(s)); }, p, sp.knots_u, &error);
    const int j = line.at == 0.0 ? 0 : nv - 1;
    for (int i = 0; i < nu; ++i) hold(i, j, col.poles.row(i));
  }
  for (int j = 0; j < nv; ++j) {
    hold(0, j, row0.poles.row(j));
    hold(nu - 1, j, row1.poles.row(j));
  }
  // Hermite: P_u(0, v) = p / t_(p+1) (row 1 - row 0) and P_u(1, v) = p / (1 - t_(nu-1))
  // (row nu-1 - row nu-2) on the clamped knots.
  auto hermite = [&](const BSplineCurve& d, const BSplineCurve& c, const ParameterMap& map,
                     double magnitude, const BSplineCurve& row, int i, double step) {
    const BSplineCurve dv =
        fit_row([&](double s) -> Vec3 { return magnitude * (at(d, map(s)) - at(c, map(s))); }, p,
                sp.knots_v, &error);
    for (int j = 0; j < nv; ++j) hold(i, j, row.poles.row(j) + step * dv.poles.row(j));
  };
  if (hermite0)
    hermite(b.d0, b.u0, along_v[0].map, in.magnitude0, row0, 1,
            sp.knots_u[static_cast<size_t>(p + 1)] / p);
  if (hermite1)
    hermite(b.d1, b.u1, along_v[1].map, in.magnitude1, row1, nu - 2,
            -(1.0 - sp.knots_u[static_cast<size_t>(nu - 1)]) / p);
  for (int k = 0; k < sp.size(); ++k)
    if (fixed[static_cast<size_t>(k)]) pb.fixed_poles.push_back(k);
  for (size_t k = 2; k < along_v.size(); ++k) add_curve_constraints(pb, along_v[k], true);
  for (const Line& line : along_u)
    if (line.at > 0.0 && line.at < 1.0) add_curve_constraints(pb, line, false);
  if (fit_error) *fit_error = error;
  return pb;
}

}  // namespace varsurf
