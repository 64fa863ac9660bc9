// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/detail_edit.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "region_solver.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Row = Eigen::SparseVector<double>;

template <class Constraint>
std::string name(const Constraint& c, const char* what) {
  return std::string("the ") + what + " on vertex " + std::to_string(c.vertex) + " of level " +
         std::to_string(c.level);
}

// A constraint acting at one level: its row on that level's points (the masks composed from the
// constraint's own level down), for a pin's three coordinates or a normal's tangent `tangent`.
struct Active {
  Row row;
  const DetailPin* pin = nullptr;
  const DetailNormal* normal = nullptr;
  const Row* tangent = nullptr;  // a normal's divided-difference row at its own level
};

// The angle between a vertex's normal from its tangents (rows u, v on `points`) and the line of n.
double normal_angle(const Row& u, const Row& v, const Eigen::MatrixX3d& points,
                    const Eigen::Vector3d& n) {
  const Eigen::Vector3d qu = (u.transpose() * points).transpose();
  const Eigen::Vector3d qv = (v.transpose() * points).transpose();
  const Eigen::Vector3d normal = qu.cross(qv);
  return std::atan2(normal.cross(n).norm(), std::abs(normal.dot(n)));
}

Row row_of(const Sparse& d, Eigen::Index r) {
  return Row(d.row(r).transpose());
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
  for (const SubdivisionMesh& mesh : meshes_) incident_.push_back(vertex_faces(mesh));
}

