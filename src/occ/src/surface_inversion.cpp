// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/surface_inversion.hpp"

#include <BSplSLib_Cache.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomConvert_BSplineSurfaceToBezierSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TColStd_Array1OfReal.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace varsurf::occ {

namespace {

struct Box {
  std::array<double, 3> lo{{std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity()}};
  std::array<double, 3> hi{{-std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity()}};
  void add(const gp_XYZ& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p.Coord(k + 1));
      hi[k] = std::max(hi[k], p.Coord(k + 1));
    }
  }
  void add(const Box& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], b.lo[k]);
      hi[k] = std::max(hi[k], b.hi[k]);
    }
  }
  double square_distance(const gp_XYZ& p) const {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double x = p.Coord(k + 1);
      const double d = x < lo[k] ? lo[k] - x : x > hi[k] ? x - hi[k] : 0.0;
      s += d * d;
    }
    return s;
  }
};

// Where t falls on the sorted breakpoints: interval index plus the fraction across it.
double grid_coordinate(const std::vector<double>& breaks, double t) {
  const int n = static_cast<int>(breaks.size()) - 1;
  const auto it = std::upper_bound(breaks.begin(), breaks.end(), t);
  const int i = std::min(std::max(static_cast<int>(it - breaks.begin()) - 1, 0), n - 1);
  const double f = (t - breaks[i]) / (breaks[i + 1] - breaks[i]);
  return i + std::min(std::max(f, 0.0), 1.0);
}

}  // namespace

struct SurfaceInversion::Parts {
  // A node of the patch tree covers patches [i0, i1) x [j0, j1); leaves cover one patch.
  struct Node {
    Box box;
    int i0, i1, j0, j1;
    int child[2] = {-1, -1};
  };
  // Newton's starts: a (degree + 1)^2 grid of surface points per patch.
  struct Seed {
    gp_XYZ point;
    double u, v;
  };

  Handle(Geom_BSplineSurface) surface;
  // The current span's polynomial, for fast repeated evaluation. GeomAdaptor_Surface keeps one
  // too, but evaluates every point on a knot line (every sample of a curve along the sheet's
  // boundary) by de Boor's algorithm from scratch, and locates the knots of every point first to
  // find out: that was a sixth of measuring benchmark 2's curves (perf).
  Handle(BSplSLib_Cache) cache;
  void d2(double u, double v, gp_Pnt& s, gp_Vec& su, gp_Vec& sv, gp_Vec& suu, gp_Vec& svv,
          gp_Vec& suv) {
    if (!cache->IsCacheValid(u, v))
      cache->BuildCache(u, v, surface->UKnotSequence(), surface->VKnotSequence(), surface->Poles(),
                        surface->Weights());
    cache->D2(u, v, s, su, sv, suu, svv, suv);
  }
  gp_Pnt value(double u, double v) {
    if (!cache->IsCacheValid(u, v))
      cache->BuildCache(u, v, surface->UKnotSequence(), surface->VKnotSequence(), surface->Poles(),
                        surface->Weights());
    gp_Pnt s;
    cache->D0(u, v, s);
    return s;
  }
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  double scale = 1.0;  // the surface's size: absolute tolerances are relative to it
  std::vector<double> breaks_u, breaks_v;
  std::vector<Node> nodes;
  std::vector<std::vector<Seed>> seeds;             // per patch, index i * patches_v + j
  std::vector<Handle(Geom_BezierSurface)> patches;  // the same index
  int patches_v = 0;
  long fallbacks = 0;

