// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/closest_point.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Curve.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <ShapeAnalysis_Curve.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <algorithm>
#include <gp_Vec.hxx>
#include <limits>
#include <vector>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

Eigen::Vector3d to_eigen(const gp_XYZ& p) {
  return {p.X(), p.Y(), p.Z()};
}

// Inside (u0, u1) by more than a relative 1e-9: the closest point is not on a boundary.
bool strictly_inside(double t, double t0, double t1) {
  const double margin = 1e-9 * (t1 - t0);
  return t > t0 + margin && t < t1 - margin;
}

// The closest point of curve([first, last]) to p: its distance, point and parameter.
// ShapeAnalysis_Curve::Project may answer outside the range on unbounded curves (measured on a
// Geom_Line), so the answer is clamped and the ends compared.
double project_on_curve(const Handle(Geom_Curve) & curve, const gp_Pnt& p, double first,
                        double last, gp_Pnt& point, double& param) {
  ShapeAnalysis_Curve().Project(curve, p, 1e-9, point, param, first, last, false);
  param = std::min(std::max(param, first), last);
  point = curve->Value(param);
  for (double end : {first, last}) {
    const gp_Pnt q = curve->Value(end);
    if (q.Distance(p) < point.Distance(p)) {
      point = q;
      param = end;
    }
  }
  return point.Distance(p);
}

}  // namespace

struct ClosestPointTarget::Parts {
  struct Face {
    Handle(ShapeAnalysis_Surface) analysis;  // over the face's UV box; caches its grid
    Handle(Geom_Surface) surface;
    TopoDS_Face face;
    double u0, u1, v0, v1;
  };
  struct Edge {
    Handle(Geom_Curve) curve;
    double first, last;
  };
  std::vector<Face> faces;
  std::vector<Edge> edges;
};

ClosestPointTarget::ClosestPointTarget(const TopoDS_Shape& shape) : parts_(new Parts) {
  if (shape.IsNull()) throw InvalidInput("attractor target: the shape is null");
  guarded("attractor target", [&] {
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Face face = TopoDS::Face(ex.Current());
      Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
      if (surface.IsNull()) continue;
      Parts::Face f;
      BRepTools::UVBounds(face, f.u0, f.u1, f.v0, f.v1);
      // Bounded to the face's UV box so the closest point never lies on the infinite surface of
      // a plane or beyond a trimmed patch.
      Handle(Geom_RectangularTrimmedSurface) box =
          new Geom_RectangularTrimmedSurface(surface, f.u0, f.u1, f.v0, f.v1);
      f.analysis = new ShapeAnalysis_Surface(box);
      f.face = face;
      f.surface = surface;
      parts_->faces.push_back(f);
    }
    if (!parts_->faces.empty()) return;
    for (TopExp_Explorer ex(shape, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge edge = TopoDS::Edge(ex.Current());
      Parts::Edge e;
      e.curve = BRep_Tool::Curve(edge, e.first, e.last);
      if (!e.curve.IsNull() && e.last > e.first) parts_->edges.push_back(e);
    }
  });
  if (parts_->faces.empty() && parts_->edges.empty())
    throw InvalidInput("attractor target: the shape has no face and no edge with a 3D curve");
}

ClosestPointTarget::~ClosestPointTarget() = default;

bool ClosestPointTarget::on_faces() const {
  return !parts_->faces.empty();
}

ClosestPoint ClosestPointTarget::operator()(const Eigen::Vector3d& point) const {
  if (!point.allFinite()) throw InvalidInput("attractor target: the point is not finite");
  return guarded("closest point", [&] {
    const gp_Pnt p(point.x(), point.y(), point.z());
    ClosestPoint best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (const Parts::Face& f : parts_->faces) {
      gp_Pnt2d uv = f.analysis->ValueOfUV(p, 1e-9);
      gp_Pnt q = f.analysis->Value(uv);
      if (uv.X() < f.u0 || uv.X() > f.u1 || uv.Y() < f.v0 || uv.Y() > f.v1) {
        // ShapeAnalysis_Surface does not stop at the box (measured: a plane face is projected
        // onto its infinite plane), so the closest point is on one of the box's four sides.
        double side_distance = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 4; ++k) {
          const bool along_v = k < 2;  // sides u = u0, u = u1 run along v
          const double fixed = k == 0 ? f.u0 : k == 1 ? f.u1 : k == 2 ? f.v0 : f.v1;
          Handle(Geom_Curve) iso = along_v ? f.surface->UIso(fixed) : f.surface->VIso(fixed);
          double t = 0.0;
          gp_Pnt on;
          const double d =
              project_on_curve(iso, p, along_v ? f.v0 : f.u0, along_v ? f.v1 : f.u1, on, t);
          if (d < side_distance) {
            side_distance = d;
            q = on;
            uv = along_v ? gp_Pnt2d(fixed, t) : gp_Pnt2d(t, fixed);
          }
        }
      }
      const double d = q.Distance(p);
      if (!(d < best_distance)) continue;
      best_distance = d;
      best.point = to_eigen(q.XYZ());
      best.metric = Eigen::Matrix3d::Identity();
      if (strictly_inside(uv.X(), f.u0, f.u1) && strictly_inside(uv.Y(), f.v0, f.v1)) {
        BRepAdaptor_Surface adaptor(f.face, false);
        BRepLProp_SLProps props(adaptor, uv.X(), uv.Y(), 1, 1e-9);
        if (props.IsNormalDefined()) {
          const Eigen::Vector3d n = to_eigen(props.Normal().XYZ());
          best.metric = n * n.transpose();
        }
      }
    }
    for (const Parts::Edge& e : parts_->edges) {
      gp_Pnt q;
      double t = 0.0;
      const double d = project_on_curve(e.curve, p, e.first, e.last, q, t);
      if (!(d < best_distance)) continue;
      best_distance = d;
      best.point = to_eigen(q.XYZ());
      best.metric = Eigen::Matrix3d::Identity();
      if (strictly_inside(t, e.first, e.last)) {
        gp_Pnt c;
        gp_Vec tangent;
        e.curve->D1(t, c, tangent);
        if (tangent.Magnitude() > 0.0) {
          const Eigen::Vector3d u = to_eigen(tangent.Normalized().XYZ());
          best.metric -= u * u.transpose();
        }
      }
    }
    if (!std::isfinite(best_distance)) throw GeometryError("closest point: none found");
    return best;
  });
}

}  // namespace varsurf::occ
