// SPDX-License-Identifier: LGPL-2.1-or-later
// Sides of a sheet that are a point within tolerance made exactly a point.
#pragma once

#include <Geom_BSplineSurface.hxx>

namespace varsurf::occ {

// Each side of `s` (the pole rows u = first, u = last, v = first, v = last) whose poles all lie
// within `tolerance` of their mean is collapsed onto that mean. A sphere's pole or a cone's apex
// carried over from a converted base spreads by rounding (1e-14 mm), and OCCT's
// self-intersection check (Shape.check(True)) then fails the face at random: OCCT's own sphere
// converted to NURBS fails it, the same surface with its pole rows equal passes, and a sheet
// over a sphere flipped between the two with the last bits of its solve (measured).
void collapse_degenerate_sides(const Handle(Geom_BSplineSurface) & s, double tolerance);

}  // namespace varsurf::occ
