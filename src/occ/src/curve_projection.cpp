// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/curve_projection.hpp"

#include <Geom_BSplineSurface.hxx>
#include <ShapeAnalysis_Surface.hxx>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "affine_pre_image.hpp"
#include "varsurf/core/curve_fit.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/occ/directional_projection.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"
#include "varsurf/occ/sheet_domain.hpp"

namespace varsurf::occ {

namespace {

struct Sample {
  Eigen::Vector2d uv;
  double distance;
};

// Projects target points onto the base sheet: OCCT for the (global or continued) first guess,
// then a few bounded Newton steps on |S(u, v) - P|^2 with the core's exact evaluator.
class Projector {
 public:
  Projector(const BSplineSurface& base, const SheetDomain& domain, const BSplineCurve& target,
            double tolerance, const LineFoot* along)
      : base_(base),
        domain_(domain),
        along_(along),
        target_(target),
        tolerance_(tolerance),
        lo_(domain.lo()),
        hi_(domain.hi()),
        scale_(domain.model_size()),
        analysis_(to_geom(base)) {}

  // `neighbour` is an already projected sample at parameter `neighbour_t` (or null).
  Sample project(double t, const Sample* neighbour, double neighbour_t) {
    const Eigen::Vector3d p = target_.evaluate(t);
    const Eigen::Vector2d* previous = neighbour ? &neighbour->uv : nullptr;
    if (along_) {  // seen along a direction: the line's meeting point, continued from the last
      const Eigen::Vector2d uv = domain_.snapped((*along_)(p, previous));
      return {uv, (surface(uv, 0).row(0).transpose() - p).norm()};
    }
    // Along the curve, Newton from the previous sample's (u, v) usually suffices; OCCT decides
    // the first sample, samples that newly reach the domain's edge, and wherever the distance
    // jumps by more than the step between samples allows. (Measured: OCCT's NextValueOfUV for every
    // sample cost 6 ms per curve on a 19 x 19 sheet, most of a sheet's set-up time.)
    // From a pole or apex Newton cannot start (the sheet has no u-derivative there and it would
    // stay put): the global search decides.
    if (previous && domain_.at_degenerate_side(*previous)) previous = nullptr;
    if (previous) {
      Eigen::Vector2d uv = *previous;
      polish(p, uv);
      double d = (surface(uv, 0).row(0).transpose() - p).norm();
      // From a closed sheet's seam the curve may continue on either side of it.
      for (int c = 0; c < 2; ++c) {
        if (!domain_.on_seam(*previous, c)) continue;
        Eigen::Vector2d other = domain_.across_seam(*previous, c);
        polish(p, other);
        const double d_other = (surface(other, 0).row(0).transpose() - p).norm();
        if (d_other < d) {
          uv = other;
          d = d_other;
        }
      }
      const double step = (p - target_.evaluate(neighbour_t)).norm();
      // Newly on the domain's edge, the global search decides (a closed sheet continues on the
      // other side of its seam).
      const Eigen::Vector2d margin = 1e-9 * (hi_ - lo_);
      auto on_edge = [&](const Eigen::Vector2d& q) {
        return ((q - lo_).array() <= margin.array()).any() ||
               ((hi_ - q).array() <= margin.array()).any();
      };
      const bool reached_edge = on_edge(uv) && !on_edge(*previous);
      if (!reached_edge && d <= neighbour->distance + step + 1e-9 * scale_) return accept(t, p, uv);
    }
    const gp_Pnt point(p(0), p(1), p(2));
    const double preci = 1e-9 * scale_;
    const gp_Pnt2d guess = guarded("projecting onto the sheet", [&] {
      return previous
                 ? analysis_.NextValueOfUV(gp_Pnt2d((*previous)(0), (*previous)(1)), point, preci)
                 : analysis_.ValueOfUV(point, preci);
    });
    Eigen::Vector2d uv(guess.X(), guess.Y());
    if (!uv.allFinite()) uv = previous ? *previous : Eigen::Vector2d(0.5 * (lo_ + hi_));
    uv = uv.cwiseMax(lo_).cwiseMin(hi_);
    polish(p, uv);
    return accept(t, p, uv);
  }

 private:
  // A sample on the boundary is placed exactly on it: see SheetDomain.
  Sample accept(double t, const Eigen::Vector3d& p, const Eigen::Vector2d& projected) {
    const Eigen::Vector2d uv = domain_.snapped(projected);
    check_inside(t, p, uv);
    return {uv, (surface(uv, 0).row(0).transpose() - p).norm()};
  }

