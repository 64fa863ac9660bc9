// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/single_shape.hpp"

#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf::occ {

namespace {

TopoDS_Shape only(const TopoDS_Shape& shape, TopAbs_ShapeEnum type, const char* name) {
  if (shape.IsNull())
    throw InvalidInput(std::string("expected one ") + name + ", got a null shape");
  TopTools_IndexedMapOfShape found;
  TopExp::MapShapes(shape, type, found);
  if (found.Extent() != 1)
    throw InvalidInput(std::string("expected exactly one ") + name + ", the shape holds " +
                       std::to_string(found.Extent()));
  return found(1);
}

}  // namespace

TopoDS_Face only_face(const TopoDS_Shape& shape) {
  return TopoDS::Face(only(shape, TopAbs_FACE, "face"));
}

TopoDS_Edge only_edge(const TopoDS_Shape& shape) {
  return TopoDS::Edge(only(shape, TopAbs_EDGE, "edge"));
}

}  // namespace varsurf::occ
