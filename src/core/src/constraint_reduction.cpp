// SPDX-License-Identifier: LGPL-2.1-or-later
#include "constraint_reduction.hpp"

#include <Eigen/Householder>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <unordered_map>

#include "dense_lapack.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(static_cast<size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int x) {
    while (parent[static_cast<size_t>(x)] != x) {
      parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
      x = parent[static_cast<size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) { parent[static_cast<size_t>(find(a))] = find(b); }
};

// One sample row in terms of free unknowns.
struct FreeRow {
  std::vector<int> cols;
  std::vector<double> vals;
  Eigen::RowVectorXd rhs;
  double weight;
  bool exact;
  int id;  // global sample row
};

// A sample row's right-hand side with the fixed columns moved over.
Eigen::RowVectorXd free_rhs(const ConstraintSamples& block, int r,
                            const std::vector<int>& free_index, const Eigen::MatrixXd& fixed) {
  Eigen::RowVectorXd rhs = block.rhs.row(r);
  const auto& idx = block.index[static_cast<size_t>(r)];
  const Eigen::VectorXd& c = block.coeff[static_cast<size_t>(r)];
  for (size_t k = 0; k < idx.size(); ++k) {
    const double v = c(static_cast<Eigen::Index>(k));
    if (v != 0.0 && free_index[static_cast<size_t>(idx[k])] < 0) rhs -= v * fixed.row(idx[k]);
  }
  return rhs;
}

// One cluster after its SVD.
struct Cluster {
  std::vector<int> cols;         // free unknowns, ascending
  std::vector<int> sample_rows;  // global ids
  // The core's data from the cluster's sample data: Q_1^T d through `compress` (a tall cluster
  // compressed by QR), or `to_core` d (two-stage clusters), or d itself when both are empty.
  std::shared_ptr<const ThinQ> compress;
  Eigen::MatrixXd to_core;
  Eigen::MatrixXd u, v;  // thin SVD factors of the core matrix
  Eigen::VectorXd s;
  Eigen::MatrixXd beta;  // U^T core rhs
  Eigen::MatrixXd gain;  // U^T core start residual
  Eigen::Index numeric_rank = 0;
  Eigen::Index rank = 0;  // kept
  double start_sq = 0.0, weight = 0.0;
  double start_far = 0.0;  // the start's largest sample distance
  bool exact = false;
  bool held = false;  // met by the start: kept rows hold the start's values
};

// The cluster's core map as a matrix (core rows x m sample rows).
Eigen::MatrixXd core_map(const Cluster& cl, Eigen::Index m) {
  if (cl.compress) return cl.compress->transpose();
  return cl.to_core.size() ? cl.to_core : Eigen::MatrixXd(Eigen::MatrixXd::Identity(m, m));
}

