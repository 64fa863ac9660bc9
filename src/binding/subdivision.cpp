// SPDX-License-Identifier: LGPL-2.1-or-later
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "binding.hpp"
#include "varsurf/core/curve_chain.hpp"
#include "varsurf/core/detail_edit.hpp"
#include "varsurf/core/limit_patches.hpp"
#include "varsurf/core/multiresolution.hpp"
#include "varsurf/core/patch_blocks.hpp"
#include "varsurf/core/subdivision.hpp"
#include "varsurf/core/triangle_surface.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

namespace {

void bind_meshes(py::module_& m) {
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

void bind_multiresolution(py::module_& m) {
  py::class_<Multiresolution>(m, "Multiresolution",
                              "A base mesh and, per level, detail vectors in local frames.")
      .def(py::init([](SubdivisionMesh base, std::vector<Eigen::MatrixX3d> details) {
             return Multiresolution{std::move(base), std::move(details)};
           }),
           "base"_a, "details"_a)
      .def_readwrite("base", &Multiresolution::base)
      .def_readwrite("details", &Multiresolution::details);
  py::class_<CaptureFit>(m, "CaptureFit", "The limit surface's distance from a captured target.")
      .def_readonly("max_distance", &CaptureFit::max_distance)
      .def_readonly("rms_distance", &CaptureFit::rms_distance);
  py::class_<TriangleSurface>(m, "TriangleSurface",
                              "A triangle mesh to find closest points on (a capture target).")
      .def(py::init<Eigen::MatrixX3d, std::vector<std::array<int, 3>>>(), "points"_a, "triangles"_a)
      .def(
          "closest",
          [](const TriangleSurface& s, const Eigen::MatrixX3d& points) {
            Eigen::MatrixX3d out(points.rows(), 3);
            for (Eigen::Index k = 0; k < points.rows(); ++k)
              out.row(k) = s.closest(points.row(k).transpose()).transpose();
            return out;
          },
          "points"_a, py::call_guard<py::gil_scoped_release>(),
          "The closest point on the mesh to each row.")
      .def("size", &TriangleSurface::size, "The bounding box's diagonal.");
  m.def(
      "capture",
      [](const SubdivisionMesh& base, int levels, const TriangleSurface& target) {
        return capture(base, levels, [&](const Eigen::Vector3d& p) { return target.closest(p); });
      },
      "base"_a, "levels"_a, "target"_a, py::call_guard<py::gil_scoped_release>(),
      "Detail captured from the target onto the base mesh, level by level.");
  m.def(
      "capture_fit",
      [](const Multiresolution& surface, const TriangleSurface& target) {
        return capture_fit(surface, [&](const Eigen::Vector3d& p) { return target.closest(p); });
      },
      "surface"_a, "target"_a, py::call_guard<py::gil_scoped_release>(),
      "How far the surface's limit lies from the target.");
  m.def("reconstruct", &reconstruct, "surface"_a, py::call_guard<py::gil_scoped_release>(),
        "Every level's mesh of a multiresolution surface.");
}

void bind_detail_edit(py::module_& m) {
  py::class_<DetailPin>(m, "DetailPin",
                        "A vertex of a level moved to a target, propagated to its influence "
                        "level.")
      .def(
          py::init([](int level, int vertex, Eigen::Vector3d target, int influence, bool on_limit) {
            return DetailPin{level, vertex, target, influence, on_limit};
          }),
          "level"_a, "vertex"_a, "target"_a, "influence"_a, "on_limit"_a = false)
      .def_readwrite("level", &DetailPin::level)
      .def_readwrite("vertex", &DetailPin::vertex)
      .def_readwrite("target", &DetailPin::target)
      .def_readwrite("influence", &DetailPin::influence)
      .def_readwrite("on_limit", &DetailPin::on_limit);
  py::class_<DetailNormal>(m, "DetailNormal",
                           "A normal prescribed at a vertex of a level, propagated to its "
                           "influence level.")
      .def(py::init([](int level, int vertex, Eigen::Vector3d normal, int influence) {
             return DetailNormal{level, vertex, normal, influence};
           }),
           "level"_a, "vertex"_a, "normal"_a, "influence"_a)
      .def_readwrite("level", &DetailNormal::level)
      .def_readwrite("vertex", &DetailNormal::vertex)
      .def_readwrite("normal", &DetailNormal::normal)
      .def_readwrite("influence", &DetailNormal::influence);
  py::enum_<DetailSolve>(m, "DetailSolve")
      .value("approximate", DetailSolve::approximate)
      .value("direct", DetailSolve::direct)
      .value("sor", DetailSolve::sor);
  py::class_<DetailEditOptions>(m, "DetailEditOptions", "How a detail edit is solved.")
      .def(py::init<>())
      .def_property(
          "stretch", [](const DetailEditOptions& o) { return o.weights.stretch; },
          [](DetailEditOptions& o, double v) { o.weights.stretch = v; })
      .def_property(
          "bend", [](const DetailEditOptions& o) { return o.weights.bend; },
          [](DetailEditOptions& o, double v) { o.weights.bend = v; })
      .def_readwrite("rings", &DetailEditOptions::rings)
      .def_readwrite("solve", &DetailEditOptions::solve)
      .def_readwrite("omega", &DetailEditOptions::omega)
      .def_readwrite("max_sweeps", &DetailEditOptions::max_sweeps)
      .def_readwrite("max_rounds", &DetailEditOptions::max_rounds)
      .def_readwrite("tolerance", &DetailEditOptions::tolerance);
  py::class_<DetailEditReport>(m, "DetailEditReport")
      .def_readonly("max_residual", &DetailEditReport::max_residual)
      .def_readonly("max_normal_angle", &DetailEditReport::max_normal_angle)
      .def_readonly("rounds", &DetailEditReport::rounds)
      .def_readonly("sweeps", &DetailEditReport::sweeps)
      .def_readonly("region_sizes", &DetailEditReport::region_sizes)
      .def_readonly("region_levels", &DetailEditReport::region_levels);
  py::class_<DetailEditResult>(m, "DetailEditResult")
      .def_readonly("surface", &DetailEditResult::surface)
      .def_readonly("report", &DetailEditResult::report);
  py::class_<DetailEditor>(m, "DetailEditor",
                           "The refinement operators of a multiresolution surface's topology, "
                           "shared by its edits.")
      .def(py::init<const SubdivisionMesh&, int>(), "base"_a, "levels"_a,
           py::call_guard<py::gil_scoped_release>())
      .def("levels", &DetailEditor::levels)
      .def("vertices", &DetailEditor::vertices, "level"_a)
      .def("topology", &DetailEditor::topology, "level"_a)
      .def("points", &DetailEditor::points, "surface"_a, py::call_guard<py::gil_scoped_release>(),
           "Every level's points, the base first.")
      .def("normal", &DetailEditor::normal, "surface"_a, "level"_a, "vertex"_a,
           py::call_guard<py::gil_scoped_release>(),
           "The unit normal at a vertex of a level from its divided differences.")
      .def("limit", &DetailEditor::limit, "surface"_a, py::call_guard<py::gil_scoped_release>(),
           "The limit surface at the finest level's vertices.")
      .def("edit",
           py::overload_cast<const Multiresolution&, const std::vector<DetailPin>&,
                             const std::vector<DetailNormal>&, const DetailEditOptions&>(
               &DetailEditor::edit, py::const_),
           "surface"_a, "pins"_a, "normals"_a, "options"_a,
           py::call_guard<py::gil_scoped_release>(), "The surface edited by the pins and normals.")
      .def(
          "snap",
          [](const DetailEditor& e, const Multiresolution& surface, int level,
             const std::vector<int>& vertices, const Eigen::MatrixX3d& targets,
             const TriangleSurface& before) {
            return e.snap(surface, level, vertices, targets,
                          [&](const Eigen::Vector3d& p) { return before.closest(p); });
          },
          "surface"_a, "level"_a, "vertices"_a, "targets"_a, "before"_a,
          py::call_guard<py::gil_scoped_release>(),
          "The surface re-parameterized so that the vertices of a level lie on the targets, its "
          "shape kept (before: the surface as triangles).");
}

void bind_curve_chain(py::module_& m) {
  py::class_<CurveChain>(m, "CurveChain", "The vertices of a mesh level that follow a curve.")
      .def_readonly("vertices", &CurveChain::vertices)
      .def_readonly("parameters", &CurveChain::parameters)
      .def_readonly("points", &CurveChain::points)
      .def_readonly("max_distance", &CurveChain::max_distance)
      .def_readonly("max_gap", &CurveChain::max_gap)
      .def_readonly("closed", &CurveChain::closed);
  m.def("curve_chain", &curve_chain, "mesh"_a, "curve"_a, py::call_guard<py::gil_scoped_release>(),
        "The chain of the mesh's vertices along a curve (a polyline) lying on it.");
}

void bind_limit_patches(py::module_& m) {
  py::class_<LimitPatch>(m, "LimitPatch", "A bicubic Bezier patch of a limit surface.")
      .def_readonly("surface", &LimitPatch::surface)
      .def_readonly("face", &LimitPatch::face)
      .def_readonly("regular", &LimitPatch::regular)
      .def_readonly("u0", &LimitPatch::u0)
      .def_readonly("v0", &LimitPatch::v0)
      .def_readonly("size", &LimitPatch::size);
  py::class_<LimitPatches>(m, "LimitPatches")
      .def_readonly("patches", &LimitPatches::patches)
      .def_readonly("regular", &LimitPatches::regular)
      .def_readonly("end_caps", &LimitPatches::end_caps);
  m.def("limit_patches", &limit_patches, "mesh"_a, "isolation"_a,
        py::call_guard<py::gil_scoped_release>(),
        "The limit surface of a quad mesh as bicubic patches (OpenSubdiv's patch table).");
  m.def("end_cap_deviation", &end_cap_deviation, "mesh"_a, "patches"_a,
        "reference_isolation"_a = 10, "samples"_a = 9, py::call_guard<py::gil_scoped_release>(),
        "The end caps' largest distance from the limit surface.");
  py::class_<PatchBlock>(m, "PatchBlock", "Limit patches written as one B-spline surface.")
      .def_readonly("surface", &PatchBlock::surface)
      .def_readonly("patches", &PatchBlock::patches)
      .def_readonly("cells", &PatchBlock::cells)
      .def_readonly("width", &PatchBlock::width)
      .def_readonly("height", &PatchBlock::height)
      .def_readonly("face", &PatchBlock::face)
      .def_readonly("regular", &PatchBlock::regular);
  py::class_<PatchBlocks>(m, "PatchBlocks")
      .def_readonly("blocks", &PatchBlocks::blocks)
      .def_readonly("deviation", &PatchBlocks::deviation);
  m.def("patch_blocks", &patch_blocks, "mesh"_a, "patches"_a, "max_span"_a = 64,
        "tolerance"_a = 1e-9, py::call_guard<py::gil_scoped_release>(),
        "The limit patches of a quad mesh merged into larger B-spline surfaces.");
}

}  // namespace

void bind_subdivision(py::module_& m) {
  bind_meshes(m);
  bind_limit_patches(m);
  bind_multiresolution(m);
  bind_detail_edit(m);
  bind_curve_chain(m);
}

}  // namespace varsurf::binding
