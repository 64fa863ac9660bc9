// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/spline_space.hpp"

#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

void SplineSpace::validate() const {
  if (degree_u < 1 || degree_v < 1) throw InvalidInput("sheet: degrees must be at least 1");
  validate_knots(knots_u, degree_u, nu(), "sheet u knots");
  validate_knots(knots_v, degree_v, nv(), "sheet v knots");
  if (rational()) {
    if (weights.size() != size())
      throw InvalidInput("sheet: expected " + std::to_string(size()) + " weights, got " +
                         std::to_string(weights.size()));
    if (!weights.allFinite() || (weights.array() <= 0.0).any())
      throw InvalidInput("sheet: weights must be finite and positive");
  }
}

BasisSample SplineSpace::basis(double u, double v, int order) const {
  if (order < 0 || order > 2) throw InvalidInput("basis: derivative order must be 0, 1 or 2");
  const int pu = degree_u, pv = degree_v;
  const int su = find_span(knots_u, pu, u), sv = find_span(knots_v, pv, v);
  if (pu > kStackDegree || pv > kStackDegree) {
    Eigen::MatrixXd nu_d(order + 1, pu + 1), nv_d(order + 1, pv + 1);
    basis_derivatives(knots_u, pu, su, u, order, nu_d);
    basis_derivatives(knots_v, pv, sv, v, order, nv_d);
    return tensor_basis(nu_d, nv_d, su, sv, order);
  }
  using Basis = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, kStackDegree + 1>;
  Basis nu_d(order + 1, pu + 1), nv_d(order + 1, pv + 1);
  basis_derivatives(knots_u, pu, su, u, order, nu_d);
  basis_derivatives(knots_v, pv, sv, v, order, nv_d);
  return tensor_basis(nu_d, nv_d, su, sv, order);
}

template <class Basis>
BasisSample SplineSpace::tensor_basis(const Basis& nu_d, const Basis& nv_d, int su, int sv,
                                      int order) const {
  const int pu = degree_u, pv = degree_v;

  // Derivative rows as (order in u, order in v).
  static const int du[6] = {0, 1, 0, 2, 1, 0};
  static const int dv[6] = {0, 0, 1, 0, 1, 2};
  const int rows = order == 0 ? 1 : (order == 1 ? 3 : 6);
  const int count = (pu + 1) * (pv + 1);

  BasisSample s;
  s.index.resize(static_cast<size_t>(count));
  s.values.resize(rows, count);
  int k = 0;
  for (int a = 0; a <= pu; ++a) {
    for (int b = 0; b <= pv; ++b, ++k) {
      s.index[static_cast<size_t>(k)] = index(su - pu + a, sv - pv + b);
      for (int d = 0; d < rows; ++d) s.values(d, k) = nu_d(du[d], a) * nv_d(dv[d], b);
    }
  }
  if (!rational()) return s;

  // Rational basis R = A / W with A = w N: quotient rule for the derivatives.
  for (int j = 0; j < count; ++j) s.values.col(j) *= weights(s.index[static_cast<size_t>(j)]);
  const Eigen::VectorXd W = s.values.rowwise().sum();
  Eigen::MatrixXd R(rows, count);
  R.row(0) = s.values.row(0) / W(0);
  if (rows > 1) {
    R.row(1) = (s.values.row(1) - R.row(0) * W(1)) / W(0);
    R.row(2) = (s.values.row(2) - R.row(0) * W(2)) / W(0);
  }
  if (rows > 3) {
    R.row(3) = (s.values.row(3) - 2.0 * R.row(1) * W(1) - R.row(0) * W(3)) / W(0);
    R.row(4) = (s.values.row(4) - R.row(1) * W(2) - R.row(2) * W(1) - R.row(0) * W(4)) / W(0);
    R.row(5) = (s.values.row(5) - 2.0 * R.row(2) * W(2) - R.row(0) * W(5)) / W(0);
  }
  s.values = R;
  return s;
}