  Eigen::MatrixXd surface(const Eigen::Vector2d& uv, int order) const {
    return evaluate_surface(base_.space, base_.poles, uv(0), uv(1), order);
  }

  // Newton (Gauss-Newton where the Hessian is indefinite) with the step clipped to the domain.
  void polish(const Eigen::Vector3d& p, Eigen::Vector2d& uv) const {
    Eigen::MatrixXd s = surface(uv, 2);
    double f = (s.row(0).transpose() - p).squaredNorm();
    for (int it = 0; it < 40; ++it) {
      const Eigen::Vector3d d = s.row(0).transpose() - p;
      const Eigen::Vector3d su = s.row(1), sv = s.row(2);
      const Eigen::Vector2d g(su.dot(d), sv.dot(d));
      // Converged: the offset is normal to the sheet to rounding.
      if (g.norm() <= 1e-15 * (su.norm() + sv.norm()) * (d.norm() + scale_)) return;
      Eigen::Matrix2d h;
      h << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
      Eigen::Matrix2d full = h;
      full(0, 0) += Eigen::Vector3d(s.row(3)).dot(d);
      full(0, 1) += Eigen::Vector3d(s.row(4)).dot(d);
      full(1, 0) += Eigen::Vector3d(s.row(4)).dot(d);
      full(1, 1) += Eigen::Vector3d(s.row(5)).dot(d);
      // Coordinates held by a bound they push against stay there.
      Eigen::Vector2d free(1.0, 1.0);
      for (int c = 0; c < 2; ++c) {
        if ((uv(c) <= lo_(c) && g(c) > 0.0) || (uv(c) >= hi_(c) && g(c) < 0.0)) free(c) = 0.0;
      }
      auto solve = [&](Eigen::Matrix2d m) -> Eigen::Vector2d {
        for (int c = 0; c < 2; ++c) {
          if (free(c) == 0.0) {
            m.row(c).setZero();
            m.col(c).setZero();
            m(c, c) = 1.0;
          }
        }
        const Eigen::Vector2d rhs = -g.cwiseProduct(free);
        Eigen::LDLT<Eigen::Matrix2d> ldlt(m);
        if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || m.determinant() <= 0.0)
          return Eigen::Vector2d::Zero();
        return ldlt.solve(rhs);
      };
      Eigen::Vector2d step = solve(full);
      if (!step.allFinite() || step.isZero()) step = solve(h);
      if (!step.allFinite() || step.isZero()) return;
      bool improved = false;
      for (int half = 0; half < 20 && !improved; ++half, step *= 0.5) {
        const Eigen::Vector2d next = (uv + step).cwiseMax(lo_).cwiseMin(hi_);
        const Eigen::MatrixXd sn = surface(next, 2);
        const Eigen::Vector3d dn = sn.row(0).transpose() - p;
        const double fn = dn.squaredNorm();
        // Far from the sheet, |S - P|^2 cannot resolve the last digits of (u, v) (its change is
        // below rounding of the distance); the gradient still can.
        const double gn =
            std::hypot(Eigen::Vector3d(sn.row(1)).dot(dn), Eigen::Vector3d(sn.row(2)).dot(dn));
        if (fn < f || (fn <= f * (1.0 + 4e-16) && gn < g.norm())) {
          const double moved = (next - uv).cwiseAbs().maxCoeff();
          uv = next;
          s = sn;
          f = fn;
          improved = true;
          if (moved <= 1e-15 * (hi_ - lo_).maxCoeff()) return;
        }
      }
      if (!improved) return;
    }
  }

