// SPDX-License-Identifier: LGPL-2.1-or-later
// The Catmull-Clark limit surface of a quad mesh as bicubic Bezier patches, by OpenSubdiv's patch
// table (adaptive refinement around extraordinary vertices and creases): the regular patches are
// the limit surface exactly; the few patches that end the refinement at an extraordinary vertex
// are OpenSubdiv's B-spline end caps, bicubic approximations of it whose deviation is measured.
#pragma once

#include <vector>

#include "varsurf/core/spline_space.hpp"
#include "varsurf/core/subdivision.hpp"

namespace varsurf {

struct LimitPatch {
  BSplineSurface surface;  // bicubic Bezier on [0, 1]^2: u along the face's first edge, v its last
  int face = 0;            // the mesh face it covers part of
  bool regular = true;     // false: an end cap at an extraordinary vertex
  double u0 = 0.0, v0 = 0.0, size = 1.0;  // its square in the face's own (u, v)
};

struct LimitPatches {
  std::vector<LimitPatch> patches;
  int regular = 0, end_caps = 0;
};

// The patches of the limit surface of `mesh` with `isolation` levels of adaptive refinement
// (1..10) around extraordinary vertices: the end caps cover 1 / 2^isolation of each face at such
// a vertex. InvalidInput for a bad mesh or one with faces other than quads (refine it once).
LimitPatches limit_patches(const SubdivisionMesh& mesh, int isolation);

// The end caps' largest distance from the limit surface, sampled at `samples` x `samples` points
// of each: the reference is OpenSubdiv's evaluation with `reference_isolation` levels and
// Gregory end caps (whose share of a face shrinks as 1 / 2^levels).
double end_cap_deviation(const SubdivisionMesh& mesh, const LimitPatches& patches,
                         int reference_isolation, int samples);

// The limit surface's curvature at (u, v) of a face: the sum of its squared principal curvatures
// (the bend energy's density), from OpenSubdiv's first and second derivatives with
// `isolation` levels of adaptive refinement (regular patches, exact, down to 1 / 2^isolation of
// a face from an extraordinary vertex; Gregory end caps inside that).
double limit_curvature(const SubdivisionMesh& mesh, int face, double u, double v, int isolation);

}  // namespace varsurf
