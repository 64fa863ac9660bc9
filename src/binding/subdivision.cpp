// SPDX-License-Identifier: LGPL-2.1-or-later
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "binding.hpp"
#include "varsurf/core/subdivision.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

void bind_subdivision(py::module_& m) {
  py::class_<SubdivisionMesh>(m, "SubdivisionMesh",
                              "A Catmull-Clark control mesh: points (n x 3), faces (vertex index "
                              "lists), creases (((a, b), sharpness) per creased edge).")
      .def(py::init<>())
      .def(py::init([](Eigen::MatrixX3d points, std::vector<std::vector<int>> faces,
                       std::vector<std::pair<std::pair<int, int>, double>> creases) {
             return SubdivisionMesh{std::move(points), std::move(faces), std::move(creases)};
           }),
           "points"_a, "faces"_a,
           "creases"_a = std::vector<std::pair<std::pair<int, int>, double>>())
      .def_readwrite("points", &SubdivisionMesh::points)
      .def_readwrite("faces", &SubdivisionMesh::faces)
      .def_readwrite("creases", &SubdivisionMesh::creases);
  py::class_<SubdivisionLevels>(m, "SubdivisionLevels",
                                "The meshes of each level and the limit surface at the finest "
                                "level's vertices.")
      .def_readonly("levels", &SubdivisionLevels::levels)
      .def_readonly("limit_points", &SubdivisionLevels::limit_points)
      .def_readonly("limit_tangent_u", &SubdivisionLevels::limit_tangent_u)
      .def_readonly("limit_tangent_v", &SubdivisionLevels::limit_tangent_v);
  m.def("subdivide", &subdivide, "mesh"_a, "levels"_a, py::call_guard<py::gil_scoped_release>(),
        "Catmull-Clark refinement of the mesh `levels` times (OpenSubdiv), with the limit "
        "surface's points and tangents at the finest level's vertices.");
}

}  // namespace varsurf::binding
