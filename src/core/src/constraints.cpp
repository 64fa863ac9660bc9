// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/constraints.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "curve_pieces.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

void check_weight(double w, const char* what) {
  if (!std::isfinite(w) || w <= 0.0)
    throw InvalidInput(std::string(what) + ": weight must be positive and finite");
}

void append_row(ConstraintSamples& out, const BasisSample& s, double sqrt_w,
                const Eigen::Vector3d& target, std::vector<Eigen::RowVector3d>& rhs) {
  out.index.push_back(s.index);
  out.coeff.push_back(sqrt_w * s.values.row(0).transpose());
  out.weight.push_back(sqrt_w * sqrt_w);
  rhs.push_back(sqrt_w * target.transpose());
}

Eigen::MatrixXd stack(const std::vector<Eigen::RowVector3d>& rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = rows[i];
  return m;
}

}  // namespace

ConstraintSamples to_coupled(const ConstraintSamples& sep) {
  if (sep.rhs.cols() != 3) throw InvalidInput("to_coupled: samples are not separable");
  ConstraintSamples out;
  out.rhs.resize(3 * sep.rows(), 1);
  for (int r = 0; r < sep.rows(); ++r) {
    const std::vector<int>& idx = sep.index[static_cast<size_t>(r)];
    for (int c = 0; c < 3; ++c) {
      std::vector<int> cols(idx.size());
      for (size_t k = 0; k < idx.size(); ++k) cols[k] = 3 * idx[k] + c;
      out.index.push_back(std::move(cols));
      out.coeff.push_back(sep.coeff[static_cast<size_t>(r)]);
      out.rhs(3 * r + c, 0) = sep.rhs(r, c);
      // A separable row's weight is shared by its three coordinate rows.
      out.weight.push_back(sep.weight[static_cast<size_t>(r)] / 3.0);
    }
  }
  out.exact = sep.exact;
  return out;
}

ConstraintSamples sample_point(const SplineSpace& space, const PointConstraint& c) {
  if (!std::isfinite(c.u) || !std::isfinite(c.v) || !c.target.allFinite())
    throw InvalidInput("point constraint: parameters or target are not finite");
  check_weight(c.weight, "point constraint");
  const Eigen::Vector2d uv = clamp_to_domain(space, {c.u, c.v}, 0.0);
  ConstraintSamples out;
  std::vector<Eigen::RowVector3d> rhs;
  append_row(out, space.basis(uv(0), uv(1), 0), std::sqrt(c.weight), c.target, rhs);
  out.rhs = stack(rhs);
  return out;
}

CurveSampling curve_sampling(const SplineSpace& space, const CurveConstraint& c) {
  c.preimage.validate("curve pre-image");
  c.target.validate("target curve");
  check_weight(c.weight, "curve constraint");
  if (c.preimage.dim() != 2) throw InvalidInput("curve pre-image must be a 2D (u, v) curve");
  if (c.target.dim() != 3) throw InvalidInput("target curve must be a 3D curve");
  const double t0 = c.target.first(), t1 = c.target.last();
  const double tol = 1e-9 * (t1 - t0);
  if (std::abs(c.preimage.first() - t0) > tol || std::abs(c.preimage.last() - t1) > tol)
    throw InvalidInput("curve pre-image and target must share their parameter range");

  const std::vector<double> pieces = curve_pieces(space, c.preimage, &c.target);
  const std::vector<int> points = gauss_points_per_piece(space, c.preimage, pieces);
  CurveSampling out;
  for (size_t i = 0; i + 1 < pieces.size(); ++i) {
    const GaussRule& g = gauss_legendre(points[i]);
    const double a = pieces[i], h = 0.5 * (pieces[i + 1] - pieces[i]);
    for (size_t q = 0; q < g.nodes.size(); ++q) {
      out.t.push_back(a + h * (g.nodes[q] + 1.0));
      out.rule_weight.push_back(g.weights[q] * h);
    }
  }
  return out;
}

void curve_rhs(const CurveConstraint& c, const CurveSampling& s, Eigen::MatrixXd& rhs,
               std::vector<double>& weights, std::vector<bool>& kept) {
  std::vector<double> ds(s.t.size());
  std::vector<Eigen::RowVector3d> points(s.t.size());
  double length = 0.0;
  for (size_t k = 0; k < s.t.size(); ++k) {
    const Eigen::MatrixXd d = c.target.derivatives(s.t[k], 1);
    ds[k] = s.rule_weight[k] * d.row(1).norm();
    points[k] = d.row(0);
    length += ds[k];
  }
  if (!(length > 0.0) || !std::isfinite(length)) throw InvalidInput("target curve has zero length");
  std::vector<Eigen::RowVector3d> rows;
  weights.clear();
  kept.assign(s.t.size(), false);
  for (size_t k = 0; k < s.t.size(); ++k) {
    if (ds[k] <= 0.0) continue;  // a stationary point of the target carries no arc length
    kept[k] = true;
    const double w = c.weight * ds[k] / length;
    rows.push_back(std::sqrt(w) * points[k]);
    weights.push_back(w);
  }
  rhs = stack(rows);
}

ConstraintSamples sample_curve(const SplineSpace& space, const CurveConstraint& c) {
  return sample_curve(space, c, curve_sampling(space, c));
}

ConstraintSamples sample_curve(const SplineSpace& space, const CurveConstraint& c,
                               const CurveSampling& s) {
  ConstraintSamples out;
  std::vector<bool> kept;
  curve_rhs(c, s, out.rhs, out.weight, kept);
  out.index.reserve(out.weight.size());
  size_t row = 0;
  for (size_t k = 0; k < s.t.size(); ++k) {
    if (!kept[k]) continue;
    const double sqrt_w = std::sqrt(out.weight[row]);
    const Eigen::Vector2d uv = clamp_to_domain(space, c.preimage.evaluate(s.t[k]), s.t[k]);
    const BasisSample b = space.basis(uv(0), uv(1), 0);
    out.index.push_back(b.index);
    out.coeff.push_back(sqrt_w * b.values.row(0).transpose());
    ++row;
  }
  out.exact = c.exact;
  return out;
}

double incidence_error(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                       const CurveConstraint& c, int samples) {
  if (samples < 2 || samples > 1000000)
    throw InvalidInput("incidence_error takes 2 to 1,000,000 samples");
  BSplineSurface{space, poles}.validate();
  c.preimage.validate("curve pre-image");
  c.target.validate("target curve");
  double worst = 0.0;
  const double t0 = c.target.first(), t1 = c.target.last();
  for (int i = 0; i < samples; ++i) {
    const double t = t0 + (t1 - t0) * i / (samples - 1);
    const Eigen::Vector2d uv = clamp_to_domain(space, c.preimage.evaluate(t), t);
    const Eigen::Vector3d w = evaluate_surface(space, poles, uv(0), uv(1), 0).row(0).transpose();
    worst = std::max(worst, (w - c.target.evaluate(t)).norm());
  }
  return worst;
}

}  // namespace varsurf