// The SVD of a cluster's rows `b` (data `d`, the free columns' start values `start`, weights
// per row) and how many of its directions are kept. A tall system is compressed by QR first
// (same solution set; the SVD then works on an n x n matrix).
bool analyse(Cluster& cl, const Eigen::MatrixXd& b, const Eigen::MatrixXd& d,
             const Eigen::MatrixXd& start, const Eigen::VectorXd& row_weight, bool exact,
             const ReductionOptions& opt, double& conflict) {
  const Eigen::Index m = b.rows(), n = b.cols();
  cl.exact = exact;
  cl.weight = row_weight.sum();
  cl.compress.reset();
  cl.to_core.resize(0, 0);
  // The start shape's residual decides how many directions to fit: a homogeneous constraint
  // (a normal, rhs 0) is far from met by a start that violates it, not already met.
  const Eigen::MatrixXd d_start = d - b * start;
  Eigen::MatrixXd core = b, core_rhs = d, core_start = d_start;
  if (!b.allFinite()) throw InvalidInput("constraint values are not finite");
  if (m > n) {
    auto q = std::make_shared<ThinQ>();
    Eigen::MatrixXd r;
    if (thin_qr(b, *q, r)) {
      core = std::move(r);
      core_rhs = q->apply_transpose(d);
      core_start = q->apply_transpose(d_start);
      cl.compress = std::move(q);
    } else {  // LAPACK refused: Eigen's own, with an explicit Q_1^T
      Eigen::HouseholderQR<Eigen::MatrixXd> qr(b);
      core = qr.matrixQR().topRows(n).triangularView<Eigen::Upper>();
      cl.to_core = (qr.householderQ() * Eigen::MatrixXd::Identity(m, n)).transpose();
      core_rhs = cl.to_core * d;
      core_start = cl.to_core * d_start;
    }
  }
  // No direction at all (rows of zeros): nothing kept, and a two-stage reduction goes on with
  // an empty first stage.
  cl.u = Eigen::MatrixXd::Zero(core.rows(), 0);
  cl.v = Eigen::MatrixXd::Zero(n, 0);
  cl.s.resize(0);
  Eigen::MatrixXd u, v;
  Eigen::VectorXd s;
  if (!thin_svd(core, u, s, v)) {  // LAPACK's divide and conquer did not converge: Eigen's
    Eigen::BDCSVD<Eigen::MatrixXd> svd(core, Eigen::ComputeThinU | Eigen::ComputeThinV);
    u = svd.matrixU();
    s = svd.singularValues();
    v = svd.matrixV();
  }
  if (s.size() == 0 || !(s(0) > 0.0)) return false;
  if (!s.allFinite()) throw InvalidInput("constraint values are not finite");
  cl.s = std::move(s);
  cl.u = std::move(u);
  cl.v = std::move(v);
  cl.beta = cl.u.transpose() * core_rhs;
  cl.gain = cl.u.transpose() * core_start;
  while (cl.numeric_rank < cl.s.size() && cl.s(cl.numeric_rank) > opt.rank_tolerance * cl.s(0))
    ++cl.numeric_rank;
  cl.start_sq = d_start.squaredNorm();
  // Rows are scaled by sqrt(w): a sample's distance is |residual| / sqrt(w).
  for (Eigen::Index i = 0; i < m; ++i)
    if (row_weight(i) > 0.0)
      cl.start_far =
          std::max(cl.start_far, std::sqrt(d_start.row(i).squaredNorm() / row_weight(i)));
  // Residual that no choice of poles removes: constraints that contradict each other (curves
  // crossing at different heights).
  const double best = std::max(0.0, cl.start_sq - cl.gain.topRows(cl.numeric_rank).squaredNorm());
  if (cl.weight > 0.0) conflict = std::max(conflict, std::sqrt(best / cl.weight));
  const double fit_sq = opt.fit_tolerance * opt.fit_tolerance * cl.weight;
  cl.held = opt.truncation == Truncation::discrepancy && opt.start_is_minimum && !cl.exact &&
            opt.fit_tolerance > 0.0 && cl.start_sq <= fit_sq &&
            (opt.max_fit_factor <= 0.0 || cl.start_far <= opt.max_fit_factor * opt.fit_tolerance);
  if (cl.held) {
    // The discrepancy principle needs no direction of this data: the unconstrained minimum
    // already meets it. Fitting it anyway would bend the sheet to noise below the tolerance;
    // holding the well-conditioned directions where the start has them keeps it there.
    while (cl.rank < cl.numeric_rank && cl.s(cl.rank) >= opt.keep_tolerance * cl.s(0)) ++cl.rank;
  } else if (opt.truncation == Truncation::discrepancy) {
    const double allowed = best + fit_sq;
    // Well-conditioned directions are always kept: they cannot throw poles far (|coefficient|
    // <= |data| / (keep_tolerance s_max)), and dropping one that the start happens to meet
    // would let the solve drift off it. Only the weak ones are left to the discrepancy test.
    double residual = cl.start_sq;
    while (cl.rank < cl.numeric_rank) {
      const bool strong = cl.s(cl.rank) >= opt.keep_tolerance * cl.s(0);
      if (!strong && !cl.exact && opt.fit_tolerance > 0.0 && residual <= allowed) break;
      residual -= cl.gain.row(cl.rank).squaredNorm();
      ++cl.rank;
    }
  }
  return true;  // with Truncation::lcurve the L-curve decides the rank over all clusters
}

}  // namespace

