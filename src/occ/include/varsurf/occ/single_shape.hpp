// SPDX-License-Identifier: LGPL-2.1-or-later
// The one face or edge a shape stands for, as sent from FreeCAD (a bare face/edge, or a compound,
// shell or wire holding exactly one).
#pragma once

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

namespace varsurf::occ {

// InvalidInput unless the shape holds exactly one face (edge).
TopoDS_Face only_face(const TopoDS_Shape& shape);
TopoDS_Edge only_edge(const TopoDS_Shape& shape);

}  // namespace varsurf::occ
