// SPDX-License-Identifier: LGPL-2.1-or-later
// Core data types. Fields are copied in and out (numpy arrays, lists): assign whole values, e.g.
// `problem.curves = [...]`, not `problem.curves.append(...)`.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>

#include "binding.hpp"
#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/constraints.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"
#include "varsurf/core/spline_space.hpp"
#include "varsurf/core/thin_plate_energy.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

namespace {

void check_finite(double x, const char* what) {
  if (!std::isfinite(x)) throw InvalidInput(std::string(what) + " is not finite");
}

const std::vector<double>& non_empty(const std::vector<double>& knots, const char* what) {
  if (knots.empty()) throw InvalidInput(std::string(what) + " is empty");
  return knots;
}

}  // namespace

void bind_core_types(py::module_& m) {
  py::class_<SplineSpace>(m, "SplineSpace",
                          "Tensor-product B-spline space with fixed weights. Flat clamped knot "
                          "vectors; pole (i, j), i along u, has flat index i * nv() + j.")
      .def(py::init([](int degree_u, int degree_v, std::vector<double> knots_u,
                       std::vector<double> knots_v, Eigen::VectorXd weights) {
             SplineSpace s;
             s.degree_u = degree_u;
             s.degree_v = degree_v;
             s.knots_u = std::move(knots_u);
             s.knots_v = std::move(knots_v);
             s.weights = std::move(weights);
             return s;
           }),
           "degree_u"_a = 3, "degree_v"_a = 3, "knots_u"_a = std::vector<double>{},
           "knots_v"_a = std::vector<double>{}, "weights"_a = Eigen::VectorXd(),
           "Space from degrees and flat knot vectors; weights empty (non-rational) or one per "
           "pole in flat order.")
      .def_readwrite("degree_u", &SplineSpace::degree_u)
      .def_readwrite("degree_v", &SplineSpace::degree_v)
      .def_readwrite("knots_u", &SplineSpace::knots_u, "Flat clamped knot vector along u.")
      .def_readwrite("knots_v", &SplineSpace::knots_v, "Flat clamped knot vector along v.")
      .def_readwrite("weights", &SplineSpace::weights,
                     "Empty (non-rational) or size() positive weights in flat pole order.")
      .def("nu", &SplineSpace::nu, "Number of poles along u.")
      .def("nv", &SplineSpace::nv, "Number of poles along v.")
      .def("size", &SplineSpace::size, "Number of poles, nu() * nv().")
      .def("index", &SplineSpace::index, "i"_a, "j"_a, "Flat index of pole (i, j).")
      .def("rational", &SplineSpace::rational, "True if the space has weights.")
      .def(
          "domain",
          [](const SplineSpace& s) {
            return py::make_tuple(non_empty(s.knots_u, "knots_u").front(), s.knots_u.back(),
                                  non_empty(s.knots_v, "knots_v").front(), s.knots_v.back());
          },
          "Parameter domain as (u_first, u_last, v_first, v_last).")
      .def("validate", &SplineSpace::validate, "Raise InvalidInput if the space is inconsistent.")
      .def_static("uniform", &SplineSpace::uniform, "degree_u"_a, "degree_v"_a, "spans_u"_a,
                  "spans_v"_a, "Uniform clamped space on [0, 1]^2.")
      .def("__repr__", [](const SplineSpace& s) {
        return "SplineSpace(degree_u=" + std::to_string(s.degree_u) +
               ", degree_v=" + std::to_string(s.degree_v) + ", nu=" + std::to_string(s.nu()) +
               ", nv=" + std::to_string(s.nv()) + (s.rational() ? ", rational)" : ")");
      });

  py::class_<BSplineSurface>(m, "BSplineSurface", "A surface of a SplineSpace: size() x 3 poles.")
      .def(py::init([](SplineSpace space, Eigen::MatrixX3d poles) {
             BSplineSurface s;
             s.space = std::move(space);
             s.poles = std::move(poles);
             return s;
           }),
           "space"_a = SplineSpace(), "poles"_a = Eigen::MatrixX3d(0, 3))
      .def_readwrite("space", &BSplineSurface::space)
      .def_readwrite("poles", &BSplineSurface::poles, "size() x 3 poles in flat order.")
      .def(
          "evaluate",
          [](const BSplineSurface& s, double u, double v) {
            s.validate();
            check_finite(u, "u");
            check_finite(v, "v");
            return s.evaluate(u, v);
          },
          "u"_a, "v"_a, "Surface point at (u, v) (clamped into the domain).")
      .def(
          "derivatives",
          [](const BSplineSurface& s, double u, double v, int order) {
            s.validate();
            check_finite(u, "u");
            check_finite(v, "v");
            return evaluate_surface(s.space, s.poles, u, v, order);
          },
          "u"_a, "v"_a, "order"_a = 1,
          "Rows w, w_u, w_v (order >= 1), w_uu, w_uv, w_vv (order 2) at (u, v).")
      .def("validate", &BSplineSurface::validate,
           "Raise InvalidInput if space and poles are inconsistent or not finite.")
      .def("__repr__", [](const BSplineSurface& s) {
        return "BSplineSurface(degree_u=" + std::to_string(s.space.degree_u) +
               ", degree_v=" + std::to_string(s.space.degree_v) +
               ", poles=" + std::to_string(s.poles.rows()) + ")";
      });

  py::class_<BSplineCurve>(m, "BSplineCurve",
                           "A (possibly rational) B-spline curve in any dimension: 3D targets, "
                           "2D (u, v) pre-images.")
      .def(py::init([](int degree, std::vector<double> knots, Eigen::MatrixXd poles,
                       Eigen::VectorXd weights) {
             BSplineCurve c;
             c.degree = degree;
             c.knots = std::move(knots);
             c.poles = std::move(poles);
             c.weights = std::move(weights);
             return c;
           }),
           "degree"_a = 0, "knots"_a = std::vector<double>{}, "poles"_a = Eigen::MatrixXd(),
           "weights"_a = Eigen::VectorXd(),
           "Curve from degree, flat clamped knots, poles (count x dim) and optional weights.")
      .def_readwrite("degree", &BSplineCurve::degree)
      .def_readwrite("knots", &BSplineCurve::knots, "Flat clamped knots, poles + degree + 1.")
      .def_readwrite("poles", &BSplineCurve::poles, "pole_count x dim.")
      .def_readwrite("weights", &BSplineCurve::weights, "Empty, or one positive weight per pole.")
      .def("dim", &BSplineCurve::dim, "Dimension of the poles.")
      .def("pole_count", &BSplineCurve::pole_count)
      .def("rational", &BSplineCurve::rational)
      .def(
          "first", [](const BSplineCurve& c) { return non_empty(c.knots, "knots").front(); },
          "First parameter.")
      .def(
          "last", [](const BSplineCurve& c) { return non_empty(c.knots, "knots").back(); },
          "Last parameter.")
      .def(
          "evaluate",
          [](const BSplineCurve& c, double t) {
            c.validate("curve");
            check_finite(t, "t");
            return c.evaluate(t);
          },
          "t"_a, "Point at t (clamped into the parameter range).")
      .def(
          "derivatives",
          [](const BSplineCurve& c, double t, int order) {
            c.validate("curve");
            check_finite(t, "t");
            return c.derivatives(t, order);
          },
          "t"_a, "order"_a, "Rows 0..order (<= 2): point and derivatives at t.")
      .def(
          "validate",
          [](const BSplineCurve& c, const std::string& what) { c.validate(what.c_str()); },
          "what"_a = "curve", "Raise InvalidInput (message starting with `what`) if inconsistent.")
      .def("__repr__", [](const BSplineCurve& c) {
        return "BSplineCurve(degree=" + std::to_string(c.degree) +
               ", poles=" + std::to_string(c.poles.rows()) + ", dim=" + std::to_string(c.dim()) +
               (c.rational() ? ", rational)" : ")");
      });

  py::class_<ThinPlateWeights>(m, "ThinPlateWeights",
                               "Thin plate under tension: alpha (2x2, stretch) and beta (2x2, "
                               "bend) weights of Welch & Witkin's eq. 4.")
      .def(py::init([](Eigen::Matrix2d alpha, Eigen::Matrix2d beta) {
             ThinPlateWeights w;
             w.alpha = alpha;
             w.beta = beta;
             return w;
           }),
           "alpha"_a = Eigen::Matrix2d::Identity().eval(),
           "beta"_a = Eigen::Matrix2d::Ones().eval())
      .def_readwrite("alpha", &ThinPlateWeights::alpha)
      .def_readwrite("beta", &ThinPlateWeights::beta)
      .def_static("isotropic", &ThinPlateWeights::isotropic, "stretch"_a, "bend"_a,
                  "alpha = stretch * I, beta = bend everywhere.")
      .def("validate", &ThinPlateWeights::validate);

  py::class_<PointConstraint>(m, "PointConstraint", "The sheet point at (u, v) must be target.")
      .def(py::init([](double u, double v, Eigen::Vector3d target, double weight) {
             PointConstraint c;
             c.u = u;
             c.v = v;
             c.target = target;
             c.weight = weight;
             return c;
           }),
           "u"_a = 0.0, "v"_a = 0.0, "target"_a = Eigen::Vector3d::Zero().eval(), "weight"_a = 1.0)
      .def_readwrite("u", &PointConstraint::u)
      .def_readwrite("v", &PointConstraint::v)
      .def_readwrite("target", &PointConstraint::target)
      .def_readwrite("weight", &PointConstraint::weight);

  py::class_<CurveConstraint>(m, "CurveConstraint",
                              "Curve incidence: sheet(preimage(t)) = target(t) over the shared "
                              "parameter range.")
      .def(py::init([](BSplineCurve preimage, BSplineCurve target, double weight, bool exact) {
             CurveConstraint c;
             c.preimage = std::move(preimage);
             c.target = std::move(target);
             c.weight = weight;
             c.exact = exact;
             return c;
           }),
           "preimage"_a = BSplineCurve(), "target"_a = BSplineCurve(), "weight"_a = 1.0,
           "exact"_a = false)
      .def_readwrite("exact", &CurveConstraint::exact,
                     "Fit every direction the space holds (not only to fit_tolerance).")
      .def_readwrite("preimage", &CurveConstraint::preimage, "2D (u, v) curve.")
      .def_readwrite("target", &CurveConstraint::target, "3D curve, same parameter range.")
      .def_readwrite("weight", &CurveConstraint::weight);

  py::class_<SheetProblem>(m, "SheetProblem",
                           "A sheet to solve: space, start poles, energy, constraints and fixed "
                           "poles. List fields are copies: assign whole lists.")
      .def(py::init([](SplineSpace space, Eigen::MatrixX3d initial_poles, ThinPlateWeights energy,
                       std::vector<PointConstraint> points, std::vector<CurveConstraint> curves,
                       std::vector<int> fixed_poles) {
             SheetProblem p;
             p.space = std::move(space);
             p.initial_poles = std::move(initial_poles);
             p.energy = energy;
             p.points = std::move(points);
             p.curves = std::move(curves);
             p.fixed_poles = std::move(fixed_poles);
             return p;
           }),
           "space"_a = SplineSpace(), "initial_poles"_a = Eigen::MatrixX3d(0, 3),
           "energy"_a = ThinPlateWeights(), "points"_a = std::vector<PointConstraint>{},
           "curves"_a = std::vector<CurveConstraint>{}, "fixed_poles"_a = std::vector<int>{})
      .def("__copy__", [](const SheetProblem& p) { return p; })
      .def_readwrite("space", &SheetProblem::space)
      .def_readwrite("initial_poles", &SheetProblem::initial_poles)
      .def_readwrite("energy", &SheetProblem::energy)
      .def_readwrite("pde", &SheetProblem::pde,
                     "PdeCoefficient or None: the Bloor-Wilson PDE energy instead of the thin "
                     "plate (energy is then unused).")
      .def_readwrite("points", &SheetProblem::points)
      .def_readwrite("curves", &SheetProblem::curves)
      .def_readwrite("fixed_poles", &SheetProblem::fixed_poles, "Flat indices held in place.")
      .def_readwrite("rest_poles", &SheetProblem::rest_poles,
                     "Rest shape (size x 3) or empty: the energy acts on p - rest_poles.")
      .def_readwrite("kept_region", &SheetProblem::kept_region,
                     "Region or None: a trimmed sheet's kept part, where the energy and the "
                     "pressure act.")
      .def_readwrite("overhang_energy", &SheetProblem::overhang_energy,
                     "The energy's weight outside kept_region, in [0, 1).")
      .def_readwrite("tangents", &SheetProblem::tangents)
      .def_readwrite("normals", &SheetProblem::normals)
      .def_readwrite("plane_points", &SheetProblem::plane_points)
      .def_readwrite("line_points", &SheetProblem::line_points)
      .def_readwrite("ribbons", &SheetProblem::ribbons)
      .def_readwrite("curvatures", &SheetProblem::curvatures, "G2 conditions (iterated).")
      .def_readwrite("point_curvatures", &SheetProblem::point_curvatures,
                     "Normal curvatures at points (iterated with the G2 conditions).")
      .def_readwrite("closed_u", &SheetProblem::closed_u,
                     "The space's u ends are one seam (the displacement from the start tied "
                     "smooth across it): a sheet closed along u.")
      .def_readwrite("closed_v", &SheetProblem::closed_v,
                     "The space's v ends are one seam (the displacement from the start tied "
                     "smooth across it): a sheet closed along v.")
      .def_readwrite("attractors", &SheetProblem::attractors)
      .def_readwrite("directors", &SheetProblem::directors)
      .def_readwrite("repellers", &SheetProblem::repellers)
      .def_readwrite("shape_attractors", &SheetProblem::shape_attractors)
      .def_readwrite("pressure", &SheetProblem::pressure,
                     "Inflate (> 0, along w_u x w_v) or deflate (< 0); iterated.");

  py::enum_<SolveMode>(m, "SolveMode", "How the constrained problem is solved.")
      .value("automatic", SolveMode::automatic)
      .value("exact", SolveMode::exact)
      .value("penalty", SolveMode::penalty)
      .value("cg", SolveMode::cg)
      .value("tsvd", SolveMode::tsvd)
      .value("mtsvd", SolveMode::mtsvd)
      .value("multigrid", SolveMode::multigrid);

  py::class_<LCurve>(m, "LCurve",
                     "The L-curve of a TSVD/MTSVD solve: per truncation k the "
                     "residual norm and the solution norm, and the chosen corner.")
      .def(py::init<>())
      .def_readonly("k", &LCurve::k)
      .def_readonly("residual", &LCurve::residual)
      .def_readonly("solution_norm", &LCurve::solution_norm)
      .def_readonly("corner", &LCurve::corner);

  py::class_<SolveOptions>(m, "SolveOptions", "Numerical settings of solve_sheet.")
      .def(py::init([](double rank_tolerance, double fit_tolerance, double regularization,
                       int refinement_steps, int max_unknowns) {
             SolveOptions o;
             o.rank_tolerance = rank_tolerance;
             o.fit_tolerance = fit_tolerance;
             o.regularization = regularization;
             o.refinement_steps = refinement_steps;
             o.max_unknowns = max_unknowns;
             return o;
           }),
           "rank_tolerance"_a = SolveOptions().rank_tolerance,
           "fit_tolerance"_a = SolveOptions().fit_tolerance,
           "regularization"_a = SolveOptions().regularization,
           "refinement_steps"_a = SolveOptions().refinement_steps,
           "max_unknowns"_a = SolveOptions().max_unknowns)
      .def("__copy__", [](const SolveOptions& o) { return o; })
      .def_readwrite("rank_tolerance", &SolveOptions::rank_tolerance,
                     "Singular values below rank_tolerance * largest count as zero.")
      .def_readwrite("fit_tolerance", &SolveOptions::fit_tolerance,
                     "RMS distance (model units) at which a constraint cluster counts as met; "
                     "0 fits every direction above rank_tolerance.")
      .def_readwrite("regularization", &SolveOptions::regularization,
                     "Pull toward initial_poles, relative to the energy's scale.")
      .def_readwrite("refinement_steps", &SolveOptions::refinement_steps,
                     "Refinement sweeps of the KKT solve.")
      .def_readwrite("max_unknowns", &SolveOptions::max_unknowns,
                     "Larger problems are refused with InvalidInput.")
      .def_readwrite("keep_tolerance", &SolveOptions::keep_tolerance,
                     "Singular directions at least this fraction of the largest are always kept.")
      .def_readwrite("max_iterations", &SolveOptions::max_iterations,
                     "Nonlinear steps allowed (repellers, shape attractors, pressure).")
      .def_readwrite("step_limit", &SolveOptions::step_limit,
                     "Largest pole move per nonlinear step, relative to the sheet's size.")
      .def_readwrite("curvature_tolerance", &SolveOptions::curvature_tolerance,
                     "G2: stop when every sample's relative curvature jump is below this.")
      .def_readwrite("max_curvature_iterations", &SolveOptions::max_curvature_iterations)
      .def_readwrite("nonlinear_tolerance", &SolveOptions::nonlinear_tolerance,
                     "Converged when no pole moves more than this (relative to the size).")
      .def_readwrite("force_coupled", &SolveOptions::force_coupled,
                     "Solve one 3n system even when every term is separable.")
      .def_readwrite("mode", &SolveOptions::mode, "SolveMode (default automatic).")
      .def_readwrite("penalty_weight", &SolveOptions::penalty_weight,
                     "Penalty mode: mu^2 relative to the energy's mean diagonal.")
      .def_readwrite("cg_tolerance", &SolveOptions::cg_tolerance,
                     "CG mode: relative reduction of the projected residual.")
      .def_readwrite("direct_limit", &SolveOptions::direct_limit,
                     "Automatic mode: more free unknowns than this use CG.")
      .def_readwrite("krylov_limit", &SolveOptions::krylov_limit,
                     "TSVD/MTSVD: larger constraint groups are truncated by CGLS iterations.")
      .def_readwrite("penalty_qr", &SolveOptions::penalty_qr,
                     "Penalty mode: sparse QR of the stacked system instead of Cholesky of its "
                     "normal equations.")
      .def_readwrite("max_fit_factor", &SolveOptions::max_fit_factor,
                     "Penalty mode: refine while a sample is farther than this times "
                     "fit_tolerance.")
      .def_readwrite("time_limit", &SolveOptions::time_limit,
                     "Seconds the solve may take (0: no limit); past it, ResourceLimit.")
      .def_readwrite("memory_limit", &SolveOptions::memory_limit,
                     "Bytes the solve may need by estimate_solve_bytes (0: no limit); larger "
                     "problems are refused with ResourceLimit before allocating.")
      .def_readwrite("keep_going", &SolveOptions::keep_going,
                     "None, or a callable asked between iterative steps; False stops the solve "
                     "(Cancelled).")
      .def_readwrite("penalty_steps", &SolveOptions::penalty_steps,
                     "Penalty mode: at most this many refinement steps.")
      .def_readwrite("max_weight_gain", &SolveOptions::max_weight_gain,
                     "Penalty mode: a slow refinement restarts on a heavier weight, up to this "
                     "multiple of penalty_weight (1: never).")
      .def_readwrite("drag_responses", &SolveOptions::drag_responses,
                     "Penalty mode: updates that translate one or two whole constraints after a "
                     "one-step solve reuse precomputed responses instead of a back-substitution.")
      .def_readwrite("give_up_early", &SolveOptions::give_up_early,
                     "Penalty mode: stop the refinement steps once the residual falls too slowly "
                     "to reach fit_tolerance within penalty_steps (for a caller that refines).")
      .def_readwrite("cluster_limit", &SolveOptions::cluster_limit,
                     "Automatic mode: larger groups of interacting constraints use the penalty "
                     "mode.")
      .def_readwrite("multigrid_from", &SolveOptions::multigrid_from,
                     "Automatic mode: a sheet held by its fixed poles alone with at least this "
                     "many free poles (and a coarser B-spline level) is solved by multigrid.");

  py::class_<SolveReport>(m, "SolveReport", "Sizes, residuals and timings of a solve.")
      .def(py::init<>())
      .def_readonly("mode", &SolveReport::mode, "The SolveMode used (automatic resolved).")
      .def_readonly("mode_reason", &SolveReport::mode_reason, "Why that mode, in words.")
      .def_readonly("back_substitutions", &SolveReport::back_substitutions,
                    "Penalty mode: back-substitutions with the factor (a drag step taken from kept "
                    "responses needs none).")
      .def_readonly("factor_kept", &SolveReport::factor_kept,
                    "Penalty mode, PreparedSheet.change: the earlier factorization served the "
                    "added constraints (the same answer as a new one's, to rounding).")
      .def_readonly("inner_iterations", &SolveReport::inner_iterations,
                    "Penalty refinement steps or CG iterations.")
      .def_readonly("lcurve", &SolveReport::lcurve, "The L-curve (tsvd and mtsvd modes).")
      .def_readonly("unknowns", &SolveReport::unknowns)
      .def_readonly("constraint_samples", &SolveReport::constraint_samples)
      .def_readonly("constraint_rank", &SolveReport::constraint_rank)
      .def_readonly("clusters", &SolveReport::clusters)
      .def_readonly("held_constraints", &SolveReport::held_constraints,
                    "Constraints the rest shape already meets within the fit tolerance: held "
                    "where it has them, not fitted to their data.")
      .def_readonly("coupled", &SolveReport::coupled, "True if one 3n system was solved.")
      .def_readonly("iterations", &SolveReport::iterations, "Nonlinear steps taken.")
      .def_readonly("curvature_iterations", &SolveReport::curvature_iterations,
                    "Newton steps of the G2 conditions (0 without them).")
      .def_readonly("curvature_jump", &SolveReport::curvature_jump,
                    "Largest relative curvature jump of the G2 conditions after the solve.")
      .def_readonly("converged", &SolveReport::converged)
      .def_readonly("last_step", &SolveReport::last_step,
                    "Largest pole move of the last nonlinear step.")
      .def_readonly("conflict", &SolveReport::conflict,
                    "RMS distance by which the constraints contradict each other (near 0 when "
                    "compatible).")
      .def_readonly("constraint_residual", &SolveReport::constraint_residual)
      .def_readonly("kkt_residual", &SolveReport::kkt_residual)
      .def_readonly("assemble_seconds", &SolveReport::assemble_seconds)
      .def_readonly("reduce_seconds", &SolveReport::reduce_seconds)
      .def_readonly("factor_seconds", &SolveReport::factor_seconds)
      .def_readonly("solve_seconds", &SolveReport::solve_seconds)
      .def_readonly("total_seconds", &SolveReport::total_seconds);

  py::class_<SolveResult>(m, "SolveResult", "Solved poles (size() x 3) and the report.")
      .def(py::init<>())
      .def_readonly("poles", &SolveResult::poles)
      .def_readonly("report", &SolveResult::report);
}

}  // namespace varsurf::binding
