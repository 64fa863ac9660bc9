// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/hierarchical_space.hpp"

#include <algorithm>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_refinement.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

// For each basis function of (knots, degree): the first and last span (distinct-breakpoint
// interval) of its support.
void support_spans(const std::vector<double>& knots, int degree, std::vector<int>& first,
                   std::vector<int>& last) {
  const std::vector<double> bp = breakpoints(knots, degree);
  const auto index = [&](double t) {
    return static_cast<int>(std::lower_bound(bp.begin(), bp.end(), t) - bp.begin());
  };
  const int n = static_cast<int>(knots.size()) - degree - 1;
  first.resize(static_cast<size_t>(n));
  last.resize(static_cast<size_t>(n));
  for (int a = 0; a < n; ++a) {
    first[static_cast<size_t>(a)] = index(knots[static_cast<size_t>(a)]);
    last[static_cast<size_t>(a)] = index(knots[static_cast<size_t>(a + degree + 1)]) - 1;
  }
}

int spans_of(const std::vector<double>& knots, int degree) {
  return static_cast<int>(breakpoints(knots, degree).size()) - 1;
}

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Values on a coarse tensor grid (flat, pole order i * nv + j) written on the finer grid: tu * G *
// tv^T, knot insertion along both directions.
Eigen::VectorXd refine_grid(const Eigen::MatrixXd& tu, const Eigen::MatrixXd& tv,
                            const Eigen::VectorXd& flat) {
  const RowMajor out =
      tu * Eigen::Map<const RowMajor>(flat.data(), tu.cols(), tv.cols()) * tv.transpose();
  return Eigen::Map<const Eigen::VectorXd>(out.data(), out.size());
}

// A rational layer's weights written on the finer layer's knots: the weight function w(u, v) is
// a polynomial spline, so knot insertion carries it over exactly.
Eigen::VectorXd refined_weights(const SplineSpace& coarse, const SplineSpace& fine) {
  return refine_grid(
      Eigen::MatrixXd(refinement_matrix(coarse.knots_u, coarse.degree_u, fine.knots_u)),
      Eigen::MatrixXd(refinement_matrix(coarse.knots_v, coarse.degree_v, fine.knots_v)),
      coarse.weights);
}

}  // namespace

HierarchicalSpace::HierarchicalSpace(SplineSpace base) {
  base.validate();
  layers_.push_back(make_layer(std::move(base)));
  std::fill(layers_[0].region.begin(), layers_[0].region.end(), 1);
  collect_dofs();
}

HierarchicalSpace::Layer HierarchicalSpace::make_layer(SplineSpace space) const {
  Layer l;
  support_spans(space.knots_u, space.degree_u, l.first_u, l.last_u);
  support_spans(space.knots_v, space.degree_v, l.first_v, l.last_v);
  const size_t cells = static_cast<size_t>(spans_of(space.knots_u, space.degree_u)) *
                       static_cast<size_t>(spans_of(space.knots_v, space.degree_v));
  l.region.assign(cells, 0);
  l.refined.assign(cells, 0);
  l.space = std::move(space);
  return l;
}

const HierarchicalSpace::Layer& HierarchicalSpace::at(int level) const {
  if (level < 0 || level >= levels())
    throw InvalidInput("no level " + std::to_string(level) + " (the space has " +
                       std::to_string(levels()) + ")");
  return layers_[static_cast<size_t>(level)];
}

const SplineSpace& HierarchicalSpace::layer(int level) const {
  return at(level).space;
}

int HierarchicalSpace::spans_u(int level) const {
  return spans_of(at(level).space.knots_u, at(level).space.degree_u);
}

int HierarchicalSpace::spans_v(int level) const {
  return spans_of(at(level).space.knots_v, at(level).space.degree_v);
}

bool HierarchicalSpace::in_region(int level, int su, int sv) const {
  const Layer& l = at(level);
  if (su < 0 || sv < 0 || su >= spans_u(level) || sv >= spans_v(level)) return false;
  return l.region[static_cast<size_t>(su * spans_v(level) + sv)] != 0;
}

bool HierarchicalSpace::refined(int level, int su, int sv) const {
  const Layer& l = at(level);
  if (su < 0 || sv < 0 || su >= spans_u(level) || sv >= spans_v(level)) return false;
  return l.refined[static_cast<size_t>(su * spans_v(level) + sv)] != 0;
}

