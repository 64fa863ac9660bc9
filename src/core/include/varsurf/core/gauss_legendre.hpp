// SPDX-License-Identifier: LGPL-2.1-or-later
// Gauss–Legendre nodes and weights on [-1, 1] (Golub–Welsch free: Newton on P_n, exact to 1e-15).
#pragma once

#include <vector>

namespace varsurf {

struct GaussRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

// n-point rule, integrating polynomials of degree <= 2n - 1 exactly. Cached per n.
const GaussRule& gauss_legendre(int n);

}  // namespace varsurf
