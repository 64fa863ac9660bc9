// SPDX-License-Identifier: LGPL-2.1-or-later
// Reduction of weighted least-squares constraint samples to independent equality rows.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "dense_lapack.hpp"
#include "varsurf/core/constraints.hpp"
#include "varsurf/core/lcurve.hpp"

namespace varsurf {

// How many singular directions of the constraints are fitted.
enum class Truncation {
  // Per cluster of constraints: the discrepancy principle (see reduce_constraints).
  discrepancy,
  // Over all constraints at once: the corner of the L-curve (Michalik & Bruderlin 4.2).
  lcurve,
};

struct ReductionOptions {
  double rank_tolerance = 1e-9;
  double fit_tolerance = 0.0;
  double keep_tolerance = 1e-2;
  // A cluster also counts as met only while no sample is farther than max_fit_factor *
  // fit_tolerance (0: the RMS alone decides).
  double max_fit_factor = 0.0;
  // The start values of the free columns are the energy's unconstrained minimum (a rest shape,
  // nothing else pulling): a cluster the start already meets within fit_tolerance takes none of
  // its data, only its motion from the prepared data (see reduce_constraints).
  bool start_is_minimum = false;
  Truncation truncation = Truncation::discrepancy;
};

struct ReducedConstraints {
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows;  // rank x free unknowns, orthonormal rows
  Eigen::MatrixXd rhs;                                // rank x width
  int samples = 0;
  int clusters = 0;
  double conflict = 0.0;  // largest RMS residual that no pole choice removes, over clusters
  LCurve lcurve;          // with Truncation::lcurve
  // rhs rows [first_row, first_row + left.rows()) = transform * (right-hand sides of the
  // cluster's sample rows, fixed columns moved over) + offset: what a drag recomputes.
  struct ClusterMap {
    std::vector<int> sample_rows;  // global sample row ids (blocks concatenated)
    // transform = left * right (kept rows x sample rows), kept as its factors: forming the
    // product cost a 280 x 394 x 2912 GEMM (a fifth of a 500-pole TSVD) where applying them to
    // the samples' data costs a few matrix-vector products.
    Eigen::MatrixXd left;  // kept rows x core rows: S^-1 U^T
    // right: Q_1^T of a cluster compressed by QR (kept as reflectors), else an explicit matrix
    // (core rows x sample rows), else the identity (both empty).
    std::shared_ptr<const ThinQ> compress;
    Eigen::MatrixXd right;
    Eigen::MatrixXd offset;  // kept rows x width, or empty for none
    int first_row = 0;
  };
  int held = 0;  // clusters the start already met: held where the start has them
  std::vector<ClusterMap> maps;
};

// `free_index[k]` is the unknown of column k, or -1 for a fixed column whose value `fixed.row(k)`
// (as wide as the samples' right-hand sides) moves to the right-hand side. Rows touching no free
// pole are dropped. Within each cluster of rows that share unknowns, B p = d (least squares) is
// replaced by V_r^T p = S_r^-1 U_r^T d from the SVD B = U S V^T truncated at rank_tolerance *
// s_max: exactly the set of least-squares minimizers. With fit_tolerance > 0 the discrepancy
// truncation also stops at the first rank whose least-squares residual, counted from the start
// values (fixed.row(k) holds them for free columns too; an RMS distance, since sample weights sum
// to each constraint's weight), is within fit_tolerance of the best the cluster can reach;
// directions with singular values of at least keep_tolerance * s_max are kept regardless.
// Directions beyond it are left to the energy instead of being fitted to data the space cannot
// hold, which is what makes coarse sheets go wild. With start_is_minimum, a cluster whose start
// residual is already within the fit tolerance (the discrepancy principle's answer: no direction
// is needed) keeps its well-conditioned directions with the start's own values as right-hand
// side, so data noise below the tolerance moves nothing while the other constraints cannot drag
// the sheet off it; later moved data shifts those values by the data's motion (offset). The
// L-curve truncation keeps the globally largest singular directions up to the L-curve's corner,
// and no more than the discrepancy principle needs to bring all clusters within fit_tolerance;
// exact clusters keep all their directions. With fit_tolerance > 0, a cluster whose exact rows
// (a closed sheet's seam ties) share unknowns with fitted ones (curves) is reduced in two
// stages: the exact rows first, then the fitted rows, projected onto the directions the exact
// ones leave free, as a fitted cluster of their own.
ReducedConstraints reduce_constraints(const std::vector<ConstraintSamples>& blocks,
                                      const std::vector<int>& free_index,
                                      const Eigen::MatrixXd& fixed, int free_count,
                                      const ReductionOptions& options);

// Free unknowns in the largest cluster of constraint rows sharing unknowns: what the reduction's
// dense SVDs cost (cubic in it) and how dense the reduced rows make the KKT system.
int largest_cluster(const std::vector<ConstraintSamples>& blocks,
                    const std::vector<int>& free_index, int free_count);

// The reduced right-hand sides for new samples with the same matrices (moved targets).
Eigen::MatrixXd reduced_rhs(const ReducedConstraints& reduced,
                            const std::vector<ConstraintSamples>& blocks,
                            const std::vector<int>& free_index, const Eigen::MatrixXd& fixed);

}  // namespace varsurf
