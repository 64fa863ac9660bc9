// SPDX-License-Identifier: LGPL-2.1-or-later
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "binding.hpp"
#include "varsurf/core/model_solver.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

void bind_model(py::module_& m) {
  py::class_<CurveHandle>(m, "CurveHandle", "A point of a variational curve: C(t) = target.")
      .def(py::init<>())
      .def_readwrite("t", &CurveHandle::t)
      .def_readwrite("target", &CurveHandle::target)
      .def_readwrite("weight", &CurveHandle::weight);
  py::class_<SpaceCurve>(m, "SpaceCurve",
                         "A curve sheets are joined along: fixed, or variational (its poles are "
                         "unknowns; energy of the displacement from `start`; handles).")
      .def(py::init<>())
      .def_readwrite("start", &SpaceCurve::start)
      .def_readwrite("variational", &SpaceCurve::variational)
      .def_readwrite("stretch", &SpaceCurve::stretch)
      .def_readwrite("bend", &SpaceCurve::bend)
      .def_readwrite("handles", &SpaceCurve::handles)
      .def_readwrite("closed", &SpaceCurve::closed,
                     "Variational: a ring whose two ends are one point (its displacement tied "
                     "smooth across it).");
  py::class_<Join>(m, "Join", "Sheet `sheet` contains curve `curve` along its 2D `preimage`.")
      .def(py::init<>())
      .def_readwrite("sheet", &Join::sheet)
      .def_readwrite("curve", &Join::curve)
      .def_readwrite("preimage", &Join::preimage)
      .def_readwrite("side", &Join::side,
                     "+1 if the sheet's region lies left of the pre-image in (u, v), -1 right")
      .def_readwrite("weight", &Join::weight)
      .def_readwrite("exact", &Join::exact);
  py::class_<Hinge>(m, "Hinge", "The angle (radians, (0, pi]) between two sheets across a curve.")
      .def(py::init<>())
      .def_readwrite("curve", &Hinge::curve)
      .def_readwrite("sheet_a", &Hinge::sheet_a)
      .def_readwrite("sheet_b", &Hinge::sheet_b)
      .def_readwrite("angle", &Hinge::angle)
      .def_readwrite("weight", &Hinge::weight);
  py::class_<ModelProblem>(m, "ModelProblem",
                           "Sheets, space curves, joins and hinges solved as one system. List "
                           "fields are copies: assign whole lists.")
      .def(py::init<>())
      .def_readwrite("sheets", &ModelProblem::sheets)
      .def_readwrite("curves", &ModelProblem::curves)
      .def_readwrite("joins", &ModelProblem::joins)
      .def_readwrite("hinges", &ModelProblem::hinges)
      .def_readwrite("hinge_iterations", &ModelProblem::hinge_iterations)
      .def_readwrite("hinge_tolerance", &ModelProblem::hinge_tolerance)
      .def_readwrite("hinge_nodes", &ModelProblem::hinge_nodes);
  py::class_<HingeReport>(m, "HingeReport")
      .def_readonly("min_angle", &HingeReport::min_angle)
      .def_readonly("max_angle", &HingeReport::max_angle)
      .def_readonly("max_error", &HingeReport::max_error);
  py::class_<ModelReport>(m, "ModelReport")
      .def_readonly("solve", &ModelReport::solve)
      .def_readonly("hinge_iterations", &ModelReport::hinge_iterations)
      .def_readonly("converged", &ModelReport::converged)
      .def_readonly("last_turn", &ModelReport::last_turn)
      .def_readonly("join_gaps", &ModelReport::join_gaps)
      .def_readonly("hinges", &ModelReport::hinges)
      .def_readonly("total_seconds", &ModelReport::total_seconds);
  py::class_<ModelResult>(m, "ModelResult")
      .def_readonly("sheet_poles", &ModelResult::sheet_poles)
      .def_readonly("curve_poles", &ModelResult::curve_poles)
      .def_readonly("report", &ModelResult::report);
  m.def("solve_model", &solve_model, "problem"_a, "options"_a = SolveOptions(),
        py::call_guard<py::gil_scoped_release>(),
        "Solve sheets and space curves as one system (joins, variational curves, hinges); "
        "returns ModelResult. InvalidInput names the sheet, curve, join or hinge at fault.");
}

}  // namespace varsurf::binding
