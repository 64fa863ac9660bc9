// SPDX-License-Identifier: LGPL-2.1-or-later
// Bicubic patches of a subdivision surface's limit as one B-rep: a face per patch, sewn into a
// shell (a solid when it closes), with the tangent-plane angle measured across every seam.
#pragma once

#include <vector>

#include "varsurf/core/spline_space.hpp"
#include "varsurf/occ/shell_builder.hpp"

namespace varsurf::occ {

struct PatchShell {
  ShellResult shell;
  // The largest angle (degrees) between the two faces' tangent planes along a seam: between two
  // regular patches, and where an end cap takes part.
  double regular_angle = 0.0, end_cap_angle = 0.0;
  int regular_seams = 0, end_cap_seams = 0;
};

// A face for each patch (end_cap[k] marks patch k as an end cap), sewn at `tolerance`; each seam
// sampled at `samples` points. InvalidInput for no patches, mismatched lists, a bad tolerance or
// sample count; GeometryError if OCCT fails.
PatchShell patch_shell(const std::vector<BSplineSurface>& patches, const std::vector<bool>& end_cap,
                       double tolerance, int samples);

}  // namespace varsurf::occ
