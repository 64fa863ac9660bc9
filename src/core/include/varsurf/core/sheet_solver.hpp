// SPDX-License-Identifier: LGPL-2.1-or-later
// Minimize the sheet energy subject to its constraints (Welch & Witkin sec. 4.3, eq. 9).
//
// All point and curve constraints form one weighted least-squares system B p = d. Their solution
// set {p : B^T W B p = B^T W d} is reduced to independent rows by an SVD per cluster of constraints
// that share poles (dependent rows -- crossing curves, isoparametric curves, points on curves --
// drop out; contradictory ones are met in least squares). Fixed poles are eliminated. The remaining
// equality-constrained quadratic problem is solved through its sparse KKT system, one factorization
// shared by x, y and z.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "varsurf/core/constraints.hpp"
#include "varsurf/core/curvature_constraint.hpp"
#include "varsurf/core/external_energy.hpp"
#include "varsurf/core/lcurve.hpp"
#include "varsurf/core/pde_coefficient.hpp"
#include "varsurf/core/point_constraints.hpp"
#include "varsurf/core/point_curvature.hpp"
#include "varsurf/core/ribbon_constraint.hpp"
#include "varsurf/core/seam_ties.hpp"
#include "varsurf/core/spline_space.hpp"
#include "varsurf/core/thin_plate_energy.hpp"

