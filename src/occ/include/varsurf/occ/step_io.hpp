// SPDX-License-Identifier: LGPL-2.1-or-later
// STEP exchange (AP214, surface curves written as 3D curves and pcurves).
#pragma once

#include <TopoDS_Shape.hxx>

#include <string>

namespace varsurf::occ {

// Edges whose 3D curve and pcurves disagree are split where the disagreement peaks and the
// file's uncertainty covers it, so that the re-read shape passes OCCT's curve-on-surface check
// (prepare_for_exchange). InvalidInput for a null shape or an empty path; GeometryError if
// translation or writing fails.
// OCCT's global STEP settings are restored afterwards (they are shared with the host, e.g.
// FreeCAD).
void write_step(const TopoDS_Shape& shape, const std::string& path);

// All roots of the file as one shape, its edge tolerances covering the deviation OCCT measures
// (cover_measured_deviations). GeometryError if the file cannot be read or holds no shape.
TopoDS_Shape read_step(const std::string& path);

}  // namespace varsurf::occ
