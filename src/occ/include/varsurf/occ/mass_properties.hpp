// SPDX-License-Identifier: LGPL-2.1-or-later
// Area and volume of a shape integrated to a stated relative precision. The default integration
// (BRepGProp without a precision, what Part.Shape.Area / Volume use) is accurate to only a few
// 1e-6 on trimmed B-spline faces, and its error changes with how the boundary is split into
// edges: comparisons of a shape with its re-read copy need the adaptive one.
#pragma once

#include <TopoDS_Shape.hxx>

namespace varsurf::occ {

struct MassProperties {
  double area = 0.0;
  double volume = 0.0;  // signed: negative for an inward-oriented or open shell's complement
};

// InvalidInput for a null shape or a precision outside (0, 0.1]; GeometryError if OCCT fails.
MassProperties mass_properties(const TopoDS_Shape& shape, double relative_precision = 1e-9);

}  // namespace varsurf::occ
