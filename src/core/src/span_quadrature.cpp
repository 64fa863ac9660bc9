// SPDX-License-Identifier: LGPL-2.1-or-later
#include "span_quadrature.hpp"

#include <algorithm>
#include <cmath>

#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

// The breakpoints with each piece cut into pieces no longer than `step` (a fraction of the domain).
std::vector<double> cells(const std::vector<double>& knots, int degree, double step) {
  const std::vector<double> br = breakpoints(knots, degree);
  std::vector<double> out{br.front()};
  const double whole = br.back() - br.front();
  for (size_t s = 0; s + 1 < br.size(); ++s) {
    const int m = std::max(1, static_cast<int>(std::ceil((br[s + 1] - br[s]) / (step * whole))));
    for (int k = 1; k <= m; ++k) out.push_back(br[s] + (br[s + 1] - br[s]) * k / m);
  }
  return out;
}

}  // namespace

std::vector<QuadraturePoint> span_points(const SplineSpace& space, int n, double step) {
  const GaussRule& g = gauss_legendre(n);
  const std::vector<double> bu = cells(space.knots_u, space.degree_u, step);
  const std::vector<double> bv = cells(space.knots_v, space.degree_v, step);
  std::vector<QuadraturePoint> out;
  out.reserve((bu.size() - 1) * (bv.size() - 1) * g.nodes.size() * g.nodes.size());
  for (size_t a = 0; a + 1 < bu.size(); ++a) {
    const double hu = 0.5 * (bu[a + 1] - bu[a]);
    for (size_t b = 0; b + 1 < bv.size(); ++b) {
      const double hv = 0.5 * (bv[b + 1] - bv[b]);
      for (size_t i = 0; i < g.nodes.size(); ++i)
        for (size_t j = 0; j < g.nodes.size(); ++j)
          out.push_back({bu[a] + hu * (g.nodes[i] + 1.0), bv[b] + hv * (g.nodes[j] + 1.0),
                         g.weights[i] * g.weights[j] * hu * hv});
    }
  }
  return out;
}

}  // namespace varsurf
