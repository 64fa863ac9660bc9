// SPDX-License-Identifier: LGPL-2.1-or-later
// The LAPACK QR and SVD of the constraint reduction against their defining identities and Eigen's
// own (Jacobi) SVD, on tall, square, wide and rank-deficient matrices.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <random>

#include "dense_lapack.hpp"

using varsurf::thin_qr;
using varsurf::thin_svd;
using varsurf::ThinQ;

namespace {

Eigen::MatrixXd random_matrix(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd a(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) a(i, j) = value(rng);
  return a;
}

}  // namespace

TEST(DenseLapack, ThinQrReproducesTheMatrixWithOrthonormalColumns) {
  for (auto [m, n] : {std::pair{40, 7}, std::pair{300, 60}, std::pair{9, 9}}) {
    const Eigen::MatrixXd a = random_matrix(m, n, static_cast<unsigned>(m + n));
    ThinQ q;
    Eigen::MatrixXd r;
    ASSERT_TRUE(thin_qr(a, q, r));
    ASSERT_EQ(q.rows(), m);
    ASSERT_EQ(q.cols(), n);
    EXPECT_TRUE(r.isUpperTriangular(0.0));
    const Eigen::MatrixXd q1t = q.transpose();
    EXPECT_LT((q1t * q1t.transpose() - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(),
              1e-13);
    EXPECT_LT((q1t.transpose() * r - a).cwiseAbs().maxCoeff(), 1e-13);
    // Q_1^T applied to data equals the explicit product, and Q_1^T A = R.
    const Eigen::MatrixXd d = random_matrix(m, 3, 5);
    EXPECT_LT((q.apply_transpose(d) - q1t * d).cwiseAbs().maxCoeff(), 1e-13);
    EXPECT_LT((q.apply_transpose(a) - r).cwiseAbs().maxCoeff(), 1e-13);
  }
}

TEST(DenseLapack, ThinQrRefusesWideMatrices) {
  ThinQ q;
  Eigen::MatrixXd r;
  EXPECT_FALSE(thin_qr(random_matrix(3, 5, 1), q, r));
  EXPECT_THROW(q.apply_transpose(Eigen::MatrixXd::Zero(4, 1)), std::invalid_argument);
}

TEST(DenseLapack, ThinSvdMatchesJacobiOnAnyShape) {
  for (auto [m, n] : {std::pair{50, 12}, std::pair{12, 50}, std::pair{30, 30}}) {
    const Eigen::MatrixXd a = random_matrix(m, n, static_cast<unsigned>(3 * m + n));
    Eigen::MatrixXd u, v;
    Eigen::VectorXd s;
    ASSERT_TRUE(thin_svd(a, u, s, v));
    const int k = std::min(m, n);
    ASSERT_EQ(u.rows(), m);
    ASSERT_EQ(u.cols(), k);
    ASSERT_EQ(v.rows(), n);
    ASSERT_EQ(v.cols(), k);
    const Eigen::JacobiSVD<Eigen::MatrixXd> jacobi(a);
    EXPECT_LT((s - jacobi.singularValues()).cwiseAbs().maxCoeff(), 1e-12);
    for (int i = 1; i < k; ++i) EXPECT_GE(s(i - 1), s(i));
    EXPECT_LT((u * s.asDiagonal() * v.transpose() - a).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((u.transpose() * u - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((v.transpose() * v - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(DenseLapack, ThinSvdOfARankTwoMatrixHasTwoSingularValues) {
  // a = x y^T + 2 z w^T with orthonormal pairs: singular values 2 and 1, the rest rounding.
  const Eigen::MatrixXd basis =
      random_matrix(20, 4, 9).householderQr().householderQ() * Eigen::MatrixXd::Identity(20, 4);
  const Eigen::MatrixXd a =
      basis.col(0) * basis.col(1).transpose() + 2.0 * basis.col(2) * basis.col(3).transpose();
  Eigen::MatrixXd u, v;
  Eigen::VectorXd s;
  ASSERT_TRUE(thin_svd(a, u, s, v));
  EXPECT_NEAR(s(0), 2.0, 1e-13);
  EXPECT_NEAR(s(1), 1.0, 1e-13);
  EXPECT_LT(s(2), 1e-14);
}

TEST(DenseLapack, EmptyMatricesHaveEmptyFactors) {
  Eigen::MatrixXd u, v;
  Eigen::VectorXd s;
  ASSERT_TRUE(thin_svd(Eigen::MatrixXd(0, 4), u, s, v));
  EXPECT_EQ(s.size(), 0);
  EXPECT_EQ(v.rows(), 4);
  ThinQ q;
  Eigen::MatrixXd r;
  ASSERT_TRUE(thin_qr(Eigen::MatrixXd(5, 0), q, r));
  EXPECT_EQ(q.apply_transpose(Eigen::MatrixXd::Ones(5, 2)).rows(), 0);
}
