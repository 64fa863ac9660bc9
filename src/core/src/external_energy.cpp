// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/external_energy.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "unit_vector.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/operator_terms.hpp"

namespace varsurf {

QuadraticTerms::QuadraticTerms(int poles)
    : separable_f(Eigen::MatrixX3d::Zero(poles, 3)), coupled_f(Eigen::VectorXd::Zero(3 * poles)) {}

namespace {

void check_strength(double s, const char* what) {
  if (!std::isfinite(s) || s < 0.0)
    throw InvalidInput(std::string(what) + ": strength must be finite and non-negative");
}

// A region of the sheet as an operator's domain: the region's quadrature points with the basis
// functions and their u and v derivatives there.
OperatorDomain region_domain(const SplineSpace& space, const Region& r) {
  return [&space, r](const SampleVisitor& f) {
    for (const QuadraturePoint& q : region_quadrature(space, r))
      f(space.basis(q.u, q.v, 1), q.weight);
  };
}

}  // namespace

OperatorScales operator_scales(const SplineSpace& space, const Eigen::SparseMatrix<double>& h) {
  return operator_scales(
      region_domain(space, {space.u_first(), space.u_last(), space.v_first(), space.v_last()}), h);
}

void add_attractor(const SplineSpace& space, const Attractor& at, double scale, QuadraticTerms& t) {
  check_region(space, at.region, "attractor");
  check_strength(at.strength, "attractor");
  if (!at.origin.allFinite()) throw InvalidInput("attractor: origin is not finite");
  if (at.strength == 0.0) return;
  const Eigen::Vector3d d = at.kind == AttractorKind::point
                                ? Eigen::Vector3d::UnitZ()
                                : unit_vector(at.direction, "attractor: the direction");
  attractor_terms(region_domain(space, at.region), at.kind, at.origin, d, scale * at.strength, t);
}

void add_director(const SplineSpace& space, const Director& dir, double scale, QuadraticTerms& t) {
  check_region(space, dir.region, "director");
  check_strength(dir.strength, "director");
  const Eigen::Vector3d d = unit_vector(dir.direction, "director: the direction");
  if (dir.strength == 0.0) return;
  director_terms(region_domain(space, dir.region), d, scale * dir.strength, t);
}

void add_repeller_model(const SplineSpace& space, const Repeller& rep, double scale,
                        const Eigen::MatrixX3d& poles, double min_distance, QuadraticTerms& t) {
  check_region(space, rep.region, "repeller");
  check_strength(rep.strength, "repeller");
  if (!rep.origin.allFinite()) throw InvalidInput("repeller: origin is not finite");
  if (rep.strength == 0.0) return;
  repeller_terms(region_domain(space, rep.region), rep.origin, scale * rep.strength, poles,
                 min_distance, t);
}

void add_shape_attractor_model(const SplineSpace& space, const ShapeAttractor& a, double scale,
                               const Eigen::MatrixX3d& poles, QuadraticTerms& t) {
  check_region(space, a.region, "shape attractor");
  check_strength(a.strength, "shape attractor");
  if (!a.closest) throw InvalidInput("shape attractor: no target shape");
  if (a.strength == 0.0) return;
  shape_attractor_terms(region_domain(space, a.region), a.closest, scale * a.strength, poles, t);
}

void add_pressure_force(const SplineSpace& space, double pressure, const Eigen::MatrixX3d& poles,
                        QuadraticTerms& t, const std::optional<Region>& region) {
  if (!std::isfinite(pressure)) throw InvalidInput("pressure must be finite");
  if (pressure == 0.0) return;
  const Region all{space.u_first(), space.u_last(), space.v_first(), space.v_last()};
  region_domain(space, region ? *region : all)([&](const BasisSample& s, double dA) {
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
