// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/external_energy.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "unit_vector.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

QuadraticTerms::QuadraticTerms(int poles)
    : separable_f(Eigen::MatrixX3d::Zero(poles, 3)), coupled_f(Eigen::VectorXd::Zero(3 * poles)) {}

namespace {

void check_strength(double s, const char* what) {
  if (!std::isfinite(s) || s < 0.0)
    throw InvalidInput(std::string(what) + ": strength must be finite and non-negative");
}

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

// Calls f(basis sample with first derivatives, dA, assembler) at quadrature points covering the
// region, exact for products of two basis functions (or derivatives) of a non-rational space.
template <class F>
void integrate_region(const SplineSpace& space, const Region& r, QuadraticTerms& t, F&& f) {
  PieceAssembler assembler(t);
  for (const QuadraturePoint& q : region_quadrature(space, r))
    f(space.basis(q.u, q.v, 1), q.weight, assembler);
  assembler.flush();
}

}  // namespace

OperatorScales operator_scales(const SplineSpace& space, const Eigen::SparseMatrix<double>& h) {
  double mass = 0.0, gradient = 0.0;
  const Region all{space.u_first(), space.u_last(), space.v_first(), space.v_last()};
  for (const QuadraturePoint& q : region_quadrature(space, all)) {
    const BasisSample s = space.basis(q.u, q.v, 1);
    const double dA = q.weight;
    mass += dA * s.values.row(0).squaredNorm();
    gradient += dA * (s.values.row(1).squaredNorm() + s.values.row(2).squaredNorm());
  }
  const double n = space.size();
  const double stiffness = h.diagonal().sum() / n;
  OperatorScales out;
  if (mass > 0.0) out.value = stiffness / (mass / n);
  if (gradient > 0.0) out.gradient = stiffness / (gradient / n);
  return out;
}

void add_attractor(const SplineSpace& space, const Attractor& at, double scale, QuadraticTerms& t) {
  check_region(space, at.region, "attractor");
  check_strength(at.strength, "attractor");
  if (!at.origin.allFinite()) throw InvalidInput("attractor: origin is not finite");
  if (at.strength == 0.0) return;
  if (at.kind == AttractorKind::point) {
    integrate_region(space, at.region, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
      as.add_separable(s, scale * at.strength * dA, at.origin);
    });
    return;
  }
  const Eigen::Vector3d d = unit_vector(at.direction, "attractor: the direction");
  const Eigen::Matrix3d m = at.kind == AttractorKind::plane
                                ? Eigen::Matrix3d(d * d.transpose())
                                : Eigen::Matrix3d(Eigen::Matrix3d::Identity() - d * d.transpose());
  integrate_region(space, at.region, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
    as.add_coupled(s, 0, scale * at.strength * dA, m, at.origin);
  });
}

void add_director(const SplineSpace& space, const Director& dir, double scale, QuadraticTerms& t) {
  check_region(space, dir.region, "director");
  check_strength(dir.strength, "director");
  const Eigen::Vector3d d = unit_vector(dir.direction, "director: the direction");
  if (dir.strength == 0.0) return;
  const Eigen::Matrix3d m = d * d.transpose();
  integrate_region(space, dir.region, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
    as.add_coupled(s, 1, scale * dir.strength * dA, m, Eigen::Vector3d::Zero());
    as.add_coupled(s, 2, scale * dir.strength * dA, m, Eigen::Vector3d::Zero());
  });
}

void add_repeller_model(const SplineSpace& space, const Repeller& rep, double scale,
                        const Eigen::MatrixX3d& poles, double min_distance, QuadraticTerms& t) {
  check_region(space, rep.region, "repeller");
  check_strength(rep.strength, "repeller");
  if (!rep.origin.allFinite()) throw InvalidInput("repeller: origin is not finite");
  if (rep.strength == 0.0) return;
  integrate_region(space, rep.region, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < s.index.size(); ++k)
      w += s.values(0, static_cast<Eigen::Index>(k)) * poles.row(s.index[k]).transpose();
    const Eigen::Vector3d d = w - rep.origin;
    const double r = std::max(d.norm(), min_distance);
    const Eigen::Vector3d e =
        d.norm() > 0.0 ? Eigen::Vector3d(d / d.norm()) : Eigen::Vector3d::UnitZ();
    const double c = scale * rep.strength * dA;
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

void add_shape_attractor_model(const SplineSpace& space, const ShapeAttractor& a, double scale,
                               const Eigen::MatrixX3d& poles, QuadraticTerms& t) {
  check_region(space, a.region, "shape attractor");
  check_strength(a.strength, "shape attractor");
  if (!a.closest) throw InvalidInput("shape attractor: no target shape");
  if (a.strength == 0.0) return;
  integrate_region(space, a.region, t, [&](const BasisSample& s, double dA, PieceAssembler& as) {
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < s.index.size(); ++k)
      w += s.values(0, static_cast<Eigen::Index>(k)) * poles.row(s.index[k]).transpose();
    const ClosestPoint c = a.closest(w);
    if (!c.point.allFinite() || !c.metric.allFinite())
      throw InvalidInput("shape attractor: the target gave no closest point");
    as.add_coupled(s, 0, scale * a.strength * dA, c.metric, c.point);
  });
}

void add_pressure_force(const SplineSpace& space, double pressure, const Eigen::MatrixX3d& poles,
                        QuadraticTerms& t, const std::optional<Region>& region) {
  if (!std::isfinite(pressure)) throw InvalidInput("pressure must be finite");
  if (pressure == 0.0) return;
  const Region all{space.u_first(), space.u_last(), space.v_first(), space.v_last()};
  integrate_region(
      space, region ? *region : all, t, [&](const BasisSample& s, double dA, PieceAssembler&) {
        Eigen::Vector3d wu = Eigen::Vector3d::Zero(), wv = Eigen::Vector3d::Zero();
        for (size_t k = 0; k < s.index.size(); ++k) {
          wu += s.values(1, static_cast<Eigen::Index>(k)) * poles.row(s.index[k]).transpose();
          wv += s.values(2, static_cast<Eigen::Index>(k)) * poles.row(s.index[k]).transpose();
        }
        // The work P * V has the gradient P * (w_u x w_v) per unit (u, v) area; E = ... - 2 f.x
        // takes half of it.
        const Eigen::Vector3d n = 0.5 * pressure * dA * wu.cross(wv);
        for (size_t k = 0; k < s.index.size(); ++k)
          for (int a = 0; a < 3; ++a)
            t.coupled_f(3 * s.index[k] + a) += s.values(0, static_cast<Eigen::Index>(k)) * n(a);
      });
}

}  // namespace varsurf
