// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/thin_plate_energy.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <vector>

#include "point_assembly.hpp"
#include "separable_energy.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

ThinPlateWeights ThinPlateWeights::isotropic(double stretch, double bend) {
  ThinPlateWeights w;
  w.alpha = stretch * Eigen::Matrix2d::Identity();
  w.beta = bend * Eigen::Matrix2d::Ones();
  w.validate();
  return w;
}

void ThinPlateWeights::validate() const {
  if (!alpha.allFinite() || !beta.allFinite()) throw InvalidInput("energy weights are not finite");
  if (std::abs(alpha(0, 1) - alpha(1, 0)) > 1e-12 * (1.0 + alpha.norm()))
    throw InvalidInput("stretch weights alpha must be symmetric");
  // Alpha must be positive semi-definite or the energy has no minimum.
  if (alpha(0, 0) < 0.0 || alpha(1, 1) < 0.0 || alpha.determinant() < -1e-12 * alpha.squaredNorm())
    throw InvalidInput("stretch weights alpha must be positive semi-definite");
  if ((beta.array() < 0.0).any()) throw InvalidInput("bend weights beta must be non-negative");
  if (alpha.isZero(0.0) && beta.isZero(0.0))
    throw InvalidInput("energy is zero: give a positive stretch or bend weight");
}

namespace {

// Terms coef * int D^(au, av) phi_row D^(bu, bv) phi_col: the gradient's alpha and the Hessian's
// beta, the mixed second derivative counted twice as in sum_ij beta_ij (D_i D_j w)^2.
std::vector<SeparableTerm> thin_plate_terms(const ThinPlateWeights& w, bool bends) {
  std::vector<SeparableTerm> terms;
  const int grad[2][2] = {{1, 0}, {0, 1}};  // (u order, v order) of w_u and w_v
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      if (w.alpha(a, b) != 0.0)
        terms.push_back({w.alpha(a, b), grad[a][0], grad[b][0], grad[a][1], grad[b][1]});
  if (bends) {
    const double hess[3] = {w.beta(0, 0), w.beta(0, 1) + w.beta(1, 0), w.beta(1, 1)};
    const int order_u[3] = {2, 1, 0};
    for (int m = 0; m < 3; ++m)
      if (hess[m] != 0.0)
        terms.push_back({hess[m], order_u[m], order_u[m], 2 - order_u[m], 2 - order_u[m]});
  }
  return terms;
}

}  // namespace

