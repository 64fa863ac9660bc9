// SPDX-License-Identifier: LGPL-2.1-or-later
// Several sheets and their shared space curves solved as one system (Welch & Witkin sec. 5).
//
// A join says that a sheet contains a space curve: w_s(c_s(t)) = C(t) along the sheet's own
// pre-image c_s. A fixed curve is data (a curve constraint on each sheet); a variational curve's
// poles are unknowns of the same system, with their own fairness energy (of the displacement from
// the start curve, so that the curve keeps its shape where nothing pulls it) and their own point
// handles, so moving a handle moves the curve and every sheet joined to it.
//
// A hinge sets the angle between two sheets across a join (pi: tangent-continuous). The angle is
// not linear in the poles: each sheet's tangent plane along the seam is held by a ribbon across its
// pre-image (W&W 4.2.2, RibbonConstraint::across_only) to aimed normals, whose normals
// are re-aimed after every solve -- the two sheets' in-sheet directions across the seam are turned
// evenly about their bisector until they make the angle -- and the system is solved again until
// the aim stops changing. The rows are fitted like curves (to SolveOptions::fit_tolerance), so a
// seam the sheets' spaces cannot turn exactly is met as closely as fairness allows; the report
// gives the angles reached.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/sheet_solver.hpp"

namespace varsurf {

// The curve point at parameter t must be `target` (a handle of a variational curve).
struct CurveHandle {
  double t = 0.0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double weight = 1.0;
};

struct SpaceCurve {
  BSplineCurve start;  // 3D, non-rational: the curve (fixed) or the start and rest shape
  bool variational = false;
  double stretch = 0.0;              // energy of the displacement from `start`:
  double bend = 1.0;                 // integral of stretch |D'|^2 + bend |D''|^2 dt
  std::vector<CurveHandle> handles;  // variational only
  // Variational only: the curve is closed (a ring); its two ends are one point, across which its
  // displacement from `start` is tied C^(degree-1), so the closing point is like any other.
  bool closed = false;
};

struct Join {
  int sheet = 0;
  int curve = 0;
  BSplineCurve preimage;  // 2D, in the sheet's (u, v), over the curve's parameter range
  // +1 if the sheet's trimmed region lies left of the pre-image's direction in (u, v), -1 if
  // right; needed by hinges to tell which way each sheet leaves the seam.
  int side = 0;
  double weight = 1.0;
  // Fit every direction the space holds (as CurveConstraint::exact); otherwise the join is fitted
  // until it is within SolveOptions::fit_tolerance (rows of a variational curve count their
  // distance from the start shapes) and the rest is left to fairness.
  bool exact = false;
};

struct Hinge {
  int curve = 0;
  int sheet_a = 0;
  int sheet_b = 0;
  double angle = 3.14159265358979323846;  // radians in (0, pi]: between the sheets across the seam
  double weight = 1.0;
};

struct ModelProblem {
  std::vector<SheetProblem> sheets;  // their own constraints stay theirs
  std::vector<SpaceCurve> curves;
  std::vector<Join> joins;
  std::vector<Hinge> hinges;
  int hinge_iterations = 40;
  double hinge_tolerance = 1e-6;  // radians: stop when no aim turns by more
  int hinge_nodes = 65;           // nodes of each re-aimed normal field (piecewise linear)
};

struct HingeReport {
  double min_angle = 0.0;  // radians, sampled along the seam
  double max_angle = 0.0;
  double max_error = 0.0;  // largest |angle - target|
};

struct ModelReport {
  SolveReport solve;  // of the last solve
  int hinge_iterations = 0;
  bool converged = true;   // false: the aims still turned after hinge_iterations (result kept)
  double last_turn = 0.0;  // radians: the largest change of aim in the last iteration
  std::vector<double> join_gaps;  // per join: largest |w_s(c_s(t)) - C(t)| (model units)
  std::vector<HingeReport> hinges;
  double total_seconds = 0.0;
};

struct ModelResult {
  std::vector<Eigen::MatrixX3d> sheet_poles;
  std::vector<Eigen::MatrixXd> curve_poles;  // pole_count x 3 (fixed curves: as given)
  ModelReport report;
};

// InvalidInput naming the sheet, curve, join or hinge at fault (bad indices, a hinge on a curve
// one of its sheets does not join, a pre-image leaving its sheet, iterated sheet terms).
ModelResult solve_model(const ModelProblem& problem, const SolveOptions& options = {});

}  // namespace varsurf
