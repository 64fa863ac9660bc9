// SPDX-License-Identifier: LGPL-2.1-or-later
// A sheet solved on a locally refined space, refined where its curves are not met (Welch &
// Witkin sec. 4.4 and Figure 3): spans whose measured constraint error exceeds the tolerance are
// refined, recursively, until every curve is within the tolerance or the depth limit is reached.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "varsurf/core/hierarchical_space.hpp"
#include "varsurf/core/sheet_solver.hpp"

namespace varsurf {

struct RefineBox {
  int level = 0;  // refine the spans under the box at every level down to this one (with a ring
                  // of neighbours): detail down to level + 1 there
  double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
};

struct HierarchicalOptions {
  double tolerance = 0.01;        // model units: the largest curve deviation accepted
  int max_depth = 4;              // levels above the base
  bool automatic = true;          // refine where curves are off; else only the manual boxes
  std::vector<RefineBox> manual;  // refined before the first solve
  int samples = 400;              // per curve, where its deviation is measured
  // Region of influence (Boier-Martin et al. sec. 4.2): levels below this keep the start shape,
  // so an edit moves the sheet only as far as the finer levels reach (refined around the
  // constraints that need it); 0 lets the whole sheet move.
  int influence_level = 0;
};

struct HierarchicalReport {
  int depth = 0;         // levels above the base in the final space
  int dofs = 0;          // hierarchical degrees of freedom (poles; x3 coordinates)
  int export_poles = 0;  // poles of the exported tensor-product sheet (the finest space)
  bool met = true;       // every curve within the tolerance (false: the depth limit stopped it)
  std::vector<double> max_deviation;  // per curve, in the final solve
  std::vector<double> round_error;    // largest curve deviation after each solve
  std::vector<int> round_dofs;        // dofs of each solve
  std::vector<RefineBox> refined;     // every refined span: its level and parameter box
  SolveReport solve;                  // of the last solve
  double total_seconds = 0.0;         // every round: solves, measurements and refinement
};

struct HierarchicalResult {
  SplineSpace space;       // the finest level's space: the exported sheet
  Eigen::MatrixX3d poles;  // on `space`
  HierarchicalReport report;
};

// The problem's poles on `space`'s finest level, minimizing the problem's energy over the
// hierarchical space (the displacement from the start shape lies in it). `base` is the problem
// on level 0; its fixed poles may only be the whole boundary (a kept boundary). InvalidInput as
// for solve_sheet, and for iterated terms (pressure, repellers, shape attractors).
Eigen::MatrixX3d solve_on_hierarchy(const SheetProblem& base, const HierarchicalSpace& space,
                                    const SolveOptions& options, SolveReport& report,
                                    int influence_level = 0);

// Refine and solve until the curves are met (or the depth limit); see HierarchicalOptions.
HierarchicalResult solve_hierarchical(const SheetProblem& base, const HierarchicalOptions& h,
                                      const SolveOptions& options);

}  // namespace varsurf
