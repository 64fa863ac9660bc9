// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/shape_check.hpp"

#include <BRepCheck.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <ShapeAnalysis_ShapeTolerance.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>

#include <sstream>

#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

const char* type_name(TopAbs_ShapeEnum t) {
  switch (t) {
    case TopAbs_COMPOUND:
      return "compound";
    case TopAbs_COMPSOLID:
      return "compsolid";
    case TopAbs_SOLID:
      return "solid";
    case TopAbs_SHELL:
      return "shell";
    case TopAbs_FACE:
      return "face";
    case TopAbs_WIRE:
      return "wire";
    case TopAbs_EDGE:
      return "edge";
    case TopAbs_VERTEX:
      return "vertex";
    case TopAbs_SHAPE:
      return "shape";
  }
  return "shape";
}

std::string status_name(BRepCheck_Status status) {
  std::ostringstream out;
  BRepCheck::Print(status, out);
  std::string text = out.str();
  const size_t end = text.find_last_not_of(" \n\r\t");
  text.resize(end == std::string::npos ? 0 : end + 1);
  if (text.rfind("BRepCheck_", 0) == 0) text.erase(0, 10);
  return text;
}

// First problem of a sub-shape, on its own or in the context of a shape containing it (an edge
// may be fine alone but lack its curve on a face).
std::string first_problem(const Handle(BRepCheck_Result) & result) {
  for (BRepCheck_ListIteratorOfListOfStatus it(result->Status()); it.More(); it.Next()) {
    if (it.Value() != BRepCheck_NoError) return status_name(it.Value());
  }
  for (result->InitContextIterator(); result->MoreShapeInContext(); result->NextShapeInContext()) {
    for (BRepCheck_ListIteratorOfListOfStatus it(result->StatusOnShape()); it.More(); it.Next()) {
      if (it.Value() != BRepCheck_NoError) return status_name(it.Value());
    }
  }
  return {};
}

// "edge 2: InvalidCurveOnSurface; face 1: UnorientableShape" for the first few problems, small
// shapes first (their problems are usually the cause).
std::string problems(const BRepCheck_Analyzer& analyzer, const TopoDS_Shape& shape) {
  std::ostringstream out;
  int reported = 0;
  for (TopAbs_ShapeEnum type :
       {TopAbs_VERTEX, TopAbs_EDGE, TopAbs_WIRE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID}) {
    TopTools_IndexedMapOfShape map;
    TopExp::MapShapes(shape, type, map);
    for (int i = 1; i <= map.Extent() && reported < 8; ++i) {
      const Handle(BRepCheck_Result)& result = analyzer.Result(map(i));
      if (result.IsNull()) continue;
      const std::string problem = first_problem(result);
      if (problem.empty()) continue;
      out << (reported++ > 0 ? "; " : "") << type_name(type) << ' ' << i << ": " << problem;
    }
  }
  const std::string text = out.str();
  return text.empty() ? "invalid" : text;
}

}  // namespace

ShapeCheck check_shape(const TopoDS_Shape& shape) {
  ShapeCheck check;
  if (shape.IsNull()) {
    check.message = "null shape";
    return check;
  }
  try {
    BRepCheck_Analyzer analyzer(shape);
    check.valid = analyzer.IsValid();
    check.max_tolerance = ShapeAnalysis_ShapeTolerance().Tolerance(shape, 1);
    check.message = check.valid ? "valid" : problems(analyzer, shape);
  } catch (const Standard_Failure& failure) {
    check.valid = false;
    check.message = "checking failed: " + describe(failure);
  }
  return check;
}

}  // namespace varsurf::occ
