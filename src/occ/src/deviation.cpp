// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/deviation.hpp"

#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <math_BrentMinimum.hxx>
#include <math_Function.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/surface_inversion.hpp"

namespace varsurf::occ {

namespace {

struct Sample {
  double t;
  gp_Pnt point;
  gp_Vec tangent;
  SurfacePoint foot;
  bool global = true;  // foot found over the whole sheet (else: Newton's, accepted)
};

// Where the sampling along the curve is dense enough: consecutive samples turn the tangent by
// less than this, and their closest points move less than this fraction of a surface patch.
constexpr double kMaxTurn = 10.0 * M_PI / 180.0;
constexpr double kMaxPatchStep = 1.0 / 3.0;
constexpr int kMaxBisections = 14;
// Local maxima of the distance refined by a 1-D maximization, largest first.
constexpr int kRefinedMaxima = 24;

class Measure {
 public:
  Measure(const Handle(Geom_BSplineSurface) & surface, SurfaceInversion& inversion,
          const Handle(Geom_BSplineCurve) & curve, double accept)
      : accept_(accept),
        inversion_(inversion),
        curve_(curve),
        patches_u_(inversion_.patch_coordinate_u(surface->UKnot(surface->LastUKnotIndex()))),
        patches_v_(inversion_.patch_coordinate_v(surface->VKnot(surface->LastVKnotIndex()))),
        closed_u_(surface->IsUClosed()),
        closed_v_(surface->IsVClosed()) {}

  // The sample at t, its foot found from `previous` (a neighbouring sample) when there is one.
  Sample at(double t, const Sample* previous) {
    Sample s;
    s.t = t;
    curve_->D1(t, s.point, s.tangent);
    if (previous != nullptr && accept_ > 0.0) {
      bool settled = false;
      s.foot = inversion_.local(s.point, previous->foot, settled);
      s.global = true;
      if (settled && s.foot.distance <= accept_) {
        s.global = false;
        return s;
      }
      // An accepted neighbour may lie on another fold of the sheet: not a start to trust.
      if (!previous->global) {
        s.foot = nearest(s.point, s.foot);
        return s;
      }
    }
    s.foot = inversion_.closest(s.point, previous != nullptr ? &previous->foot : nullptr);
    return s;
  }

  // The sample's foot over the whole sheet, if Newton's was accepted.
  void make_global(Sample& s) {
    if (s.global) return;
    s.foot = nearest(s.point, s.foot);
    s.global = true;
  }

  // The globally closest distance at t, the search also started from `near` (a foot nearby).
  double exact(double t, const SurfacePoint& near) {
    gp_Pnt point;
    curve_->D0(t, point);
    return nearest(point, near).distance;
  }

  // Samples a and b are close enough that the distance between them is captured.
  bool dense_enough(const Sample& a, const Sample& b) const {
    const double ta = a.tangent.Magnitude(), tb = b.tangent.Magnitude();
    if (ta > 0 && tb > 0 && a.tangent.Angle(b.tangent) > kMaxTurn) return false;
    return step(inversion_.patch_coordinate_u(a.foot.u) - inversion_.patch_coordinate_u(b.foot.u),
                patches_u_, closed_u_) <= kMaxPatchStep &&
           step(inversion_.patch_coordinate_v(a.foot.v) - inversion_.patch_coordinate_v(b.foot.v),
                patches_v_, closed_v_) <= kMaxPatchStep;
  }

 private:
  // Around a closed surface the foot of a curve along its seam steps from one end of the
  // parameter range to the other: that is no step at all (bisecting it to the limit made the
  // measure of a tube's end section take minutes).
  static double step(double delta, double patches, bool closed) {
    const double d = std::abs(delta);
    return closed ? std::min(d, std::abs(patches - d)) : d;
  }

  // The global search from no start and from `start` (on a folded sheet either alone can stop
  // at another fold's point, 0.53 mm off on a face's own edge): any surface point they find
  // bounds the distance, so the nearer is kept.
  SurfacePoint nearest(const gp_Pnt& point, const SurfacePoint& start) {
    const SurfacePoint free = inversion_.closest(point, nullptr);
    const SurfacePoint from = inversion_.closest(point, &start);
    return from.distance < free.distance ? from : free;
  }