  int build(const std::vector<Box>& patch_boxes, int i0, int i1, int j0, int j1);
  // Newton on |S(u, v) - p|^2 / 2 inside the parameter box, or inside `within` (u0, u1, v0, v1).
  // `settled` says whether it converged.
  SurfacePoint descend(const gp_XYZ& p, double u, double v, bool& settled,
                       const std::array<double, 4>* within = nullptr);
  // Newton kept inside one piece of the surface first (on a folded surface a start inside the
  // piece that holds the closest point can still wander off to another minimum), then over the
  // whole surface from there.
  SurfacePoint descend_in(const gp_XYZ& p, double u, double v, const std::array<double, 4>& piece,
                          bool& settled);
  SurfacePoint global_search(const gp_Pnt& p);
  // A lower bound on the distance from p to a Bezier piece: the larger of its poles' box's
  // distance and of the slab bound along the direction from the best foot point to p (the piece
  // is in its poles' hull, rational or not). The slab bound is second-order tight around a foot
  // point, where the box alone needs pieces as small as the wanted accuracy.
  double lower_bound(const Handle(Geom_BezierSurface) & piece, const gp_XYZ& p,
                     const SurfacePoint& best);
  // How close the bound must come to the best distance before a piece is let go.
  double slack(const SurfacePoint& best) const;
  // Whether the settled best point lies in the parameter box and the squared distance to p is
  // convex there (its Hessian positive definite on a 3 x 3 grid over the box): then the best
  // point is the box's only minimum. On the concave side of a face neither bound tightens around
  // a foot point faster than the square of the piece's size, and splitting on to prove it cost
  // 10 to 20 times the search.
  bool holds_only_minimum(const gp_XYZ& p, const std::array<double, 4>& box,
                          const SurfacePoint& best, bool best_settled);
  // Quarters of a patch (its Bezier form over [ua, ub] x [va, vb]) that may hold a point nearer
  // than the best: Newton from each one's centre, and their quarters in turn, until no piece can
  // (branch and bound), or the depth or the patch's piece budget runs out.
  void subdivide(const gp_XYZ& p, const Handle(Geom_BezierSurface) & patch, double ua, double ub,
                 double va, double vb, int depth, SurfacePoint& best, bool& best_settled,
                 int& budget);
};

namespace {

Box box_of(const Handle(Geom_BezierSurface) & patch) {
  // With positive weights a rational patch is a convex combination of its poles too.
  Box box;
  for (int a = 1; a <= patch->NbUPoles(); ++a)
    for (int b = 1; b <= patch->NbVPoles(); ++b) box.add(patch->Pole(a, b).XYZ());
  return box;
}

// A patch that may hold a closer point is split into quarters, each with its own bound and Newton
// start, as long as one may: wild patches hold several local minima, and the nearest start need
// not lead to the closest (random folded rational faces measured up to 3.4 mm from their own
// edges, on 26 of 1,200, when the splitting stopped at a fixed depth of 3; now 1). The depth and
// the pieces per patch are capped: an uncapped search, or OCCT's global search past the cap, took
// three times as long on wild faces for a few fewer misses (4 in 2,640 edges).
constexpr int kMaxDepth = 24;
constexpr int kPieceBudget = 64;
// Levels below a patch from which a convex piece around the best point is let go unsplit (see
// holds_only_minimum); larger pieces are split regardless.
constexpr int kShortcutDepth = 2;
// A piece is searched only while its bound leaves room for a point nearer than the best by this
// fraction of the best distance (and by 1e-12 of the surface's size).
constexpr double kRelative = 1e-7;

}  // namespace

double SurfaceInversion::Parts::lower_bound(const Handle(Geom_BezierSurface) & piece,
                                            const gp_XYZ& p, const SurfacePoint& best) {
  const double from_box = std::sqrt(box_of(piece).square_distance(p));
  if (!(std::isfinite(best.distance) && best.distance > 1e-12 * scale)) return from_box;
  const gp_XYZ n = (p - value(best.u, best.v).XYZ()) / best.distance;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (int a = 1; a <= piece->NbUPoles(); ++a)
    for (int b = 1; b <= piece->NbVPoles(); ++b) {
      const double along = n.Dot(p - piece->Pole(a, b).XYZ());
      low = std::min(low, along);
      high = std::max(high, along);
    }
  const double from_slab = low > 0.0 ? low : high < 0.0 ? -high : 0.0;
  return std::max(from_box, from_slab);
}

double SurfaceInversion::Parts::slack(const SurfacePoint& best) const {
  return std::max(1e-12 * scale, kRelative * best.distance);
}

