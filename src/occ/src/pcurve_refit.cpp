// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/pcurve_refit.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRep_Builder.hxx>
#include <BRep_TEdge.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Precision.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_MapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "varsurf/core/curve_fit.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/occ/curve_on_surface.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

// Quintic: a third of a circle within 1e-9 takes some 70 poles, where cubics took 259.
constexpr int kDegree = 5;
constexpr int kMaxPoles = 4000;
constexpr int kRounds = 12;
constexpr int kPerSpan = 2 * (kDegree + 1);

// The edge's 3D curve and one face's surface, both placed (locations applied).
class EdgeOnFace {
 public:
  EdgeOnFace(const TopoDS_Edge& edge, const TopoDS_Face& face)
      : curve_(edge), surface_(face, Standard_False) {}

  gp_Pnt point(double t) const { return curve_.Value(t); }
  gp_Pnt on_surface(const Eigen::Vector2d& uv) const { return surface_.Value(uv(0), uv(1)); }

  // The foot of p on the surface by Gauss-Newton from `uv`: the edge lies on the face within
  // its tolerance, so the old pcurve's (u, v) is already close and the steps converge fast.
  // (point_projection is not used: it takes the core's B-spline sheets and searches the whole
  // face; here the surface is any face's, a fillet's torus too, and a start is at hand.)
  std::optional<Eigen::Vector2d> foot(const gp_Pnt& p, Eigen::Vector2d uv) const {
    for (int it = 0; it < 30; ++it) {
      gp_Pnt s;
      gp_Vec su, sv;
      surface_.D1(uv(0), uv(1), s, su, sv);
      const gp_Vec r(s, p);
      Eigen::Matrix2d a;
      a << su.Dot(su), su.Dot(sv), su.Dot(sv), sv.Dot(sv);
      const Eigen::Vector2d b(su.Dot(r), sv.Dot(r));
      if (std::abs(a.determinant()) <= 1e-30 * a.squaredNorm()) return std::nullopt;
      const Eigen::Vector2d step = a.ldlt().solve(b);
      if (!step.allFinite()) return std::nullopt;
      uv += step;
      if (step.norm() <= 1e-15 * (1.0 + uv.norm())) break;
    }
    return uv;
  }

 private:
  BRepAdaptor_Curve curve_;
  BRepAdaptor_Surface surface_;
};

// The (u, v) of the 3D curve's point at t, its projection started at `guess`.
Eigen::Vector2d foot_at(const EdgeOnFace& geometry, double t, const Eigen::Vector2d& guess) {
  const auto foot = geometry.foot(geometry.point(t), guess);
  if (!foot) throw SolveFailure("refitting a pcurve: a projection does not converge");
  return *foot;
}

Eigen::Vector2d old_value(const Handle(Geom2d_Curve) & old, double t) {
  const gp_Pnt2d p = old->Value(t);
  return {p.X(), p.Y()};
}

// The refitted pcurve on [f, l]. Its error is measured against the projections themselves, in
// 3D, at the samples and between them (where a fit misses most): where the surface does not hold
// the 3D curve (a sewing gap), no pcurve comes closer than the feet, and refining stops there.
// SolveFailure when a projection fails or the fit is singular.
BSplineCurve refit(const EdgeOnFace& geometry, const Handle(Geom2d_Curve) & old, double f, double l,
                   double target) {
  std::vector<double> breaks;
  const int start = 8;
  for (int i = 0; i <= start; ++i) breaks.push_back(f + (l - f) * i / start);
  BSplineCurve best;
  double best_error = std::numeric_limits<double>::infinity();
  int stalls = 0;
  for (int round = 0; round < kRounds; ++round) {
    std::vector<double> t;
    for (size_t s = 0; s + 1 < breaks.size(); ++s)
      for (int k = 0; k < kPerSpan; ++k)
        t.push_back(breaks[s] + (breaks[s + 1] - breaks[s]) * k / kPerSpan);
    t.push_back(l);
    Eigen::MatrixXd uv(static_cast<Eigen::Index>(t.size()), 2);
    for (size_t k = 0; k < t.size(); ++k) {
      const Eigen::Vector2d guess =
          best.pole_count() > 0 ? Eigen::Vector2d(best.evaluate(t[k])) : old_value(old, t[k]);
      uv.row(static_cast<Eigen::Index>(k)) = foot_at(geometry, t[k], guess).transpose();
    }
    std::vector<double> knots(kDegree + 1, f);
    knots.insert(knots.end(), breaks.begin() + 1, breaks.end() - 1);
    knots.insert(knots.end(), kDegree + 1, l);
    const BSplineCurve trial = fit_clamped_curve(t, uv, kDegree, knots);
    std::vector<double> span_error(breaks.size() - 1, 0.0);
    double worst = 0.0;
    for (size_t k = 0; k + 1 < t.size(); ++k) {
      const double mid = 0.5 * (t[k] + t[k + 1]);
      const Eigen::Vector2d at_mid = trial.evaluate(mid);
      const Eigen::Vector2d foot_mid = foot_at(geometry, mid, at_mid);
      const Eigen::Vector2d sample = uv.row(static_cast<Eigen::Index>(k)).transpose();
      const double e =
          std::max(geometry.on_surface(trial.evaluate(t[k])).Distance(geometry.on_surface(sample)),
                   geometry.on_surface(at_mid).Distance(geometry.on_surface(foot_mid)));
      const size_t span = std::min(k / kPerSpan, span_error.size() - 1);
      span_error[span] = std::max(span_error[span], e);
      worst = std::max(worst, e);
    }
    stalls = worst < 0.5 * best_error ? 0 : stalls + 1;
    if (worst < best_error) best = trial, best_error = worst;
    if (best_error <= target || stalls >= 2) break;
    std::vector<double> refined{breaks.front()};
    for (size_t s = 0; s + 1 < breaks.size(); ++s) {
      if (span_error[s] > target) refined.push_back(0.5 * (breaks[s] + breaks[s + 1]));
      refined.push_back(breaks[s + 1]);
    }
    if (static_cast<int>(refined.size()) + kDegree - 1 > kMaxPoles) break;
    breaks = refined;
  }
  return best;
}

}  // namespace

