#include "constraint_reduction.hpp"

#include <Eigen/Householder>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

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
};

}  // namespace

ReducedConstraints reduce_constraints(const std::vector<ConstraintSamples>& blocks,
                                      const std::vector<int>& free_index,
                                      const Eigen::MatrixXd& fixed, int free_count,
                                      double rank_tolerance, double fit_tolerance,
                                      double keep_tolerance) {
  if (!(rank_tolerance > 0.0 && rank_tolerance < 1.0))
    throw InvalidInput("rank tolerance must be in (0, 1)");
  if (!(keep_tolerance >= rank_tolerance && keep_tolerance <= 1.0))
    throw InvalidInput("keep tolerance must be in [rank tolerance, 1]");
  if (!(fit_tolerance >= 0.0) || !std::isfinite(fit_tolerance))
    throw InvalidInput("fit tolerance must be a finite non-negative length");
  const Eigen::Index width = fixed.cols();
  for (const ConstraintSamples& block : blocks)
    if (block.rhs.cols() != width) throw InvalidInput("constraint samples of mixed widths");
  ReducedConstraints out;
  std::vector<FreeRow> rows;
  DisjointSets sets(free_count);
  for (const ConstraintSamples& block : blocks) {
    for (int r = 0; r < block.rows(); ++r) {
      FreeRow row;
      row.rhs = block.rhs.row(r);
      const auto& idx = block.index[static_cast<size_t>(r)];
      const Eigen::VectorXd& c = block.coeff[static_cast<size_t>(r)];
      row.weight = block.weight[static_cast<size_t>(r)];
      row.exact = block.exact;
      for (size_t k = 0; k < idx.size(); ++k) {
        const double v = c(static_cast<Eigen::Index>(k));
        if (v == 0.0) continue;
        const int f = free_index[static_cast<size_t>(idx[k])];
        if (f < 0) {
          row.rhs -= v * fixed.row(idx[k]);
        } else {
          row.cols.push_back(f);
          row.vals.push_back(v);
        }
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

  std::vector<Eigen::Triplet<double>> trip;
  std::vector<Eigen::RowVectorXd> rhs;
  int rank_total = 0;
  std::vector<int> local(static_cast<size_t>(free_count), -1);
  for (int root : roots) {
    const std::vector<size_t>& members = cluster_rows[root];
    std::vector<int> cols;
    for (size_t i : members)
      for (int c : rows[i].cols)
        if (local[static_cast<size_t>(c)] < 0) {
          local[static_cast<size_t>(c)] = 0;
          cols.push_back(c);
        }
    std::sort(cols.begin(), cols.end());
    for (size_t k = 0; k < cols.size(); ++k)
      local[static_cast<size_t>(cols[k])] = static_cast<int>(k);

    const Eigen::Index m = static_cast<Eigen::Index>(members.size());
    const Eigen::Index n = static_cast<Eigen::Index>(cols.size());
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(m, n);
    Eigen::MatrixXd d(m, width);
    double cluster_weight = 0.0;
    bool exact = false;  // an exact constraint in the cluster: no discrepancy truncation
    for (Eigen::Index i = 0; i < m; ++i) {
      const FreeRow& row = rows[members[static_cast<size_t>(i)]];
      for (size_t k = 0; k < row.cols.size(); ++k)
        b(i, local[static_cast<size_t>(row.cols[k])]) += row.vals[k];
      d.row(i) = row.rhs;
      cluster_weight += row.weight;
      exact = exact || row.exact;
    }
    for (int c : cols) local[static_cast<size_t>(c)] = -1;

    // Tall clusters (many samples, few poles) are compressed by QR first: same solution set,
    // and the SVD then works on an n x n matrix.
    // The start shape's residual decides how many directions to fit: a homogeneous constraint
    // (a normal, rhs 0) is far from met by a start that violates it, not already met.
    Eigen::MatrixXd start(n, width);
    for (Eigen::Index k = 0; k < n; ++k) start.row(k) = fixed.row(cols[static_cast<size_t>(k)]);
    const Eigen::MatrixXd d_start = d - b * start;
    Eigen::MatrixXd core = b;
    Eigen::MatrixXd core_rhs = d, core_start = d_start;
    if (m > n) {
      Eigen::HouseholderQR<Eigen::MatrixXd> qr(b);
      core = qr.matrixQR().topRows(n).triangularView<Eigen::Upper>();
      core_rhs = (qr.householderQ().transpose() * d).topRows(n);
      core_start = (qr.householderQ().transpose() * d_start).topRows(n);
    }
    Eigen::BDCSVD<Eigen::MatrixXd> svd(core, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& s = svd.singularValues();
    if (s.size() == 0 || !(s(0) > 0.0)) continue;
    if (!s.allFinite()) throw InvalidInput("constraint values are not finite");
    const Eigen::MatrixXd beta = svd.matrixU().transpose() * core_rhs;
    const Eigen::MatrixXd gain = svd.matrixU().transpose() * core_start;
    Eigen::Index numeric_rank = 0;
    while (numeric_rank < s.size() && s(numeric_rank) > rank_tolerance * s(0)) ++numeric_rank;
    // Residual left by each truncation; the full-rank one is what no choice of poles removes:
    // constraints that contradict each other (curves crossing at different heights).
    double residual = d_start.squaredNorm();
    const double best = std::max(0.0, residual - gain.topRows(numeric_rank).squaredNorm());
    const double allowed = best + fit_tolerance * fit_tolerance * cluster_weight;
    // Well-conditioned directions are always kept: they cannot throw poles far (|coefficient| <=
    // |data| / (keep_tolerance s_max)), and dropping one that the start happens to meet would let
    // the solve drift off it. Only the weak ones are left to the discrepancy test.
    Eigen::Index rank = 0;
    while (rank < numeric_rank) {
      const bool strong = s(rank) >= keep_tolerance * s(0);
      if (!strong && !exact && fit_tolerance > 0.0 && residual <= allowed) break;
      residual -= gain.row(rank).squaredNorm();
      ++rank;
    }
    if (cluster_weight > 0.0)
      out.conflict = std::max(out.conflict, std::sqrt(best / cluster_weight));
    const Eigen::MatrixXd vr = svd.matrixV().leftCols(rank);
    const Eigen::MatrixXd br = beta.topRows(rank).array().colwise() / s.head(rank).array();
    for (Eigen::Index r = 0; r < rank; ++r) {
      for (Eigen::Index k = 0; k < n; ++k) {
        if (vr(k, r) != 0.0)
          trip.emplace_back(rank_total + static_cast<int>(r), cols[static_cast<size_t>(k)],
                            vr(k, r));
      }
      rhs.push_back(br.row(r));
    }
    rank_total += static_cast<int>(rank);
    ++out.clusters;
  }
  out.rows.resize(rank_total, free_count);
  out.rows.setFromTriplets(trip.begin(), trip.end());
  out.rhs.resize(rank_total, width);
  for (int r = 0; r < rank_total; ++r) out.rhs.row(r) = rhs[static_cast<size_t>(r)];
  return out;
}

}  // namespace varsurf