void HierarchicalSpace::add_level() {
  const SplineSpace& last = layers_.back().space;
  SplineSpace next = last;
  next.knots_u = dyadic_knots(last.knots_u, last.degree_u);
  next.knots_v = dyadic_knots(last.knots_v, last.degree_v);
  if (last.rational()) next.weights = refined_weights(last, next);
  layers_.push_back(make_layer(std::move(next)));
}

void HierarchicalSpace::refine(int level, int su, int sv) {
  if (!in_region(level, su, sv))
    throw InvalidInput("span (" + std::to_string(su) + ", " + std::to_string(sv) + ") of level " +
                       std::to_string(level) + " is not in that level's region");
  Layer& l = layers_[static_cast<size_t>(level)];
  const int nv = spans_v(level);
  char& flag = l.refined[static_cast<size_t>(su * nv + sv)];
  if (flag) return;
  flag = 1;
  if (level + 1 == levels()) add_level();
  Layer& child = layers_[static_cast<size_t>(level + 1)];
  const int cv = spans_v(level + 1);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      child.region[static_cast<size_t>((2 * su + a) * cv + 2 * sv + b)] = 1;
  collect_dofs();
}

int HierarchicalSpace::refine_box(int level, double u0, double u1, double v0, double v1) {
  const SplineSpace& s = layer(level);
  const std::vector<double> bu = breakpoints(s.knots_u, s.degree_u);
  const std::vector<double> bv = breakpoints(s.knots_v, s.degree_v);
  int count = 0;
  for (int su = 0; su + 1 < static_cast<int>(bu.size()); ++su)
    for (int sv = 0; sv + 1 < static_cast<int>(bv.size()); ++sv) {
      const bool overlaps =
          bu[static_cast<size_t>(su)] < u1 && bu[static_cast<size_t>(su + 1)] > u0 &&
          bv[static_cast<size_t>(sv)] < v1 && bv[static_cast<size_t>(sv + 1)] > v0;
      if (overlaps && in_region(level, su, sv) && !refined(level, su, sv)) {
        refine(level, su, sv);
        ++count;
      }
    }
  return count;
}

void HierarchicalSpace::collect_dofs() {
  dofs_.clear();
  for (int k = 0; k < levels(); ++k) {
    const Layer& l = layers_[static_cast<size_t>(k)];
    const int nv = spans_v(k);
    for (int i = 0; i < l.space.nu(); ++i)
      for (int j = 0; j < l.space.nv(); ++j) {
        bool inside = true, all_refined = true;
        for (int su = l.first_u[static_cast<size_t>(i)]; su <= l.last_u[static_cast<size_t>(i)];
             ++su)
          for (int sv = l.first_v[static_cast<size_t>(j)]; sv <= l.last_v[static_cast<size_t>(j)];
               ++sv) {
            const size_t cell = static_cast<size_t>(su * nv + sv);
            inside = inside && l.region[cell];
            all_refined = all_refined && l.refined[cell];
          }
        if (inside && !all_refined) dofs_.push_back({k, i, j});
      }
  }
}

namespace {

// Knot insertion from `level` to the finest level along one direction, chained level by level.
Eigen::SparseMatrix<double> chain_to_finest(const HierarchicalSpace& h, int level, bool along_u) {
  auto knots = [&](int k) -> const std::vector<double>& {
    return along_u ? h.layer(k).knots_u : h.layer(k).knots_v;
  };
  const int degree = along_u ? h.layer(level).degree_u : h.layer(level).degree_v;
  const int n = along_u ? h.layer(level).nu() : h.layer(level).nv();
  Eigen::SparseMatrix<double> t(n, n);
  t.setIdentity();
  for (int k = level; k + 1 < h.levels(); ++k)
    t = refinement_matrix(knots(k), degree, knots(k + 1)) * t;
  return t;
}

}  // namespace

Eigen::SparseMatrix<double> HierarchicalSpace::level_to_finest_u(int level) const {
  return chain_to_finest(*this, level, true);
}

Eigen::SparseMatrix<double> HierarchicalSpace::level_to_finest_v(int level) const {
  return chain_to_finest(*this, level, false);
}

