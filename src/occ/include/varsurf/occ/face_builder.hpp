// SPDX-License-Identifier: LGPL-2.1-or-later
// A sheet as a topological face bounded by its natural (domain) boundary.
#pragma once

#include <TopoDS_Face.hxx>

#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

// InvalidInput for invalid data; GeometryError if OCCT cannot build a valid face.
TopoDS_Face make_face(const BSplineSurface& surface);

}  // namespace varsurf::occ
