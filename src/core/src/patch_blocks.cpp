// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/patch_blocks.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "bicubic_bezier.hpp"
#include "osd_refiner.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_refinement.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

// A face placed in a block: `rot` is the face's own edge that faces the block's south, so the
// face's edge (d + rot) % 4 faces block direction d (0 south, 1 east, 2 north, 3 west; a face's
// edge k runs from its corner k to k + 1: edge 0 is v = 0, 1 is u = 1, 2 is v = 1, 3 is u = 0).
struct Cell {
  int face = -1, rot = 0;
  bool operator==(const Cell& o) const { return face == o.face && rot == o.rot; }
};

constexpr int kSouth = 0, kEast = 1, kNorth = 2, kWest = 3;

class QuadGrid {
 public:
  explicit QuadGrid(const SubdivisionMesh& mesh) : across_(mesh.faces.size()) {
    for (auto& a : across_) a.fill({-1, 0});  // no neighbour until an edge says so
    std::map<std::pair<int, int>, double> sharp;
    for (const auto& crease : mesh.creases)
      sharp[std::minmax(crease.first.first, crease.first.second)] = crease.second;
    std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edges;
    for (size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 4; ++k)
        edges[std::minmax(mesh.faces[f][k], mesh.faces[f][(k + 1) % 4])].push_back(
            {static_cast<int>(f), k});
    for (auto& [key, sides] : edges) {
      const auto crease = sharp.find(key);
      // A creased edge is at most C1 across: the spline stops there.
      if (sides.size() != 2 || (crease != sharp.end() && crease->second > 0.0)) continue;
      across_[sides[0].first][sides[0].second] = sides[1];
      across_[sides[1].first][sides[1].second] = sides[0];
    }
  }

  // The cell next to `c` in block direction d, or face -1 where the surface ends.
  Cell step(const Cell& c, int d) const {
    const auto [g, k] = across_[c.face][(d + c.rot) % 4];
    if (g < 0) return {};
    return {g, ((k - (d + 2)) % 4 + 8) % 4};
  }

 private:
  std::vector<std::array<std::pair<int, int>, 4>> across_;  // (face, its edge) across each edge
};

// Bezier pole (a, b) of a cell in block coordinates from its face's patch (poles 4 i + j at
// u = i / 3, v = j / 3 of the face).
Eigen::Vector3d cell_pole(const BSplineSurface& patch, int rot, int a, int b) {
  int i = a, j = b;
  switch (rot) {
    case 1:
      i = 3 - b, j = a;
      break;  // s = v, t = 1 - u
    case 2:
      i = 3 - a, j = 3 - b;
      break;  // s = 1 - u, t = 1 - v
    case 3:
      i = b, j = 3 - a;
      break;  // s = 1 - v, t = u
    default:
      break;
  }
  return patch.poles.row(4 * i + j).transpose();
}

using Bezier = Eigen::Matrix<double, 16, 3>;

// Knot vectors on breakpoints: C2 (a merged surface's) and every breakpoint a triple knot (the
// Bezier pieces').
std::vector<double> c2_knots(const std::vector<double>& breaks) {
  std::vector<double> k(4, breaks.front());
  k.insert(k.end(), breaks.begin() + 1, breaks.end() - 1);
  k.insert(k.end(), 4, breaks.back());
  return k;
}
std::vector<double> bezier_knots(const std::vector<double>& breaks) {
  std::vector<double> k(4, breaks.front());
  for (size_t n = 1; n + 1 < breaks.size(); ++n) k.insert(k.end(), 3, breaks[n]);
  k.insert(k.end(), 4, breaks.back());
  return k;
}

struct Merge {
  BSplineSurface surface;
  double deviation = 0.0;
};