  // At the domain boundary the offset to the target must be normal to the sheet; a component
  // along the outward tangent means the target passes beyond the sheet's edge.
  void check_inside(double t, const Eigen::Vector3d& p, const Eigen::Vector2d& uv) const {
    const Eigen::MatrixXd s = surface(uv, 1);
    const Eigen::Vector3d d = p - s.row(0).transpose();
    if (d.norm() <= tolerance_) return;
    const Eigen::Vector2d near = 1e-7 * (hi_ - lo_);
    // A foot held at a closed sheet's seam belongs to a target crossing it (the jump check
    // says so and the target is split there): its offset is along the seam's other side, not
    // beyond an edge.
    for (int c = 0; c < 2; ++c) {
      if (domain_.closed(c) && (uv(c) <= lo_(c) + near(c) || uv(c) >= hi_(c) - near(c))) return;
    }
    for (int c = 0; c < 2; ++c) {
      // Beyond a closed sheet's seam lies the sheet's other side: a crossing shows as a jump.
      if (domain_.closed(c)) continue;
      for (int side = 0; side < 2; ++side) {
        const bool at = side == 0 ? uv(c) <= lo_(c) + near(c) : uv(c) >= hi_(c) - near(c);
        if (!at) continue;
        // Outward direction in the tangent plane, perpendicular to the boundary curve.
        const Eigen::Vector3d across = s.row(1 + c), along = s.row(2 - c);
        if (along.norm() <= 1e-12 * scale_ || across.norm() <= 1e-12 * scale_) continue;
        const Eigen::Vector3d a = along.normalized();
        Eigen::Vector3d out = across - across.dot(a) * a;
        if (out.norm() <= 1e-9 * across.norm()) continue;
        out = (side == 0 ? -1.0 : 1.0) * out.normalized();
        const double beyond = d.dot(out);
        if (beyond > tolerance_) {
          std::ostringstream msg;
          msg << "the target curve leaves the face at (" << p(0) << ", " << p(1) << ", " << p(2)
              << ") (t = " << t << "): from there on it lies beyond the sheet's "
              << (c == 0 ? "u" : "v") << (side == 0 ? "-min" : "-max") << " boundary (" << beyond
              << " mm past it there, " << d.norm()
              << " mm from the sheet); no orthogonal projection exists there";
          throw InvalidInput(msg.str());
        }
      }
    }
  }

  const BSplineSurface& base_;
  const SheetDomain& domain_;
  const LineFoot* along_;  // null: orthogonal projection
  const BSplineCurve& target_;
  double tolerance_;
  Eigen::Vector2d lo_, hi_;
  double scale_;  // model size, for relative tolerances
  ShapeAnalysis_Surface analysis_;
};

// Least-squares fit of a clamped B-spline with the given knots through (t_k, uv_k), interpolating
// both ends; the parameters are the samples' own t. Banded normal equations: B-spline least
// squares with samples in every span is well conditioned.
// Why not Geom2dAPI_PointsToBSpline: it chooses its own knots and raises the degree. Measured on
// a diagonal line and an arc over a curved 8-span sheet, at the same 1e-7 fit tolerance, it gave
// 66 and 144 degree-5 poles where knots at the sheet's knot-line crossings give 25 and 49 cubic
// ones; every pre-image piece and degree multiplies the solver's constraint samples.
BSplineCurve fit(const std::map<double, Sample>& samples, int degree,
                 const std::vector<double>& knots) {
  std::vector<double> t;
  Eigen::MatrixXd uv(static_cast<Eigen::Index>(samples.size()), 2);
  for (const auto& [at, s] : samples) {
    uv.row(static_cast<Eigen::Index>(t.size())) = s.uv.transpose();
    t.push_back(at);
  }
  try {
    return fit_clamped_curve(t, uv, degree, knots);
  } catch (const SolveFailure&) {
    throw GeometryError("projection: the pre-image fit is singular (too few samples per span)");
  }
}

// Samples of the pre-image, ordered by t; new ones start from their left neighbour's (u, v).
class Samples {
 public:
  Samples(Projector& projector, const SheetDomain& domain)
      : projector_(projector), domain_(domain) {}

