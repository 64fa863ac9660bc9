// SPDX-License-Identifier: LGPL-2.1-or-later
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <utility>
#include <vector>

#include "binding.hpp"
#include "varsurf/core/constraints.hpp"
#include "varsurf/core/curve_loop.hpp"
#include "varsurf/core/curve_orientation.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/core/sheet_solver.hpp"
#include "varsurf/core/spline_space.hpp"
#include "varsurf/core/surface_grid.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

void bind_core_functions(py::module_& m) {
  m.def("solve_sheet", &solve_sheet, "problem"_a, "options"_a = SolveOptions(),
        py::call_guard<py::gil_scoped_release>(),
        "Minimize the sheet energy subject to the problem's constraints; returns SolveResult. "
        "Raises InvalidInput for inconsistent problems, SolveFailure for singular systems.");

  py::class_<PreparedSheet>(m, "PreparedSheet",
                            "A solve that keeps its factorization: update() re-solves for moved "
                            "constraint targets by back-substitution (for dragging).")
      .def(py::init<const SheetProblem&, const SolveOptions&>(), "problem"_a,
           "options"_a = SolveOptions(), py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("result", &PreparedSheet::result)
      .def("update", &PreparedSheet::update, "moved"_a, py::call_guard<py::gil_scoped_release>(),
           "SolveResult for the same problem with moved targets; InvalidInput if anything else "
           "changed.")
      .def("change", &PreparedSheet::change, "changed"_a, py::call_guard<py::gil_scoped_release>(),
           "SolveResult with constraints added, removed or re-placed: keeps the energy's assembly "
           "and unchanged curves' samples, rebuilds the constraint side; later updates start from "
           "it.");

  py::class_<LoopStep>(m, "LoopStep")
      .def_readonly("curve", &LoopStep::curve)
      .def_readonly("reversed", &LoopStep::reversed)
      .def_readonly("inside", &LoopStep::inside,
                    "+1 if the enclosed region lies left of the curve's own direction, -1 right");
  py::class_<CurveLoop>(m, "CurveLoop", "2D curves chained into one closed loop.")
      .def_readonly("steps", &CurveLoop::steps)
      .def_readonly("signed_area", &CurveLoop::signed_area);
  m.def("estimate_solve_bytes", &estimate_solve_bytes, "unknowns"_a, "row_nonzeros"_a,
        "mode"_a = SolveMode::automatic,
        "Bytes a solve in `mode` of `unknowns` unknowns, each coupled to `row_nonzeros` others, "
        "needs at most (what SolveOptions.memory_limit is compared with).");

  m.def("reversed_curve", &reversed, "curve"_a,
        "The curve with its parameter reversed (the same points on the same range).");
  m.def("curve_on_range", &on_range, "curve"_a, "t0"_a, "t1"_a,
        "The same points on the parameter range [t0, t1] (knots mapped affinely: exact).");
  m.def("oriented_curve", &oriented, "curve"_a, "start"_a, "end"_a,
        "The curve, or it reversed, whichever pairs its start with `start` and its end with "
        "`end` better (the smaller sum of the two distances).");

  m.def("chain_loop", &chain_loop, "curves"_a, "gap"_a,
        "Order 2D curves end to start into one closed loop (ends within `gap` join); "
        "InvalidInput if they do not close one.");

  m.def(
      "boundary_pole_indices",
      [](const SplineSpace& space, bool closed_u, bool closed_v) {
        space.validate();
        return boundary_pole_indices(space, closed_u, closed_v);
      },
      "space"_a, "closed_u"_a = false, "closed_v"_a = false,
      "Flat indices of the poles on the four boundary rows of the space (the rows at the ends of "
      "a closed direction are a seam and are left out).");

  m.def(
      "incidence_error",
      [](const SplineSpace& space, const Eigen::MatrixX3d& poles, const CurveConstraint& c,
         int samples) {
        // The core trusts its arguments here; check them so bad input cannot crash the host.
        BSplineSurface surface;
        surface.space = space;
        surface.poles = poles;
        surface.validate();
        c.preimage.validate("curve pre-image");
        c.target.validate("target curve");
        if (c.preimage.dim() != 2) throw InvalidInput("curve pre-image must be a 2D (u, v) curve");
        if (c.target.dim() != 3) throw InvalidInput("target curve must be a 3D curve");
        return incidence_error(space, poles, c, samples);
      },
      "space"_a, "poles"_a, "constraint"_a, "samples"_a = 200,
      "Largest |sheet(preimage(t)) - target(t)| over `samples` evenly spaced t.");

  py::class_<SurfaceGrid>(m, "SurfaceGrid", "Points and unit normals on a uniform parameter grid.")
      .def_readonly("nu", &SurfaceGrid::nu)
      .def_readonly("nv", &SurfaceGrid::nv)
      .def_readonly("points", &SurfaceGrid::points, "((nu+1)(nv+1)) x 3, u outer")
      .def_readonly("normals", &SurfaceGrid::normals);
  m.def("sample_grid", &sample_grid, "surface"_a, "nu"_a, "nv"_a,
        py::call_guard<py::gil_scoped_release>(),
        "Points and unit normals of the surface on an (nu+1) x (nv+1) grid over its domain.");

  m.def("flat_knots", &flat_knots, "knots"_a, "mults"_a,
        "Flat knot vector from distinct knots and multiplicities (FreeCAD's form).");

  m.def(
      "split_knots",
      [](const std::vector<double>& flat) {
        std::vector<double> knots;
        std::vector<int> mults;
        split_knots(flat, knots, mults);
        return std::make_pair(knots, mults);
      },
      "flat"_a, "(knots, mults) of a flat knot vector, as FreeCAD's B-spline constructors want.");
}

}  // namespace varsurf::binding
