// SPDX-License-Identifier: LGPL-2.1-or-later
// A PDE surface from Du & Qin's boundary conditions (their eq. 2, 3 and sec. 4.2) on a sheet over
// [0, 1]^2: Hermite-like (two boundary curves and their derivative curves), Coons-like (four
// boundary curves) and Gordon-like (networks of isoparametric curves), the interior left to the
// Bloor-Wilson energy (pde_energy.hpp). Boundary rows of poles are fitted to the curves and held;
// Hermite data also hold the row beside each, so P_u across the boundary is the derivative curve's.
#pragma once

#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/pde_coefficient.hpp"
#include "varsurf/core/sheet_solver.hpp"

namespace varsurf {

// P(at, t) for a u-curve (t = v), P(t, at) for a v-curve (t = u), with t in [0, 1] the curve's own
// parameter mapped linearly between its crossings with the curves across it (so a curve drawn
// with another parameter range or direction is placed by where it meets the others; between two
// crossings its parameter is taken to run like the surface's).
struct IsoCurve {
  double at = 0.0;
  BSplineCurve curve;  // 3D
};

struct PdeBoundary {
  // P(0, v) and P(1, v): required.
  BSplineCurve u0, u1;
  // Hermite: P_u(0, v) = magnitude0 * (d0(v) - u0(v)), likewise at u = 1 (Du & Qin: the
  // difference between a boundary curve's point and its correspondence on the derivative curve
  // gives the cross-boundary tangent's direction and length per unit of u). Empty: none there.
  BSplineCurve d0, d1;
  double magnitude0 = 1.0, magnitude1 = 1.0;
  // Coons: P(u, 0) and P(u, 1). Empty: free sides (natural boundary conditions of the energy).
  BSplineCurve v0, v1;
  // Gordon: curves the surface contains at interior u_i (P(u_i, v)) and v_j (P(u, v_j)).
  std::vector<IsoCurve> u_curves, v_curves;
  PdeCoefficient a;
};

struct PdeSurfaceOptions {
  int degree = 3;
  int spans_u = 8;
  int spans_v = 8;
  // Distance (model units) within which curves count as meeting: corners, network crossings.
  double tolerance = 1e-3;
};

// Closed boundary curves (both: one closed and the other open is refused) make the surface closed
// along v: the rows are fitted closed and the sheet's seam tied (SheetProblem::closed_v);
// derivative curves and u-curves must be closed too. Without v-curves the closed curves are paired
// by the seam shift and direction that best match u0's shape (v = 0 at u0's start); v-curves
// (open, from u0 to u1, at v in [0, 1)) place them by their crossings, in their cyclic order.
// The energy's plate form (PdeCoefficient::plate_form) is set where a side is free
// (no v0 or v1 on an open surface), the operator's own square elsewhere.
// The curves oriented and checked, fitted, and the sheet to solve: space [0, 1]^2 of the options'
// degree and spans, the fitted rows (and Hermite rows) as fixed poles, Gordon curves as curve
// constraints, the PDE energy. `fit_error` (if given) receives the largest distance between a
// held boundary row's curve and its data. InvalidInput names the curve (u0, d1, v0, u-curve 2,
// ...) and says what is wrong: missing or degenerate curves, corners that do not meet (Coons),
// a derivative curve that does not run beside its boundary curve, isoparametric values outside
// (0, 1), Gordon curves that miss the boundary curves they should meet.
SheetProblem pde_surface_problem(const PdeBoundary& b, const PdeSurfaceOptions& o,
                                 double* fit_error = nullptr);

}  // namespace varsurf