SplineSpace SplineSpace::uniform(int degree_u, int degree_v, int spans_u, int spans_v) {
  SplineSpace s;
  s.degree_u = degree_u;
  s.degree_v = degree_v;
  s.knots_u = uniform_clamped_knots(degree_u, spans_u);
  s.knots_v = uniform_clamped_knots(degree_v, spans_v);
  return s;
}

void BSplineSurface::validate() const {
  space.validate();
  if (poles.rows() != space.size())
    throw InvalidInput("sheet: expected " + std::to_string(space.size()) + " poles, got " +
                       std::to_string(poles.rows()));
  if (!poles.allFinite()) throw InvalidInput("sheet: pole coordinates are not finite");
  // Finite but huge poles overflow when evaluated (1e308: a deviation search ran for minutes).
  if (poles.size() > 0 && poles.cwiseAbs().maxCoeff() > kMaxCoordinate)
    throw InvalidInput("sheet: pole coordinates must lie within +-1e12 (model units)");
}

Eigen::Vector3d BSplineSurface::evaluate(double u, double v) const {
  return evaluate_surface(space, poles, u, v, 0).row(0).transpose();
}

std::vector<int> boundary_pole_indices(const SplineSpace& space, bool closed_u, bool closed_v) {
  std::vector<int> idx;
  const int nu = space.nu(), nv = space.nv();
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const bool u_side = !closed_u && (i == 0 || i == nu - 1);
      const bool v_side = !closed_v && (j == 0 || j == nv - 1);
      if (u_side || v_side) idx.push_back(space.index(i, j));
    }
  }
  return idx;
}

Eigen::MatrixXd evaluate_surface(const SplineSpace& space, const Eigen::MatrixX3d& poles, double u,
                                 double v, int order) {
  if (order < 0 || order > 2) throw InvalidInput("basis: derivative order must be 0, 1 or 2");
  const int pu = space.degree_u, pv = space.degree_v;
  const int rows = order == 0 ? 1 : (order == 1 ? 3 : 6);
  // Rational sheets sum the rational basis as the solver's constraint rows do: S = sum R_k P_k
  // equal to the rows' rounding (the quotient of the homogeneous sums below differs by 1e-15,
  // and a sphere's sheet then came out 1e-6 degrees apart at its seam and failed OCCT's BOP
  // self-intersection check at its poles).
  if (space.rational() || pu > kStackDegree || pv > kStackDegree) {
    const BasisSample s = space.basis(u, v, order);
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(rows, 3);
    for (size_t k = 0; k < s.index.size(); ++k)
      out += s.values.col(static_cast<Eigen::Index>(k)) * poles.row(s.index[k]);
    return out;
  }
  // The basis products summed pole by pole in basis()'s order (the same figures to the last
  // bit), without a BasisSample: every projection, measurement and constraint sample evaluates
  // here, and its index list and value matrix on the heap cost more than the sum (perf, bicubic
  // sheets).
  using Basis = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, kStackDegree + 1>;
  const int su = find_span(space.knots_u, pu, u), sv = find_span(space.knots_v, pv, v);
  Basis nu(order + 1, pu + 1), nv(order + 1, pv + 1);
  basis_derivatives(space.knots_u, pu, su, u, order, nu);
  basis_derivatives(space.knots_v, pv, sv, v, order, nv);
  static const int du[6] = {0, 1, 0, 2, 1, 0};
  static const int dv[6] = {0, 0, 1, 0, 1, 2};
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(rows, 3);
  for (int a = 0; a <= pu; ++a) {
    for (int b = 0; b <= pv; ++b) {
      const int k = space.index(su - pu + a, sv - pv + b);
      for (int d = 0; d < rows; ++d) {
        const double value = nu(du[d], a) * nv(dv[d], b);
        for (int c = 0; c < 3; ++c) out(d, c) += value * poles(k, c);
      }
    }
  }
  return out;
}

}  // namespace varsurf
