// SPDX-License-Identifier: LGPL-2.1-or-later
// The discrete L-curve of a truncated SVD (Hansen; Michalik & Bruderlin 4.2): for each truncation
// k, the residual norm rho_k and the norm eta_k of the solution's change, and its corner.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace varsurf {

struct LCurve {
  std::vector<int> k;                 // truncations 1..K
  std::vector<double> residual;       // rho_k = |A x_k - b|
  std::vector<double> solution_norm;  // eta_k = |x_k - x_0| (TSVD) -- grows with k
  int corner = 0;                     // the chosen truncation (0 if there are no directions)
};

// sigma: singular values, descending and positive. gain_sq(i): |u_i^T r_0|^2, the squared
// projection of the start residual r_0 = b - A x_0 on u_i (summed over right-hand sides).
// total_sq: |r_0|^2. The corner is the point of the log-log curve farthest below the chord from
// its first to its last point, with both axes scaled to [0, 1]: the knee between the steep
// residual leg and the steep solution-norm leg. Every direction is kept when the problem is well
// posed: its condition number is at most 1e3, or the solution norm grows less than twofold
// beyond the knee. InvalidInput for
// mismatched or unsorted input.
LCurve lcurve(const Eigen::VectorXd& sigma, const Eigen::VectorXd& gain_sq, double total_sq);

// The corner (1-based) of any discrete L-curve given by its points, e.g. the iterates of a
// regularizing Krylov method: the knee rule and the well-posed rule of lcurve().
int lcurve_corner(const std::vector<double>& residual, const std::vector<double>& solution_norm);

}  // namespace varsurf