  double accept_;
  SurfaceInversion& inversion_;
  Handle(Geom_BSplineCurve) curve_;
  double patches_u_, patches_v_;  // patch coordinate of the last knot: the number of patches
  bool closed_u_, closed_v_;
};

// -distance(t) for math_BrentMinimum, starting each inversion from the nearest sample's foot.
class NegativeDistance : public math_Function {
 public:
  NegativeDistance(Measure& measure, const Sample& start) : measure_(measure), start_(start) {}
  Standard_Boolean Value(const Standard_Real t, Standard_Real& f) override {
    const Sample s = measure_.at(t, &start_);
    f = -s.foot.distance;
    return Standard_True;
  }

 private:
  Measure& measure_;
  Sample start_;
};

// The starting parameters: `samples` evenly spaced, and in every knot span of the curve enough
// for its degree (a span is where the curve can bend on its own).
std::vector<double> initial_parameters(const Handle(Geom_BSplineCurve) & curve, int samples) {
  const double t0 = curve->FirstParameter(), t1 = curve->LastParameter();
  const double even = (t1 - t0) / (samples - 1);
  std::vector<double> ts;
  const int per_span = 2 * curve->Degree() + 2;
  for (int k = 1; k < curve->NbKnots(); ++k) {
    const double a = curve->Knot(k), b = curve->Knot(k + 1);
    for (int i = 0; i <= per_span; ++i) ts.push_back(a + (b - a) * i / per_span);
  }
  // The even samples only where the spans' own are sparser: a curve of many spans (an
  // interpolation of 65 points has 62) is sampled more densely by them alone, and the even
  // samples on top were a quarter of its samples.
  for (int i = 0; i < samples; ++i) {
    const double t = i == samples - 1 ? t1 : t0 + even * i;
    int first = 1, last = 1;
    curve->LocateU(t, 0.0, first, last);
    const int k = std::clamp(first, 1, curve->NbKnots() - 1);
    if ((curve->Knot(k + 1) - curve->Knot(k)) / per_span > even) ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  const double gap = 1e-12 * (t1 - t0);
  ts.erase(std::unique(ts.begin(), ts.end(), [&](double a, double b) { return b - a <= gap; }),
           ts.end());
  return ts;
}

void check_measure_arguments(const BSplineSurface& surface, int samples, double accept) {
  surface.validate();
  if (samples < 2 || samples > 10000000)
    throw InvalidInput("max_deviation needs between 2 and 10^7 samples");
  if (!(accept >= 0.0) || !std::isfinite(accept))
    throw InvalidInput("max_deviation: accept must be a finite distance >= 0");
}

// The curve's largest distance from the sheet; past stop_above, the first global distance found
// beyond it (a proof that the curve is farther, not its largest distance).
double measure_curve(const Handle(Geom_BSplineSurface) & geom, SurfaceInversion& inversion,
                     const Handle(Geom_BSplineCurve) & curve, int samples, double accept,
                     double stop_above) {
  Measure measure(geom, inversion, curve, accept);
  const auto beyond = [&](const Sample& s) { return s.global && s.foot.distance > stop_above; };
  // 1. The starting samples, each inverted from the previous one's closest point.
  std::vector<Sample> coarse;
  for (double t : initial_parameters(curve, samples)) {
    coarse.push_back(measure.at(t, coarse.empty() ? nullptr : &coarse.back()));
    if (beyond(coarse.back())) return coarse.back().foot.distance;
  }
  // 2. Bisection wherever the curve turns or its closest point crosses a surface patch faster
  //    than the distance can be followed.
  std::vector<Sample> fine{coarse.front()};
  const double min_step = 1e-9 * (curve->LastParameter() - curve->FirstParameter());
  for (size_t k = 1; k < coarse.size(); ++k) {
    std::vector<std::pair<Sample, int>> pending{{coarse[k], 0}};
    while (!pending.empty()) {
      const auto [b, depth] = pending.back();
      const Sample& a = fine.back();
      if (depth >= kMaxBisections || b.t - a.t <= min_step || measure.dense_enough(a, b)) {
        fine.push_back(b);
        pending.pop_back();
        continue;
      }
      const Sample mid = measure.at(0.5 * (a.t + b.t), &a);
      if (beyond(mid)) return mid.foot.distance;
      pending.back().second = depth + 1;
      pending.emplace_back(mid, depth + 1);
    }
  }
  // Accepted Newton answers overstate where Newton tracked another part of the sheet (along a
  // sphere's meridian through its poles: 0.01 mm for 5e-14): the largest are searched globally
  // until one that is global exceeds every accepted answer left.
  if (accept > 0.0) {
    std::vector<size_t> order(fine.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return fine[a].foot.distance > fine[b].foot.distance; });
    double proven = 0.0;
    for (size_t k : order) {
      if (fine[k].foot.distance <= proven) break;
      measure.make_global(fine[k]);
      if (beyond(fine[k])) return fine[k].foot.distance;
      proven = std::max(proven, fine[k].foot.distance);
    }
  }
  double worst = 0.0;
  for (const Sample& s : fine) worst = std::max(worst, s.foot.distance);
  // 3. The largest local maxima between samples, found by Brent's method on [t_{i-1}, t_{i+1}]
  //    so the figure is the curve's, not its samples'.
  std::vector<size_t> maxima;
  for (size_t i = 1; i + 1 < fine.size(); ++i) {
    const double d = fine[i].foot.distance;
    if (d >= fine[i - 1].foot.distance && d >= fine[i + 1].foot.distance && d >= 0.25 * worst &&
        d > 0.0)
      maxima.push_back(i);
  }
  const size_t kept = std::min<size_t>(maxima.size(), kRefinedMaxima);
  std::partial_sort(maxima.begin(), maxima.begin() + kept, maxima.end(), [&](size_t a, size_t b) {
    return fine[a].foot.distance > fine[b].foot.distance;
  });
  struct Peak {
    double distance, t;
    size_t sample;
  };
  std::vector<Peak> peaks;
  for (size_t k = 0; k < kept; ++k) {
    const size_t i = maxima[k];
    NegativeDistance f(measure, fine[i]);
    // Brent's tolerance is relative to |t| plus an absolute part: both a millionth of the
    // bracket. The distance is flat at its peak, so its error is of the order of the square of
    // that (a billionth took 22 evaluations a peak instead of 10, for the same figures).
    const double width = fine[i + 1].t - fine[i - 1].t;
    const double relative = 1e-6 * width / (std::abs(fine[i].t) + width);
    math_BrentMinimum brent(relative, -fine[i].foot.distance, 60, 1e-6 * width);
    brent.Perform(f, fine[i - 1].t, fine[i].t, fine[i + 1].t);
    if (!brent.IsDone() || !std::isfinite(brent.Minimum())) continue;
    peaks.push_back({-brent.Minimum(), brent.Location(), i});
  }
  if (accept <= 0.0) {
    for (const Peak& p : peaks) worst = std::max(worst, p.distance);
    return worst;
  }
  // Brent maximized what Newton from the sample's foot finds, an upper bound of the distance:
  // the peaks are checked against the whole sheet from the highest down, until none left could
  // exceed the largest so far (the same figure as checking all; two global searches a peak
  // were most of a curve's measure).
  std::sort(peaks.begin(), peaks.end(),
            [](const Peak& a, const Peak& b) { return a.distance > b.distance; });
  for (const Peak& p : peaks) {
    if (p.distance <= worst) break;
    worst = std::max(worst, measure.exact(p.t, fine[p.sample].foot));
    if (worst > stop_above) break;
  }
  return worst;
}

}  // namespace

double max_deviation(const BSplineSurface& surface, const BSplineCurve& target, int samples,
                     double accept) {
  return max_deviations(surface, {target}, samples, accept).front();
}

std::vector<double> max_deviations(const BSplineSurface& surface,
                                   const std::vector<BSplineCurve>& targets, int samples,
                                   double accept, double stop_above) {
  check_measure_arguments(surface, samples, accept);
  if (!(stop_above >= 0.0)) throw InvalidInput("max_deviations: stop_above must be >= 0");
  for (const BSplineCurve& target : targets) {
    target.validate("target curve");
    if (target.dim() != 3) throw InvalidInput("target curve must be a 3D curve");
  }
  const Handle(Geom_BSplineSurface) geom = to_geom(surface);
  return guarded("measuring the deviation", [&] {
    // One inversion (the sheet cut into Bezier patches with their bounds) for all the curves:
    // building it was a fifth of each curve's measure.
    SurfaceInversion inversion(geom);
    std::vector<double> out(targets.size(), std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < targets.size(); ++i) {
      out[i] =
          measure_curve(geom, inversion, to_geom_curve(targets[i]), samples, accept, stop_above);
      if (out[i] > stop_above) break;
    }
    return out;
  });
}

}  // namespace varsurf::occ
