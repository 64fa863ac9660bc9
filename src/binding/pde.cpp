// SPDX-License-Identifier: LGPL-2.1-or-later
// The Bloor-Wilson PDE energy's coefficient a(u, v) (Du & Qin).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "binding.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/multigrid.hpp"
#include "varsurf/core/pde_coefficient.hpp"
#include "varsurf/core/pde_energy.hpp"
#include "varsurf/core/pde_surface.hpp"
#include "varsurf/core/sheet_dynamics.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

void bind_pde(py::module_& m) {
  py::class_<PaintedCoefficient>(m, "PaintedCoefficient", "The PDE coefficient a over a Region.")
      .def(py::init([](Region region, double a) {
             return PaintedCoefficient{std::move(region), a};
           }),
           "region"_a, "a"_a)
      .def_readwrite("region", &PaintedCoefficient::region)
      .def_readwrite("a", &PaintedCoefficient::a);

  py::class_<PdeCoefficient>(
      m, "PdeCoefficient",
      "a(u, v) of Du & Qin's (d_ss + a^2 d_tt)^2 P = 0 in the domain's normalized parameters: a "
      "constant or a scalar B-spline field, with painted regions over it (later over earlier), "
      "blended across their borders over `blend` (a fraction of the domain; 0: sharp).")
      .def(py::init([](double a, std::vector<PaintedCoefficient> painted, double blend) {
             PdeCoefficient c;
             c.a = a;
             c.painted = std::move(painted);
             c.blend = blend;
             return c;
           }),
           "a"_a = 1.0, "painted"_a = std::vector<PaintedCoefficient>{}, "blend"_a = 0.0)
      .def_readwrite("a", &PdeCoefficient::a)
      .def_readwrite("painted", &PdeCoefficient::painted, "List of PaintedCoefficient (a copy).")
      .def_readwrite("blend", &PdeCoefficient::blend)
      .def_readwrite("plate_form", &PdeCoefficient::plate_form,
                     "The plate form int P_ss^2 + 2 a^2 P_st^2 + a^4 P_tt^2 (the same equation "
                     "inside for constant a; free sides held like a free plate's).")
      .def_readwrite("field_space", &PdeCoefficient::field_space,
                     "SplineSpace of the scalar field a(u, v) (with field_values).")
      .def_readwrite("field_values", &PdeCoefficient::field_values,
                     "The field's values, one per basis function of field_space; empty: none.")
      .def("validate", &PdeCoefficient::validate, "sheet"_a,
           "Raise InvalidInput naming the field or region that is wrong on this sheet's space.")
      .def(
          "value",
          [](const PdeCoefficient& c, const SplineSpace& sheet, double u, double v) {
            c.validate(sheet);
            if (!(u >= sheet.u_first() && u <= sheet.u_last() && v >= sheet.v_first() &&
                  v <= sheet.v_last()))
              throw InvalidInput("PdeCoefficient.value: (u, v) is not in the sheet's domain");
            return c.value(sheet, u, v);
          },
          "sheet"_a, "u"_a, "v"_a, "a(u, v) on the sheet's domain.");

  m.def(
      "pde_energy",
      [](const SplineSpace& space, const PdeCoefficient& a, const Eigen::MatrixX3d& poles) {
        const Eigen::SparseMatrix<double> h = assemble_pde(space, a);
        if (poles.rows() != h.rows())
          throw InvalidInput("pde_energy: poles do not match the space");
        return Eigen::Vector3d((poles.transpose() * (h * poles)).diagonal());
      },
      "space"_a, "a"_a, "poles"_a, "The PDE energy of each coordinate of the surface (x, y, z).");

  py::class_<IsoCurve>(
      m, "IsoCurve", "A Gordon curve: P(at, t) (u-curve) or P(t, at) (v-curve), t along the curve.")
      .def(py::init([](double at, BSplineCurve curve) {
             return IsoCurve{at, std::move(curve)};
           }),
           "at"_a, "curve"_a)
      .def_readwrite("at", &IsoCurve::at)
      .def_readwrite("curve", &IsoCurve::curve);

  py::class_<PdeBoundary>(
      m, "PdeBoundary",
      "Du & Qin's boundary conditions: u0, u1 = P(0, v), P(1, v); Hermite derivative curves d0, d1 "
      "(P_u = magnitude * (d - u)); Coons sides v0, v1; Gordon u_curves, v_curves; coefficient a. "
      "Empty curves: not given. List fields are copies: assign whole lists.")
      .def(py::init<>())
      .def_readwrite("u0", &PdeBoundary::u0)
      .def_readwrite("u1", &PdeBoundary::u1)
      .def_readwrite("d0", &PdeBoundary::d0)
      .def_readwrite("d1", &PdeBoundary::d1)
      .def_readwrite("magnitude0", &PdeBoundary::magnitude0)
      .def_readwrite("magnitude1", &PdeBoundary::magnitude1)
      .def_readwrite("v0", &PdeBoundary::v0)
      .def_readwrite("v1", &PdeBoundary::v1)
      .def_readwrite("u_curves", &PdeBoundary::u_curves)
      .def_readwrite("v_curves", &PdeBoundary::v_curves)
      .def_readwrite("a", &PdeBoundary::a);

  py::class_<PdeSurfaceOptions>(m, "PdeSurfaceOptions", "Degree, spans and meeting tolerance.")
      .def(py::init<>())
      .def_readwrite("degree", &PdeSurfaceOptions::degree)
      .def_readwrite("spans_u", &PdeSurfaceOptions::spans_u)
      .def_readwrite("spans_v", &PdeSurfaceOptions::spans_v)
      .def_readwrite("tolerance", &PdeSurfaceOptions::tolerance);

  m.def(
      "pde_surface_problem",
      [](const PdeBoundary& b, const PdeSurfaceOptions& o) {
        double fit = 0.0;
        SheetProblem pb = pde_surface_problem(b, o, &fit);
        return py::make_tuple(std::move(pb), fit);
      },
      "boundary"_a, "options"_a = PdeSurfaceOptions(),
      "(SheetProblem, fit error): the sheet whose solve is the PDE surface, and the largest "
      "distance between a held boundary row and its curve.");

  py::class_<DynamicsParameters>(
      m, "DynamicsParameters",
      "Mass and damping densities (PdeCoefficient as a scalar field: a is "
      "the value), stiffness of the energy, time step (s).")
      .def(py::init<>())
      .def_readwrite("mass", &DynamicsParameters::mass)
      .def_readwrite("damping", &DynamicsParameters::damping)
      .def_readwrite("stiffness", &DynamicsParameters::stiffness)
      .def_readwrite("time_step", &DynamicsParameters::time_step);

  py::class_<Spring>(m, "Spring", "The sheet pulled at (u, v) toward target.")
      .def(py::init([](double u, double v, Eigen::Vector3d target, double stiffness) {
             return Spring{u, v, target, stiffness};
           }),
           "u"_a, "v"_a, "target"_a, "stiffness"_a = 1.0)
      .def_readwrite("u", &Spring::u)
      .def_readwrite("v", &Spring::v)
      .def_readwrite("target", &Spring::target)
      .def_readwrite("stiffness", &Spring::stiffness);

  py::class_<DynamicSheet>(m, "DynamicSheet",
                           "A sheet with mass and damping (Du & Qin eq. 16), held by its fixed "
                           "poles, stepped by backward Euler.")
      .def(py::init<const SheetProblem&, const DynamicsParameters&>(), "problem"_a, "parameters"_a)
      .def("set_springs", &DynamicSheet::set_springs, "springs"_a)
      .def("move_targets", &DynamicSheet::move_targets, "targets"_a)
      .def("step", &DynamicSheet::step, "count"_a = 1, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("poles", &DynamicSheet::poles)
      .def_property_readonly("velocities", &DynamicSheet::velocities)
      .def_property_readonly("time", &DynamicSheet::time)
      .def("kinetic_energy", &DynamicSheet::kinetic_energy)
      .def("potential_energy", &DynamicSheet::potential_energy)
      .def("equilibrium", &DynamicSheet::equilibrium,
           "Where the motion settles (A P = b with the springs).")
      .def_property_readonly("masses", &DynamicSheet::masses);

  py::class_<PinStiffness>(m, "PinStiffness", "A sheet's stiffness where it is pinned.")
      .def_readonly("stiffness", &PinStiffness::stiffness)
      .def_readonly("shape_mass", &PinStiffness::shape_mass);
  m.def("pin_stiffness", &pin_stiffness, "problem"_a, "u"_a, "v"_a,
        "The force per unit move a pull along the normal at (u, v) meets, and the mass per unit "
        "density of the shape the sheet deflects in (the problem's start poles the shape).");

  py::class_<MultigridOptions>(m, "MultigridOptions", "Smoothing sweeps, coarsest size, tolerance.")
      .def(py::init<>())
      .def_readwrite("smoothing", &MultigridOptions::smoothing)
      .def_readwrite("coarsest_poles", &MultigridOptions::coarsest_poles)
      .def_readwrite("tolerance", &MultigridOptions::tolerance)
      .def_readwrite("max_iterations", &MultigridOptions::max_iterations);

  py::class_<MultigridReport>(m, "MultigridReport", "Levels, steps, residual, timings, storage.")
      .def(py::init<>())
      .def_readonly("levels", &MultigridReport::levels)
      .def_readonly("iterations", &MultigridReport::iterations)
      .def_readonly("residual", &MultigridReport::residual)
      .def_readonly("setup_seconds", &MultigridReport::setup_seconds)
      .def_readonly("solve_seconds", &MultigridReport::solve_seconds)
      .def_readonly("stored_entries", &MultigridReport::stored_entries);

  m.def(
      "solve_sheet_multigrid",
      [](const SheetProblem& problem, const MultigridOptions& options) {
        MultigridReport report;
        SolveResult result;
        {
          py::gil_scoped_release release;  // the tuple below needs the interpreter again
          result = solve_sheet_multigrid(problem, options, &report);
        }
        return py::make_tuple(std::move(result), report);
      },
      "problem"_a, "options"_a = MultigridOptions(),
      "(SolveResult, MultigridReport) of a sheet held by its fixed poles alone, by "
      "multigrid-preconditioned conjugate gradients on its B-spline levels.");
}

}  // namespace varsurf::binding
