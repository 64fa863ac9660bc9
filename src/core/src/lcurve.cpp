// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/lcurve.hpp"

#include <algorithm>
#include <cmath>

#include "varsurf/core/errors.hpp"

namespace varsurf {

int lcurve_corner(const std::vector<double>& residual, const std::vector<double>& solution_norm) {
  if (residual.size() != solution_norm.size()) throw InvalidInput("L-curve: sizes differ");
  const size_t n = residual.size();
  if (n < 3) return static_cast<int>(n);
  // Knee of the log-log curve, axes normalized to [0, 1].
  std::vector<double> x(n), y(n);
  for (size_t i = 0; i < n; ++i) {
    x[i] = std::log10(std::max(residual[i], 1e-300));
    y[i] = std::log10(std::max(solution_norm[i], 1e-300));
  }
  auto normalize = [](std::vector<double>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    const double a = *lo, span = *hi - *lo;
    for (double& t : v) t = span > 0.0 ? (t - a) / span : 0.0;
  };
  normalize(x);
  normalize(y);
  const double dx = x.back() - x.front(), dy = y.back() - y.front();
  const double len = std::hypot(dx, dy);
  double best = -1.0;
  int corner = static_cast<int>(n);
  for (size_t i = 0; i < n; ++i) {
    // Signed distance from the chord; positive on the side of the origin (small rho, small eta).
    const double d = len > 0.0 ? (dx * (y[i] - y.front()) - dy * (x[i] - x.front())) / len : 0.0;
    if (d > best) {
      best = d;
      corner = static_cast<int>(i + 1);
    }
  }
  // A well-posed problem has no corner: no point lies clearly below the chord (no L), or past the
  // knee the solution norm barely grows, so every direction is stable and all are kept (Hansen:
  // truncate only where the norm blows up).
  if (best <= 0.02 || solution_norm.back() <= 2.0 * solution_norm[static_cast<size_t>(corner - 1)])
    corner = static_cast<int>(n);
  return corner;
}

LCurve lcurve(const Eigen::VectorXd& sigma, const Eigen::VectorXd& gain_sq, double total_sq) {
  if (sigma.size() != gain_sq.size()) throw InvalidInput("L-curve: sizes differ");
  if (!sigma.allFinite() || !gain_sq.allFinite() || !std::isfinite(total_sq))
    throw InvalidInput("L-curve: values are not finite");
  for (Eigen::Index i = 0; i < sigma.size(); ++i)
    if (!(sigma(i) > 0.0) || (i > 0 && sigma(i) > sigma(i - 1)))
      throw InvalidInput("L-curve: singular values must be positive and descending");
  LCurve out;
  const Eigen::Index n = sigma.size();
  if (n == 0) return out;
  double rho_sq = std::max(total_sq, gain_sq.sum()), eta_sq = 0.0;
  // Residuals below this are rounding: the log scale would otherwise be ruled by noise.
  const double floor = 1e-14 * std::sqrt(std::max(rho_sq, 1e-300));
  for (Eigen::Index i = 0; i < n; ++i) {
    rho_sq = std::max(0.0, rho_sq - gain_sq(i));
    eta_sq += gain_sq(i) / (sigma(i) * sigma(i));
    out.k.push_back(static_cast<int>(i + 1));
    out.residual.push_back(std::max(std::sqrt(rho_sq), floor));
    out.solution_norm.push_back(std::sqrt(eta_sq));
  }
  // A well-conditioned problem has no L: every direction is stable and all are kept.
  if (n < 3 || sigma(n - 1) >= 1e-3 * sigma(0)) {
    out.corner = static_cast<int>(n);
    return out;
  }
  out.corner = lcurve_corner(out.residual, out.solution_norm);
  return out;
}

}  // namespace varsurf
