// SPDX-License-Identifier: LGPL-2.1-or-later
// Validity of a shape as OCCT's BRepCheck_Analyzer sees it.
#pragma once

#include <TopoDS_Shape.hxx>

#include <string>

namespace varsurf::occ {

struct ShapeCheck {
  bool valid = false;
  double max_tolerance = 0.0;  // largest vertex/edge/face tolerance
  std::string message;         // "valid", or the first problems found
};

// Never throws for a null or broken shape: that is reported in the result.
ShapeCheck check_shape(const TopoDS_Shape& shape);

}  // namespace varsurf::occ