// The C2 bicubic on breakpoints bu x bv whose pieces are cell(a, b) (Bezier poles), by least
// squares on their poles (exact when they are the spans of one C2 spline, as regular limit
// patches are), and how far it lands from them (shared borders included).
Merge c2_surface(const std::vector<double>& bu, const std::vector<double>& bv,
                 const std::function<Bezier(int, int)>& cell) {
  const int nu = static_cast<int>(bu.size()) - 1, nv = static_cast<int>(bv.size()) - 1;
  const Eigen::MatrixXd tu = Eigen::MatrixXd(refinement_matrix(c2_knots(bu), 3, bezier_knots(bu)));
  const Eigen::MatrixXd tv = Eigen::MatrixXd(refinement_matrix(c2_knots(bv), 3, bezier_knots(bv)));
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qu(tu), qv(tv);
  std::vector<Bezier> pieces;
  std::array<Eigen::MatrixXd, 3> fine;
  for (auto& f : fine) f.resize(3 * nu + 1, 3 * nv + 1);
  for (int a = 0; a < nu; ++a)
    for (int b = 0; b < nv; ++b) {
      pieces.push_back(cell(a, b));
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          for (int d = 0; d < 3; ++d) fine[d](3 * a + i, 3 * b + j) = pieces.back()(4 * i + j, d);
    }
  Merge out;
  out.surface.space.knots_u = c2_knots(bu);
  out.surface.space.knots_v = c2_knots(bv);
  out.surface.poles.resize((nu + 3) * (nv + 3), 3);
  std::array<Eigen::MatrixXd, 3> back;
  for (int d = 0; d < 3; ++d) {
    const Eigen::MatrixXd half = qu.solve(fine[d]);                    // (nu + 3) x (3 nv + 1)
    const Eigen::MatrixXd q = qv.solve(half.transpose()).transpose();  // (nu + 3) x (nv + 3)
    for (int i = 0; i < nu + 3; ++i)
      for (int j = 0; j < nv + 3; ++j) out.surface.poles(i * (nv + 3) + j, d) = q(i, j);
    back[d] = tu * q * tv.transpose();
  }
  for (int a = 0, c = 0; a < nu; ++a)
    for (int b = 0; b < nv; ++b, ++c)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const Eigen::Vector3d m(back[0](3 * a + i, 3 * b + j), back[1](3 * a + i, 3 * b + j),
                                  back[2](3 * a + i, 3 * b + j));
          out.deviation =
              std::max(out.deviation,
                       (pieces[static_cast<size_t>(c)].row(4 * i + j).transpose() - m).norm());
        }
  return out;
}

// A block of whole faces (rows[y][x], each one regular patch) as one C2 surface on
// [0, width] x [0, height].
Merge merge(const std::vector<std::vector<Cell>>& rows, const std::vector<int>& single,
            const LimitPatches& patches) {
  std::vector<double> bu(rows[0].size() + 1), bv(rows.size() + 1);
  for (size_t n = 0; n < bu.size(); ++n) bu[n] = static_cast<double>(n);
  for (size_t n = 0; n < bv.size(); ++n) bv[n] = static_cast<double>(n);
  return c2_surface(bu, bv, [&](int x, int y) {
    const Cell& c = rows[static_cast<size_t>(y)][static_cast<size_t>(x)];
    const BSplineSurface& patch = patches.patches[static_cast<size_t>(single[c.face])].surface;
    Bezier poles;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) poles.row(4 * a + b) = cell_pole(patch, c.rot, a, b).transpose();
    return poles;
  });
}

