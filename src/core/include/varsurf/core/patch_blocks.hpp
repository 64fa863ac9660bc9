// SPDX-License-Identifier: LGPL-2.1-or-later
// Fewer, larger faces for a subdivision surface's B-rep: the regular bicubic patches of a
// rectangular block of quads (valence-4 vertices inside it, no crease) are spans of one C2
// bicubic B-spline, so the block is written as that surface exactly, a knot at every face border.
// A face refined near an extraordinary vertex or a crease keeps its end caps (they meet their
// neighbours only C0) and covers its regular pieces by a few rectangles, C2 each.
#pragma once

#include <array>
#include <vector>

#include "varsurf/core/limit_patches.hpp"

namespace varsurf {

struct PatchBlock {
  BSplineSurface surface;    // on [0, width] x [0, height]: a unit square a face
  std::vector<int> patches;  // the patches it covers (a refined face's, possibly in part)
  // For each of them, where it lies: the block's column x and row y (its square is
  // [x, x + 1] x [y, y + 1]) and the turn r of its face's (u, v) into the block's (s, t):
  // r = 0: (u, v); 1: (v, 1 - u); 2: (1 - u, 1 - v); 3: (1 - v, u).
  std::vector<std::array<int, 3>> cells;
  // A rectangle of a refined face: that face, the surface on part of the face's own (u, v), where
  // each piece lies at its u0, v0, size (its cells all (0, 0, 0)); -1 for the blocks above.
  int face = -1;
  int width = 1, height = 1;
  bool regular = true;  // false: it holds an end cap
};

struct PatchBlocks {
  std::vector<PatchBlock> blocks;
  // The largest distance, over every merged patch's Bezier poles, between the patch and the
  // block's surface there: the rounding of an exact merge.
  double deviation = 0.0;
};

// The patches of `mesh` (limit_patches of it) grouped into blocks of at most `max_span` x
// `max_span` faces, and the regular pieces of each refined face into a few rectangles. A block
// whose surface would leave a patch's poles by more than `tolerance` (give the sewing tolerance) is
// not merged: its patches stay faces of their own. InvalidInput for patches not of this mesh, a
// max_span outside 1..1000 or a bad tolerance.
PatchBlocks patch_blocks(const SubdivisionMesh& mesh, const LimitPatches& patches, int max_span,
                         double tolerance);

}  // namespace varsurf