double HierarchicalSpace::layer_weight(int level, int i, int j) const {
  const SplineSpace& s = layer(level);
  return s.rational() ? s.weights(s.index(i, j)) : 1.0;
}

Eigen::MatrixX3d HierarchicalSpace::base_to_finest(const Eigen::MatrixX3d& poles) const {
  const SplineSpace& base = layer(0);
  const SplineSpace& fine = finest();
  if (poles.rows() != base.size())
    throw InvalidInput("base_to_finest: " + std::to_string(poles.rows()) + " poles for " +
                       std::to_string(base.size()));
  const Eigen::MatrixXd tu = Eigen::MatrixXd(level_to_finest_u(0));
  const Eigen::MatrixXd tv = Eigen::MatrixXd(level_to_finest_v(0));
  // Rational: refined in homogeneous coordinates (w P), where knot insertion is exact.
  const Eigen::VectorXd w0 = base.rational() ? base.weights : Eigen::VectorXd::Ones(base.size());
  const Eigen::VectorXd w = fine.rational() ? fine.weights : Eigen::VectorXd::Ones(fine.size());
  Eigen::MatrixX3d out(fine.size(), 3);
  for (int c = 0; c < 3; ++c)
    out.col(c) = refine_grid(tu, tv, w0.cwiseProduct(poles.col(c))).cwiseQuotient(w);
  return out;
}

Eigen::SparseMatrix<double> HierarchicalSpace::to_finest() const {
  const SplineSpace& fine = finest();
  std::vector<Eigen::SparseMatrix<double>> tu, tv;
  for (int k = 0; k < levels(); ++k) {
    tu.push_back(level_to_finest_u(k));
    tv.push_back(level_to_finest_v(k));
  }
  std::vector<Eigen::Triplet<double>> t;
  for (size_t d = 0; d < dofs_.size(); ++d) {
    const HierarchicalDof& f = dofs_[d];
    const Eigen::SparseMatrix<double>& a = tu[static_cast<size_t>(f.level)];
    const Eigen::SparseMatrix<double>& b = tv[static_cast<size_t>(f.level)];
    // Rational: the layers add up in homogeneous coordinates (w P), where knot insertion is exact.
    const double w = layer_weight(f.level, f.i, f.j);
    for (Eigen::SparseMatrix<double>::InnerIterator x(a, f.i); x; ++x)
      for (Eigen::SparseMatrix<double>::InnerIterator y(b, f.j); y; ++y) {
        const int row = fine.index(static_cast<int>(x.row()), static_cast<int>(y.row()));
        const double scale = fine.rational() ? w / fine.weights(row) : 1.0;
        t.emplace_back(row, static_cast<int>(d), x.value() * y.value() * scale);
      }
  }
  Eigen::SparseMatrix<double> out(fine.size(), dof_count());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

Eigen::Vector3d HierarchicalSpace::evaluate(const Eigen::MatrixX3d& values, double u,
                                            double v) const {
  if (values.rows() != dof_count())
    throw InvalidInput("evaluate: " + std::to_string(values.rows()) + " values for " +
                       std::to_string(dof_count()) + " degrees of freedom");
  // Each layer's share of the numerator sum w P N (of the weight function alone, with all-one
  // weights, when the base is polynomial), divided by the base's weight function.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < levels(); ++k) {
    SplineSpace s = layer(k);
    s.weights.resize(0);
    Eigen::MatrixX3d poles = Eigen::MatrixX3d::Zero(s.size(), 3);
    bool any = false;
    for (size_t d = 0; d < dofs_.size(); ++d)
      if (dofs_[d].level == k) {
        const HierarchicalDof& f = dofs_[d];
        poles.row(s.index(f.i, f.j)) =
            layer_weight(k, f.i, f.j) * values.row(static_cast<Eigen::Index>(d));
        any = true;
      }
    if (any) sum += evaluate_surface(s, poles, u, v, 0).row(0).transpose();
  }
  const SplineSpace& base = layer(0);
  if (!base.rational()) return sum;
  SplineSpace plain = base;
  plain.weights.resize(0);
  Eigen::MatrixX3d w = Eigen::MatrixX3d::Zero(base.size(), 3);
  w.col(0) = base.weights;
  return sum / evaluate_surface(plain, w, u, v, 0)(0, 0);
}

}  // namespace varsurf