// A face refined near an extraordinary vertex or a crease, cut along all its pieces' borders:
// the end caps stay faces of their own (they meet their neighbours only C0, which OCCT's check
// refuses inside a face); the regular cells, C2 throughout, are covered greedily by rectangles,
// each one C2 surface in the face's own (u, v). Empty if some rectangle misses `tolerance`.
std::vector<PatchBlock> refined_face(int face, const std::vector<int>& members,
                                     const LimitPatches& patches, double tolerance,
                                     double& deviation) {
  std::vector<double> us{0.0, 1.0}, vs{0.0, 1.0};
  for (int k : members) {
    const LimitPatch& p = patches.patches[static_cast<size_t>(k)];
    us.insert(us.end(), {p.u0, p.u0 + p.size});
    vs.insert(vs.end(), {p.v0, p.v0 + p.size});
  }
  for (auto* knots : {&us, &vs}) {
    std::sort(knots->begin(), knots->end());
    knots->erase(std::unique(knots->begin(), knots->end()), knots->end());
  }
  const int nu = static_cast<int>(us.size()) - 1, nv = static_cast<int>(vs.size()) - 1;
  // cover[a][b]: the regular patch covering cell (a, b), or -1 (an end cap's cell).
  std::vector<std::vector<int>> cover(static_cast<size_t>(nu), std::vector<int>(nv, -1));
  for (int a = 0; a < nu; ++a)
    for (int b = 0; b < nv; ++b) {
      const double um = 0.5 * (us[a] + us[a + 1]), vm = 0.5 * (vs[b] + vs[b + 1]);
      for (int k : members) {
        const LimitPatch& p = patches.patches[static_cast<size_t>(k)];
        if (p.regular && p.u0 <= um && um <= p.u0 + p.size && p.v0 <= vm && vm <= p.v0 + p.size)
          cover[a][b] = k;
      }
    }
  std::vector<PatchBlock> out;
  double worst = 0.0;
  std::vector<std::vector<char>> used(static_cast<size_t>(nu), std::vector<char>(nv, 0));
  for (int a0 = 0; a0 < nu; ++a0)
    for (int b0 = 0; b0 < nv; ++b0) {
      if (used[a0][b0] || cover[a0][b0] < 0) continue;
      int b1 = b0 + 1, a1 = a0 + 1;
      while (b1 < nv && !used[a0][b1] && cover[a0][b1] >= 0) ++b1;
      for (; a1 < nu; ++a1) {
        bool free = true;
        for (int b = b0; b < b1; ++b) free = free && !used[a1][b] && cover[a1][b] >= 0;
        if (!free) break;
      }
      PatchBlock block;
      for (int a = a0; a < a1; ++a)
        for (int b = b0; b < b1; ++b) {
          used[a][b] = 1;
          if (std::find(block.patches.begin(), block.patches.end(), cover[a][b]) ==
              block.patches.end())
            block.patches.push_back(cover[a][b]);
        }
      const std::vector<double> bu(us.begin() + a0, us.begin() + a1 + 1);
      const std::vector<double> bv(vs.begin() + b0, vs.begin() + b1 + 1);
      Merge m = c2_surface(bu, bv, [&](int a, int b) {
        const LimitPatch& p = patches.patches[static_cast<size_t>(cover[a0 + a][b0 + b])];
        return bicubic_bezier([&](double s, double t) {
          return p.surface.evaluate((bu[a] + s * (bu[a + 1] - bu[a]) - p.u0) / p.size,
                                    (bv[b] + t * (bv[b + 1] - bv[b]) - p.v0) / p.size);
        });
      });
      if (m.deviation > tolerance) return {};
      worst = std::max(worst, m.deviation);
      block.surface = std::move(m.surface);
      block.cells.assign(block.patches.size(), {0, 0, 0});
      block.face = face;
      out.push_back(std::move(block));
    }
  deviation = std::max(deviation, worst);
  return out;
}

}  // namespace

