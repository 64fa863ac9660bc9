// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/operator_terms.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

// The per-point terms of an operator, summed in dense blocks while consecutive quadrature points
// share their basis functions (the points of one polynomial piece come together) and written as
// triplets once per piece. Writing triplets per point made a loop region on 16 x 16 spans cost
// about 1 s per Gauss-Newton step (tens of millions of triplets); per piece it is milliseconds.
class PieceAssembler {
 public:
  explicit PieceAssembler(QuadraticTerms& t) : t_(t) {}

  // Adds w * (sum_k beta_k p_k - q)^T M (sum_k beta_k p_k - q), beta = row `d` of the sample,
  // in the coupled (3n) terms.
  void add_coupled(const BasisSample& s, int d, double w, const Eigen::Matrix3d& m,
                   const Eigen::Vector3d& q) {
    start(s);
    const Eigen::Index n = static_cast<Eigen::Index>(s.index.size());
    const Eigen::Vector3d mq = m * q;
    for (Eigen::Index a = 0; a < n; ++a) {
      const double ba = w * s.values(d, a);
      t_.coupled_f.segment<3>(3 * s.index[static_cast<size_t>(a)]) += ba * mq;
      for (Eigen::Index b = 0; b < n; ++b)
        coupled_.block<3, 3>(3 * a, 3 * b) += (ba * s.values(d, b)) * m;
    }
    has_coupled_ = true;
  }

  // Adds w * |sum_k b_k p_k - q|^2 in the separable (per coordinate) terms.
  void add_separable(const BasisSample& s, double w, const Eigen::Vector3d& q) {
    start(s);
    const Eigen::Index n = static_cast<Eigen::Index>(s.index.size());
    for (Eigen::Index a = 0; a < n; ++a) {
      const double ba = w * s.values(0, a);
      t_.separable_f.row(s.index[static_cast<size_t>(a)]) += ba * q.transpose();
      for (Eigen::Index b = 0; b < n; ++b) separable_(a, b) += ba * s.values(0, b);
    }
    has_separable_ = true;
  }

  void flush() {
    const Eigen::Index n = static_cast<Eigen::Index>(index_.size());
    if (has_coupled_)
      for (Eigen::Index a = 0; a < 3 * n; ++a)
        for (Eigen::Index b = 0; b < 3 * n; ++b)
          if (coupled_(a, b) != 0.0)
            t_.coupled.emplace_back(
                3 * index_[static_cast<size_t>(a / 3)] + static_cast<int>(a % 3),
                3 * index_[static_cast<size_t>(b / 3)] + static_cast<int>(b % 3), coupled_(a, b));
    if (has_separable_)
      for (Eigen::Index a = 0; a < n; ++a)
        for (Eigen::Index b = 0; b < n; ++b)
          if (separable_(a, b) != 0.0)
            t_.separable.emplace_back(index_[static_cast<size_t>(a)],
                                      index_[static_cast<size_t>(b)], separable_(a, b));
    has_coupled_ = has_separable_ = false;
    index_.clear();
  }

 private:
  void start(const BasisSample& s) {
    if (s.index == index_) return;
    flush();
    index_ = s.index;
    const Eigen::Index n = static_cast<Eigen::Index>(index_.size());
    coupled_ = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    separable_ = Eigen::MatrixXd::Zero(n, n);
  }

  QuadraticTerms& t_;
  std::vector<int> index_;
  Eigen::MatrixXd coupled_, separable_;
  bool has_coupled_ = false, has_separable_ = false;
};

// Calls f(sample, dA, assembler) at the domain's quadrature points, one assembler for them all.
template <class F>
void integrate(const OperatorDomain& domain, QuadraticTerms& t, F&& f) {
  PieceAssembler assembler(t);
  domain([&](const BasisSample& s, double dA) { f(s, dA, assembler); });
  assembler.flush();
}