  const Sample& add(double t) {
    auto it = points_.lower_bound(t);
    if (it != points_.end() && it->first == t) return it->second;
    const std::pair<const double, Sample>* neighbour = nullptr;
    if (it != points_.begin()) {
      neighbour = &*std::prev(it);
    } else if (it != points_.end()) {
      neighbour = &*it;
    }
    if (points_.size() >= 500000)
      throw InvalidInput("projection: the pre-image needs too many samples (does it settle?)");
    const Sample s = neighbour ? projector_.project(t, &neighbour->second, neighbour->first)
                               : projector_.project(t, nullptr, 0.0);
    const auto added = points_.emplace_hint(it, t, s);
    for (int c = 0; c < 2; ++c) {
      // At a side that collapses to a point (a sphere's pole) the other coordinate is free.
      if (domain_.degenerate(c, -1) || domain_.degenerate(c, 1)) {
        settle(
            added,
            [&](const Sample& k) {
              const int side = domain_.side(k.uv, c);
              return side != 0 && domain_.degenerate(c, side);
            },
            [&](Sample& k, const Sample& anchor) { k.uv(1 - c) = anchor.uv(1 - c); });
      }
    }
    for (int c = 0; c < 2; ++c) {
      if (!domain_.closed(c)) continue;
      // On a closed sheet's seam a sample is on both of its sides.
      settle(
          added, [&](const Sample& k) { return domain_.on_seam(k.uv, c); },
          [&](Sample& k, const Sample& anchor) {
            const double lo = domain_.lo()(c), hi = domain_.hi()(c);
            k.uv(c) = anchor.uv(c) - lo < hi - anchor.uv(c) ? lo : hi;
          });
    }
    return added->second;
  }
  const std::map<double, Sample>& points() const { return points_; }
  size_t count_in(double a, double b) const {
    return static_cast<size_t>(std::distance(points_.lower_bound(a), points_.upper_bound(b)));
  }

 private:
  using Iterator = std::map<double, Sample>::iterator;

  // A sample whose sheet point does not decide a coordinate (`free`) takes it from the nearest
  // sample that is decided (to its left, else to its right) by `assign`, so that the pre-image
  // runs on continuously instead of jumping: from a seam into the sheet on the curve's side, from
  // a pole along the curve's meridian. A curve that starts there learns from its second sample.
  template <class Free, class Assign>
  void settle(Iterator added, Free free, Assign assign) {
    if (free(added->second)) {
      for (Iterator k = added; k != points_.begin();) {
        if (!free((--k)->second)) return assign(added->second, k->second);
      }
      for (Iterator k = std::next(added); k != points_.end(); ++k) {
        if (!free(k->second)) return assign(added->second, k->second);
      }
      // None decided (a curve along the seam): the same as its neighbour, for one side only.
      if (added != points_.begin()) return assign(added->second, std::prev(added)->second);
      if (std::next(added) != points_.end()) assign(added->second, std::next(added)->second);
      return;
    }
    // Free samples at either end of the curve with no anchor on their far side follow this one.
    Iterator k = added;
    while (k != points_.begin() && free(std::prev(k)->second)) --k;
    if (k == points_.begin())
      for (; k != added; ++k) assign(k->second, added->second);
    k = std::next(added);
    while (k != points_.end() && free(k->second)) ++k;
    if (k == points_.end())
      for (Iterator j = std::next(added); j != points_.end(); ++j) assign(j->second, added->second);
  }

  Projector& projector_;
  const SheetDomain& domain_;
  std::map<double, Sample> points_;
};

// Interior breakpoints of the pre-image and their multiplicities.
class Breaks {
 public:
  Breaks(double t0, double t1, int degree)
      : t0_(t0), t1_(t1), merge_(1e-9 * (t1 - t0)), degree_(degree) {}

  // A breakpoint where the pre-image has C^continuity (merged with a close one).
  void add(double t, int continuity) {
    if (!(t > t0_ + merge_ && t < t1_ - merge_)) return;
    const int mult = std::clamp(degree_ - std::max(continuity, 0), 1, degree_);
    auto it = mults_.lower_bound(t - merge_);
    if (it != mults_.end() && it->first <= t + merge_) {
      it->second = std::max(it->second, mult);
    } else {
      mults_.emplace(t, mult);
    }
  }
  std::vector<double> flat() const {
    std::vector<double> k(static_cast<size_t>(degree_ + 1), t0_);
    for (const auto& [t, m] : mults_) k.insert(k.end(), static_cast<size_t>(m), t);
    k.insert(k.end(), static_cast<size_t>(degree_ + 1), t1_);
    return k;
  }
  std::vector<double> values() const {
    std::vector<double> v{t0_};
    for (const auto& [t, m] : mults_) v.push_back(t);
    v.push_back(t1_);
    return v;
  }
  int poles() const {
    int n = degree_ + 1;
    for (const auto& [t, m] : mults_) n += m;
    return n;
  }

