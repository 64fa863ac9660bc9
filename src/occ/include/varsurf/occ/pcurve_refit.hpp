// SPDX-License-Identifier: LGPL-2.1-or-later
// Pcurves made exact again after OCCT has projected them coarsely.
//
// Sewing keeps one 3D curve per merged edge and projects it onto the other face with OCCT's
// approximation: a part's circle sewn to a sheet got a 9-pole pcurve 7e-7 mm off it, and the
// sheet's B-spline circle one 8 poles on the fillet's torus, 6.8e-7 mm off. Edges that far off
// need tolerances a STEP file does not store, and a reader's re-derived ones fall short of them.
#pragma once

#include <TopoDS_Shape.hxx>

namespace varsurf::occ {

// Refits, on every face, each pcurve whose distance from its edge's 3D curve (OCCT's
// curve-on-surface check) exceeds `above`: the 3D curve's points at its own parameters are
// projected onto the face's surface by Newton steps started on the old pcurve, and a quintic is
// fitted to them with spans halved until it lies within 1e-2 * `above` of them (or stops gaining,
// or reaches 4000 poles). The new pcurve replaces the old only where it halves the distance; the
// edge's tolerance then follows the measured distance (never below 1e-7; vertices keep theirs).
// Seam edges, degenerate edges and edges without a shared range are left alone. Returns how many
// pcurves were replaced.
int refit_pcurves(const TopoDS_Shape& shape, double above);

}  // namespace varsurf::occ