bool SurfaceInversion::Parts::holds_only_minimum(const gp_XYZ& p, const std::array<double, 4>& box,
                                                 const SurfacePoint& best, bool best_settled) {
  if (!best_settled || best.u < box[0] || best.u > box[1] || best.v < box[2] || best.v > box[3])
    return false;
  for (int a = 0; a <= 2; ++a)
    for (int b = 0; b <= 2; ++b) {
      const double u = box[0] + 0.5 * a * (box[1] - box[0]);
      const double v = box[2] + 0.5 * b * (box[3] - box[2]);
      gp_Pnt s;
      gp_Vec su, sv, suu, svv, suv;
      d2(u, v, s, su, sv, suu, svv, suv);
      const gp_Vec r(p, s);
      const double huu = su.Dot(su) + suu.Dot(r), hvv = sv.Dot(sv) + svv.Dot(r);
      const double huv = su.Dot(sv) + suv.Dot(r);
      if (!(huu > 0.0 && hvv > 0.0 && huu * hvv - huv * huv > 1e-6 * huu * hvv)) return false;
    }
  return true;
}

void SurfaceInversion::Parts::subdivide(const gp_XYZ& p, const Handle(Geom_BezierSurface) & patch,
                                        double ua, double ub, double va, double vb, int depth,
                                        SurfacePoint& best, bool& best_settled, int& budget) {
  if (depth == 0 || budget <= 0) return;
  struct Quarter {
    Handle(Geom_BezierSurface) patch;
    double bound, ua, ub, va, vb;
  };
  std::array<Quarter, 4> quarters;
  for (int q = 0; q < 4; ++q) {
    const double s0 = 0.5 * (q / 2), t0 = 0.5 * (q % 2);
    Handle(Geom_BezierSurface) piece = Handle(Geom_BezierSurface)::DownCast(patch->Copy());
    piece->Segment(s0, s0 + 0.5, t0, t0 + 0.5);  // a Bezier patch's own parameters are [0, 1]
    const double qa = ua + (ub - ua) * s0, qc = va + (vb - va) * t0;
    quarters[q] = Quarter{piece, lower_bound(piece, p, best), qa, qa + 0.5 * (ub - ua),
                          qc,    qc + 0.5 * (vb - va)};
  }
  --budget;
  std::sort(quarters.begin(), quarters.end(),
            [](const Quarter& a, const Quarter& b) { return a.bound < b.bound; });
  for (const Quarter& q : quarters) {
    if (q.bound >= best.distance - slack(best)) break;
    bool settled = false;
    const SurfacePoint candidate =
        descend_in(p, 0.5 * (q.ua + q.ub), 0.5 * (q.va + q.vb), {q.ua, q.ub, q.va, q.vb}, settled);
    if (candidate.distance < best.distance) {
      best = candidate;
      best_settled = settled;
    }
    // The bound again: the best point (and with it the slab's direction) may have moved.
    // Pieces of at least a sixteenth of a patch are split regardless: a fold that large can
    // look convex at the grid's nine points (random folded faces missed by up to 0.94 mm).
    if (lower_bound(q.patch, p, best) < best.distance - slack(best) &&
        !(depth <= kMaxDepth - kShortcutDepth &&
          holds_only_minimum(p, {q.ua, q.ub, q.va, q.vb}, best, best_settled)))
      subdivide(p, q.patch, q.ua, q.ub, q.va, q.vb, depth - 1, best, best_settled, budget);
  }
}

int SurfaceInversion::Parts::build(const std::vector<Box>& patch_boxes, int i0, int i1, int j0,
                                   int j1) {
  const int id = static_cast<int>(nodes.size());
  nodes.push_back(Node{Box{}, i0, i1, j0, j1});
  if (i1 - i0 == 1 && j1 - j0 == 1) {
    nodes[id].box = patch_boxes[i0 * patches_v + j0];
    return id;
  }
  int a, b;
  if (i1 - i0 >= j1 - j0) {
    const int im = (i0 + i1) / 2;
    a = build(patch_boxes, i0, im, j0, j1);
    b = build(patch_boxes, im, i1, j0, j1);
  } else {
    const int jm = (j0 + j1) / 2;
    a = build(patch_boxes, i0, i1, j0, jm);
    b = build(patch_boxes, i0, i1, jm, j1);
  }
  nodes[id].child[0] = a;
  nodes[id].child[1] = b;
  nodes[id].box = nodes[a].box;
  nodes[id].box.add(nodes[b].box);
  return id;
}

