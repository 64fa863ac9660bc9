// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/detail_edit.hpp"

#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Row = Eigen::SparseVector<double>;

std::string name(const DetailPin& pin) {
  return "the pin on vertex " + std::to_string(pin.vertex) + " of level " +
         std::to_string(pin.level);
}

// The vertices sharing a face with any of `seed`, `rings` times over.
std::set<int> grown(const SubdivisionMesh& mesh, std::set<int> seed, int rings) {
  for (int r = 0; r < rings; ++r) {
    std::set<int> next = seed;
    for (const std::vector<int>& face : mesh.faces)
      if (std::any_of(face.begin(), face.end(), [&](int v) { return seed.count(v) > 0; }))
        next.insert(face.begin(), face.end());
    seed = std::move(next);
  }
  return seed;
}

}  // namespace

DetailEditor::DetailEditor(const SubdivisionMesh& base, int levels) {
  if (levels < 1 || levels > 8) throw InvalidInput("a multiresolution surface has 1..8 levels");
  // One level at a time, as reconstruct and capture refine: OpenSubdiv numbers a level's edge
  // vertices by its own edge order, which differs between a refined level and the same mesh
  // given as a base, and the details are indexed by this order.
  meshes_.push_back(base);
  for (int k = 0; k < levels; ++k) {
    steps_.push_back(subdivision_step(meshes_.back()));
    meshes_.push_back(subdivide(meshes_.back(), 1).levels[1]);
  }
}

int DetailEditor::vertices(int level) const {
  return static_cast<int>(topology(level).points.rows());
}

const SubdivisionMesh& DetailEditor::topology(int level) const {
  if (level < 0 || level > levels())
    throw InvalidInput("level " + std::to_string(level) + " does not exist: the surface has " +
                       "levels 0.." + std::to_string(levels()));
  return meshes_[static_cast<size_t>(level)];
}

void DetailEditor::check(const Multiresolution& surface) const {
  const bool same = surface.base.faces == meshes_[0].faces &&
                    surface.base.points.rows() == meshes_[0].points.rows() &&
                    surface.details.size() == steps_.size();
  if (!same) throw InvalidInput("the surface's base mesh or number of levels is not the editor's");
  for (size_t k = 0; k < steps_.size(); ++k) {
    if (surface.details[k].rows() != steps_[k].refine.rows())
      throw InvalidInput("level " + std::to_string(k + 1) + " has " +
                         std::to_string(surface.details[k].rows()) + " detail vectors for " +
                         std::to_string(steps_[k].refine.rows()) + " vertices");
    if (!surface.details[k].allFinite())
      throw InvalidInput("level " + std::to_string(k + 1) + " has details that are not finite");
  }
  if (!surface.base.points.allFinite())
    throw InvalidInput("the control mesh has points that are not finite");
}

std::vector<Eigen::MatrixX3d> DetailEditor::points(const Multiresolution& surface) const {
  check(surface);
  std::vector<Eigen::MatrixX3d> out{surface.base.points};
  for (size_t k = 0; k < steps_.size(); ++k) {
    const SubdivisionStep& step = steps_[k];
    Eigen::MatrixX3d next = step.refine * out.back();
    const Eigen::MatrixX3d frames = frames_of(step.limit_u * next, step.limit_v * next);
    for (Eigen::Index v = 0; v < next.rows(); ++v)
      next.row(v) += surface.details[k].row(v) * frames.middleRows(3 * v, 3);
    out.push_back(std::move(next));
  }
  return out;
}

Eigen::MatrixX3d DetailEditor::limit(const Multiresolution& surface) const {
  return steps_.back().limit * points(surface).back();
}