int refit_pcurves(const TopoDS_Shape& shape, double above) {
  if (shape.IsNull()) return 0;
  return guarded("refitting pcurves", [&] {
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    BRep_Builder builder;
    int replaced = 0;
    for (int k = 1; k <= edge_faces.Extent(); ++k) {
      const TopoDS_Edge edge = TopoDS::Edge(edge_faces.FindKey(k).Oriented(TopAbs_FORWARD));
      if (BRep_Tool::Degenerated(edge) || !BRep_Tool::SameRange(edge)) continue;
      double f = 0.0, l = 0.0;
      if (BRep_Tool::Curve(edge, f, l).IsNull() || !(l > f)) continue;
      std::vector<TopoDS_Face> faces;
      TopTools_MapOfShape seen;
      for (TopTools_ListIteratorOfListOfShape it(edge_faces(k)); it.More(); it.Next())
        if (seen.Add(it.Value().Oriented(TopAbs_FORWARD)))
          faces.push_back(TopoDS::Face(it.Value().Oriented(TopAbs_FORWARD)));
      bool changed = false;
      for (const TopoDS_Face& face : faces) {
        const double before = curve_on_surface_deviation(edge, face);
        if (before <= above || BRep_Tool::IsClosed(edge, face)) continue;
        double pf = 0.0, pl = 0.0;
        const Handle(Geom2d_Curve) old = BRep_Tool::CurveOnSurface(edge, face, pf, pl);
        if (old.IsNull() || std::abs(pf - f) > 1e-12 * (1.0 + std::abs(f)) ||
            std::abs(pl - l) > 1e-12 * (1.0 + std::abs(l)))
          continue;
        const EdgeOnFace geometry(edge, face);
        BSplineCurve fitted;
        try {
          fitted = refit(geometry, old, f, l, 1e-2 * above);
        } catch (const SolveFailure&) {
          continue;  // a projection or the fit failed: keep OCCT's pcurve
        }
        const double tolerance = BRep_Tool::Tolerance(edge);
        builder.UpdateEdge(edge, to_geom2d_curve(fitted), face, tolerance);
        const double after = curve_on_surface_deviation(edge, face);
        if (after < 0.0 || after > 0.5 * before) {
          // Not much closer (the surfaces part there): the old one has fewer poles.
          builder.UpdateEdge(edge, old, face, tolerance);
          continue;
        }
        changed = true;
        ++replaced;
      }
      if (!changed) continue;
      double measured = 0.0;
      for (const TopoDS_Face& face : faces)
        measured = std::max(measured, curve_on_surface_deviation(edge, face));
      // BRep_Builder only raises a tolerance: set the measured one on the edge itself.
      Handle(BRep_TEdge)::DownCast(edge.TShape())
          ->Tolerance(std::max(Precision::Confusion(), 1.0001 * measured));
      edge.TShape()->Modified(Standard_True);
    }
    return replaced;
  });
}

}  // namespace varsurf::occ
