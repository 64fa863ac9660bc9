// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/curvature_constraint.hpp"

#include <cmath>
#include <string>

#include "curve_pieces.hpp"
#include "unit_vector.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"

namespace varsurf {

namespace {

void validate(const SplineSpace& space, const CurvatureConstraint& c) {
  c.preimage.validate("curvature pre-image");
  c.normals.validate("curvature normal field");
  c.shape.validate("curvature shape field");
  if (c.preimage.dim() != 2) throw InvalidInput("curvature pre-image must be a 2D (u, v) curve");
  if (c.normals.dim() != 3) throw InvalidInput("curvature normal field must be 3D");
  if (c.shape.dim() != 6) throw InvalidInput("curvature shape field must have 6 components");
  if (!std::isfinite(c.weight) || c.weight <= 0.0)
    throw InvalidInput("curvature: weight must be positive and finite");
  if (space.degree_u < 3 || space.degree_v < 3)
    throw InvalidInput("G2 needs a sheet of degree 3 or more in u and v (this one has " +
                       std::to_string(space.degree_u) + " x " + std::to_string(space.degree_v) +
                       "): its curvature jumps at every knot line");
  const double tol = 1e-9 * (c.preimage.last() - c.preimage.first());
  for (const BSplineCurve* f : {&c.normals, &c.shape})
    if (std::abs(c.preimage.first() - f->first()) > tol ||
        std::abs(c.preimage.last() - f->last()) > tol)
      throw InvalidInput("curvature pre-image and its fields must share their parameter range");
}

// The unit direction across the pre-image in the parameter plane, (-v', u') / |(u', v')|.
Eigen::Vector2d across(const Eigen::MatrixXd& pre, double t) {
  const Eigen::Vector2d d(-pre(1, 1), pre(1, 0));
  const double n = d.norm();
  if (!(n > 1e-300))
    throw InvalidInput("curvature pre-image stops (zero derivative) at t = " + std::to_string(t));
  return d / n;
}

}  // namespace

Eigen::Matrix3d shape_tensor(const Eigen::VectorXd& s) {
  Eigen::Matrix3d k;
  k << s(0), s(3), s(4), s(3), s(1), s(5), s(4), s(5), s(2);
  return k;
}

ConstraintSamples sample_curvature(const SplineSpace& space, const CurvatureConstraint& c,
                                   const Eigen::MatrixX3d& poles) {
  validate(space, c);
  BSplineSurface{space, poles}.validate();
  const double t0 = c.preimage.first(), t1 = c.preimage.last();
  const std::vector<double> pieces = curve_pieces(space, c.preimage, &c.shape);
  const GaussRule& g = gauss_legendre(gauss_points_along(space, c.preimage));
  ConstraintSamples out;
  std::vector<double> rhs;
  for (size_t i = 0; i + 1 < pieces.size(); ++i) {
    const double a = pieces[i], h = 0.5 * (pieces[i + 1] - pieces[i]);
    for (size_t q = 0; q < g.nodes.size(); ++q) {
      const double t = a + h * (g.nodes[q] + 1.0);
      const Eigen::MatrixXd pre = c.preimage.derivatives(t, 1);
      const Eigen::Vector2d uv = clamp_to_domain(space, pre.row(0).transpose(), t);
      const Eigen::Vector2d d = across(pre, t);
      const Eigen::Vector3d n = unit_vector(c.normals.evaluate(t), "curvature: the normal field");
      const Eigen::Matrix3d k = shape_tensor(c.shape.evaluate(t));
      const BasisSample s = space.basis(uv(0), uv(1), 2);
      const Eigen::Index m = static_cast<Eigen::Index>(s.index.size());
      // b_d and b_dd of each basis function, and w_d at the current poles.
      Eigen::VectorXd bd(m), bdd(m);
      Eigen::Vector3d wd = Eigen::Vector3d::Zero();
      for (Eigen::Index j = 0; j < m; ++j) {
        bd(j) = d(0) * s.values(1, j) + d(1) * s.values(2, j);
        bdd(j) = d(0) * d(0) * s.values(3, j) + 2.0 * d(0) * d(1) * s.values(4, j) +
                 d(1) * d(1) * s.values(5, j);
        wd += bd(j) * poles.row(s.index[static_cast<size_t>(j)]).transpose();
      }
      const Eigen::Vector3d kwd = k * wd;
      const double scale = bd.norm() / std::max(bdd.norm(), 1e-300);
      const double w = c.weight * g.weights[q] * h / (t1 - t0), sw = std::sqrt(w) * scale;
      std::vector<int> cols;
      Eigen::VectorXd coeff(3 * m);
      for (Eigen::Index j = 0; j < m; ++j)
        for (int e = 0; e < 3; ++e) {
          cols.push_back(3 * s.index[static_cast<size_t>(j)] + e);
          coeff(3 * j + e) = sw * (bdd(j) * n(e) - 2.0 * bd(j) * kwd(e));
        }
      out.index.push_back(std::move(cols));
      out.coeff.push_back(std::move(coeff));
      out.weight.push_back(w);
      rhs.push_back(-sw * wd.dot(kwd));
    }
  }
  out.rhs = Eigen::Map<Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  return out;
}

double curvature_jump(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                      const CurvatureConstraint& c, double floor, int samples, double* rms) {
  validate(space, c);
  BSplineSurface{space, poles}.validate();
  // Beyond a million samples a measure takes minutes and says nothing more.
  if (samples < 2 || samples > 1000000)
    throw InvalidInput("curvature_jump takes 2 to 1,000,000 samples");
  double worst = 0.0, sum = 0.0;
  const double t0 = c.preimage.first(), t1 = c.preimage.last();
  for (int i = 0; i < samples; ++i) {
    const double t = t0 + (t1 - t0) * i / (samples - 1);
    const Eigen::MatrixXd pre = c.preimage.derivatives(t, 1);
    const Eigen::Vector2d uv = clamp_to_domain(space, pre.row(0).transpose(), t);
    const Eigen::Vector2d d = across(pre, t);
    const Eigen::MatrixXd w = evaluate_surface(space, poles, uv(0), uv(1), 2);
    const Eigen::Vector3d wd = d(0) * w.row(1) + d(1) * w.row(2);
    const Eigen::Vector3d wdd =
        d(0) * d(0) * w.row(3) + 2.0 * d(0) * d(1) * w.row(4) + d(1) * d(1) * w.row(5);
    const Eigen::Vector3d n = unit_vector(c.normals.evaluate(t), "curvature: the normal field");
    const double len2 = wd.squaredNorm();
    if (!(len2 > 1e-300)) continue;
    const double k_sheet = n.dot(wdd) / len2;
    const double k_neighbour = wd.dot(shape_tensor(c.shape.evaluate(t)) * wd) / len2;
    const double scale = std::max({std::abs(k_sheet), std::abs(k_neighbour), floor});
    const double jump = scale > 0.0 ? std::abs(k_sheet - k_neighbour) / scale : 0.0;
    worst = std::max(worst, jump);
    sum += jump * jump;
  }
  if (rms) *rms = std::sqrt(sum / samples);
  return worst;
}

}  // namespace varsurf
