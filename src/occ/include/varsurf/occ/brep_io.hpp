// SPDX-License-Identifier: LGPL-2.1-or-later
// Shapes as OCCT's ASCII BREP text: the format of FreeCAD's Part.Shape.exportBrepToString() and
// importBrepFromString() (same OCCT version on both sides).
#pragma once

#include <TopoDS_Shape.hxx>

#include <string>

namespace varsurf::occ {

// Throws InvalidInput for empty or non-BREP text, GeometryError if OCCT cannot read it.
TopoDS_Shape read_brep(const std::string& text);

// Throws InvalidInput for a null shape. Triangulations are not written.
std::string write_brep(const TopoDS_Shape& shape);

}  // namespace varsurf::occ
