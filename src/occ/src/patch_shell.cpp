// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/patch_shell.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <map>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

// The unit normal of a face at (u, v), or zero where its tangents are parallel.
gp_Vec normal_at(const BRepAdaptor_Surface& s, double u, double v) {
  gp_Pnt p;
  gp_Vec du, dv;
  s.D1(u, v, p, du, dv);
  const gp_Vec n = du.Crossed(dv);
  return n.Magnitude() > 1e-300 ? n.Normalized() : gp_Vec(0, 0, 0);
}

}  // namespace

PatchShell patch_shell(const std::vector<BSplineSurface>& patches, const std::vector<bool>& end_cap,
                       double tolerance, int samples) {
  if (patches.empty()) throw InvalidInput("no patches to make a shell of");
  if (end_cap.size() != patches.size())
    throw InvalidInput("the end-cap marks do not match the patches");
  if (samples < 2 || samples > 1000) throw InvalidInput("seam samples must be 2..1000");
  return guarded("making the patches' shell", [&] {
    std::vector<TopoDS_Face> faces;
    std::map<const Geom_Surface*, size_t> which;
    for (size_t k = 0; k < patches.size(); ++k) {
      const Handle(Geom_BSplineSurface) surface = to_geom(patches[k]);
      BRepBuilderAPI_MakeFace make(surface, Precision::Confusion());
      if (!make.IsDone())
        throw GeometryError("OCCT could not make a face of patch " + std::to_string(k));
      faces.push_back(make.Face());
      which[surface.get()] = k;
    }
    PatchShell out;
    out.shell = sew_faces(faces, tolerance);
    // Seams: edges of two faces, their tangent planes compared along each edge's pcurves (the
    // angle between the planes, whatever the faces' orientations).
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndAncestors(out.shell.shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    for (int e = 1; e <= edge_faces.Extent(); ++e) {
      const TopTools_ListOfShape& list = edge_faces(e);
      if (list.Extent() != 2) continue;
      const TopoDS_Edge edge = TopoDS::Edge(edge_faces.FindKey(e));
      const TopoDS_Face a = TopoDS::Face(list.First()), b = TopoDS::Face(list.Last());
      if (a.IsSame(b)) continue;  // a seam of one face
      double fa, la, fb, lb;
      const Handle(Geom2d_Curve) ca = BRep_Tool::CurveOnSurface(edge, a, fa, la);
      const Handle(Geom2d_Curve) cb = BRep_Tool::CurveOnSurface(edge, b, fb, lb);
      if (ca.IsNull() || cb.IsNull()) continue;
      const BRepAdaptor_Surface sa(a), sb(b);
      double worst = 0.0;
      for (int i = 0; i < samples; ++i) {
        const double t = i / (samples - 1.0);
        const gp_Pnt2d pa = ca->Value(fa + t * (la - fa)), pb = cb->Value(fb + t * (lb - fb));
        const gp_Vec na = normal_at(sa, pa.X(), pa.Y()), nb = normal_at(sb, pb.X(), pb.Y());
        if (na.Magnitude() == 0.0 || nb.Magnitude() == 0.0) continue;
        // atan2 of the cross and dot products: acos loses the small angles G1 is about.
        worst = std::max(
            worst, std::atan2(na.Crossed(nb).Magnitude(), std::abs(na.Dot(nb))) * 180.0 / M_PI);
      }
      auto is_cap = [&](const TopoDS_Face& f) {
        const auto found = which.find(BRep_Tool::Surface(f).get());
        return found == which.end() || end_cap[found->second];
      };
      if (is_cap(a) || is_cap(b)) {
        out.end_cap_angle = std::max(out.end_cap_angle, worst);
        ++out.end_cap_seams;
      } else {
        out.regular_angle = std::max(out.regular_angle, worst);
        ++out.regular_seams;
      }
    }
    return out;
  });
}

}  // namespace varsurf::occ
