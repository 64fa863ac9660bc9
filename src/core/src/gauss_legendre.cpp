// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/gauss_legendre.hpp"

#include <cmath>
#include <map>
#include <mutex>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

// P_n(x) and P_n'(x) by the three-term recurrence.
void legendre(int n, double x, double& p, double& dp) {
  double p0 = 1.0, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  p = p1;
  dp = n * (x * p1 - p0) / (x * x - 1.0);
}

GaussRule compute_rule(int n) {
  GaussRule r;
  r.nodes.resize(static_cast<size_t>(n));
  r.weights.resize(static_cast<size_t>(n));
  const double pi = std::acos(-1.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Newton iteration on the Legendre polynomial from the Chebyshev-like initial guess.
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double p = 0.0, dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      legendre(n, x, p, dp);
      const double dx = p / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    legendre(n, x, p, dp);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    r.nodes[static_cast<size_t>(i)] = -x;
    r.nodes[static_cast<size_t>(n - 1 - i)] = x;
    r.weights[static_cast<size_t>(i)] = w;
    r.weights[static_cast<size_t>(n - 1 - i)] = w;
  }
  if (n % 2 == 1) r.nodes[static_cast<size_t>(n / 2)] = 0.0;
  return r;
}

}  // namespace

const GaussRule& gauss_legendre(int n) {
  if (n < 1 || n > 64) throw InvalidInput("Gauss rule size must be in 1..64");
  static std::mutex mutex;
  static std::map<int, GaussRule> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, compute_rule(n)).first;
  return it->second;
}

}  // namespace varsurf
