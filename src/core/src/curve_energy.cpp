// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/curve_energy.hpp"

#include <cmath>
#include <vector>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

Eigen::SparseMatrix<double> assemble_curve_energy(const BSplineCurve& curve, double stretch,
                                                  double bend) {
  curve.validate("space curve");
  if (curve.rational()) throw InvalidInput("a variational space curve must be non-rational");
  if (!(stretch >= 0.0) || !(bend >= 0.0) || !std::isfinite(stretch) || !std::isfinite(bend) ||
      stretch + bend <= 0.0)
    throw InvalidInput("curve energy: stretch and bend must be finite, >= 0 and not both 0");
  const int p = curve.degree;
  // |C'|^2 has degree 2p - 2: p Gauss points per span integrate it exactly.
  const GaussRule& g = gauss_legendre(std::max(p, 1));
  const std::vector<double> breaks = breakpoints(curve.knots, p);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd ders(3, p + 1);
  for (size_t s = 0; s + 1 < breaks.size(); ++s) {
    const double a = breaks[s], h = 0.5 * (breaks[s + 1] - breaks[s]);
    for (size_t q = 0; q < g.nodes.size(); ++q) {
      const double t = a + h * (g.nodes[q] + 1.0), w = g.weights[q] * h;
      const int span = find_span(curve.knots, p, t);
      const int order = std::min(2, p);
      basis_derivatives(curve.knots, p, span, t, order, ders.topRows(order + 1));
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= p; ++j) {
          double v = stretch * ders(1, i) * ders(1, j);
          if (order == 2) v += bend * ders(2, i) * ders(2, j);
          triplets.emplace_back(span - p + i, span - p + j, w * v);
        }
    }
  }
  Eigen::SparseMatrix<double> h(curve.pole_count(), curve.pole_count());
  h.setFromTriplets(triplets.begin(), triplets.end());
  return h;
}

}  // namespace varsurf
