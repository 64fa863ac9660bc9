// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/face_builder.hpp"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <Precision.hxx>

#include <string>

#include "collapsed_sides.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

const char* face_error(BRepBuilderAPI_FaceError e) {
  switch (e) {
    case BRepBuilderAPI_FaceDone:
      return "done";
    case BRepBuilderAPI_NoFace:
      return "no face";
    case BRepBuilderAPI_NotPlanar:
      return "not planar";
    case BRepBuilderAPI_CurveProjectionFailed:
      return "curve projection failed";
    case BRepBuilderAPI_ParametersOutOfRange:
      return "parameters out of range";
  }
  return "unknown error";
}

}  // namespace

TopoDS_Face make_face(const BSplineSurface& surface) {
  const Handle(Geom_BSplineSurface) geom = to_geom(surface);
  return guarded("building a face", [&] {
    collapse_degenerate_sides(geom, Precision::Confusion());
    BRepBuilderAPI_MakeFace maker(geom, Precision::Confusion());
    if (!maker.IsDone())
      throw GeometryError(std::string("building a face failed: ") + face_error(maker.Error()));
    TopoDS_Face face = maker.Face();
    BRepCheck_Analyzer analyzer(face);
    if (!analyzer.IsValid())
      throw GeometryError(
          "building a face: OpenCASCADE's checker rejects the result "
          "(self-intersecting or degenerate sheet?)");
    return face;
  });
}

}  // namespace varsurf::occ