 private:
  double t0_, t1_, merge_;
  int degree_;
  std::map<double, int> mults_;
};

// Where the pre-image crosses an interior knot line of the sheet, the foot point moves with the
// sheet's normal, which is one order less smooth there: the pre-image gets a breakpoint of that
// continuity (else the fit converges slowly around the kink).
void add_knot_crossings(const SplineSpace& space, Samples& samples, Breaks& breaks,
                        double t_range) {
  for (int c = 0; c < 2; ++c) {
    const std::vector<double>& flat = c == 0 ? space.knots_u : space.knots_v;
    const int degree = c == 0 ? space.degree_u : space.degree_v;
    std::vector<double> values;
    std::vector<int> mults;
    split_knots(flat, values, mults);
    const double eps = 1e-10 * (flat.back() - flat.front());
    for (size_t k = 1; k + 1 < values.size(); ++k) {
      const double line = values[k];
      const int continuity = degree - mults[k] - 1;
      auto side = [&](const Sample& s) {
        return s.uv(c) > line + eps ? 1 : (s.uv(c) < line - eps ? -1 : 0);
      };
      // Pairs of samples strictly on opposite sides, with only on-line samples between them.
      std::vector<std::pair<double, double>> brackets;
      double last_t = 0.0;
      int last_side = 0;
      for (const auto& [t, s] : samples.points()) {
        const int sd = side(s);
        if (sd == 0) continue;
        if (last_side != 0 && sd != last_side) brackets.emplace_back(last_t, t);
        last_t = t;
        last_side = sd;
      }
      for (auto [a, b] : brackets) {
        const int side_a = side(samples.points().at(a));
        for (int it = 0; it < 100 && b - a > 1e-13 * t_range; ++it) {
          const double mid = 0.5 * (a + b);
          const int sd = side(samples.add(mid));
          if (sd == 0) {
            a = b = mid;
          } else if (sd == side_a) {
            a = mid;
          } else {
            b = mid;
          }
        }
        breaks.add(0.5 * (a + b), continuity);
      }
    }
  }
}

// Every knot span gets samples spread over all of it (one in each of `count` equal parts), so
// that the least-squares fit is well posed there. Bisection samples cluster at a crossing and do
// not count for the rest of the span.
void fill_spans(Samples& samples, const std::vector<double>& span_ends, int count) {
  for (size_t s = 0; s + 1 < span_ends.size(); ++s) {
    const double a = span_ends[s], h = (span_ends[s + 1] - a) / count;
    for (int i = 0; i < count; ++i) {
      if (samples.count_in(a + i * h, a + (i + 1) * h) == 0) samples.add(a + (i + 0.5) * h);
    }
  }
}

}  // namespace

