#include "varsurf/core/thin_plate_energy.hpp"

#include <Eigen/LU>
#include <cmath>
#include <vector>

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

Eigen::SparseMatrix<double> assemble_thin_plate(const SplineSpace& space,
                                                const ThinPlateWeights& w) {
  space.validate();
  w.validate();
  const bool bends = !w.beta.isZero(0.0);
  if (bends && (space.degree_u < 2 || space.degree_v < 2))
    throw InvalidInput("a bending energy needs degree 2 or more in both directions");

  // Products of two degree-p derivatives are polynomials of degree <= 2p per span: p + 1 points
  // integrate them exactly. Rational bases are not polynomial; two extra points keep the error
  // far below the solver's tolerances for the weight ratios CAD data uses.
  const int extra = space.rational() ? 2 : 0;
  const GaussRule& gu = gauss_legendre(space.degree_u + 1 + extra);
  const GaussRule& gv = gauss_legendre(space.degree_v + 1 + extra);
  const std::vector<double> bu = breakpoints(space.knots_u, space.degree_u);
  const std::vector<double> bv = breakpoints(space.knots_v, space.degree_v);

  const int order = bends ? 2 : 1;
  const int count = (space.degree_u + 1) * (space.degree_v + 1);
  // The mixed term appears twice in sum_ij beta_ij (D_i D_j w)^2.
  const Eigen::Vector3d hess_w(w.beta(0, 0), w.beta(0, 1) + w.beta(1, 0), w.beta(1, 1));

  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve((bu.size() - 1) * (bv.size() - 1) * static_cast<size_t>(count * count));
  Eigen::MatrixXd local(count, count);
  for (size_t a = 0; a + 1 < bu.size(); ++a) {
    const double u0 = bu[a], hu = 0.5 * (bu[a + 1] - bu[a]);
    for (size_t b = 0; b + 1 < bv.size(); ++b) {
      const double v0 = bv[b], hv = 0.5 * (bv[b + 1] - bv[b]);
      local.setZero();
      std::vector<int> index;
      for (size_t i = 0; i < gu.nodes.size(); ++i) {
        const double u = u0 + hu * (gu.nodes[i] + 1.0);
        for (size_t j = 0; j < gv.nodes.size(); ++j) {
          const double v = v0 + hv * (gv.nodes[j] + 1.0);
          const double dA = gu.weights[i] * gv.weights[j] * hu * hv;
          BasisSample s = space.basis(u, v, order);
          const auto grad = s.values.middleRows(1, 2);
          local.noalias() += dA * (grad.transpose() * w.alpha * grad);
          if (bends) {
            const auto hess = s.values.middleRows(3, 3);
            local.noalias() += dA * (hess.transpose() * hess_w.asDiagonal() * hess);
          }
          index = std::move(s.index);
        }
      }
      // All quadrature points of a span share its basis functions.
      for (int r = 0; r < count; ++r)
        for (int c = 0; c < count; ++c)
          trip.emplace_back(index[static_cast<size_t>(r)], index[static_cast<size_t>(c)],
                            local(r, c));
    }
  }
  Eigen::SparseMatrix<double> h(space.size(), space.size());
  h.setFromTriplets(trip.begin(), trip.end());
  return h;
}

}  // namespace varsurf