SurfacePoint SurfaceInversion::Parts::descend(const gp_XYZ& p, double u, double v, bool& settled,
                                              const std::array<double, 4>* within) {
  const double u0 = within ? (*within)[0] : this->u0, u1 = within ? (*within)[1] : this->u1;
  const double v0 = within ? (*within)[2] : this->v0, v1 = within ? (*within)[3] : this->v1;
  settled = false;
  u = std::min(std::max(u, u0), u1);
  v = std::min(std::max(v, v0), v1);
  gp_Pnt s;
  gp_Vec su, sv, suu, svv, suv;
  d2(u, v, s, su, sv, suu, svv, suv);
  gp_Vec r(p, s);
  double f = r.SquareMagnitude();
  const double tiny = 1e-13 * scale;
  for (int iteration = 0; iteration < 60 && !settled; ++iteration) {
    const double gu = su.Dot(r), gv = sv.Dot(r);
    // A variable at its bound whose descent direction points out of the box stays there: that
    // is how a closest point on the boundary is found.
    const bool free_u = !((u <= u0 && gu > 0) || (u >= u1 && gu < 0));
    const bool free_v = !((v <= v0 && gv > 0) || (v >= v1 && gv < 0));
    const double a = su.Dot(su), b = su.Dot(sv), c = sv.Dot(sv);
    double huu = a + suu.Dot(r), huv = b + suv.Dot(r), hvv = c + svv.Dot(r);
    double du = 0.0, dv = 0.0;
    for (int attempt = 0; attempt < 2; ++attempt) {
      // Newton first; where its Hessian is not positive definite (far from a convex spot), the
      // Gauss-Newton metric with a little damping, which always descends.
      if (attempt == 1) {
        const double damping = 1e-10 * (a + c) + 1e-300;
        huu = a + damping;
        huv = b;
        hvv = c + damping;
      }
      if (free_u && free_v) {
        const double det = huu * hvv - huv * huv;
        if (huu > 0 && hvv > 0 && det > 1e-14 * huu * hvv) {
          du = -(hvv * gu - huv * gv) / det;
          dv = -(huu * gv - huv * gu) / det;
          break;
        }
      } else if (free_u) {
        if (huu > 0) {
          du = -gu / huu;
          break;
        }
      } else if (free_v) {
        if (hvv > 0) {
          dv = -gv / hvv;
          break;
        }
      } else {
        break;  // a corner, held by both bounds
      }
    }
    // Newton's own step being negligible on the surface is convergence (quadratic near the end).
    const bool last = (su * du + sv * dv).Magnitude() <= tiny + 1e-9 * std::sqrt(f);
    if (du == 0.0 && dv == 0.0) {
      settled = true;
      break;
    }
    // Backtracking along the clamped step until the distance drops (Armijo).
    bool moved = false;
    for (double alpha = 1.0; alpha > 1e-12; alpha *= 0.5) {
      const double un = std::min(std::max(u + alpha * du, u0), u1);
      const double vn = std::min(std::max(v + alpha * dv, v0), v1);
      gp_Pnt sn;
      gp_Vec sun, svn, suun, svvn, suvn;
      d2(un, vn, sn, sun, svn, suun, svvn, suvn);
      const gp_Vec rn(p, sn);
      const double fn = rn.SquareMagnitude();
      const double predicted = gu * (un - u) + gv * (vn - v);  // <= 0 for a descent step
      if (fn <= f + 1e-4 * predicted) {
        const double travel = s.Distance(sn);
        u = un;
        v = vn;
        s = sn;
        su = sun;
        sv = svn;
        suu = suun;
        svv = svvn;
        suv = suvn;
        r = rn;
        const double previous = f;
        f = fn;
        moved = true;
        // Settled when the point no longer moves on the surface, or the distance stopped
        // changing at machine precision.
        settled = last || travel <= tiny + 1e-10 * std::sqrt(f) || previous - f <= 1e-15 * previous;
        break;
      }
    }
    if (!moved) {
      // No descent along Newton's step: rounding. Stationary if the point is on the surface to
      // rounding or the free gradient is (nearly) normal to the surface.
      const double g = std::hypot(free_u ? gu : 0.0, free_v ? gv : 0.0);
      settled = last || std::sqrt(f) <= tiny || g <= 1e-7 * std::sqrt(a + c) * std::sqrt(f);
      break;
    }
  }
  return SurfacePoint{u, v, std::sqrt(f)};
}

