// SPDX-License-Identifier: LGPL-2.1-or-later
#include "dense_lapack.hpp"

#include <algorithm>
#include <climits>
#include <stdexcept>
#include <vector>

// LAPACK's Fortran interface (Debian's liblapack3 / OpenBLAS: 32-bit integers).
extern "C" {
void dgeqrf_(const int* m, const int* n, double* a, const int* lda, double* tau, double* work,
             const int* lwork, int* info);
void dormqr_(const char* side, const char* trans, const int* m, const int* n, const int* k,
             const double* a, const int* lda, const double* tau, double* c, const int* ldc,
             double* work, const int* lwork, int* info);
void dgesdd_(const char* jobz, const int* m, const int* n, double* a, const int* lda, double* s,
             double* u, const int* ldu, double* vt, const int* ldvt, double* work, const int* lwork,
             int* iwork, int* info);
}

namespace varsurf {

namespace {

bool fits_int(const Eigen::MatrixXd& a) {
  return a.rows() < INT_MAX && a.cols() < INT_MAX && a.size() < INT_MAX;
}

}  // namespace

bool thin_qr(const Eigen::MatrixXd& a, ThinQ& q, Eigen::MatrixXd& r) {
  if (a.rows() < a.cols() || !fits_int(a)) return false;
  const int m = static_cast<int>(a.rows()), n = static_cast<int>(a.cols());
  q.reflectors_ = a;
  q.tau_.resize(n);
  r.resize(n, n);
  if (n == 0) return true;
  const int lda = std::max(1, m);
  int info = 0, query = -1;
  double size = 0.0;
  dgeqrf_(&m, &n, q.reflectors_.data(), &lda, q.tau_.data(), &size, &query, &info);
  if (info != 0) return false;
  std::vector<double> work(static_cast<size_t>(std::max(1.0, size)));
  const int lwork = static_cast<int>(work.size());
  dgeqrf_(&m, &n, q.reflectors_.data(), &lda, q.tau_.data(), work.data(), &lwork, &info);
  if (info != 0) return false;
  r = q.reflectors_.topRows(n).triangularView<Eigen::Upper>();
  return true;
}

void ThinQ::apply(char trans, Eigen::MatrixXd& c) const {
  const int m = static_cast<int>(rows()), n = static_cast<int>(cols());
  const int w = static_cast<int>(c.cols());
  if (c.rows() != rows()) throw std::invalid_argument("ThinQ: data of the wrong height");
  if (n == 0 || w == 0) return;
  const char side = 'L';
  const int lda = std::max(1, m), ldc = std::max(1, m);
  int info = 0, query = -1;
  double size = 0.0;
  dormqr_(&side, &trans, &m, &w, &n, reflectors_.data(), &lda, tau_.data(), c.data(), &ldc, &size,
          &query, &info);
  std::vector<double> work(static_cast<size_t>(std::max(1.0, size)));
  const int lwork = static_cast<int>(work.size());
  if (info == 0)
    dormqr_(&side, &trans, &m, &w, &n, reflectors_.data(), &lda, tau_.data(), c.data(), &ldc,
            work.data(), &lwork, &info);
  // The shapes were checked above: LAPACK reports only argument errors here.
  if (info != 0) throw std::logic_error("dormqr refused its arguments");
}

Eigen::MatrixXd ThinQ::apply_transpose(const Eigen::MatrixXd& d) const {
  Eigen::MatrixXd c = d;
  apply('T', c);
  return c.topRows(cols());
}

Eigen::MatrixXd ThinQ::transpose() const {
  Eigen::MatrixXd q1 = Eigen::MatrixXd::Identity(rows(), cols());
  apply('N', q1);
  return q1.transpose();
}

bool thin_svd(const Eigen::MatrixXd& a, Eigen::MatrixXd& u, Eigen::VectorXd& s,
              Eigen::MatrixXd& v) {
  if (!fits_int(a)) return false;
  const int m = static_cast<int>(a.rows()), n = static_cast<int>(a.cols());
  const int k = std::min(m, n);
  u.resize(m, k);
  s.resize(k);
  v.resize(n, k);
  if (k == 0) return true;
  Eigen::MatrixXd work_a = a;  // dgesdd overwrites its input
  Eigen::MatrixXd vt(k, n);
  std::vector<int> iwork(8 * static_cast<size_t>(k));
  const char jobz = 'S';
  const int lda = std::max(1, m), ldu = std::max(1, m), ldvt = std::max(1, k);
  int info = 0, query = -1;
  double size = 0.0;
  dgesdd_(&jobz, &m, &n, work_a.data(), &lda, s.data(), u.data(), &ldu, vt.data(), &ldvt, &size,
          &query, iwork.data(), &info);
  if (info != 0) return false;
  std::vector<double> work(static_cast<size_t>(std::max(1.0, size)));
  const int lwork = static_cast<int>(work.size());
  dgesdd_(&jobz, &m, &n, work_a.data(), &lda, s.data(), u.data(), &ldu, vt.data(), &ldvt,
          work.data(), &lwork, iwork.data(), &info);
  if (info != 0) return false;
  v = vt.transpose();
  return true;
}

}  // namespace varsurf
