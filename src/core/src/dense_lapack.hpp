// SPDX-License-Identifier: LGPL-2.1-or-later
// Thin QR and SVD of dense matrices through the system LAPACK (OpenBLAS on Debian). Eigen's own
// are built for the baseline x86-64 and unblocked in places: on the 2912 x 394 constraint
// block of a 500-pole TSVD, Householder QR with its explicit Q took 75 ms and BDCSVD of the
// 394 x 394 core 49 ms; LAPACK's dgeqrf and dgesdd took 18 and 30 ms (measured in one
// process on the same machine).
#pragma once

#include <Eigen/Core>

namespace varsurf {

// The orthonormal factor Q1 (m x n) of a thin QR, kept as LAPACK's Householder reflectors:
// forming it explicitly (dorgqr) cost as much as the factorization, and the reduction needs only
// Q1^T applied to a few columns of data.
class ThinQ {
 public:
  Eigen::Index rows() const { return reflectors_.rows(); }
  Eigen::Index cols() const { return reflectors_.cols(); }
  Eigen::MatrixXd apply_transpose(const Eigen::MatrixXd& d) const;  // Q1^T d, n x d.cols()
  Eigen::MatrixXd transpose() const;                                // Q1^T, n x m

 private:
  void apply(char trans, Eigen::MatrixXd& c) const;  // c = Q c or Q^T c, c m x k
  friend bool thin_qr(const Eigen::MatrixXd& a, ThinQ& q, Eigen::MatrixXd& r);
  Eigen::MatrixXd reflectors_;
  Eigen::VectorXd tau_;
};

// a = q r with q m x n (orthonormal columns) and r n x n upper triangular; needs m >= n.
// False if LAPACK reports a failure.
bool thin_qr(const Eigen::MatrixXd& a, ThinQ& q, Eigen::MatrixXd& r);

// a = u diag(s) v^T with k = min(m, n) singular values, descending; u m x k, v n x k.
// False if LAPACK reports a failure (its divide and conquer did not converge).
bool thin_svd(const Eigen::MatrixXd& a, Eigen::MatrixXd& u, Eigen::VectorXd& s, Eigen::MatrixXd& v);

}  // namespace varsurf