ReducedConstraints reduce_constraints(const std::vector<ConstraintSamples>& blocks,
                                      const std::vector<int>& free_index,
                                      const Eigen::MatrixXd& fixed, int free_count,
                                      const ReductionOptions& opt) {
  if (!(opt.rank_tolerance > 0.0 && opt.rank_tolerance < 1.0))
    throw InvalidInput("rank tolerance must be in (0, 1)");
  if (!(opt.keep_tolerance >= opt.rank_tolerance && opt.keep_tolerance <= 1.0))
    throw InvalidInput("keep tolerance must be in [rank tolerance, 1]");
  if (!(opt.fit_tolerance >= 0.0) || !std::isfinite(opt.fit_tolerance))
    throw InvalidInput("fit tolerance must be a finite non-negative length");
  const Eigen::Index width = fixed.cols();
  for (const ConstraintSamples& block : blocks)
    if (block.rhs.cols() != width) throw InvalidInput("constraint samples of mixed widths");
  ReducedConstraints out;
  std::vector<FreeRow> rows;
  DisjointSets sets(free_count);
  int id = 0;
  for (const ConstraintSamples& block : blocks) {
    for (int r = 0; r < block.rows(); ++r, ++id) {
      FreeRow row;
      row.id = id;
      row.rhs = free_rhs(block, r, free_index, fixed);
      const auto& idx = block.index[static_cast<size_t>(r)];
      const Eigen::VectorXd& c = block.coeff[static_cast<size_t>(r)];
      row.weight = block.weight[static_cast<size_t>(r)];
      row.exact = block.exact;
      for (size_t k = 0; k < idx.size(); ++k) {
        const double v = c(static_cast<Eigen::Index>(k));
        const int f = free_index[static_cast<size_t>(idx[k])];
        if (v == 0.0 || f < 0) continue;
        row.cols.push_back(f);
        row.vals.push_back(v);
      }
      ++out.samples;
      if (row.cols.empty()) continue;
      for (size_t k = 1; k < row.cols.size(); ++k) sets.unite(row.cols[0], row.cols[k]);
      rows.push_back(std::move(row));
    }
  }

  // Group rows by cluster.
  std::unordered_map<int, std::vector<size_t>> cluster_rows;
  for (size_t i = 0; i < rows.size(); ++i) cluster_rows[sets.find(rows[i].cols[0])].push_back(i);
  std::vector<int> roots;
  for (const auto& kv : cluster_rows) roots.push_back(kv.first);
  std::sort(roots.begin(), roots.end());  // deterministic row order

  std::vector<Cluster> clusters;
  std::vector<int> local(static_cast<size_t>(free_count), -1);
  for (int root : roots) {
    const std::vector<size_t>& members = cluster_rows[root];
    Cluster cl;
    for (size_t i : members)
      for (int c : rows[i].cols)
        if (local[static_cast<size_t>(c)] < 0) {
          local[static_cast<size_t>(c)] = 0;
          cl.cols.push_back(c);
        }
    std::sort(cl.cols.begin(), cl.cols.end());
    for (size_t k = 0; k < cl.cols.size(); ++k)
      local[static_cast<size_t>(cl.cols[k])] = static_cast<int>(k);

    const Eigen::Index m = static_cast<Eigen::Index>(members.size());
    const Eigen::Index n = static_cast<Eigen::Index>(cl.cols.size());
    Eigen::MatrixXd bm = Eigen::MatrixXd::Zero(m, n);
    Eigen::MatrixXd d(m, width);
    Eigen::VectorXd row_weight(m);
    std::vector<bool> exact(static_cast<size_t>(m));
    // Exact rows first: a cluster that mixes them with fitted ones is reduced in two stages.
    std::vector<size_t> order(members.begin(), members.end());
    std::stable_partition(order.begin(), order.end(), [&](size_t i) { return rows[i].exact; });
    for (Eigen::Index i = 0; i < m; ++i) {
      const FreeRow& row = rows[order[static_cast<size_t>(i)]];
      for (size_t k = 0; k < row.cols.size(); ++k)
        bm(i, local[static_cast<size_t>(row.cols[k])]) += row.vals[k];
      d.row(i) = row.rhs;
      row_weight(i) = row.weight;
      exact[static_cast<size_t>(i)] = row.exact;
      cl.sample_rows.push_back(row.id);
    }
    for (int c : cl.cols) local[static_cast<size_t>(c)] = -1;
    Eigen::MatrixXd start(n, width);
    for (Eigen::Index k = 0; k < n; ++k) start.row(k) = fixed.row(cl.cols[static_cast<size_t>(k)]);
    const Eigen::Index hard = std::count(exact.begin(), exact.end(), true);
    // Without a fit tolerance every direction of the fitted rows is fitted anyway: one stage.
    if (hard == 0 || hard == m || !(opt.fit_tolerance > 0.0)) {
      if (analyse(cl, bm, d, start, row_weight, hard > 0, opt, out.conflict))
        clusters.push_back(std::move(cl));
      continue;
    }
    // Exact rows (a closed sheet's seam ties) sharing poles with fitted ones (curves): the exact
    // rows are met first, and the fitted rows act only in the directions they leave free, where
    // the discrepancy principle decides as for any fitted cluster. Counting the whole cluster as
    // exact would fit every direction of the curves' data, noise below the tolerance included.
    Cluster first = cl, second = cl;
    const Eigen::Index soft = m - hard;
    analyse(first, bm.topRows(hard), d.topRows(hard), start, row_weight.head(hard), true, opt,
            out.conflict);
    const Eigen::MatrixXd first_core = core_map(first, hard);
    const Eigen::MatrixXd ve = first.v.leftCols(first.rank);
    // x = ve c + P y with c = T d_exact, T = S^-1 U^T (core of the exact rows' data).
    const Eigen::MatrixXd to_c = first.s.head(first.rank).cwiseInverse().asDiagonal() *
                                 first.u.leftCols(first.rank).transpose() * first_core;
    const Eigen::MatrixXd soft_b = bm.bottomRows(soft);
    const Eigen::MatrixXd soft_ve = soft_b * ve;
    // The fitted rows act where the exact ones leave the poles free; their data, less what c
    // already does there: d_soft - B_soft ve c.
    const Eigen::MatrixXd projected = soft_b - soft_ve * ve.transpose();
    analyse(second, projected, d.bottomRows(soft) - soft_ve * (to_c * d.topRows(hard)), start,
            row_weight.tail(soft), false, opt, out.conflict);
    // Both stages' maps from the whole cluster's data (exact rows first), for a drag's moved
    // data: never an m x m matrix (thousands of curve samples).
    const Eigen::MatrixXd second_core = core_map(second, soft);
    Eigen::MatrixXd first_map = Eigen::MatrixXd::Zero(first_core.rows(), m);
    first_map.leftCols(hard) = first_core;
    first.compress.reset();
    first.to_core = std::move(first_map);
    Eigen::MatrixXd second_map(second_core.rows(), m);
    second_map.leftCols(hard) = -(second_core * soft_ve) * to_c;
    second_map.rightCols(soft) = second_core;
    second.compress.reset();
    second.to_core = std::move(second_map);
    clusters.push_back(std::move(first));
    clusters.push_back(std::move(second));
  }

  if (opt.truncation == Truncation::lcurve) {
    // One SVD of all constraints is the union of the clusters' (they share no unknowns): merge
    // their directions by singular value and keep the largest up to the L-curve's corner.
    struct Direction {
      double sigma, gain_sq;
      size_t cluster;
    };
    std::vector<Direction> all;
    double total_sq = 0.0, allowed = 0.0;
    for (size_t c = 0; c < clusters.size(); ++c) {
      Cluster& cl = clusters[c];
      if (cl.exact) {  // exact rows keep every direction the space holds, as in any solve
        cl.rank = cl.numeric_rank;
        continue;
      }
      total_sq += cl.start_sq;
      allowed += std::max(0.0, cl.start_sq - cl.gain.topRows(cl.numeric_rank).squaredNorm()) +
                 opt.fit_tolerance * opt.fit_tolerance * cl.weight;
      for (Eigen::Index i = 0; i < clusters[c].numeric_rank; ++i)
        all.push_back({clusters[c].s(i), clusters[c].gain.row(i).squaredNorm(), c});
    }
    std::stable_sort(all.begin(), all.end(),
                     [](const Direction& a, const Direction& b) { return a.sigma > b.sigma; });
    Eigen::VectorXd sigma(static_cast<Eigen::Index>(all.size())), gain(sigma.size());
    for (size_t i = 0; i < all.size(); ++i) {
      sigma(static_cast<Eigen::Index>(i)) = all[i].sigma;
      gain(static_cast<Eigen::Index>(i)) = all[i].gain_sq;
    }
    out.lcurve = lcurve(sigma, gain, total_sq);
    // Past the point where every cluster is within fit_tolerance the remaining directions fit
    // only noise (the discrepancy principle): the corner is not taken beyond it.
    int kept = out.lcurve.corner;
    if (opt.fit_tolerance > 0.0) {
      double residual = total_sq;
      int needed = 0;
      while (needed < kept && residual > allowed)
        residual -= all[static_cast<size_t>(needed++)].gain_sq;
      kept = needed;
    }
    for (int i = 0; i < kept; ++i) ++clusters[all[static_cast<size_t>(i)].cluster].rank;
  }

  std::vector<Eigen::Triplet<double>> trip;
  std::vector<Eigen::RowVectorXd> rhs;
  int rank_total = 0;
  for (const Cluster& cl : clusters) {
    const Eigen::Index rank = cl.rank;
    const Eigen::Index n = static_cast<Eigen::Index>(cl.cols.size());
    // A held cluster's rows take the start's values: (beta - gain) / s = V^T start.
    const Eigen::MatrixXd br =
        (cl.held ? Eigen::MatrixXd(cl.beta.topRows(rank) - cl.gain.topRows(rank))
                 : Eigen::MatrixXd(cl.beta.topRows(rank)))
            .array()
            .colwise() /
        cl.s.head(rank).array();
    for (Eigen::Index r = 0; r < rank; ++r) {
      for (Eigen::Index k = 0; k < n; ++k)
        if (cl.v(k, r) != 0.0)
          trip.emplace_back(rank_total + static_cast<int>(r), cl.cols[static_cast<size_t>(k)],
                            cl.v(k, r));
      rhs.push_back(br.row(r));
    }
    ReducedConstraints::ClusterMap map;
    map.sample_rows = cl.sample_rows;
    map.first_row = rank_total;
    map.left = cl.s.head(rank).cwiseInverse().asDiagonal() * cl.u.leftCols(rank).transpose();
    map.compress = cl.compress;
    map.right = cl.to_core;
    if (cl.held) {
      map.offset = -(cl.gain.topRows(rank).array().colwise() / cl.s.head(rank).array()).matrix();
      ++out.held;
    }
    out.maps.push_back(std::move(map));
    rank_total += static_cast<int>(rank);
    ++out.clusters;
  }
  out.rows.resize(rank_total, free_count);
  out.rows.setFromTriplets(trip.begin(), trip.end());
  out.rhs.resize(rank_total, width);
  for (int r = 0; r < rank_total; ++r) out.rhs.row(r) = rhs[static_cast<size_t>(r)];
  return out;
}

