// SPDX-License-Identifier: LGPL-2.1-or-later
// The core's way into OpenSubdiv, shared by its subdivision files (not installed): a mesh's
// checks and its refiner.
#pragma once

#include <opensubdiv/far/topologyRefiner.h>

#include <memory>

#include "varsurf/core/subdivision.hpp"

namespace varsurf {

// InvalidInput, naming the fault, for a mesh subdivide refuses (see subdivision.hpp).
void validate_mesh(const SubdivisionMesh& mesh, int levels);

// OpenSubdiv's Catmull-Clark refiner of a checked mesh: boundary corners sharp (an open mesh's
// corner vertices are interpolated), the creases as given.
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> make_refiner(const SubdivisionMesh& mesh);

// A point OpenSubdiv's refiners interpolate (their Clear / AddWithWeight protocol).
struct OsdPoint {
  double p[3];
  void Clear() { p[0] = p[1] = p[2] = 0.0; }
  void AddWithWeight(const OsdPoint& src, double w) {
    p[0] += w * src.p[0];
    p[1] += w * src.p[1];
    p[2] += w * src.p[2];
  }
};

}  // namespace varsurf