Eigen::Vector3d point_at(const BasisSample& s, const Eigen::MatrixX3d& points) {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < s.index.size(); ++k)
    w += s.values(0, static_cast<Eigen::Index>(k)) * points.row(s.index[k]).transpose();
  return w;
}

}  // namespace

OperatorScales operator_scales(const OperatorDomain& whole, const Eigen::SparseMatrix<double>& h) {
  double mass = 0.0, gradient = 0.0;
  whole([&](const BasisSample& s, double dA) {
    mass += dA * s.values.row(0).squaredNorm();
    gradient += dA * (s.values.row(1).squaredNorm() + s.values.row(2).squaredNorm());
  });
  const double n = static_cast<double>(h.rows());
  const double stiffness = h.diagonal().sum() / n;
  OperatorScales out;
  if (mass > 0.0) out.value = stiffness / (mass / n);
  if (gradient > 0.0) out.gradient = stiffness / (gradient / n);
  return out;
}

void attractor_terms(const OperatorDomain& domain, AttractorKind kind,
                     const Eigen::Vector3d& origin, const Eigen::Vector3d& d, double weight,
                     QuadraticTerms& t) {
  if (kind == AttractorKind::point) {
    integrate(domain, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
      as.add_separable(s, weight * dA, origin);
    });
    return;
  }
  const Eigen::Matrix3d m = kind == AttractorKind::plane
                                ? Eigen::Matrix3d(d * d.transpose())
                                : Eigen::Matrix3d(Eigen::Matrix3d::Identity() - d * d.transpose());
  integrate(domain, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
    as.add_coupled(s, 0, weight * dA, m, origin);
  });
}

void director_terms(const OperatorDomain& domain, const Eigen::Vector3d& d, double weight,
                    QuadraticTerms& t) {
  const Eigen::Matrix3d m = d * d.transpose();
  integrate(domain, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
    as.add_coupled(s, 1, weight * dA, m, Eigen::Vector3d::Zero());
    as.add_coupled(s, 2, weight * dA, m, Eigen::Vector3d::Zero());
  });
}

void repeller_terms(const OperatorDomain& domain, const Eigen::Vector3d& origin, double weight,
                    const Eigen::MatrixX3d& points, double min_distance, QuadraticTerms& t) {
  integrate(domain, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
    const Eigen::Vector3d w = point_at(s, points);
    const Eigen::Vector3d d = w - origin;
    const double r = std::max(d.norm(), min_distance);
    const Eigen::Vector3d e =
        d.norm() > 0.0 ? Eigen::Vector3d(d / d.norm()) : Eigen::Vector3d::UnitZ();
    const double c = weight * dA;
    // E = c r^-2: gradient -2 c r^-4 d, radial curvature 6 c r^-4. In the x^T Q x - 2 f^T x form
    // the model E(w0) + g.(w - w0) + 1/2 (w - w0)^T J (w - w0) adds Q += J / 2 and
    // f += (J w0 - g) / 2.
    const Eigen::Matrix3d j = 6.0 * c / std::pow(r, 4) * e * e.transpose();
    const Eigen::Vector3d g = -2.0 * c / std::pow(r, 4) * d;
    as.add_coupled(s, 0, 1.0, 0.5 * j, Eigen::Vector3d::Zero());
    const Eigen::Vector3d f = 0.5 * (j * w - g);
    for (size_t k = 0; k < s.index.size(); ++k)
      for (int a = 0; a < 3; ++a)
        t.coupled_f(3 * s.index[k] + a) += s.values(0, static_cast<Eigen::Index>(k)) * f(a);
  });
}

void shape_attractor_terms(const OperatorDomain& domain, const ClosestPointFunction& closest,
                           double weight, const Eigen::MatrixX3d& points, QuadraticTerms& t) {
  integrate(domain, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
    const ClosestPoint c = closest(point_at(s, points));
    if (!c.point.allFinite() || !c.metric.allFinite())
      throw InvalidInput("shape attractor: the target gave no closest point");
    as.add_coupled(s, 0, weight * dA, c.metric, c.point);
  });
}

}  // namespace varsurf
