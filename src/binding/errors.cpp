// SPDX-License-Identifier: LGPL-2.1-or-later
#include <Standard_Failure.hxx>

#include <string>

#include "binding.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace py = pybind11;

namespace varsurf::binding {

void bind_errors(py::module_& m) {
  auto& invalid = py::register_exception<InvalidInput>(m, "InvalidInput", PyExc_ValueError);
  invalid.attr("__doc__") =
      "Input the model cannot represent: inconsistent knots or sizes, NaN, a curve outside the "
      "sheet, a garbage BREP string. Subclass of ValueError.";
  auto& solve = py::register_exception<SolveFailure>(m, "SolveFailure", PyExc_RuntimeError);
  solve.attr("__doc__") =
      "Well-formed input, but the numerical solve failed (singular system). Subclass of "
      "RuntimeError.";
  auto& cancelled = py::register_exception<Cancelled>(m, "Cancelled", PyExc_RuntimeError);
  cancelled.attr("__doc__") =
      "The solve stopped because SolveOptions.keep_going returned False. Subclass of "
      "RuntimeError.";
  auto& limit = py::register_exception<ResourceLimit>(m, "ResourceLimit", PyExc_RuntimeError);
  limit.attr("__doc__") =
      "The solve would exceed SolveOptions.max_unknowns, memory_limit or time_limit. Subclass "
      "of RuntimeError.";
  auto& geometry =
      py::register_exception<occ::GeometryError>(m, "GeometryError", PyExc_RuntimeError);
  geometry.attr("__doc__") =
      "OpenCASCADE failed (Standard_Failure) or a bridge step (BREP, STEP, face building) failed. "
      "Subclass of RuntimeError.";
  // OCCT exceptions are not std::exception; pybind11 would call them unknown.
  static PyObject* geometry_type = geometry.ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Standard_Failure& failure) {
      PyErr_SetString(geometry_type, ("OpenCASCADE raised " + occ::describe(failure)).c_str());
    }
  });
}

}  // namespace varsurf::binding
