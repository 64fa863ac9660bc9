// SPDX-License-Identifier: LGPL-2.1-or-later
// Merging a limit surface's regular patches into larger C2 B-spline faces, against independent
// answers: on a regular grid the one block is the bicubic B-spline of the control heights to
// 1e-12; on a refined cube (closed, valence-3 corners) every merged patch is its block's surface
// where the block's cells say, to 1e-12 of the size, and every patch is in exactly one block;
// blocks stop at creases and at max_span; a patch that is not its neighbours' spline is not
// merged; bad input is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "bicubic_grid.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/patch_blocks.hpp"

using namespace varsurf;
using namespace varsurf::test;

namespace {

SubdivisionMesh refined_cube(int levels) {
  SubdivisionMesh m;
  m.points.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    m.points.row(k) << (k & 1 ? 3.0 : -3.0), (k & 2 ? 2.0 : -2.0), (k & 4 ? 4.0 : -4.0);
  m.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return subdivide(m, levels).levels[static_cast<size_t>(levels)];
}

// (s, t) in a block of the point (a, b) of a patch placed at `cell` (x, y, turn), written
// independently of the merge: the turn of the face's (u, v) the header states.
std::pair<double, double> in_block(const std::array<int, 3>& cell, const LimitPatch& patch,
                                   double a, double b) {
  const double u = patch.u0 + patch.size * a, v = patch.v0 + patch.size * b;
  double s = u, t = v;
  if (cell[2] == 1) s = v, t = 1 - u;
  if (cell[2] == 2) s = 1 - u, t = 1 - v;
  if (cell[2] == 3) s = 1 - v, t = u;
  return {cell[0] + s, cell[1] + t};
}

// Every patch in some block, the blocks tiling the mesh's faces (their areas in face units sum to
// the face count), and the largest distance between a patch and its block's surface at 7 x 7
// points of it (those inside the block, for a refined face's rectangle).
double check_cover(const SubdivisionMesh& mesh, const LimitPatches& patches,
                   const PatchBlocks& blocks) {
  std::vector<int> seen(patches.patches.size(), 0);
  double worst = 0.0, area = 0.0;
  for (const PatchBlock& block : blocks.blocks) {
    const SplineSpace& space = block.surface.space;
    // A lone patch keeps its own [0, 1]^2; merged ones are placed by their cells.
    const bool lone = block.face < 0 && block.patches.size() == 1;
    const double scale = lone ? patches.patches[static_cast<size_t>(block.patches[0])].size : 1.0;
    area += (space.u_last() - space.u_first()) * (space.v_last() - space.v_first()) * scale * scale;
    EXPECT_EQ(block.patches.size(), block.cells.size());
    EXPECT_TRUE(static_cast<int>(block.patches.size()) == block.width * block.height ||
                block.face >= 0);
    for (size_t k = 0; k < block.patches.size(); ++k) {
      ++seen[static_cast<size_t>(block.patches[k])];
      const LimitPatch& piece = patches.patches[static_cast<size_t>(block.patches[k])];
      for (int i = 0; i <= 6; ++i)
        for (int j = 0; j <= 6; ++j) {
          const auto [s, t] = lone ? std::pair{i / 6.0, j / 6.0}
                                   : in_block(block.cells[k], piece, i / 6.0, j / 6.0);
          if (s < space.u_first() || s > space.u_last() || t < space.v_first() ||
              t > space.v_last())
            continue;  // the part of a refined face's piece another rectangle covers
          worst = std::max(
              worst,
              (block.surface.evaluate(s, t) - piece.surface.evaluate(i / 6.0, j / 6.0)).norm());
        }
    }
  }
  for (int n : seen) EXPECT_GE(n, 1);
  EXPECT_NEAR(area, static_cast<double>(mesh.faces.size()), 1e-9);
  return worst;
}

}  // namespace

TEST(PatchBlocks, ARegularGridIsOneBlockTheBicubicBSpline) {
  const SubdivisionMesh m = grid();
  const LimitPatches patches = limit_patches(m, 3);
  const PatchBlocks blocks = patch_blocks(m, patches, 64, 1e-9);
  ASSERT_EQ(blocks.blocks.size(), 1u);
  const PatchBlock& block = blocks.blocks[0];
  EXPECT_EQ(block.width, kGrid - 1);
  EXPECT_EQ(block.height, kGrid - 1);
  EXPECT_EQ(block.surface.space.nu(), kGrid + 2);  // C2: a pole per face and three more
  EXPECT_LT(check_cover(m, patches, blocks), 1e-12);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> inner(2.0, kGrid - 3.0);
  for (int n = 0; n < 200; ++n) {
    const double s = inner(random), t = inner(random);
    const Eigen::Vector3d p = block.surface.evaluate(s, t);  // face 0 is at x = 0..1, y = 0..1
    EXPECT_LT((p - Eigen::Vector3d(s, t, bicubic(s, t))).norm(), 1e-12) << s << " " << t;
  }
}