SurfacePoint SurfaceInversion::Parts::descend_in(const gp_XYZ& p, double u, double v,
                                                 const std::array<double, 4>& piece,
                                                 bool& settled) {
  const SurfacePoint inside = descend(p, u, v, settled, &piece);
  return descend(p, inside.u, inside.v, settled);
}

SurfacePoint SurfaceInversion::Parts::global_search(const gp_Pnt& p) {
  ++fallbacks;
  SurfacePoint best{u0, v0, std::numeric_limits<double>::infinity()};
  GeomAPI_ProjectPointOnSurf projector(p, surface, u0, u1, v0, v1);
  if (projector.IsDone() && projector.NbPoints() > 0) {
    projector.LowerDistanceParameters(best.u, best.v);
    best.distance = projector.LowerDistance();
  }
  // Interior extrema miss closest points on the boundary; ShapeAnalysis also tries those.
  ShapeAnalysis_Surface analysis(surface);
  const gp_Pnt2d uv = analysis.ValueOfUV(p, 1e-12);
  if (analysis.Gap() < best.distance) best = SurfacePoint{uv.X(), uv.Y(), analysis.Gap()};
  return best;
}

SurfaceInversion::SurfaceInversion(const Handle(Geom_BSplineSurface) & surface)
    : parts_(new Parts) {
  Parts& parts = *parts_;
  parts.surface = surface;
  parts.cache = new BSplSLib_Cache(
      surface->UDegree(), surface->IsUPeriodic(), surface->UKnotSequence(), surface->VDegree(),
      surface->IsVPeriodic(), surface->VKnotSequence(), surface->Weights());
  surface->Bounds(parts.u0, parts.u1, parts.v0, parts.v1);
  GeomConvert_BSplineSurfaceToBezierSurface converter(surface);
  const int nu = converter.NbUPatches(), nv = converter.NbVPatches();
  TColStd_Array1OfReal ku(1, nu + 1), kv(1, nv + 1);
  converter.UKnots(ku);
  converter.VKnots(kv);
  for (int i = 1; i <= nu + 1; ++i) parts.breaks_u.push_back(ku(i));
  for (int j = 1; j <= nv + 1; ++j) parts.breaks_v.push_back(kv(j));
  parts.patches_v = nv;
  std::vector<Box> boxes(static_cast<size_t>(nu) * nv);
  parts.seeds.resize(boxes.size());
  const int su = surface->UDegree() + 1, sv = surface->VDegree() + 1;
  Box all;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Handle(Geom_BezierSurface) patch = converter.Patch(i + 1, j + 1);
      parts.patches.push_back(patch);
      Box& box = boxes[i * nv + j];
      box = box_of(patch);
      all.add(box);
      std::vector<Parts::Seed>& seeds = parts.seeds[i * nv + j];
      for (int a = 0; a <= su; ++a) {
        for (int b = 0; b <= sv; ++b) {
          const double u = ku(i + 1) + (ku(i + 2) - ku(i + 1)) * a / su;
          const double v = kv(j + 1) + (kv(j + 2) - kv(j + 1)) * b / sv;
          seeds.push_back(Parts::Seed{parts.value(u, v).XYZ(), u, v});
        }
      }
    }
  }
  double diagonal = 0.0;
  for (int k = 0; k < 3; ++k) diagonal += (all.hi[k] - all.lo[k]) * (all.hi[k] - all.lo[k]);
  parts.scale = std::max(std::sqrt(diagonal), 1e-300);
  parts.build(boxes, 0, nu, 0, nv);
}