namespace varsurf {

struct SheetProblem {
  SplineSpace space;
  Eigen::MatrixX3d initial_poles;  // size() x 3: start shape, values of fixed poles
  ThinPlateWeights energy;
  // The Bloor-Wilson PDE energy (Du & Qin eq. 1) with this coefficient a(u, v) instead of the
  // thin plate (`energy` is then unused); with rest_poles it acts on the displacement (their
  // eq. 4).
  std::optional<PdeCoefficient> pde;
  // Rest shape p^ (size() x 3, or empty for none): the energy becomes (p - p^)^T H (p - p^), so
  // the sheet keeps the rest shape's detail and only its deviation is made fair (Welch & Witkin
  // eq. 6, Boier-Martin et al. 4.1).
  Eigen::MatrixX3d rest_poles;
  // A trimmed sheet's kept part of the parameter domain (e.g. the pre-image of its boundary
  // loop), or none for the whole domain. The energy and the pressure act on it; the rest (the
  // overhang, cut away by the trim) keeps overhang_energy of the energy's weight, so it cannot
  // pull on the kept part's shape but stays smooth and determined.
  std::optional<Region> kept_region;
  double overhang_energy = 1e-4;
  std::vector<PointConstraint> points;
  std::vector<CurveConstraint> curves;
  std::vector<TangentConstraint> tangents;
  std::vector<NormalConstraint> normals;           // couples x, y, z
  std::vector<PlanePointConstraint> plane_points;  // couples x, y, z
  std::vector<LinePointConstraint> line_points;    // couples x, y, z
  std::vector<RibbonConstraint> ribbons;           // couples x, y, z
  // G2 along curves the sheet also contains with G1: not linear, so Newton iterations on the
  // whole constrained solve (each linearized at the last poles); couples x, y, z.
  std::vector<CurvatureConstraint> curvatures;
  // Normal curvatures at points (Du & Qin 4.7.3): iterated with the G2 conditions.
  std::vector<PointCurvatureConstraint> point_curvatures;
  std::vector<Attractor> attractors;             // plane and line kinds couple x, y, z
  std::vector<Director> directors;               // couples x, y, z
  std::vector<Repeller> repellers;               // not quadratic: iterated, couples x, y, z
  std::vector<ShapeAttractor> shape_attractors;  // not quadratic: iterated, couples x, y, z
  // Closed along u (v): the space's two u (v) ends are one seam, as on a cylinder, a revolved
  // face or a tube through closed sections. The displacement from initial_poles is tied across
  // it (sample_seam), so the seam is as smooth as the start shape's plus a C^(p-1) (rational:
  // C2) change: a cylinder's rational circles, C1 by their parametrization, keep a seam whose
  // curvature does not jump.
  bool closed_u = false;
  bool closed_v = false;
  double pressure = 0.0;         // inflate (> 0, along w_u x w_v) or deflate (< 0): iterated
  std::vector<int> fixed_poles;  // flat indices held at initial_poles
};

// How the equality-constrained quadratic problem is solved (the constraints are always first
// reduced to independent orthonormal rows, cluster by cluster).
enum class SolveMode {
  automatic,  // exact, penalty, CG or multigrid by the problem's size and structure (the report
              // says which)
  exact,      // Lagrange multipliers: the sparse KKT system, LU with refinement (W&W eq. 9)
  penalty,    // W&W eq. 10: energy + mu^2 |A x - b|^2 factored once (sparse Cholesky), the
              // constraint residual removed by refinement steps (multiplier updates)
  cg,         // constraints eliminated by projection onto their null space, then
              // Jacobi-preconditioned conjugate gradients on the energy (Veltkamp & Wesselink 6)
  tsvd,       // truncated SVD at the L-curve corner; the rest of the poles stay nearest the start
  mtsvd,      // truncated SVD at the L-curve corner; the rest minimize the energy (side constraint)
  multigrid,  // a sheet held by its fixed poles alone: conjugate gradients preconditioned by
              // multigrid on its B-spline levels (multigrid.hpp); no factor of the fine matrix
};

const char* to_string(SolveMode mode);

struct SolveOptions;
// Throws Cancelled when options.keep_going says stop, ResourceLimit past options.time_limit.
void check_keep_going(const SolveOptions& options);

// Bytes a solve in `mode` of `unknowns` unknowns, each coupled to `row_nonzeros` others in the
// energy, needs at most (assembly and sparse factorization; measured, see solve_limits.cpp).
double estimate_solve_bytes(long long unknowns, long long row_nonzeros, SolveMode mode);

struct SolveOptions {
  SolveMode mode = SolveMode::automatic;
  // Singular values of a constraint cluster below rank_tolerance * largest are treated as zero.
  double rank_tolerance = 1e-9;
  // RMS distance (model units) at which a constraint cluster counts as met: its least-squares
  // fit keeps only as many singular directions as it needs to get there (discrepancy principle)
  // and leaves the rest to the energy. 0 fits every direction above rank_tolerance.
  double fit_tolerance = 0.0;
  // Singular directions at least this fraction of the largest are kept whatever fit_tolerance
  // says: they are well conditioned, and a dropped one would no longer hold the sheet.
  double keep_tolerance = 1e-2;
  // Tikhonov pull toward initial_poles, relative to the energy's scale: keeps directions that
  // neither energy nor constraints determine (e.g. a free affine motion) where they started.
  double regularization = 1e-10;
  // Refinement sweeps against the unshifted system; they also remove the regularization's bias
  // from every direction the problem determines.
  int refinement_steps = 6;
  int max_unknowns = 2000000;  // refuse larger problems with a clear message (ResourceLimit)
  // Wall-clock seconds one solve (with its inner solves: refinement rounds, hinge iterations) may
  // take; checked between its steps, past it the solve stops with ResourceLimit. 0: no limit.
  double time_limit = 0.0;
  // Bytes the solve may need by estimate_solve_bytes; larger problems are refused with
  // ResourceLimit before anything large is allocated. 0: no limit.
  double memory_limit = 0.0;
  // Solve the coupled 3n system even when every term is separable (the separable solve is
  // cheaper and gives the same poles).
  bool force_coupled = false;
  // Repellers, shape attractors and pressure: Gauss-Newton / fixed-point steps, each at most
  // step_limit (relative to the start shape's size) per pole, until no pole moves more than
  // nonlinear_tolerance (relative) or max_iterations is reached.
  int max_iterations = 100;
  double step_limit = 0.05;
  double nonlinear_tolerance = 1e-9;
  // G2 (curvature constraints): Newton steps until every sample's curvature jump, relative to
  // the larger curvature (and to no less than one over the sheet's size), is below
  // curvature_tolerance, at most max_curvature_iterations.
  double curvature_tolerance = 1e-4;
  int max_curvature_iterations = 30;
  // Penalty mode: mu^2 relative to the energy's mean diagonal; refinement also continues while
  // a sample of a constraint is farther than max_fit_factor * fit_tolerance from it.
  double penalty_weight = 1e4;
  double max_fit_factor = 4.0;
  // Penalty mode: at most this many refinement steps (beyond, the space is too coarse for the
  // constraints and a refining caller adds detail); a run on a raised weight that misses the
  // tolerance is followed by one on the configured weight with as many.
  int penalty_steps = 200;
  // Penalty mode: a refinement that would need many steps restarts on a heavier weight, up to
  // this multiple of penalty_weight (1: never). The raised weight stays for the prepared
  // sheet's updates (drags). Joint solves of several sheets (solve_model) keep the weight.
  double max_weight_gain = 30.0;
  // Penalty mode: a prepared sheet's update that only translates one or two whole constraints (a
  // dragged point, a curve moved along by its handle) after a solve done in one refinement step
  // takes that step from one precomputed response per dragged constraint instead of a
  // back-substitution (the same step, to rounding: a 64 x 64 drag update 1.9 -> 0.3 ms).
  bool drag_responses = true;
  // Penalty mode: stop the refinement steps once the constraints' residual falls too slowly to
  // reach fit_tolerance within penalty_steps (reported as the conflict): for a caller that adds
  // detail to a sheet that stays short of the tolerance. Measured: a 19 x 19 sheet ran all 200
  // steps (206 ms) to stop 17 % short; its 35 x 35 successor met the tolerance in 29.
  bool give_up_early = false;
  // Called between the steps of iterative solves (penalty refinement, CG, nonlinear and hinge
  // iterations); returning false stops the solve with Cancelled. Empty: never asked.
  std::function<bool()> keep_going;
  // Penalty mode: factor W&W's stacked least-squares system (mu B; S), S^T S the energy, by
  // sparse QR (SuiteSparseQR) instead of its normal equations by Cholesky: B's condition number is
  // not squared, at the price of a slower factorization.
  bool penalty_qr = false;
  // CG mode: stop when the projected residual falls below this fraction of its start.
  double cg_tolerance = 1e-13;
  // Automatic mode: more free unknowns than this are solved by CG instead of a factorization;
  // below that, constraint groups (rows sharing unknowns) larger than cluster_limit unknowns go
  // to the penalty mode (measured at 32 x 32 poles with 14 curves: the exact mode's dense
  // reduction took 1.05 s, the penalty solve 0.03 s), smaller ones to the exact mode. Problems
  // that fit every direction (fit_tolerance 0, or an exact constraint) stay exact: the penalty
  // mode's refinement converges slowly in weak directions.
  int direct_limit = 400000;
  int cluster_limit = 200;
  // Automatic mode: a sheet held by its fixed poles alone (no constraint rows: a PDE surface's
  // boundary conditions) with at least this many free poles and B-spline levels to coarsen to is
  // solved by multigrid. Measured on PDE sheets held by Hermite data (bench 9): multigrid took
  // 0.55-0.8x the direct solve's time at 35 x 35 poles (961 free), 0.4-0.6x at 67 x 67, 0.5-0.75x
  // at 131 x 131 and 0.5x at 259 x 259, with half its memory there; with fewer free poles than a
  // coarse level's 400 there is nothing to coarsen.
  int multigrid_from = 500;
  // TSVD / MTSVD: constraint groups with more unknowns than this are truncated by CGLS
  // iterations (a Krylov method) instead of a dense SVD.
  int krylov_limit = 1500;
};

struct SolveReport {
  SolveMode mode = SolveMode::exact;  // the mode used (automatic resolved)
  std::string mode_reason;            // why, in words
  int inner_iterations = 0;           // penalty refinement steps or CG iterations (largest)
  // Penalty mode: back-substitutions with the factor (one per refinement step, none for a drag
  // step taken from kept responses, one per dragged constraint when its drag starts).
  int back_substitutions = 0;
  // Penalty mode, PreparedSheet::change(): the earlier factor served, the added constraint rows
  // solved through it exactly (the same answer as a new factorization's, to rounding).
  bool factor_kept = false;
  LCurve lcurve;     // tsvd and mtsvd: the L-curve and its corner
  int unknowns = 0;  // free poles (per coordinate), or free coordinates if coupled
  bool coupled = false;
  int iterations = 0;            // nonlinear steps taken (0 for a quadratic problem)
  int curvature_iterations = 0;  // Newton steps of the G2 conditions (0 without them)
  double curvature_jump = 0.0;   // their largest relative curvature jump after the solve
  bool converged = true;         // false if max_iterations ran out
  double last_step = 0.0;  // largest pole move of the last nonlinear step (model units)        //
                           // one 3n system instead of three n systems sharing one
  int constraint_samples = 0;  // least-squares rows before reduction
  int constraint_rank = 0;     // independent rows kept
  int clusters = 0;            // independent groups of constraints
  // Constraints (clusters; penalty mode: constraints) the start shape, being the energy's
  // unconstrained minimum (a rest shape), already meets within fit_tolerance: held where it
  // has them instead of fitted to their data (discrepancy principle).
  int held_constraints = 0;
  // RMS distance (model units) by which the constraints contradict each other: the least-squares
  // residual at full rank, largest over clusters. Near 0 when they are compatible.
  double conflict = 0.0;
  double constraint_residual = 0.0;  // max |A p - b| of the reduced rows after the solve
  double kkt_residual = 0.0;         // relative residual of the KKT solve
  double assemble_seconds = 0.0;
  double reduce_seconds = 0.0;
  double factor_seconds = 0.0;
  double solve_seconds = 0.0;
  double total_seconds = 0.0;
};

struct SolveResult {
  Eigen::MatrixX3d poles;
  SolveReport report;
};

// Throws InvalidInput for inconsistent problems, SolveFailure if the KKT system is singular.
SolveResult solve_sheet(const SheetProblem& problem, const SolveOptions& options = {});

// A solve kept for interactive edits: when only constraint targets move (a dragged point, a
// curve moved with the same pre-image, a new tangent or plane origin), update() recomputes the
// reduced right-hand sides and back-substitutes with the kept factorization; when constraints
// are added or removed, change() rebuilds only the constraint side.
class PreparedSheet {
 public:
  // Solves the problem (quadratic terms only: repellers, shape attractors and pressure iterate
  // and are refused with InvalidInput).
  explicit PreparedSheet(const SheetProblem& problem, const SolveOptions& options = {});
  ~PreparedSheet();
  PreparedSheet(PreparedSheet&&) noexcept;
  PreparedSheet& operator=(PreparedSheet&&) noexcept;

  const SolveResult& result() const;

  // The same problem with moved targets. InvalidInput if anything else changed (the constraints'
  // matrices, their number, the space, fixed poles, energy or operators): prepare again.
  SolveResult update(const SheetProblem& moved);

  // The same sheet with constraints added, removed or re-placed: the energy's assembly and the
  // samples of unchanged curves are kept; the constraints are reduced and the system factored
  // again. The result is then the prepared state for further updates. InvalidInput if anything
  // but the constraints changed.
  SolveResult change(const SheetProblem& changed);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace varsurf