PreImage project_curve(const BSplineSurface& base, const BSplineCurve& target,
                       const ProjectionOptions& options) {
  base.validate();
  target.validate("target curve");
  if (target.dim() != 3) throw InvalidInput("target curve must be a 3D curve");
  if (options.samples < 0 || options.samples > 1000000 || options.samples_per_span < 1 ||
      options.samples_per_span > 10000 || options.min_samples < 2 || options.min_samples > 1000000)
    throw InvalidInput("projection: sample counts out of range");
  if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance) ||
      !(options.fit_tolerance > 0.0) || !(options.fit_tolerance <= 0.1))
    throw InvalidInput(
        "projection: tolerance must be finite and not negative, fit_tolerance in (0, 0.1] "
        "(a fraction of the sheet's parameter domain)");
  if (options.degree < 1 || options.degree > 9)
    throw InvalidInput("projection: pre-image degree must be in 1..9");
  if (options.max_poles < 4) throw InvalidInput("projection: max_poles must be at least 4");
  const int degree = std::min(std::max(options.degree, target.degree), 9);
  const double t0 = target.first(), t1 = target.last(), t_range = t1 - t0;

  // Sample parameters: evenly within each polynomial span of the target, span ends included.
  std::vector<double> target_breaks;
  std::vector<int> target_mults;
  split_knots(target.knots, target_breaks, target_mults);
  const int spans = static_cast<int>(target_breaks.size()) - 1;
  const int wanted = options.samples > 0
                         ? options.samples
                         : std::max(options.min_samples, options.samples_per_span * spans);
  const int per_span = std::max(degree + 1, (wanted + spans - 1) / spans);
  std::vector<double> ts;
  for (int s = 0; s < spans; ++s) {
    for (int i = 0; i < per_span; ++i)
      ts.push_back(target_breaks[s] + (target_breaks[s + 1] - target_breaks[s]) * i / per_span);
  }
  ts.push_back(t1);
  const SheetDomain domain(base);
  if (std::optional<PreImage> exact =
          affine_pre_image(base, domain, target, options.direction, ts, degree))
    return *exact;
  std::optional<LineFoot> along;
  if (!options.direction.isZero(0.0)) along.emplace(base, options.direction);
  Projector projector(base, domain, target, options.tolerance, along ? &*along : nullptr);
  Samples samples(projector, domain);
  for (double t : ts) samples.add(t);

  // A target along the sheet's normal projects to (nearly) one point: no pre-image can carry it.
  double target_length = 0.0, image_length = 0.0;
  Eigen::VectorXd last_target;
  Eigen::Vector3d last_image = Eigen::Vector3d::Zero();
  for (const auto& [t, s] : samples.points()) {
    const Eigen::VectorXd on_target = target.evaluate(t);
    const Eigen::Vector3d on_sheet = base.evaluate(s.uv(0), s.uv(1));
    if (last_target.size() > 0) {
      target_length += (on_target - last_target).norm();
      image_length += (on_sheet - last_image).norm();
    }
    last_target = on_target;
    last_image = on_sheet;
  }
  if (target_length > 0.0 && image_length < 1e-3 * target_length) {
    std::ostringstream msg;
    msg << std::setprecision(3) << "the target curve runs along the sheet's normal: its "
        << target_length << " mm long path projects onto " << image_length
        << " mm of the sheet, so no sheet over this face can contain it (tilt the curve or pick "
           "another base face)";
    throw InvalidInput(msg.str());
  }

  // A pre-image that jumps between neighbouring samples is refined until it is smooth or the jump
  // proves to be a discontinuity (seam of a closed sheet, a fold, a ridge of equal distances).
  const Eigen::Vector2d lo(base.space.u_first(), base.space.v_first());
  const Eigen::Vector2d hi(base.space.u_last(), base.space.v_last());
  const Eigen::Vector2d width = hi - lo;
  for (auto it = samples.points().begin(); std::next(it) != samples.points().end();) {
    const auto next = std::next(it);
    const double jump =
        (next->second.uv - it->second.uv).cwiseQuotient(width).cwiseAbs().maxCoeff();
    if (jump <= 0.05) {
      ++it;
      continue;
    }
    if (next->first - it->first < 1e-9 * t_range) {
      std::ostringstream msg;
      msg << "the target curve's projection onto the sheet jumps at t = " << it->first
          << " from (u, v) = (" << it->second.uv(0) << ", " << it->second.uv(1) << ") to ("
          << next->second.uv(0) << ", " << next->second.uv(1) << "): ";
      // From one side of a closed sheet's seam to the other: the curve goes around it.
      int seam = -1;
      for (int c = 0; c < 2; ++c) {
        const bool around = std::abs(next->second.uv(c) - it->second.uv(c)) > 0.5 * width(c);
        if (domain.closed(c) && around) seam = c;
      }
      if (seam >= 0) {
        msg << "it crosses the seam of the closed face (where " << (seam == 0 ? "u" : "v") << " = "
            << lo(seam) << " meets " << hi(seam)
            << "), and one pre-image cannot run on both sides of it; split the curve at the "
               "seam";
      } else {
        msg << "it crosses a seam or fold of the sheet, or is equally close to two regions";
      }
      throw InvalidInput(msg.str());
    }
    samples.add(0.5 * (it->first + next->first));  // `it` stays valid: std::map
  }

  // Breakpoints: the target's (as smooth as the target there) and the sheet's knot lines.
  Breaks breaks(t0, t1, degree);
  for (size_t i = 1; i + 1 < target_breaks.size(); ++i)
    breaks.add(target_breaks[i], target.degree - target_mults[i]);
  add_knot_crossings(base.space, samples, breaks, t_range);

  // Fit, then refine the knot vector where the fit misses the samples; stop at the tolerance, at
  // max_poles, or when refining no longer pays (the samples' own noise).
  // The fit may pass beyond the domain where the pre-image runs along or touches the boundary;
  // the solver clamps it back (a fit error like any other) but refuses an excursion beyond 1e-7
  // of the domain: one beyond `reach` counts as a miss of the fit, so those spans are refined.
  // (Clipping the poles instead bends the fit: a convex pre-image touching the boundary has its
  // control polygon beyond it; clipped, it was 0.007 mm off a circle touching a plane's side.)
  const double fit_tol = options.fit_tolerance * width.maxCoeff();
  // Each direction's miss relative to its own side: u and v may be in different units (radians
  // and mm on a cylinder), and a miss in the short one would otherwise count for little.
  auto miss = [&](const Eigen::Vector2d& d) {
    return d.cwiseQuotient(width).norm() * width.maxCoeff();
  };
  const Eigen::Vector2d reach = 1e-8 * width;
  auto excursion = [&](const Eigen::Vector2d& uv) {
    const Eigen::Vector2d out = (lo - uv).cwiseMax(uv - hi).cwiseMax(0.0);
    return out.cwiseQuotient(reach).maxCoeff();
  };
  const int per_knot_span = 2 * (degree + 1);
  BSplineCurve curve;
  double best = std::numeric_limits<double>::infinity();
  int stalls = 0;
  for (int round = 0; round < 40; ++round) {
    const std::vector<double> kb = breaks.values();
    fill_spans(samples, kb, per_knot_span);
    const BSplineCurve trial = fit(samples.points(), degree, breaks.flat());
    std::vector<double> span_error(kb.size() - 1, 0.0);
    double worst = 0.0;
    for (const auto& [t, s] : samples.points()) {
      const int span =
          std::clamp(static_cast<int>(std::upper_bound(kb.begin(), kb.end(), t) - kb.begin()) - 1,
                     0, static_cast<int>(kb.size()) - 2);
      const Eigen::Vector2d at = trial.evaluate(t);
      const double e = std::max(miss(at - s.uv), fit_tol * excursion(at));
      span_error[span] = std::max(span_error[span], e);
      worst = std::max(worst, e);
    }
    stalls = worst < 0.5 * best ? 0 : stalls + 1;
    if (worst < best) {
      curve = trial;
      best = worst;
    }
    if (best <= fit_tol || stalls >= 3) break;
    std::vector<double> inserts;
    for (size_t s = 0; s < span_error.size(); ++s) {
      if (span_error[s] > fit_tol) inserts.push_back(0.5 * (kb[s] + kb[s + 1]));
    }
    if (breaks.poles() + static_cast<int>(inserts.size()) > options.max_poles) break;
    for (double t : inserts) breaks.add(t, degree - 1);
  }
  // No fit with a finite error: the samples (or the sheet's domain) overflow the arithmetic.
  if (curve.pole_count() == 0)
    throw InvalidInput("projection: no pre-image fit has a finite error (coordinates too large)");

  // Poles within the snap margin of a bound go onto it: where the samples run along the
  // boundary, the fit's rounding would otherwise leave the pre-image a hair off it (see
  // SheetDomain). If refinement stopped short of keeping the fit within reach of the domain,
  // clipping the poles keeps the curve in it (convex hull) at the cost of a larger fit error.
  bool beyond = false;
  for (const auto& [t, s] : samples.points()) beyond = beyond || excursion(curve.evaluate(t)) > 1.0;
  const Eigen::Vector2d margin = SheetDomain::snap_margin * width;
  for (int i = 0; i < curve.pole_count(); ++i) {
    Eigen::Vector2d pole = curve.poles.row(i).transpose();
    if (beyond) pole = pole.cwiseMax(lo).cwiseMin(hi);
    for (int c = 0; c < 2; ++c) {
      if (std::abs(pole(c) - lo(c)) <= margin(c)) pole(c) = lo(c);
      if (std::abs(pole(c) - hi(c)) <= margin(c)) pole(c) = hi(c);
    }
    curve.poles.row(i) = pole.transpose();
  }

  PreImage out;
  out.curve = curve;
  out.boundary_t = t0;
  for (const auto& [t, s] : samples.points()) {
    out.fit_error = std::max(out.fit_error, (curve.evaluate(t) - s.uv).norm());
    out.max_distance = std::max(out.max_distance, s.distance);
    // A closed direction's seam is inside the sheet, not on its boundary.
    const bool on_boundary = (domain.side(s.uv, 0) != 0 && !domain.closed(0)) ||
                             (domain.side(s.uv, 1) != 0 && !domain.closed(1));
    if (on_boundary && s.distance >= out.boundary_distance) {
      out.boundary_distance = s.distance;
      out.boundary_t = t;
    }
  }
  out.curve.validate("pre-image");
  return out;
}

}  // namespace varsurf::occ