Eigen::SparseMatrix<double> assemble_thin_plate(const SplineSpace& space,
                                                const ThinPlateWeights& w) {
  space.validate();
  w.validate();
  const bool bends = !w.beta.isZero(0.0);
  if (bends && (space.degree_u < 2 || space.degree_v < 2))
    throw InvalidInput("a bending energy needs degree 2 or more in both directions");
  if (!space.rational())
    return assemble_separable(space, thin_plate_terms(w, bends), bends ? 2 : 1);

  // Rational bases are not polynomial: two points beyond the p + 1 that integrate a polynomial
  // space exactly keep the error far below the solver's tolerances for the weight ratios CAD data
  // uses.
  const int extra = 2;
  const GaussRule& gu = gauss_legendre(space.degree_u + 1 + extra);
  const GaussRule& gv = gauss_legendre(space.degree_v + 1 + extra);
  const std::vector<double> bu = breakpoints(space.knots_u, space.degree_u);
  const std::vector<double> bv = breakpoints(space.knots_v, space.degree_v);

  const int order = bends ? 2 : 1;
  const int count = (space.degree_u + 1) * (space.degree_v + 1);
  // The mixed term appears twice in sum_ij beta_ij (D_i D_j w)^2.
  const Eigen::Vector3d hess_w(w.beta(0, 0), w.beta(0, 1) + w.beta(1, 0), w.beta(1, 1));

  // First non-zero basis function of each span.
  auto firsts = [](const std::vector<double>& knots, int degree, const std::vector<double>& br) {
    std::vector<int> first;
    for (size_t a = 0; a + 1 < br.size(); ++a)
      first.push_back(find_span(knots, degree, 0.5 * (br[a] + br[a + 1])) - degree);
    return first;
  };
  const std::vector<int> first_u = firsts(space.knots_u, space.degree_u, bu);
  const std::vector<int> first_v = firsts(space.knots_v, space.degree_v, bv);

  // H's pattern is known: pole (i, j) couples with the poles within degree_u and degree_v of it.
  // Values are added in place (measured: 3x faster than collecting ~1M triplets at 64 x 64).
  const int nu = space.nu(), nv = space.nv(), pu = space.degree_u, pv = space.degree_v;
  const int n = space.size();
  std::vector<int> outer(static_cast<size_t>(n) + 1, 0), inner;
  inner.reserve(static_cast<size_t>(n) * static_cast<size_t>((2 * pu + 1) * (2 * pv + 1)));
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const int col = space.index(i, j);
      for (int i2 = std::max(0, i - pu); i2 <= std::min(nu - 1, i + pu); ++i2)
        for (int j2 = std::max(0, j - pv); j2 <= std::min(nv - 1, j + pv); ++j2)
          inner.push_back(space.index(i2, j2));
      outer[static_cast<size_t>(col) + 1] = static_cast<int>(inner.size());
    }
  std::vector<double> values(inner.size(), 0.0);
  auto position = [&](int row, int col) {  // of (row, col) in the column's sorted rows
    const int i = col / nv, j = col % nv, i2 = row / nv, j2 = row % nv;
    const int ilo = std::max(0, i - pu), jlo = std::max(0, j - pv);
    const int width = std::min(nv - 1, j + pv) - jlo + 1;
    return static_cast<size_t>(outer[static_cast<size_t>(col)] + (i2 - ilo) * width + (j2 - jlo));
  };
  std::vector<int> index(static_cast<size_t>(count));
  for (size_t a = 0; a + 1 < bu.size(); ++a) {
    const double u0 = bu[a], hu = 0.5 * (bu[a + 1] - bu[a]);
    for (size_t b = 0; b + 1 < bv.size(); ++b) {
      const double v0 = bv[b], hv = 0.5 * (bv[b + 1] - bv[b]);
      Eigen::MatrixXd local = Eigen::MatrixXd::Zero(count, count);
      for (size_t i = 0; i < gu.nodes.size(); ++i) {
        const double u = u0 + hu * (gu.nodes[i] + 1.0);
        for (size_t j = 0; j < gv.nodes.size(); ++j) {
          const double v = v0 + hv * (gv.nodes[j] + 1.0);
          const double dA = gu.weights[i] * gv.weights[j] * hu * hv;
          const BasisSample s = space.basis(u, v, order);
          const auto grad = s.values.middleRows(1, 2);
          local.noalias() += dA * (grad.transpose() * w.alpha * grad);
          if (bends) {
            const auto hess = s.values.middleRows(3, 3);
            local.noalias() += dA * (hess.transpose() * hess_w.asDiagonal() * hess);
          }
        }
      }
      // The span's basis functions: poles (first_u + i, first_v + j), in BasisSample's order.
      int k = 0;
      for (int i = 0; i <= space.degree_u; ++i)
        for (int j = 0; j <= space.degree_v; ++j)
          index[static_cast<size_t>(k++)] = space.index(first_u[a] + i, first_v[b] + j);
      for (int c = 0; c < count; ++c)
        for (int r = 0; r < count; ++r)
          values[position(index[static_cast<size_t>(r)], index[static_cast<size_t>(c)])] +=
              local(r, c);
    }
  }
  return Eigen::Map<const Eigen::SparseMatrix<double>>(
      n, n, static_cast<Eigen::Index>(inner.size()), outer.data(), inner.data(), values.data());
}

Eigen::SparseMatrix<double> assemble_thin_plate(const SplineSpace& space, const ThinPlateWeights& w,
                                                const Region& region, double outside) {
  if (!(outside >= 0.0 && outside < 1.0))
    throw InvalidInput("the overhang's energy weight must be in [0, 1)");
  check_region(space, region, "energy region");
  const Eigen::SparseMatrix<double> whole = assemble_thin_plate(space, w);
  const int order = w.beta.isZero(0.0) ? 1 : 2;
  const Eigen::Vector3d hess_w(w.beta(0, 0), w.beta(0, 1) + w.beta(1, 0), w.beta(1, 1));
  const Eigen::SparseMatrix<double> inside = assemble_at_points(
      space, region_quadrature(space, region), order,
      [&](const BasisSample& s, const QuadraturePoint& q, Eigen::MatrixXd& local) {
        const double weight = q.weight;
        const auto grad = s.values.middleRows(1, 2);
        local.noalias() += weight * (grad.transpose() * w.alpha * grad);
        if (order == 2) {
          const auto hess = s.values.middleRows(3, 3);
          local.noalias() += weight * (hess.transpose() * hess_w.asDiagonal() * hess);
        }
      });
  // inside + outside * (whole - inside): the rest of the domain's energy is whole - inside.
  return Eigen::SparseMatrix<double>((1.0 - outside) * inside + outside * whole);
}

}  // namespace varsurf
