// SPDX-License-Identifier: LGPL-2.1-or-later
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "binding.hpp"
#include "varsurf/core/hierarchical_solver.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

void bind_hierarchical(py::module_& m) {
  py::class_<RefineBox>(m, "RefineBox", "Refine the spans of `level` overlapping [u0,u1]x[v0,v1].")
      .def(py::init<>())
      .def(py::init([](int level, double u0, double u1, double v0, double v1) {
             return RefineBox{level, u0, u1, v0, v1};
           }),
           "level"_a, "u0"_a, "u1"_a, "v0"_a, "v1"_a)
      .def_readwrite("level", &RefineBox::level)
      .def_readwrite("u0", &RefineBox::u0)
      .def_readwrite("u1", &RefineBox::u1)
      .def_readwrite("v0", &RefineBox::v0)
      .def_readwrite("v1", &RefineBox::v1);
  py::class_<HierarchicalOptions>(m, "HierarchicalOptions")
      .def(py::init<>())
      .def_readwrite("tolerance", &HierarchicalOptions::tolerance)
      .def_readwrite("max_depth", &HierarchicalOptions::max_depth)
      .def_readwrite("automatic", &HierarchicalOptions::automatic)
      .def_readwrite("manual", &HierarchicalOptions::manual)
      .def_readwrite("samples", &HierarchicalOptions::samples)
      .def_readwrite("influence_level", &HierarchicalOptions::influence_level,
                     "Levels below this keep the start shape: the edit's region of influence.");
  py::class_<HierarchicalReport>(m, "HierarchicalReport")
      .def_readonly("depth", &HierarchicalReport::depth)
      .def_readonly("dofs", &HierarchicalReport::dofs)
      .def_readonly("export_poles", &HierarchicalReport::export_poles)
      .def_readonly("met", &HierarchicalReport::met)
      .def_readonly("max_deviation", &HierarchicalReport::max_deviation)
      .def_readonly("round_error", &HierarchicalReport::round_error)
      .def_readonly("round_dofs", &HierarchicalReport::round_dofs)
      .def_readonly("refined", &HierarchicalReport::refined)
      .def_readonly("solve", &HierarchicalReport::solve)
      .def_readonly("total_seconds", &HierarchicalReport::total_seconds);
  py::class_<HierarchicalResult>(m, "HierarchicalResult")
      .def_readonly("space", &HierarchicalResult::space)
      .def_readonly("poles", &HierarchicalResult::poles)
      .def_readonly("report", &HierarchicalResult::report);
  m.def("solve_hierarchical", &solve_hierarchical, "problem"_a, "hierarchy"_a,
        "options"_a = SolveOptions(), py::call_guard<py::gil_scoped_release>(),
        "Solve `problem` (on its base space) refining locally where its curves are off; "
        "HierarchicalResult on the finest level's space.");
}

}  // namespace varsurf::binding