DetailEditResult DetailEditor::edit(const Multiresolution& surface,
                                    const std::vector<DetailPin>& pins,
                                    const DetailEditOptions& options) const {
  check(surface);
  if (options.rings < 0 || options.rings > 16) throw InvalidInput("rings must be in 0..16");
  if (!(options.omega > 0.0 && options.omega < 2.0))
    throw InvalidInput("SOR's relaxation must lie in (0, 2)");
  if (options.max_rounds < 1 || options.max_sweeps < 1)
    throw InvalidInput("the rounds and sweeps must be at least 1");
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw InvalidInput("the tolerance must be a finite number > 0");
  std::set<std::pair<int, int>> seen;
  for (const DetailPin& pin : pins) {
    if (pin.level < 0 || pin.level > levels())
      throw InvalidInput(name(pin) + ": level " + std::to_string(pin.level) +
                         " does not exist (the surface has levels 0.." + std::to_string(levels()) +
                         "): set one of those");
    if (pin.vertex < 0 || pin.vertex >= vertices(pin.level))
      throw InvalidInput(name(pin) + ": level " + std::to_string(pin.level) + " has vertices 0.." +
                         std::to_string(vertices(pin.level) - 1) + "; pick one of those");
    if (pin.influence < 0 || pin.influence > pin.level)
      throw InvalidInput(name(pin) + ": its influence level must lie in 0.." +
                         std::to_string(pin.level) + "; set it so");
    if (!pin.target.allFinite())
      throw InvalidInput(name(pin) + " has a target that is not finite: give a point");
    if (!seen.insert({pin.level, pin.vertex}).second)
      throw InvalidInput(name(pin) + " is given twice: remove one");
  }

  DetailEditResult out{surface, {}};
  std::vector<Eigen::MatrixX3d> points = this->points(out.surface);
  const Eigen::MatrixX3d& finest = points.back();
  const double size = (finest.colwise().maxCoeff() - finest.colwise().minCoeff()).norm();
  const double tolerance = options.tolerance * std::max(size, 1e-300);
  // A pin acts from its influence level down to its own level: solved at the coarsest, then the
  // residual at each finer level on the pin's mask there (its masks there are more local, so pins
  // too many for a coarse level are met at the fine ones, as in the paper's multigrid).
  int first = levels(), last = 0;
  for (const DetailPin& pin : pins) {
    first = std::min(first, pin.influence);
    last = std::max(last, pin.level);
  }

  for (int level = first; level <= last; ++level) {
    const SubdivisionMesh& topo = meshes_[static_cast<size_t>(level)];
    // Every pin acting at this level (influence at or above it, its vertex at or below), as a row
    // on this level's points: the Catmull-Clark masks composed from the pin's level down.
    std::vector<const DetailPin*> active;
    std::vector<Row> rows;
    std::set<int> seed;
    double start_residual = 0.0;
    for (const DetailPin& pin : pins) {
      if (pin.influence > level || pin.level < level) continue;
      start_residual = std::max(
          start_residual,
          (pin.target.transpose() - points[static_cast<size_t>(pin.level)].row(pin.vertex)).norm());
      Row row(vertices(pin.level));
      row.insert(pin.vertex) = 1.0;
      for (int k = pin.level - 1; k >= level; --k) {
        const Sparse& refine = steps_[static_cast<size_t>(k)].refine;
        row = Row(refine.transpose() * row);
      }
      for (Row::InnerIterator it(row); it; ++it)
        if (it.value() != 0.0) seed.insert(static_cast<int>(it.index()));
      active.push_back(&pin);
      rows.push_back(std::move(row));
    }
    if (active.empty() || start_residual <= tolerance) continue;
    const int rings = options.solve == DetailSolve::approximate ? 0 : options.rings;
    const std::set<int> region = grown(topo, seed, rings);
    std::vector<int> free(region.begin(), region.end());
    std::map<int, int> column;
    for (size_t k = 0; k < free.size(); ++k) column[free[k]] = static_cast<int>(k);
    const Eigen::Index f = static_cast<Eigen::Index>(free.size());
    // The rows on the region; a coarser pin whose mask lies outside it is kept by standing still.
    std::vector<Eigen::Triplet<double>> a_entries;
    std::vector<size_t> kept;
    for (size_t r = 0; r < rows.size(); ++r) {
      bool touches = false;
      for (Row::InnerIterator it(rows[r]); it; ++it) {
        const auto c = column.find(static_cast<int>(it.index()));
        if (c == column.end() || it.value() == 0.0) continue;
        a_entries.emplace_back(static_cast<int>(kept.size()), c->second, it.value());
        touches = true;
      }
      if (touches) kept.push_back(r);
    }
    const Eigen::Index m = static_cast<Eigen::Index>(kept.size());
    Sparse a(m, f);
    a.setFromTriplets(a_entries.begin(), a_entries.end());
    out.report.region_levels.push_back(level);
    out.report.region_sizes.push_back(static_cast<int>(f));

    // The level's energy on the deformation (sec. 4.1), from the level's shape before the edit.
    Sparse h;
    Eigen::SparseLU<Sparse> kkt;
    Eigen::SimplicialLDLT<Sparse> penalty;
    double penalty_weight = 0.0;
    bool least_squares = false;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> masks;
    std::vector<int> relaxed;  // SOR: the region's vertices outside every mask
    const Eigen::MatrixXd dense_a = Eigen::MatrixXd(a);
    if (options.solve == DetailSolve::direct || options.solve == DetailSolve::sor) {
      SubdivisionMesh shape = topo;
      shape.points = points[static_cast<size_t>(level)];
      // The energy of the vertices whose ring reaches the region: the rest is constant.
      const std::set<int> reach = grown(topo, region, 1);
      h = detail_energy(shape, options.weights, std::vector<int>(reach.begin(), reach.end()));
    }
    if (options.solve == DetailSolve::direct) {
      std::vector<Eigen::Triplet<double>> k_entries;
      double diagonal = 0.0;
      for (Eigen::Index i = 0; i < f; ++i) diagonal = std::max(diagonal, h.coeff(free[i], free[i]));
      for (Eigen::Index i = 0; i < f; ++i) {
        for (Sparse::InnerIterator it(h, free[i]); it; ++it) {
          const auto c = column.find(static_cast<int>(it.row()));
          if (c != column.end()) k_entries.emplace_back(c->second, static_cast<int>(i), it.value());
        }
        // A whisker on the diagonal: a region that the pins leave free to translate (the energy
        // of a translation is zero) then takes the smallest move.
        k_entries.emplace_back(static_cast<int>(i), static_cast<int>(i), 1e-12 * diagonal);
      }
      for (int outer = 0; outer < a.outerSize(); ++outer)
        for (Sparse::InnerIterator it(a, outer); it; ++it) {
          k_entries.emplace_back(static_cast<int>(f + it.row()), static_cast<int>(it.col()),
                                 it.value());
          k_entries.emplace_back(static_cast<int>(it.col()), static_cast<int>(f + it.row()),
                                 it.value());
        }
      Sparse k(f + m, f + m);
      k.setFromTriplets(k_entries.begin(), k_entries.end());
      kkt.compute(k);
      if (kkt.info() != Eigen::Success) {
        // More pins than this level can meet (their masks dependent): their least-squares fit,
        // the energy keeping it smooth; the finer levels then meet them.
        Sparse h_ff(f, f);
        std::vector<Eigen::Triplet<double>> h_entries;
        for (const auto& t : k_entries)
          if (t.row() < f && t.col() < f) h_entries.push_back(t);
        h_ff.setFromTriplets(h_entries.begin(), h_entries.end());
        const Sparse ata = Sparse(a.transpose() * a);
        double ata_diagonal = 0.0;
        for (Eigen::Index i = 0; i < f; ++i) ata_diagonal = std::max(ata_diagonal, ata.coeff(i, i));
        penalty_weight = 1e6 * std::max(diagonal, 1e-300) / std::max(ata_diagonal, 1e-300);
        penalty.compute(Sparse(h_ff + penalty_weight * ata));
        if (penalty.info() != Eigen::Success)
          throw InvalidInput("the pins solved at level " + std::to_string(level) +
                             " cannot be met: remove some or solve them at a finer level");
        least_squares = true;
      }
    } else {
      masks.compute(dense_a * dense_a.transpose());
      if (options.solve == DetailSolve::sor) {
        std::set<int> in_masks;
        for (Eigen::Index c = 0; c < f; ++c)
          if (dense_a.col(c).cwiseAbs().maxCoeff() > 0.0) in_masks.insert(static_cast<int>(c));
        for (Eigen::Index c = 0; c < f; ++c)
          if (!in_masks.count(static_cast<int>(c))) relaxed.push_back(static_cast<int>(c));
      }
    }

    // The frames of this level's details (unchanged by edits at this level or finer).
    Eigen::MatrixX3d frames;
    if (level > 0) {
      const SubdivisionStep& step = steps_[static_cast<size_t>(level - 1)];
      const Eigen::MatrixX3d before = step.refine * points[static_cast<size_t>(level - 1)];
      frames = frames_of(step.limit_u * before, step.limit_v * before);
    }
    double previous = std::numeric_limits<double>::infinity();
    for (int round = 0; round < options.max_rounds && m > 0; ++round) {
      Eigen::MatrixX3d c(m, 3);
      double worst = 0.0;
      for (Eigen::Index r = 0; r < m; ++r) {
        const DetailPin& pin = *active[kept[static_cast<size_t>(r)]];
        c.row(r) = pin.target.transpose() - points[static_cast<size_t>(pin.level)].row(pin.vertex);
        worst = std::max(worst, c.row(r).norm());
      }
      // Met, or no longer improving (pins this level can meet only in least squares).
      if (worst <= tolerance || worst > 0.999 * previous) break;
      previous = worst;
      ++out.report.rounds;
      Eigen::MatrixX3d x = Eigen::MatrixX3d::Zero(f, 3);
      if (options.solve == DetailSolve::direct && least_squares) {
        x = penalty.solve(Eigen::MatrixX3d(penalty_weight * (a.transpose() * c)));
      } else if (options.solve == DetailSolve::direct) {
        Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(f + m, 3);
        rhs.bottomRows(m) = c;
        x = kkt.solve(rhs).topRows(f);
      } else {
        x = dense_a.transpose() * masks.solve(c);
        if (options.solve == DetailSolve::sor) {
          // Gauss-Seidel with over-relaxation on the rest of the region (the paper's sec. 4.3);
          // the vertices outside the region stand still.
          const double stop = 1e-3 * tolerance;
          for (int sweep = 0; sweep < options.max_sweeps; ++sweep) {
            ++out.report.sweeps;
            double change = 0.0;
            for (const int i : relaxed) {
              const int v = free[static_cast<size_t>(i)];
              Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
              double diagonal = 0.0;
              for (Sparse::InnerIterator it(h, v); it; ++it) {
                if (it.row() == v) {
                  diagonal = it.value();
                  continue;
                }
                const auto col = column.find(static_cast<int>(it.row()));
                if (col != column.end()) sum += it.value() * x.row(col->second);
              }
              if (diagonal <= 0.0) continue;
              const Eigen::RowVector3d next =
                  (1.0 - options.omega) * x.row(i) - (options.omega / diagonal) * sum;
              change = std::max(change, (next - x.row(i)).norm());
              x.row(i) = next;
            }
            if (change <= stop) break;
          }
        }
      }
      // The move becomes this level's change: the base's points, or this level's details.
      for (Eigen::Index i = 0; i < f; ++i) {
        const int v = free[static_cast<size_t>(i)];
        if (level == 0)
          out.surface.base.points.row(v) += x.row(i);
        else
          out.surface.details[static_cast<size_t>(level - 1)].row(v) +=
              x.row(i) * frames.middleRows(3 * v, 3).transpose();
      }
      points = this->points(out.surface);
    }
  }
  for (const DetailPin& pin : pins)
    out.report.max_residual = std::max(
        out.report.max_residual,
        (pin.target.transpose() - points[static_cast<size_t>(pin.level)].row(pin.vertex)).norm());
  return out;
}

}  // namespace varsurf