TEST(PatchBlocks, ARefinedCubesBlocksAreItsPatchesAndFewer) {
  for (const int levels : {2, 3}) {
    const SubdivisionMesh m = refined_cube(levels);
    const LimitPatches patches = limit_patches(m, 3);
    const PatchBlocks blocks = patch_blocks(m, patches, 64, 1e-9);
    EXPECT_LT(check_cover(m, patches, blocks), 1e-12);
    EXPECT_LT(blocks.deviation, 1e-12);
    int merged = 0;
    for (const PatchBlock& b : blocks.blocks) merged += b.width * b.height > 1;
    std::printf(
        "cube refined %d times: %zu patches (%d end caps) as %zu faces, %d of several faces\n",
        levels, patches.patches.size(), patches.end_caps, blocks.blocks.size(), merged);
    EXPECT_GT(merged, 0);
    // The 24 faces at the corners: an end cap and two rectangles of regular pieces each; each
    // side's other faces in at most two rectangles (the greedy growth's worst case on a square
    // with its corners taken).
    EXPECT_LE(blocks.blocks.size(), 24u * 3u + 2u * 6u);
    // max_span 1 merges no faces, only pieces within each face.
    const PatchBlocks none = patch_blocks(m, patches, 1, 1e-9);
    for (const PatchBlock& b : none.blocks) EXPECT_TRUE(b.width == 1 && b.height == 1);
    EXPECT_GE(none.blocks.size(), m.faces.size());
    EXPECT_LT(check_cover(m, patches, none), 1e-12);
    // max_span 2: no block wider or taller.
    for (const PatchBlock& b : patch_blocks(m, patches, 2, 1e-9).blocks)
      EXPECT_TRUE(b.width <= 2 && b.height <= 2);
  }
}

TEST(PatchBlocks, BlocksStopAtCreases) {
  SubdivisionMesh m = grid();
  // An infinitely sharp crease along x = 3: the surface is only C0 across it.
  for (int j = 0; j + 1 < kGrid; ++j)
    m.creases.push_back({{3 * kGrid + j, 3 * kGrid + j + 1}, 10.0});
  const LimitPatches patches = limit_patches(m, 3);
  const PatchBlocks blocks = patch_blocks(m, patches, 64, 1e-9);
  EXPECT_LT(check_cover(m, patches, blocks), 1e-12);
  EXPECT_GT(blocks.blocks.size(), 1u);
  for (const PatchBlock& b : blocks.blocks) {
    std::set<bool> sides;
    for (int k : b.patches)
      sides.insert(m.faces[static_cast<size_t>(patches.patches[k].face)][0] / kGrid < 3);
    EXPECT_EQ(sides.size(), 1u) << "a block crosses the crease";
  }
}

TEST(PatchBlocks, APatchThatIsNotItsNeighboursSplineIsNotMerged) {
  const SubdivisionMesh m = grid();
  LimitPatches patches = limit_patches(m, 3);
  patches.patches[20].surface.poles(5, 2) += 1e-3;  // an inner pole: the spans no longer one C2
  const PatchBlocks blocks = patch_blocks(m, patches, 64, 1e-9);
  EXPECT_LT(check_cover(m, patches, blocks), 1e-9);
  EXPECT_LE(blocks.deviation, 1e-9);
  bool alone = false;
  for (const PatchBlock& b : blocks.blocks) alone |= b.patches == std::vector<int>{20};
  EXPECT_TRUE(alone);
}

TEST(PatchBlocks, BadInputIsRefused) {
  const SubdivisionMesh m = grid();
  const LimitPatches patches = limit_patches(m, 3);
  EXPECT_THROW(patch_blocks(m, patches, 0, 1e-9), InvalidInput);
  EXPECT_THROW(patch_blocks(m, patches, 64, -1.0), InvalidInput);
  EXPECT_THROW(patch_blocks(m, patches, 64, std::nan("")), InvalidInput);
  const SubdivisionMesh cube = refined_cube(1);
  EXPECT_THROW(patch_blocks(cube, patches, 64, 1e-9), InvalidInput);  // 49 patches, 24 faces
  LimitPatches broken = patches;
  broken.patches[3].surface.poles.resize(9, 3);
  EXPECT_THROW(patch_blocks(m, broken, 64, 1e-9), InvalidInput);
}