std::vector<int> DetailEditor::grown(int level, const std::vector<int>& seed, int rings) const {
  const SubdivisionMesh& mesh = meshes_[static_cast<size_t>(level)];
  const std::vector<std::vector<int>>& incident = incident_[static_cast<size_t>(level)];
  std::vector<char> in(static_cast<size_t>(mesh.points.rows()), 0);
  std::vector<int> out, front = seed;
  for (const int v : seed)
    if (!in[static_cast<size_t>(v)]) in[static_cast<size_t>(v)] = 1, out.push_back(v);
  for (int r = 0; r < rings; ++r) {
    std::vector<int> next;
    for (const int v : front)
      for (const int f : incident[static_cast<size_t>(v)])
        for (const int w : mesh.faces[static_cast<size_t>(f)])
          if (!in[static_cast<size_t>(w)])
            in[static_cast<size_t>(w)] = 1, next.push_back(w), out.push_back(w);
    front = std::move(next);
  }
  std::sort(out.begin(), out.end());
  return out;
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

Eigen::Vector3d DetailEditor::normal(const Multiresolution& surface, int level, int vertex) const {
  if (vertex < 0 || vertex >= vertices(level))
    throw InvalidInput("level " + std::to_string(level) + " has vertices 0.." +
                       std::to_string(vertices(level) - 1) + ", not " + std::to_string(vertex) +
                       ": pick one of those");
  SubdivisionMesh shape = meshes_[static_cast<size_t>(level)];
  shape.points = points(surface)[static_cast<size_t>(level)];
  const Sparse d =
      divided_differences_checked(shape, incident_[static_cast<size_t>(level)], {vertex});
  const Eigen::Vector3d qu = (row_of(d, 5 * vertex).transpose() * shape.points).transpose();
  const Eigen::Vector3d qv = (row_of(d, 5 * vertex + 1).transpose() * shape.points).transpose();
  const Eigen::Vector3d n = qu.cross(qv);
  if (!(n.norm() > 1e-12 * qu.norm() * qv.norm()))
    throw InvalidInput("vertex " + std::to_string(vertex) + " of level " + std::to_string(level) +
                       " has no tangent plane: pick another vertex");
  return n.normalized();
}

DetailEditResult DetailEditor::edit(const Multiresolution& surface,
                                    const std::vector<DetailPin>& pins,
                                    const std::vector<DetailNormal>& normals,
                                    const DetailEditOptions& options) const {
  check(surface);
  if (options.rings < 0 || options.rings > 16) throw InvalidInput("rings must be in 0..16");
  if (!(options.omega > 0.0 && options.omega < 2.0))
    throw InvalidInput("SOR's relaxation must lie in (0, 2)");
  if (options.max_rounds < 1 || options.max_sweeps < 1)
    throw InvalidInput("the rounds and sweeps must be at least 1");
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw InvalidInput("the tolerance must be a finite number > 0");
  const auto check_place = [&](const auto& c, const char* what) {
    if (c.level < 0 || c.level > levels())
      throw InvalidInput(name(c, what) + ": level " + std::to_string(c.level) +
                         " does not exist (the surface has levels 0.." + std::to_string(levels()) +
                         "): set one of those");
    if (c.vertex < 0 || c.vertex >= vertices(c.level))
      throw InvalidInput(name(c, what) + ": level " + std::to_string(c.level) +
                         " has vertices 0.." + std::to_string(vertices(c.level) - 1) +
                         "; pick one of those");
    if (c.influence < 0 || c.influence > c.level)
      throw InvalidInput(name(c, what) + ": its influence level must lie in 0.." +
                         std::to_string(c.level) + "; set it so");
  };
  std::set<std::pair<int, int>> seen;
  for (const DetailPin& pin : pins) {
    check_place(pin, "pin");
    if (!pin.target.allFinite())
      throw InvalidInput(name(pin, "pin") + " has a target that is not finite: give a point");
    if (!seen.insert({pin.level, pin.vertex}).second)
      throw InvalidInput(name(pin, "pin") + " is given twice: remove one");
  }
  seen.clear();
  for (const DetailNormal& normal : normals) {
    check_place(normal, "normal");
    if (!normal.normal.allFinite() || !(normal.normal.norm() > 0.0))
      throw InvalidInput(name(normal, "normal") + " is zero or not finite: give a direction");
    if (!seen.insert({normal.level, normal.vertex}).second)
      throw InvalidInput(name(normal, "normal") + " is given twice: remove one");
  }

  // What a pin holds, as a row on its own level's points (the control point, or the limit
  // stencil: the limit of a vertex is the same from every level it lives on, so this is the
  // finished surface's point there while the finer details stand still) and where it is now (on
  // the finished surface, with the details riding along: the rounds close the difference).
  // A pin on the limit is held at every level from its influence on, finer ones included: an
  // edit of a finer level moves the limit there too. above[k][l]: its row at level l > its own.
  std::vector<Row> held, finished;  // finished: the limit stencil on the finest level's points
  std::vector<std::vector<Row>> above(pins.size());
  {
    using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
    std::map<int, RowMajor> stencils;  // level -> its limit stencils, one row per vertex
    const auto stencil = [&](int level, int vertex) {
      auto found = stencils.find(level);
      if (found == stencils.end())
        found =
            stencils.emplace(level, RowMajor(steps_[static_cast<size_t>(level - 1)].limit)).first;
      Row row(found->second.cols());
      for (RowMajor::InnerIterator it(found->second, vertex); it; ++it)
        row.insert(it.index()) = it.value();
      return row;
    };
    for (size_t k = 0; k < pins.size(); ++k) {
      const DetailPin& pin = pins[k];
      Row row(vertices(pin.level)), finish;
      if (!pin.on_limit) {
        row.insert(pin.vertex) = 1.0;
      } else {
        const Row at = stencil(std::max(pin.level, 1), pin.vertex);
        row = pin.level == 0 ? Row(steps_[0].refine.transpose() * at) : at;
        above[k].resize(static_cast<size_t>(levels()) + 1);
        for (int level = pin.level + 1; level <= levels(); ++level)
          above[k][static_cast<size_t>(level)] = stencil(level, pin.vertex);
        finish = stencil(levels(), pin.vertex);
      }
      held.push_back(row);
      finished.push_back(finish);
    }
  }
  const auto where = [&](const DetailPin& pin, const std::vector<Eigen::MatrixX3d>& p) {
    if (!pin.on_limit) return Eigen::RowVector3d(p[static_cast<size_t>(pin.level)].row(pin.vertex));
    return Eigen::RowVector3d(finished[static_cast<size_t>(&pin - pins.data())].transpose() *
                              p.back());
  };

  DetailEditResult out{surface, {}};
  std::vector<Eigen::MatrixX3d> points = this->points(out.surface);
  const Eigen::MatrixX3d& finest = points.back();
  const double size = (finest.colwise().maxCoeff() - finest.colwise().minCoeff()).norm();
  const double tolerance = options.tolerance * std::max(size, 1e-300);

  // Each normal's tangents at its own level (the constraint's linear form, sec. 4.2), from the
  // divided differences of the current shape: taken again each round, as the ring's local
  // parameterization turns with the edit.
  std::vector<std::array<Row, 2>> tangents(normals.size());
  std::vector<Eigen::Vector3d> directions;
  const auto linearize = [&](size_t k) {
    const DetailNormal& normal = normals[k];
    SubdivisionMesh shape = meshes_[static_cast<size_t>(normal.level)];
    shape.points = points[static_cast<size_t>(normal.level)];
    const Sparse d = divided_differences_checked(
        shape, incident_[static_cast<size_t>(normal.level)], {normal.vertex});
    tangents[k] = {row_of(d, 5 * normal.vertex), row_of(d, 5 * normal.vertex + 1)};
  };
  for (size_t k = 0; k < normals.size(); ++k) {
    linearize(k);
    const Eigen::MatrixX3d& p = points[static_cast<size_t>(normals[k].level)];
    const Eigen::Vector3d qu = (tangents[k][0].transpose() * p).transpose();
    const Eigen::Vector3d qv = (tangents[k][1].transpose() * p).transpose();
    if (!(qu.cross(qv).norm() > 1e-12 * qu.norm() * qv.norm()))
      throw InvalidInput(name(normals[k], "normal") +
                         ": the surface has no tangent plane there; pick another vertex");
    directions.push_back(normals[k].normal.normalized());
  }

  // A constraint acts from its influence level down to its own level: solved at the coarsest, then
  // the residual at each finer level on the constraint's mask there (more local there, so
  // constraints too many for a coarse level are met at the fine ones, as in the paper's
  // multigrid).
  int first = levels(), last = 0;
  for (const DetailPin& pin : pins)
    first = std::min(first, pin.influence),
    last = std::max(last, pin.on_limit ? levels() : pin.level);
  for (const DetailNormal& n : normals)
    first = std::min(first, n.influence), last = std::max(last, n.level);

  // How far the active constraints are from being met, in units of their tolerances: a pin's
  // distance over the tolerance, a normal's tangent's angle with the plane over options.tolerance.
  const auto unmet = [&](const std::vector<Active>& active) {
    double worst = 0.0;
    for (const Active& a : active) {
      if (a.pin) {
        const Eigen::RowVector3d gap = a.pin->target.transpose() - where(*a.pin, points);
        worst = std::max(worst, gap.norm() / tolerance);
      } else {
        const size_t k = static_cast<size_t>(a.normal - normals.data());
        const Eigen::Vector3d q =
            (a.tangent->transpose() * points[static_cast<size_t>(a.normal->level)]).transpose();
        worst = std::max(worst, std::abs(q.dot(directions[k])) /
                                    (std::max(q.norm(), 1e-300) * options.tolerance));
      }
    }
    return worst;
  };
  const auto propagate = [&](Row row, int from, int to) {
    for (int k = from - 1; k >= to; --k)
      row = Row(steps_[static_cast<size_t>(k)].refine.transpose() * row);
    return row;
  };

  for (int level = first; level <= last; ++level) {
    std::vector<Active> active;
    std::vector<int> seed;
    for (size_t k = 0; k < pins.size(); ++k) {
      const DetailPin& pin = pins[k];
      if (pin.influence > level || (pin.level < level && !pin.on_limit)) continue;
      active.push_back({pin.level < level ? above[k][static_cast<size_t>(level)]
                                          : propagate(held[k], pin.level, level),
                        &pin, nullptr, nullptr});
    }
    for (size_t k = 0; k < normals.size(); ++k) {
      const DetailNormal& normal = normals[k];
      if (normal.influence > level || normal.level < level) continue;
      for (const Row& tangent : tangents[k])
        active.push_back({propagate(tangent, normal.level, level), nullptr, &normal, &tangent});
    }
    if (active.empty() || unmet(active) <= 1.0) continue;
    for (const Active& a : active)
      for (Row::InnerIterator it(a.row); it; ++it)
        if (it.value() != 0.0) seed.push_back(static_cast<int>(it.index()));
    const int rings = options.solve == DetailSolve::approximate ? 0 : options.rings;
    const std::vector<int> free = grown(level, seed, rings);
    std::vector<int> column(static_cast<size_t>(vertices(level)), -1);
    for (size_t k = 0; k < free.size(); ++k)
      column[static_cast<size_t>(free[k])] = static_cast<int>(k);
    const Eigen::Index f = static_cast<Eigen::Index>(free.size());
    // The rows on the region; a coarser constraint whose mask lies outside it is kept by standing
    // still. Pins alone: three independent systems on the vertices; with normals one coupled
    // system on the coordinates (unknown 3i + d), each pin three rows, each tangent one.
    std::vector<Active*> kept;
    for (Active& a : active)
      for (Row::InnerIterator it(a.row); it; ++it)
        if (it.value() != 0.0 && column[static_cast<size_t>(it.index())] >= 0) {
          kept.push_back(&a);
          break;
        }
    const bool coupled =
        std::any_of(kept.begin(), kept.end(), [](const Active* a) { return a->normal != nullptr; });
    const int width = coupled ? 3 : 1;
    Eigen::Index m = 0;
    for (const Active* a : kept) m += a->pin && coupled ? 3 : 1;
    const auto assemble = [&]() {
      std::vector<Eigen::Triplet<double>> a_entries;
      int r = 0;
      for (const Active* a : kept) {
        const int equations = a->pin && coupled ? 3 : 1;
        for (int e = 0; e < equations; ++e, ++r)
          for (Row::InnerIterator it(a->row); it; ++it) {
            const int c = column[static_cast<size_t>(it.index())];
            if (c < 0 || it.value() == 0.0) continue;
            if (!coupled) {
              a_entries.emplace_back(r, c, it.value());
            } else if (a->pin) {
              a_entries.emplace_back(r, 3 * c + e, it.value());
            } else {
              const Eigen::Vector3d& n =
                  directions[static_cast<size_t>(a->normal - normals.data())];
              for (int d = 0; d < 3; ++d)
                if (n(d) != 0.0) a_entries.emplace_back(r, 3 * c + d, it.value() * n(d));
            }
          }
      }
      Sparse a(m, width * f);
      a.setFromTriplets(a_entries.begin(), a_entries.end());
      return a;
    };
    out.report.region_levels.push_back(level);
    out.report.region_sizes.push_back(static_cast<int>(f));

    // The level's energy on the deformation (sec. 4.1), from the level's shape before the edit,
    // restricted to the region (the vertices outside stand still), per coordinate when coupled.
    Sparse h(width * f, width * f);
    if (options.solve != DetailSolve::approximate) {
      SubdivisionMesh shape = meshes_[static_cast<size_t>(level)];
      shape.points = points[static_cast<size_t>(level)];
      // The energy of the vertices whose ring reaches the region: the rest is constant.
      const Sparse full = detail_energy_checked(shape, incident_[static_cast<size_t>(level)],
                                                options.weights, grown(level, free, 1));
      std::vector<Eigen::Triplet<double>> h_entries;
      for (Eigen::Index i = 0; i < f; ++i)
        for (Sparse::InnerIterator it(full, free[static_cast<size_t>(i)]); it; ++it) {
          const int r = column[static_cast<size_t>(it.row())];
          if (r < 0) continue;
          for (int d = 0; d < width; ++d)
            h_entries.emplace_back(width * r + d, width * static_cast<int>(i) + d, it.value());
        }
      h.setFromTriplets(h_entries.begin(), h_entries.end());
    }
    std::unique_ptr<RegionSolver> solver;

    // The frames of this level's details (unchanged by edits at this level or finer).
    Eigen::MatrixX3d frames;
    if (level > 0) {
      const SubdivisionStep& step = steps_[static_cast<size_t>(level - 1)];
      const Eigen::MatrixX3d before = step.refine * points[static_cast<size_t>(level - 1)];
      frames = frames_of(step.limit_u * before, step.limit_v * before);
    }
    double previous = std::numeric_limits<double>::infinity();
    for (int round = 0; round < options.max_rounds && m > 0; ++round) {
      if (coupled || !solver) {
        for (size_t k = 0; k < normals.size(); ++k)
          if (normals[k].influence <= level && normals[k].level >= level) linearize(k);
        for (Active* a : kept)
          if (a->normal) a->row = propagate(*a->tangent, a->normal->level, level);
        solver = std::make_unique<RegionSolver>(h, assemble(), options, level);
      }
      // Met, or no longer improving (constraints this level can meet only in least squares).
      const double worst = unmet(active);
      if (worst <= 1.0 || worst > 0.999 * previous) break;
      previous = worst;
      ++out.report.rounds;
      Eigen::MatrixXd c(m, coupled ? 1 : 3);
      Eigen::Index r = 0;
      for (const Active* a : kept) {
        if (a->pin) {
          const Eigen::RowVector3d gap = a->pin->target.transpose() - where(*a->pin, points);
          if (coupled)
            for (int d = 0; d < 3; ++d) c(r++, 0) = gap(d);
          else
            c.row(r++) = gap;
        } else {
          const Eigen::Vector3d q =
              (a->tangent->transpose() * points[static_cast<size_t>(a->normal->level)]).transpose();
          c(r++, 0) = -q.dot(directions[static_cast<size_t>(a->normal - normals.data())]);
        }
      }
      const Eigen::MatrixXd solved = solver->solve(c, 1e-3 * tolerance, out.report.sweeps);
      // The move becomes this level's change: the base's points, or this level's details.
      for (Eigen::Index i = 0; i < f; ++i) {
        const int v = free[static_cast<size_t>(i)];
        const Eigen::RowVector3d x =
            coupled
                ? Eigen::RowVector3d(solved(3 * i, 0), solved(3 * i + 1, 0), solved(3 * i + 2, 0))
                : Eigen::RowVector3d(solved.row(i));
        if (level == 0)
          out.surface.base.points.row(v) += x;
        else
          out.surface.details[static_cast<size_t>(level - 1)].row(v) +=
              x * frames.middleRows(3 * v, 3).transpose();
      }
      points = this->points(out.surface);
    }
  }
  for (const DetailPin& pin : pins)
    out.report.max_residual =
        std::max(out.report.max_residual, (pin.target.transpose() - where(pin, points)).norm());
  for (size_t k = 0; k < normals.size(); ++k) {
    const DetailNormal& normal = normals[k];
    SubdivisionMesh shape = meshes_[static_cast<size_t>(normal.level)];
    shape.points = points[static_cast<size_t>(normal.level)];
    const Sparse d = divided_differences_checked(
        shape, incident_[static_cast<size_t>(normal.level)], {normal.vertex});
    out.report.max_normal_angle =
        std::max(out.report.max_normal_angle,
                 normal_angle(row_of(d, 5 * normal.vertex), row_of(d, 5 * normal.vertex + 1),
                              shape.points, directions[k]));
  }
  return out;
}

}  // namespace varsurf
