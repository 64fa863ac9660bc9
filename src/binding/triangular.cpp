// SPDX-License-Identifier: LGPL-2.1-or-later
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "binding.hpp"
#include "varsurf/core/triangle_quads.hpp"
#include "varsurf/core/triangular_bezier.hpp"
#include "varsurf/core/triangular_surface.hpp"
#include "varsurf/occ/closest_point.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

void bind_triangular(py::module_& m) {
  py::class_<TriangularBezier>(m, "TriangularBezier",
                               "A triangular Bezier patch: degree and (n + 1)(n + 2) / 2 control "
                               "points, P_n00 first (see triangle_index).")
      .def(py::init([](int degree, Eigen::MatrixX3d points) {
             TriangularBezier p{degree, std::move(points)};
             p.validate();
             return p;
           }),
           "degree"_a, "points"_a)
      .def_readonly("degree", &TriangularBezier::degree)
      .def_readonly("points", &TriangularBezier::points)
      .def("evaluate", &TriangularBezier::evaluate, "barycentric"_a,
           "The point at barycentric coordinates (u, v, w), u + v + w = 1.");
  m.def("triangle_quads", &triangle_quads, "patch"_a,
        "The patch as three tensor-product Bezier patches of degree n x n (exactly, no "
        "collapsed edges), over the quads through its centroid and edge midpoints.");

  py::enum_<TriangularConstraint::Kind>(m, "TriangularConstraintKind")
      .value("point", TriangularConstraint::Kind::point)
      .value("normal", TriangularConstraint::Kind::normal)
      .value("plane", TriangularConstraint::Kind::plane)
      .value("line", TriangularConstraint::Kind::line);
  py::class_<TriangularConstraint>(m, "TriangularConstraint",
                                   "A point, normal, point-in-plane or point-on-line constraint "
                                   "at barycentric point `at` of a triangle.")
      .def(py::init([](TriangularConstraint::Kind kind, int triangle, Eigen::Vector3d at,
                       Eigen::Vector3d target, Eigen::Vector3d direction) {
             return TriangularConstraint{kind, triangle, at, target, direction};
           }),
           "kind"_a, "triangle"_a, "at"_a, "target"_a = Eigen::Vector3d::Zero(),
           "direction"_a = Eigen::Vector3d::UnitZ())
      .def_readwrite("kind", &TriangularConstraint::kind)
      .def_readwrite("triangle", &TriangularConstraint::triangle)
      .def_readwrite("at", &TriangularConstraint::at)
      .def_readwrite("target", &TriangularConstraint::target)
      .def_readwrite("direction", &TriangularConstraint::direction);
  using OperatorKind = TriangularOperator::Kind;
  py::enum_<OperatorKind>(m, "TriangularOperatorKind")
      .value("point_attractor", OperatorKind::point_attractor)
      .value("plane_attractor", OperatorKind::plane_attractor)
      .value("line_attractor", OperatorKind::line_attractor)
      .value("director", OperatorKind::director)
      .value("repeller", OperatorKind::repeller)
      .value("shape_attractor", OperatorKind::shape_attractor);
  py::class_<TriangularOperator>(m, "TriangularOperator",
                                 "An external energy operator on some triangles (none: all); a "
                                 "shape attractor's target is a ClosestPointTarget.")
      .def(py::init([](OperatorKind kind, std::vector<int> triangles, Eigen::Vector3d origin,
                       Eigen::Vector3d direction, double strength,
                       std::shared_ptr<occ::ClosestPointTarget> target) {
             TriangularOperator op{kind, std::move(triangles), origin, direction, strength, {}};
             if (target) op.closest = [target](const Eigen::Vector3d& p) { return (*target)(p); };
             return op;
           }),
           "kind"_a, "triangles"_a = std::vector<int>(), "origin"_a = Eigen::Vector3d::Zero(),
           "direction"_a = Eigen::Vector3d::UnitZ(), "strength"_a = 1.0,
           "target"_a = std::shared_ptr<occ::ClosestPointTarget>())
      .def_readwrite("kind", &TriangularOperator::kind)
      .def_readwrite("triangles", &TriangularOperator::triangles)
      .def_readwrite("origin", &TriangularOperator::origin)
      .def_readwrite("direction", &TriangularOperator::direction)
      .def_readwrite("strength", &TriangularOperator::strength);
  py::class_<FixedEdge>(m, "FixedEdge",
                        "The control points (degree + 1, from `from` to `to`) a mesh edge must "
                        "take: a curve the surface contains.")
      .def(py::init([](int from, int to, Eigen::MatrixX3d points) {
             return FixedEdge{from, to, std::move(points)};
           }),
           "from"_a, "to"_a, "points"_a)
      .def_readwrite("from_vertex", &FixedEdge::from)
      .def_readwrite("to_vertex", &FixedEdge::to)
      .def_readwrite("points", &FixedEdge::points);
  py::enum_<TriangularSolver>(m, "TriangularSolver")
      .value("automatic", TriangularSolver::automatic)
      .value("direct", TriangularSolver::direct)
      .value("cg", TriangularSolver::cg);
  py::class_<TriangularProblem>(m, "TriangularProblem",
                                "A triangulation (vertices n x 3, triangles) and the surface's "
                                "degree, energy weights, continuity and constraints.")
      .def(py::init<>())
      .def_readwrite("vertices", &TriangularProblem::vertices)
      .def_readwrite("triangles", &TriangularProblem::triangles)
      .def_readwrite("degree", &TriangularProblem::degree)
      .def_readwrite("stretch", &TriangularProblem::stretch)
      .def_readwrite("bend", &TriangularProblem::bend)
      .def_readwrite("interpolate_vertices", &TriangularProblem::interpolate_vertices)
      .def_readwrite("free_vertices", &TriangularProblem::free_vertices)
      .def_readwrite("equilateral_domain", &TriangularProblem::equilateral_domain)
      .def_readwrite("energy_of_displacement", &TriangularProblem::energy_of_displacement)
      .def_readwrite("g1", &TriangularProblem::g1)
      .def_readwrite("approximate_g1", &TriangularProblem::approximate_g1)
      .def_readwrite("border_angle", &TriangularProblem::border_angle)
      .def_readwrite("constraints", &TriangularProblem::constraints)
      .def_readwrite("operators", &TriangularProblem::operators)
      .def_readwrite("fixed_edges", &TriangularProblem::fixed_edges)
      .def_readwrite("nonlinear_iterations", &TriangularProblem::nonlinear_iterations)
      .def_readwrite("nonlinear_tolerance", &TriangularProblem::nonlinear_tolerance)
      .def_readwrite("g1_weight", &TriangularProblem::g1_weight)
      .def_readwrite("g1_rounds", &TriangularProblem::g1_rounds)
      .def_readwrite("solver", &TriangularProblem::solver)
      .def_readwrite("cg_above", &TriangularProblem::cg_above)
      .def_readwrite("cg_tolerance", &TriangularProblem::cg_tolerance)
      .def_readwrite("cg_iterations", &TriangularProblem::cg_iterations)
      .def_readwrite("angle_tolerance", &TriangularProblem::angle_tolerance)
      .def_readwrite("angle_samples", &TriangularProblem::angle_samples);
  py::class_<TriangularReport>(m, "TriangularReport")
      .def_readonly("patches", &TriangularReport::patches)
      .def_readonly("control_points", &TriangularReport::control_points)
      .def_readonly("unknowns", &TriangularReport::unknowns)
      .def_readonly("g1_rows", &TriangularReport::g1_rows)
      .def_readonly("g1_rounds", &TriangularReport::g1_rounds)
      .def_readonly("operator_iterations", &TriangularReport::operator_iterations)
      .def_readonly("constraint_rows", &TriangularReport::constraint_rows)
      .def_readonly("solver", &TriangularReport::solver)
      .def_readonly("cg_iterations", &TriangularReport::cg_iterations)
      .def_readonly("cg_error", &TriangularReport::cg_error)
      .def_readonly("worst_angle", &TriangularReport::worst_angle)
      .def_readonly("edges_measured", &TriangularReport::edges_measured)
      .def_readonly("overruled_edges", &TriangularReport::overruled_edges)
      .def_readonly("overruled_angles", &TriangularReport::overruled_angles)
      .def_readonly("shortest_tangent", &TriangularReport::shortest_tangent)
      .def_readonly("singular_vertices", &TriangularReport::singular_vertices)
      .def_readonly("constraint_residual", &TriangularReport::constraint_residual)
      .def_readonly("flipped", &TriangularReport::flipped)
      .def_readonly("assembly_seconds", &TriangularReport::assembly_seconds)
      .def_readonly("solve_seconds", &TriangularReport::solve_seconds)
      .def_readonly("measure_seconds", &TriangularReport::measure_seconds);
  py::class_<TriangularResult>(m, "TriangularResult")
      .def_readonly("patches", &TriangularResult::patches)
      .def_readonly("control", &TriangularResult::control)
      .def_readonly("report", &TriangularResult::report);
  m.def("solve_triangular", &solve_triangular, "problem"_a,
        py::call_guard<py::gil_scoped_release>(),
        "The fairest G1 surface of triangular Bezier patches over the triangulation.");
}

}  // namespace varsurf::binding