PatchBlocks patch_blocks(const SubdivisionMesh& mesh, const LimitPatches& patches, int max_span,
                         double tolerance) {
  validate_mesh(mesh, 0);
  if (max_span < 1 || max_span > 1000) throw InvalidInput("the blocks' span must be 1..1000");
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    throw InvalidInput("the merge tolerance must be finite and not negative");
  const int faces = static_cast<int>(mesh.faces.size());
  for (const auto& f : mesh.faces)
    if (f.size() != 4) throw InvalidInput("patch blocks need a quad mesh (refine it once)");
  // single[f]: the patch covering all of face f alone and regular, or -1.
  std::vector<int> single(faces, -1), count(faces, 0);
  for (size_t k = 0; k < patches.patches.size(); ++k) {
    const LimitPatch& p = patches.patches[k];
    if (p.face < 0 || p.face >= faces || p.surface.poles.rows() != 16)
      throw InvalidInput("the patches are not this mesh's: make them of it");
    if (++count[p.face] == 1 && p.regular && p.size == 1.0 && p.u0 == 0.0 && p.v0 == 0.0)
      single[p.face] = static_cast<int>(k);
  }
  for (int f = 0; f < faces; ++f)
    if (count[f] != 1) single[f] = -1;

  QuadGrid grid(mesh);
  std::vector<char> taken(faces, 0), in_block(faces, 0);
  auto free_cell = [&](const Cell& c) {
    return c.face >= 0 && single[c.face] >= 0 && !taken[c.face] && !in_block[c.face];
  };
  PatchBlocks out;
  auto lone = [&](int k) {
    PatchBlock b;
    b.surface = patches.patches[k].surface;
    b.patches = {k};
    b.cells = {{0, 0, 0}};
    b.regular = patches.patches[k].regular;
    out.blocks.push_back(std::move(b));
  };
  for (int seed = 0; seed < faces; ++seed) {
    while (single[seed] >= 0 && !taken[seed]) {
      // Walk west, then south, to the region's corner (a cycle stops at the seed's face).
      std::vector<int> walked;
      auto walk = [&](Cell c, int d) {
        for (int n = 1; n < max_span; ++n) {
          const Cell next = grid.step(c, d);
          if (!free_cell(next)) break;
          in_block[next.face] = 1;
          walked.push_back(next.face);
          c = next;
        }
        return c;
      };
      in_block[seed] = 1;
      walked.push_back(seed);
      const Cell corner = walk(walk(Cell{seed, 0}, kWest), kSouth);
      for (int f : walked) in_block[f] = 0;
      // The first row eastwards, then rows northwards while they line up.
      std::vector<std::vector<Cell>> rows{{corner}};
      in_block[corner.face] = 1;
      for (Cell c = corner; static_cast<int>(rows[0].size()) < max_span;) {
        c = grid.step(c, kEast);
        if (!free_cell(c)) break;
        in_block[c.face] = 1;
        rows[0].push_back(c);
      }
      // Rows northwards as far as some prefix of them lines up, then the prefix width and the
      // height of the largest rectangle (the first full row only gave strips a face wide where
      // one cell of the next row was taken).
      while (static_cast<int>(rows.size()) < max_span) {
        std::vector<Cell> next;
        for (const Cell& below : rows.back()) {
          const Cell c = grid.step(below, kNorth);
          if (!free_cell(c) || (!next.empty() && !(grid.step(next.back(), kEast) == c))) break;
          next.push_back(c);
          in_block[c.face] = 1;  // a row running into itself stops
        }
        if (next.empty()) break;
        rows.push_back(std::move(next));
      }
      size_t best_width = rows[0].size(), best_height = 1, width = rows[0].size();
      for (size_t h = 1; h <= rows.size(); ++h) {
        width = std::min(width, rows[h - 1].size());
        if (width * h > best_width * best_height) best_width = width, best_height = h;
      }
      for (const auto& row : rows)
        for (const Cell& c : row) in_block[c.face] = 0;
      rows.resize(best_height);
      for (auto& row : rows) row.resize(best_width);
      for (const auto& row : rows)
        for (const Cell& c : row) taken[c.face] = 1;
      if (rows.size() == 1 && rows[0].size() == 1) {
        lone(single[corner.face]);
        continue;
      }
      Merge m = merge(rows, single, patches);
      if (m.deviation > tolerance) {  // not one spline after all: each patch its own face
        for (const auto& row : rows)
          for (const Cell& c : row) lone(single[c.face]);
        continue;
      }
      out.deviation = std::max(out.deviation, m.deviation);
      PatchBlock b;
      b.surface = std::move(m.surface);
      b.width = static_cast<int>(rows[0].size());
      b.height = static_cast<int>(rows.size());
      for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) {
          b.patches.push_back(single[rows[y][x].face]);
          b.cells.push_back({x, y, rows[y][x].rot});
        }
      out.blocks.push_back(std::move(b));
    }
  }
  // The faces refined near an extraordinary vertex or a crease.
  std::vector<std::vector<int>> pieces(faces);
  for (size_t k = 0; k < patches.patches.size(); ++k)
    if (single[patches.patches[k].face] < 0)
      pieces[patches.patches[k].face].push_back(static_cast<int>(k));
  for (int f = 0; f < faces; ++f) {
    const std::vector<int>& members = pieces[static_cast<size_t>(f)];
    std::vector<PatchBlock> parts;
    if (members.size() > 1) parts = refined_face(f, members, patches, tolerance, out.deviation);
    if (parts.empty()) {  // a lone patch, or pieces that are not one spline
      for (int k : members) lone(k);
      continue;
    }
    for (auto& part : parts) out.blocks.push_back(std::move(part));
    for (int k : members)
      if (!patches.patches[static_cast<size_t>(k)].regular) lone(k);
  }
  return out;
}

}  // namespace varsurf