int largest_cluster(const std::vector<ConstraintSamples>& blocks,
                    const std::vector<int>& free_index, int free_count) {
  DisjointSets sets(free_count);
  std::vector<bool> used(static_cast<size_t>(free_count), false);
  for (const ConstraintSamples& block : blocks)
    for (const auto& idx : block.index) {
      int first = -1;
      for (int k : idx) {
        const int f = free_index[static_cast<size_t>(k)];
        if (f < 0) continue;
        used[static_cast<size_t>(f)] = true;
        if (first < 0)
          first = f;
        else
          sets.unite(first, f);
      }
    }
  std::unordered_map<int, int> size;
  int largest = 0;
  for (int f = 0; f < free_count; ++f)
    if (used[static_cast<size_t>(f)]) largest = std::max(largest, ++size[sets.find(f)]);
  return largest;
}

Eigen::MatrixXd reduced_rhs(const ReducedConstraints& red,
                            const std::vector<ConstraintSamples>& blocks,
                            const std::vector<int>& free_index, const Eigen::MatrixXd& fixed) {
  std::vector<std::pair<const ConstraintSamples*, int>> where;  // global id -> (block, row)
  for (const ConstraintSamples& block : blocks)
    for (int r = 0; r < block.rows(); ++r) where.emplace_back(&block, r);
  Eigen::MatrixXd out(red.rhs.rows(), fixed.cols());
  for (const auto& map : red.maps) {
    Eigen::MatrixXd d(static_cast<Eigen::Index>(map.sample_rows.size()), fixed.cols());
    for (size_t i = 0; i < map.sample_rows.size(); ++i) {
      const size_t g = static_cast<size_t>(map.sample_rows[i]);
      if (g >= where.size()) throw InvalidInput("the moved constraints have fewer samples");
      d.row(static_cast<Eigen::Index>(i)) =
          free_rhs(*where[g].first, where[g].second, free_index, fixed);
    }
    const Eigen::MatrixXd core = map.compress       ? map.compress->apply_transpose(d)
                                 : map.right.size() ? Eigen::MatrixXd(map.right * d)
                                                    : d;
    out.middleRows(map.first_row, map.left.rows()) = map.left * core;
    if (map.offset.size()) out.middleRows(map.first_row, map.offset.rows()) += map.offset;
  }
  return out;
}

}  // namespace varsurf
