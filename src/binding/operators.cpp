// SPDX-License-Identifier: LGPL-2.1-or-later
// Point constraints beyond position, and the external energy operators.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "binding.hpp"
#include "varsurf/core/curvature_constraint.hpp"
#include "varsurf/core/external_energy.hpp"
#include "varsurf/core/point_constraints.hpp"
#include "varsurf/core/point_curvature.hpp"
#include "varsurf/core/ribbon_constraint.hpp"
#include "varsurf/core/seam_ties.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace varsurf::binding {

void bind_operators(py::module_& m) {
  py::class_<TangentConstraint>(m, "TangentConstraint",
                                "The derivative w_u (direction 0) or w_v (direction 1) at (u, v) "
                                "is target.")
      .def(py::init([](double u, double v, int direction, Eigen::Vector3d target, double weight) {
             return TangentConstraint{u, v, direction, target, weight};
           }),
           "u"_a = 0.0, "v"_a = 0.0, "direction"_a = 0, "target"_a = Eigen::Vector3d::UnitX(),
           "weight"_a = 1.0)
      .def_readwrite("u", &TangentConstraint::u)
      .def_readwrite("v", &TangentConstraint::v)
      .def_readwrite("direction", &TangentConstraint::direction)
      .def_readwrite("target", &TangentConstraint::target)
      .def_readwrite("weight", &TangentConstraint::weight);

  py::class_<NormalConstraint>(m, "NormalConstraint",
                               "The normal at (u, v) is parallel to normal (couples x, y, z).")
      .def(py::init([](double u, double v, Eigen::Vector3d normal, double weight) {
             return NormalConstraint{u, v, normal, weight};
           }),
           "u"_a = 0.0, "v"_a = 0.0, "normal"_a = Eigen::Vector3d::UnitZ(), "weight"_a = 1.0)
      .def_readwrite("u", &NormalConstraint::u)
      .def_readwrite("v", &NormalConstraint::v)
      .def_readwrite("normal", &NormalConstraint::normal)
      .def_readwrite("weight", &NormalConstraint::weight);

  py::class_<PlanePointConstraint>(m, "PlanePointConstraint",
                                   "The point at (u, v) lies in the plane (origin, normal).")
      .def(py::init([](double u, double v, Eigen::Vector3d origin, Eigen::Vector3d normal,
                       double weight) {
             return PlanePointConstraint{u, v, origin, normal, weight};
           }),
           "u"_a = 0.0, "v"_a = 0.0, "origin"_a = Eigen::Vector3d::Zero(),
           "normal"_a = Eigen::Vector3d::UnitZ(), "weight"_a = 1.0)
      .def_readwrite("u", &PlanePointConstraint::u)
      .def_readwrite("v", &PlanePointConstraint::v)
      .def_readwrite("origin", &PlanePointConstraint::origin)
      .def_readwrite("normal", &PlanePointConstraint::normal)
      .def_readwrite("weight", &PlanePointConstraint::weight);

  py::class_<LinePointConstraint>(m, "LinePointConstraint",
                                  "The point at (u, v) lies on the line (origin, direction).")
      .def(py::init([](double u, double v, Eigen::Vector3d origin, Eigen::Vector3d direction,
                       double weight) {
             return LinePointConstraint{u, v, origin, direction, weight};
           }),
           "u"_a = 0.0, "v"_a = 0.0, "origin"_a = Eigen::Vector3d::Zero(),
           "direction"_a = Eigen::Vector3d::UnitZ(), "weight"_a = 1.0)
      .def_readwrite("u", &LinePointConstraint::u)
      .def_readwrite("v", &LinePointConstraint::v)
      .def_readwrite("origin", &LinePointConstraint::origin)
      .def_readwrite("direction", &LinePointConstraint::direction)
      .def_readwrite("weight", &LinePointConstraint::weight);

  py::class_<RibbonConstraint>(m, "RibbonConstraint",
                               "Along the 2D preimage, the sheet's normal follows the 3D field "
                               "normals(t) (least squares over the curve; couples x, y, z).")
      .def(py::init([](BSplineCurve preimage, BSplineCurve normals, double weight) {
             return RibbonConstraint{std::move(preimage), std::move(normals), weight};
           }),
           "preimage"_a, "normals"_a, "weight"_a = 1.0)
      .def_readwrite("preimage", &RibbonConstraint::preimage)
      .def_readwrite("normals", &RibbonConstraint::normals)
      .def_readwrite("weight", &RibbonConstraint::weight);

  m.def(
      "ribbon_angle_error",
      [](const SplineSpace& space, const Eigen::MatrixX3d& poles, const RibbonConstraint& c,
         int samples) { return ribbon_angle_error(space, poles, c, samples); },
      "space"_a, "poles"_a, "ribbon"_a, "samples"_a = 200,
      "Largest angle (radians) between the sheet's normal and the ribbon's field.");

  py::class_<CurvatureConstraint>(
      m, "CurvatureConstraint",
      "G2 along the 2D preimage: the sheet's normal curvature across it equals the neighbour's, "
      "given as its normal field normals(t) and its second fundamental form shape(t) (6 "
      "components xx, yy, zz, xy, xz, yz). Not linear: solve_sheet iterates.")
      .def(py::init(
               [](BSplineCurve preimage, BSplineCurve normals, BSplineCurve shape, double weight) {
                 return CurvatureConstraint{std::move(preimage), std::move(normals),
                                            std::move(shape), weight};
               }),
           "preimage"_a, "normals"_a, "shape"_a, "weight"_a = 1.0)
      .def_readwrite("preimage", &CurvatureConstraint::preimage)
      .def_readwrite("normals", &CurvatureConstraint::normals)
      .def_readwrite("shape", &CurvatureConstraint::shape)
      .def_readwrite("weight", &CurvatureConstraint::weight);

  m.def(
      "curvature_jump",
      [](const SplineSpace& space, const Eigen::MatrixX3d& poles, const CurvatureConstraint& c,
         double floor, int samples) { return curvature_jump(space, poles, c, floor, samples); },
      "space"_a, "poles"_a, "curvature"_a, "floor"_a, "samples"_a = 200,
      "Largest relative jump between the sheet's and the neighbour's normal curvature across the "
      "pre-image, relative to max(|k|, floor).");

  py::class_<PointCurvatureConstraint>(
      m, "PointCurvatureConstraint",
      "The sheet's normal curvatures at (u, v) along u and v are kappa_u and kappa_v (signed: "
      "positive bends toward the normal w_u x w_v); along_u/along_v say which are asked. Not "
      "linear: solve_sheet iterates.")
      .def(py::init([](double u, double v, double kappa_u, double kappa_v, bool along_u,
                       bool along_v, double weight) {
             return PointCurvatureConstraint{u, v, kappa_u, kappa_v, along_u, along_v, weight};
           }),
           "u"_a = 0.0, "v"_a = 0.0, "kappa_u"_a = 0.0, "kappa_v"_a = 0.0, "along_u"_a = true,
           "along_v"_a = true, "weight"_a = 1.0)
      .def_readwrite("u", &PointCurvatureConstraint::u)
      .def_readwrite("v", &PointCurvatureConstraint::v)
      .def_readwrite("kappa_u", &PointCurvatureConstraint::kappa_u)
      .def_readwrite("kappa_v", &PointCurvatureConstraint::kappa_v)
      .def_readwrite("along_u", &PointCurvatureConstraint::along_u)
      .def_readwrite("along_v", &PointCurvatureConstraint::along_v)
      .def_readwrite("weight", &PointCurvatureConstraint::weight);

  m.def("normal_curvatures", &normal_curvatures, "space"_a, "poles"_a, "u"_a, "v"_a,
        "The sheet's normal curvatures (kappa_u, kappa_v) at (u, v), signed along w_u x w_v.");

  m.def("point_curvature_error", &point_curvature_error, "space"_a, "poles"_a, "curvature"_a,
        "floor"_a,
        "Largest |kappa - target| over the asked directions, relative to max(|target|, floor).");

  m.def(
      "seam_mismatch",
      [](const SplineSpace& space, const Eigen::MatrixX3d& poles, int direction, int samples) {
        return seam_mismatch(space, poles, direction, samples);
      },
      "space"_a, "poles"_a, "direction"_a, "samples"_a = 100,
      "How far the sheet is from closed along u (direction 0) or v (1): the largest difference "
      "of position and derivatives (scaled by the span length) across its seam.");

  m.def(
      "seam_continuity",
      [](const SplineSpace& space, const Eigen::MatrixX3d& poles, int direction, double tolerance,
         int samples) { return seam_continuity(space, poles, direction, tolerance, samples); },
      "space"_a, "poles"_a, "direction"_a, "tolerance"_a = 1e-9, "samples"_a = 100,
      "Highest derivative order up to which the poles are continuous across the seam along u "
      "(direction 0) or v (1), relative to their extent; -1 when the two ends do not meet.");

  py::class_<Region>(m, "Region",
                     "A region of the parameter domain: the rectangle [u0, u1] x [v0, v1], or "
                     "the area enclosed by `loop` (a closed polygon of (u, v) points) if given.")
      .def(py::init(
               [](double u0, double u1, double v0, double v1, std::vector<Eigen::Vector2d> loop) {
                 Region r(u0, u1, v0, v1);
                 r.loop = std::move(loop);
                 return r;
               }),
           "u0"_a = 0.0, "u1"_a = 1.0, "v0"_a = 0.0, "v1"_a = 1.0,
           "loop"_a = std::vector<Eigen::Vector2d>())
      .def_readwrite("u0", &Region::u0)
      .def_readwrite("u1", &Region::u1)
      .def_readwrite("v0", &Region::v0)
      .def_readwrite("v1", &Region::v1)
      .def_readwrite("loop", &Region::loop);

  py::class_<QuadraturePoint>(m, "QuadraturePoint")
      .def_readonly("u", &QuadraturePoint::u)
      .def_readonly("v", &QuadraturePoint::v)
      .def_readonly("weight", &QuadraturePoint::weight);

  m.def(
      "region_quadrature",
      [](const SplineSpace& space, const Region& region) {
        space.validate();  // before its domain is read (empty knots have none)
        check_region(space, region, "region");
        return region_quadrature(space, region);
      },
      "space"_a, "region"_a,
      "Quadrature points and weights over the region, exact for products of two basis "
      "functions.");

  m.def("poles_in_region", &poles_in_region, "space"_a, "region"_a,
        "Flat indices of the poles supported inside the region (to freeze it).");

  py::enum_<AttractorKind>(m, "AttractorKind")
      .value("point", AttractorKind::point)
      .value("plane", AttractorKind::plane)
      .value("line", AttractorKind::line);

  py::class_<Attractor>(m, "Attractor",
                        "strength * integral over region of |P (w - origin)|^2: P = I (point), "
                        "along direction (plane normal), or across direction (line).")
      .def(py::init([](AttractorKind kind, Region region, Eigen::Vector3d origin,
                       Eigen::Vector3d direction, double strength) {
             return Attractor{kind, region, origin, direction, strength};
           }),
           "kind"_a = AttractorKind::point, "region"_a = Region(),
           "origin"_a = Eigen::Vector3d::Zero(), "direction"_a = Eigen::Vector3d::UnitZ(),
           "strength"_a = 1.0)
      .def_readwrite("kind", &Attractor::kind)
      .def_readwrite("region", &Attractor::region)
      .def_readwrite("origin", &Attractor::origin)
      .def_readwrite("direction", &Attractor::direction)
      .def_readwrite("strength", &Attractor::strength);

  py::class_<Repeller>(m, "Repeller",
                       "strength * integral over region of 1 / |w - origin|^2: pushes the region "
                       "away (iterated: see SolveOptions.max_iterations).")
      .def(py::init([](Region region, Eigen::Vector3d origin, double strength) {
             return Repeller{region, origin, strength};
           }),
           "region"_a = Region(), "origin"_a = Eigen::Vector3d::Zero(), "strength"_a = 1.0)
      .def_readwrite("region", &Repeller::region)
      .def_readwrite("origin", &Repeller::origin)
      .def_readwrite("strength", &Repeller::strength);

  py::class_<Director>(m, "Director",
                       "strength * integral over region of (d . w_u)^2 + (d . w_v)^2: normals "
                       "pushed toward direction d.")
      .def(py::init([](Region region, Eigen::Vector3d direction, double strength) {
             return Director{region, direction, strength};
           }),
           "region"_a = Region(), "direction"_a = Eigen::Vector3d::UnitZ(), "strength"_a = 1.0)
      .def_readwrite("region", &Director::region)
      .def_readwrite("direction", &Director::direction)
      .def_readwrite("strength", &Director::strength);
}

}  // namespace varsurf::binding