SurfaceInversion::~SurfaceInversion() = default;

long SurfaceInversion::fallbacks() const {
  return parts_->fallbacks;
}

double SurfaceInversion::patch_coordinate_u(double u) const {
  return grid_coordinate(parts_->breaks_u, u);
}

double SurfaceInversion::patch_coordinate_v(double v) const {
  return grid_coordinate(parts_->breaks_v, v);
}

SurfacePoint SurfaceInversion::local(const gp_Pnt& point, const SurfacePoint& start,
                                     bool& settled) {
  settled = false;
  return parts_->descend(point.XYZ(), start.u, start.v, settled);
}

SurfacePoint SurfaceInversion::closest(const gp_Pnt& point, const SurfacePoint* start) {
  Parts& parts = *parts_;
  const gp_XYZ p = point.XYZ();
  SurfacePoint best{parts.u0, parts.v0, std::numeric_limits<double>::infinity()};
  bool best_settled = false;
  if (start != nullptr) best = parts.descend(p, start->u, start->v, best_settled);
  // Best-first over the patch tree: a patch whose box is farther than the best point so far
  // cannot hold a closer one (to a margin far below any tolerance).
  const double margin = 1e-12 * parts.scale;
  int budget = 0;  // set per patch
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  queue.emplace(parts.nodes[0].box.square_distance(p), 0);
  while (!queue.empty()) {
    const auto [square_distance, id] = queue.top();
    queue.pop();
    if (std::sqrt(square_distance) >= best.distance - parts.slack(best)) break;
    const Parts::Node& node = parts.nodes[id];
    if (node.child[0] < 0) {
      const std::vector<Parts::Seed>& seeds = parts.seeds[node.i0 * parts.patches_v + node.j0];
      const Parts::Seed* nearest = &seeds.front();
      double nearest_distance = std::numeric_limits<double>::infinity();
      for (const Parts::Seed& seed : seeds) {
        const double d = (seed.point - p).SquareModulus();
        if (d < nearest_distance) {
          nearest_distance = d;
          nearest = &seed;
        }
      }
      const std::array<double, 4> piece{parts.breaks_u[node.i0], parts.breaks_u[node.i0 + 1],
                                        parts.breaks_v[node.j0], parts.breaks_v[node.j0 + 1]};
      bool settled = false;
      const SurfacePoint candidate = parts.descend_in(p, nearest->u, nearest->v, piece, settled);
      if (candidate.distance < best.distance) {
        best = candidate;
        best_settled = settled;
      }
      // A seed is a point of the surface: one nearer than the best point so far proves that
      // Newton went to another local minimum, so Newton starts again from it.
      for (const Parts::Seed& seed : seeds) {
        if (std::sqrt((seed.point - p).SquareModulus()) >= best.distance - margin) continue;
        const SurfacePoint again = parts.descend_in(p, seed.u, seed.v, piece, settled);
        if (again.distance < best.distance) {
          best = again;
          best_settled = settled;
        }
      }
      const int k = node.i0 * parts.patches_v + node.j0;
      // Split while the patch may still hold a nearer point than the best (its bound says so): a
      // smooth patch around its closest point is let go at once, a folded one is searched.
      budget = kPieceBudget;  // per patch: one wild patch must not use up another's search
      if (parts.lower_bound(parts.patches[k], p, best) < best.distance - parts.slack(best))
        parts.subdivide(p, parts.patches[k], parts.breaks_u[node.i0], parts.breaks_u[node.i0 + 1],
                        parts.breaks_v[node.j0], parts.breaks_v[node.j0 + 1], kMaxDepth, best,
                        best_settled, budget);
      continue;
    }
    for (int child : node.child) queue.emplace(parts.nodes[child].box.square_distance(p), child);
  }
  if (!best_settled) {
    const SurfacePoint global = parts.global_search(point);
    if (global.distance < best.distance) best = global;
  }
  return best;
}

}  // namespace varsurf::occ
