// SPDX-License-Identifier: LGPL-2.1-or-later
// Bridge functions: shapes enter and leave as BREP strings (Part.Shape.exportBrepToString /
// importBrepFromString), everything else as core types.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "binding.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/brep_io.hpp"
#include "varsurf/occ/closest_point.hpp"
#include "varsurf/occ/curve_projection.hpp"
#include "varsurf/occ/deviation.hpp"
#include "varsurf/occ/face_builder.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/mass_properties.hpp"
#include "varsurf/occ/normal_field.hpp"
#include "varsurf/occ/patch_shell.hpp"
#include "varsurf/occ/point_projection.hpp"
#include "varsurf/occ/seam_split.hpp"
#include "varsurf/occ/shape_check.hpp"
#include "varsurf/occ/shell_builder.hpp"
#include "varsurf/occ/single_shape.hpp"
#include "varsurf/occ/step_io.hpp"
#include "varsurf/occ/surface_refinement.hpp"
#include "varsurf/occ/trimmed_face.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

void bind_occ_bridge(py::module_& m) {
  py::class_<occ::PreImage>(m, "PreImage", "Result of project_curve.")
      .def(py::init<>())
      .def_readonly("curve", &occ::PreImage::curve,
                    "2D (u, v) B-spline sharing the target's parameter range.")
      .def_readonly("max_distance", &occ::PreImage::max_distance,
                    "Largest distance from the sampled target to the sheet.")
      .def_readonly("fit_error", &occ::PreImage::fit_error,
                    "Largest |preimage(t_k) - projected (u, v)_k| over the samples.")
      .def_readonly("boundary_distance", &occ::PreImage::boundary_distance,
                    "Largest distance from the target to the sheet where its foot point is on "
                    "the sheet's boundary (-1 if it never is).")
      .def_readonly("boundary_t", &occ::PreImage::boundary_t,
                    "The target's parameter where boundary_distance is reached.");

  py::class_<occ::PointOnSheet>(m, "PointOnSheet", "Result of project_point.")
      .def(py::init<>())
      .def_readonly("u", &occ::PointOnSheet::u)
      .def_readonly("v", &occ::PointOnSheet::v)
      .def_readonly("distance", &occ::PointOnSheet::distance);

  m.def(
      "normal_field_brep",
      [](const std::string& face_brep, const BSplineCurve& curve, double angle_deg,
         double max_distance, int samples) {
        return occ::normal_field(occ::only_face(occ::read_brep(face_brep)), curve, angle_deg,
                                 max_distance, samples);
      },
      "face_brep"_a, "curve"_a, "angle_deg"_a = 0.0, "max_distance"_a = 1e-3, "samples"_a = 0,
      "Normal field of a reference face along a 3D curve (turned by angle_deg about the curve's "
      "tangent) as a 3D BSplineCurve with the curve's parameter: a ribbon's target.");

  m.def("normal_field_between", &occ::normal_field_between, "curve"_a, "second"_a,
        "angle_deg"_a = 0.0, "samples"_a = 0,
        "Normal field of the ruled strip from a 3D curve to a second 3D curve (turned by "
        "angle_deg about the curve's tangent): a ribbon's target.");

  py::class_<occ::ClosestPointTarget, std::shared_ptr<occ::ClosestPointTarget>>(
      m, "ClosestPointTarget",
      "Closest points on a shape's faces (or, without faces, its edges): a shape attractor's "
      "target.")
      .def(py::init([](const std::string& brep) {
             return std::make_shared<occ::ClosestPointTarget>(occ::read_brep(brep));
           }),
           "brep"_a)
      .def_property_readonly("on_faces", &occ::ClosestPointTarget::on_faces)
      .def(
          "closest",
          [](const occ::ClosestPointTarget& t, const Eigen::Vector3d& p) { return t(p).point; },
          "point"_a, "The target's point closest to `point`.");

  py::class_<ShapeAttractor>(m, "ShapeAttractor",
                             "strength * integral over region of dist(w, target)^2: the region "
                             "pulled onto a surface or curve (iterated: see "
                             "SolveOptions.max_iterations).")
      .def(py::init(
               [](Region region, std::shared_ptr<occ::ClosestPointTarget> target, double strength) {
                 if (!target) throw InvalidInput("shape attractor: no target");
                 return ShapeAttractor{
                     region, [target](const Eigen::Vector3d& p) { return (*target)(p); }, strength};
               }),
           "region"_a, "target"_a, "strength"_a = 1.0)
      .def_readwrite("region", &ShapeAttractor::region)
      .def_readwrite("strength", &ShapeAttractor::strength);

  m.def(
      "trimmed_face_brep",
      [](const BSplineSurface& surface, const std::vector<BSplineCurve>& loop, double tolerance) {
        return occ::write_brep(occ::make_trimmed_face({surface, loop}, tolerance));
      },
      "surface"_a, "loop"_a, "tolerance"_a = 1e-6,
      "BREP of the sheet's face inside a closed loop of 2D (u, v) curves chained end to start "
      "(edges built from the pre-images, 3D curves derived).");

  py::enum_<occ::TrimPlace>(m, "TrimPlace", "Where a (u, v) of a sheet lies on its base face.")
      .value("inside", occ::TrimPlace::inside)
      .value("over_hole", occ::TrimPlace::over_hole)
      .value("outside", occ::TrimPlace::outside);

  py::class_<occ::TrimHit>(m, "TrimHit", "Result of BaseTrim.place / place_curve.")
      .def(py::init<>())
      .def_readonly("place", &occ::TrimHit::place)
      .def_readonly("parameter", &occ::TrimHit::parameter,
                    "Curve parameter of the sample farthest outside.")
      .def_readonly("distance", &occ::TrimHit::distance,
                    "Distance (mm) from that sample to the base face's boundary.");

  py::class_<occ::TrimCurve>(m, "TrimCurve", "A curve of a base face's boundary on its sheet.")
      .def_readonly("preimage", &occ::TrimCurve::preimage, "2D (u, v) curve on the sheet.")
      .def_readonly("target", &occ::TrimCurve::target,
                    "3D curve of the base face there, with the pre-image's parameter.");

  py::class_<occ::BaseTrim, std::shared_ptr<occ::BaseTrim>>(
      m, "BaseTrim",
      "A base face's trim (its wires: outer boundary and holes) and orientation, for the sheet "
      "made on it.")
      .def(py::init([](const std::string& brep) {
             return std::make_shared<occ::BaseTrim>(occ::only_face(occ::read_brep(brep)));
           }),
           "face_brep"_a)
      .def_property_readonly("natural", &occ::BaseTrim::natural,
                             "The face covers its whole parameter rectangle.")
      .def_property_readonly("same_parameters", &occ::BaseTrim::same_parameters,
                             "The NURBS conversion kept the face's own parameters.")
      .def_property_readonly("normal_sign", &occ::BaseTrim::normal_sign,
                             "+1 if the sheet's Su x Sv is the face's outward normal, else -1.")
      .def(
          "face_brep",
          [](const occ::BaseTrim& t, const BSplineSurface& sheet) {
            return occ::write_brep(t.face(sheet));
          },
          "sheet"_a,
          "BREP of the sheet's face bounded and oriented like the base face (its natural face "
          "when the base is natural).")
      .def(
          "face_binary",
          [](const occ::BaseTrim& t, const BSplineSurface& sheet) {
            return py::bytes(occ::write_brep_binary(t.face(sheet)));
          },
          "sheet"_a, "face_brep as binary BREP (bytes), for Part.Shape.importBinary.")
      .def("boundary", &occ::BaseTrim::boundary,
           "The base face's edges off its parameter rectangle, as pre-images and targets: what "
           "keeps a trimmed boundary in place (empty for a natural face).")
      .def("place", py::overload_cast<double, double, double>(&occ::BaseTrim::place, py::const_),
           "u"_a, "v"_a, "tolerance"_a,
           "Where the sheet's (u, v) lies on the base face (outside by at most `tolerance` mm "
           "counts as inside).")
      .def("place_curve",
           py::overload_cast<const BSplineCurve&, double, int>(&occ::BaseTrim::place, py::const_),
           "preimage"_a, "tolerance"_a, "samples"_a = 0,
           "The sample of a 2D pre-image farthest outside the base face, or inside.");

  py::class_<occ::ShellResult>(m, "ShellResult", "Result of sew_faces_brep.")
      .def_property_readonly("brep",
                             [](const occ::ShellResult& r) { return occ::write_brep(r.shape); })
      .def_readonly("closed", &occ::ShellResult::closed, "True if the faces close into a solid.")
      .def_readonly("valid", &occ::ShellResult::valid)
      .def_readonly("max_tolerance", &occ::ShellResult::max_tolerance)
      .def_readonly("faces", &occ::ShellResult::faces)
      .def_readonly("free_edges", &occ::ShellResult::free_edges)
      .def_readonly("message", &occ::ShellResult::message);

  py::class_<occ::JoinedSheet>(m, "JoinedSheet",
                               "A sheet bounded by shared curves: their indices and its "
                               "pre-images of them (with the 3D curves' parameters).")
      .def(py::init([](BSplineSurface surface, std::vector<int> curves,
                       std::vector<BSplineCurve> preimages) {
             return occ::JoinedSheet{std::move(surface), std::move(curves), std::move(preimages)};
           }),
           "surface"_a, "curves"_a, "preimages"_a);

  m.def("join_sheets", &occ::join_sheets, "curves"_a, "sheets"_a, "tolerance"_a = 1e-6,
        "Sheets sharing 3D curves as one shell (a solid when it closes): the shared edges are "
        "built once, with a pcurve on each sheet.");

  py::class_<occ::PatchShell>(m, "PatchShell", "Patches sewn into a shell, with seam angles.")
      .def_readonly("shell", &occ::PatchShell::shell)
      .def_readonly("regular_angle", &occ::PatchShell::regular_angle)
      .def_readonly("end_cap_angle", &occ::PatchShell::end_cap_angle)
      .def_readonly("regular_seams", &occ::PatchShell::regular_seams)
      .def_readonly("end_cap_seams", &occ::PatchShell::end_cap_seams);
  m.def("patch_shell", &occ::patch_shell, "patches"_a, "end_cap"_a, "tolerance"_a = 1e-7,
        "samples"_a = 11, py::call_guard<py::gil_scoped_release>(),
        "A face per patch sewn into a shell (a solid when it closes), with the tangent-plane "
        "angle across its seams (degrees).");

  m.def(
      "sew_faces_brep",
      [](const std::vector<std::string>& faces, double tolerance) {
        std::vector<TopoDS_Face> list;
        for (const std::string& brep : faces) list.push_back(occ::only_face(occ::read_brep(brep)));
        return occ::sew_faces(list, tolerance);
      },
      "faces"_a, "tolerance"_a = 1e-6,
      "Sew faces (BREP strings) into a shell, and a solid oriented outward when it closes.");

  m.def("project_point", &occ::project_point, "surface"_a, "point"_a,
        "Closest point of the sheet to a 3D point, as (u, v) and the distance.");

  m.def("split_at_seams", &occ::split_at_seams, "surface"_a, "curve"_a, "samples"_a = 0,
        py::call_guard<py::gil_scoped_release>(),
        "The curve's pieces between the points where its closest points on the sheet cross the "
        "seam of a closed direction (the whole curve when it crosses none).");

  py::class_<occ::ShapeCheck>(m, "ShapeCheck", "Result of check_brep (BRepCheck_Analyzer).")
      .def(py::init<>())
      .def_readonly("valid", &occ::ShapeCheck::valid)
      .def_readonly("max_tolerance", &occ::ShapeCheck::max_tolerance,
                    "Largest vertex/edge/face tolerance.")
      .def_readonly("message", &occ::ShapeCheck::message, "'valid' or the first problems found.")
      .def("__bool__", [](const occ::ShapeCheck& c) { return c.valid; });

  m.def(
      "surface_from_face_brep",
      [](const std::string& brep) {
        return occ::surface_from_face(occ::only_face(occ::read_brep(brep)));
      },
      "brep"_a,
      "BSplineSurface of the one face in a BREP string (any surface type is converted to NURBS, "
      "placed, unperiodized and restricted to the face's UV bounds).");

  m.def(
      "curve_from_edge_brep",
      [](const std::string& brep) {
        return occ::curve_from_edge(occ::only_edge(occ::read_brep(brep)));
      },
      "brep"_a, "3D BSplineCurve of the one edge in a BREP string, between its end parameters.");

  m.def(
      "project_curve",
      [](const BSplineSurface& surface, const BSplineCurve& curve, int samples, double tolerance,
         const std::optional<Eigen::Vector3d>& direction) {
        occ::ProjectionOptions options;
        options.samples = samples;
        options.tolerance = tolerance;
        if (direction) options.direction = *direction;
        return occ::project_curve(surface, curve, options);
      },
      "surface"_a, "curve"_a, "samples"_a = 0, "tolerance"_a = occ::ProjectionOptions().tolerance,
      "direction"_a = py::none(), py::call_guard<py::gil_scoped_release>(),
      "Pre-image of a 3D target curve on a sheet: projection of `samples` target points (0 = "
      "automatic) -- orthogonal, or along `direction` (x, y, z) where given -- fitted by a 2D "
      "B-spline with the target's own parameter. Raises InvalidInput if the curve passes more "
      "than `tolerance` beyond the sheet's boundary (along `direction`: if a line through it "
      "misses the sheet or grazes it).");

  m.def("refine_surface", &occ::refine_surface, "surface"_a, "min_spans_u"_a, "min_spans_v"_a,
        "min_degree"_a = 1,
        "The same surface with its degree raised to at least min_degree and knots inserted so "
        "that each direction has at least the given number of spans (longest intervals halved "
        "first).");

  m.def(
      "face_brep",
      [](const BSplineSurface& surface) { return occ::write_brep(occ::make_face(surface)); },
      "surface"_a, "BREP string of a valid face bounded by the sheet's natural boundary.");
  m.def(
      "face_binary",
      [](const BSplineSurface& surface) {
        return py::bytes(occ::write_brep_binary(occ::make_face(surface)));
      },
      "surface"_a, "face_brep as binary BREP (bytes), for Part.Shape.importBinary.");

  m.def("max_deviation", &occ::max_deviation, "surface"_a, "curve"_a, "samples"_a = 200,
        "accept"_a = 0.0, py::call_guard<py::gil_scoped_release>(),
        "Largest distance from the target curve to the whole sheet (boundary included), "
        "independent of the solver: at least `samples` evenly spaced points, more in every knot "
        "span and where the curve turns, the largest peaks refined between them. accept > 0: "
        "samples Newton finds within `accept` of the sheet skip the global search unless they "
        "could be the largest (the same figure, faster).");
  m.def("max_deviations", &occ::max_deviations, "surface"_a, "curves"_a, "samples"_a = 200,
        "accept"_a = 0.0, "stop_above"_a = std::numeric_limits<double>::infinity(),
        py::call_guard<py::gil_scoped_release>(),
        "max_deviation of each curve from one sheet (the sheet's search structure built once). "
        "A finite stop_above ends the measure at the first curve found farther than it: that "
        "curve's figure is a distance beyond stop_above, the curves after it are infinity.");

  m.def(
      "write_step",
      [](const std::string& brep, const std::string& path) {
        occ::write_step(occ::read_brep(brep), path);
      },
      "brep"_a, "path"_a, "Write a BREP string's shape to a STEP file (AP214).");

  m.def(
      "read_step", [](const std::string& path) { return occ::write_brep(occ::read_step(path)); },
      "path"_a, "Shape of a STEP file as a BREP string.");

  m.def(
      "mass_properties",
      [](const std::string& brep, double relative_precision) {
        const occ::MassProperties p =
            occ::mass_properties(occ::read_brep(brep), relative_precision);
        return py::make_tuple(p.area, p.volume);
      },
      "brep"_a, "relative_precision"_a = 1e-9,
      "(area, volume) of a BREP string's shape, integrated adaptively to the relative precision "
      "(Part.Shape.Area / Volume use a fixed rule, good to a few 1e-6 on trimmed B-spline faces).");

  m.def(
      "check_brep", [](const std::string& brep) { return occ::check_shape(occ::read_brep(brep)); },
      "brep"_a, "Validity of a BREP string's shape (BRepCheck_Analyzer) as a ShapeCheck.");
}

}  // namespace varsurf::binding
