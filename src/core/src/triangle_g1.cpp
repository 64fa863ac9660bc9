// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/triangle_g1.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

G1Weights g1_weights(int patches, bool border, double angle) {
  if (patches < (border ? 1 : 3))
    throw InvalidInput(std::string("a vertex ") + (border ? "on the border" : "inside") +
                       " needs at least " + (border ? "1 patch" : "3 patches") + ", not " +
                       std::to_string(patches));
  if (border && !(angle > 0.0 && angle < 2.0 * M_PI))
    throw InvalidInput("a border vertex's angle must lie in (0, 2 pi)");
  const double c = std::cos((border ? angle : 2.0 * M_PI) / patches);
  if (std::abs(c) < 1e-12) return {0.0, 1.0, 1.0};
  return {1.0, -0.5 / c, -0.5 / c};
}

Eigen::MatrixXd g1_edge_equations(int n, const G1Weights& start, const G1Weights& last,
                                  bool approximate) {
  if (n < 1 || n > 20) throw InvalidInput("a triangular patch has degree 1 to 20");
  // The weights hold for the vectors leaving their vertex. At M_0 those are dM_0, dL_0, dR_0; at
  // M_n they are M_n-1 - M_n = -dM, L_n-1 - M_n = dL - dM and R_n-1 - M_n = dR - dM, so in the
  // identity's terms the end's weights are (-(e + f + g), f, g).
  const G1Weights end{-(last.e + last.f + last.g), last.f, last.g};
  const int columns = 3 * n + 1;
  const auto m_col = [](int i) { return i; };
  const auto l_col = [n](int i) { return n + 1 + i; };
  const auto r_col = [n](int i) { return 2 * n + 1 + i; };
  // One difference term w (dM_i, dL_i, dR_i) of weights (e, f, g) into `row`.
  const auto add = [&](Eigen::MatrixXd& rows, int r, int i, const G1Weights& w, double s) {
    rows(r, m_col(i + 1)) += s * w.e;
    rows(r, m_col(i)) -= s * (w.e + w.f + w.g);
    rows(r, l_col(i)) += s * w.f;
    rows(r, r_col(i)) += s * w.g;
  };
  if (approximate) {
    Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(std::max(n, 2), columns);
    const G1Weights mean{0.5 * (start.e + end.e), 0.5 * (start.f + end.f), 0.5 * (start.g + end.g)};
    add(rows, 0, 0, start, 1.0);
    for (int i = 1; i + 1 < n; ++i) add(rows, i, i, mean, 1.0);
    add(rows, std::max(n, 2) - 1, n - 1, end, 1.0);
    return n == 1 ? Eigen::MatrixXd(rows.topRows(2)) : rows;
  }
  // Coefficient m of the degree-n product: (1 - t) B_i^(n-1) = (n - i) / n B_i^n and
  // t B_i^(n-1) = (i + 1) / n B_(i+1)^n, scaled by n.
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(n + 1, columns);
  for (int m = 0; m <= n; ++m) {
    if (m < n) add(rows, m, m, start, n - m);
    if (m > 0) add(rows, m, m - 1, end, m);
  }
  return rows;
}

namespace {}  // namespace

double shared_edge_angle(const TriangularBezier& a, int a_from, int a_to, const TriangularBezier& b,
                         int b_from, int b_to, int samples) {
  for (const int c : {a_from, a_to, b_from, b_to})
    if (c < 0 || c > 2) throw InvalidInput("a triangle's corners are 0, 1 and 2");
  if (a_from == a_to || b_from == b_to) throw InvalidInput("an edge joins two different corners");
  if (samples < 2 || samples > 100000)
    throw InvalidInput("an edge's angle takes 2 to 100000 samples");
  double worst = 0.0;
  for (int s = 0; s < samples; ++s) {
    const double t = static_cast<double>(s) / (samples - 1);
    const Eigen::Vector3d pa =
        (1.0 - t) * Eigen::Vector3d::Unit(a_from) + t * Eigen::Vector3d::Unit(a_to);
    const Eigen::Vector3d pb =
        (1.0 - t) * Eigen::Vector3d::Unit(b_from) + t * Eigen::Vector3d::Unit(b_to);
    const double d = patch_normal(a, pa).dot(patch_normal(b, pb));
    if (!std::isfinite(d)) return M_PI;  // a patch without a normal there: as bad as it gets
    worst = std::max(worst, std::acos(std::clamp(d, -1.0, 1.0)));
  }
  return worst;
}

}  // namespace varsurf
