// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/sheet_dynamics.hpp"

#include <Eigen/Geometry>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <string>

#include "free_block.hpp"
#include "serial_openmp.hpp"
#include "span_quadrature.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/pde_energy.hpp"
#include "varsurf/core/thin_plate_energy.hpp"

#ifdef VARSURF_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

namespace varsurf {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The lumped share of each pole of a density over the normalized domain: int rho N_i ds dt.
Eigen::VectorXd lumped(const SplineSpace& space, const PdeCoefficient& density) {
  const double area =
      1.0 / ((space.u_last() - space.u_first()) * (space.v_last() - space.v_first()));
  const int n = std::max(space.degree_u, space.degree_v) + 2 * density.field_degree() + 1;
  const double step = density.blend > 0.0 ? 0.25 * density.blend : 1.0;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(space.size());
  for (const QuadraturePoint& q : span_points(space, n + (density.painted.empty() ? 0 : 4), step)) {
    const BasisSample s = space.basis(q.u, q.v, 0);
    const double rho = density.value(space, q.u, q.v) * q.weight * area;
    for (size_t k = 0; k < s.index.size(); ++k)
      out(s.index[k]) += rho * s.values(0, static_cast<Eigen::Index>(k));
  }
  return out;
}

// A density that is 0 everywhere is allowed for damping: PdeCoefficient asks a > 0, so a zero
// constant is checked here and stands for "none".
bool zero_density(const PdeCoefficient& c) {
  return c.a == 0.0 && !c.has_field() && c.painted.empty();
}

// Damping may be 0 anywhere (an undamped region): PdeCoefficient::validate, which asks a > 0,
// checks everything else (finite values, regions, blend, the field's space) on a copy whose zero
// values stand in as 1.
void validate_non_negative(PdeCoefficient c, const SplineSpace& space) {
  auto lift = [](double& x) {
    if (x == 0.0) x = 1.0;
  };
  lift(c.a);
  for (PaintedCoefficient& p : c.painted) lift(p.a);
  for (Eigen::Index k = 0; k < c.field_values.size(); ++k) lift(c.field_values(k));
  c.validate(space);
}

}  // namespace

struct DynamicSheet::Impl {
  SplineSpace space;
  Sparse energy;          // stiffness * the sheet's energy, all poles
  Eigen::MatrixX3d rest;  // energy * rest poles: the force that holds a rest shape
  Eigen::VectorXd mass, damping;
  FreeUnknowns poles_free;  // the poles not held
  Eigen::MatrixX3d p, v;
  std::vector<Spring> springs;
  Sparse spring_matrix;  // sum k N N^T
  double h = 0.0, t = 0.0;
#ifdef VARSURF_HAVE_CHOLMOD
  Eigen::CholmodDecomposition<Sparse> factor;
#else
  Eigen::SimplicialLDLT<Sparse> factor;
#endif

  Sparse stiffness() const {
    return energy + spring_matrix;
  }

  Eigen::MatrixX3d forces() const {  // b: rest shape and springs
    Eigen::MatrixX3d b = rest;
    for (const Spring& s : springs) {
      const BasisSample n = space.basis(s.u, s.v, 0);
      for (size_t k = 0; k < n.index.size(); ++k)
        b.row(n.index[k]) +=
            s.stiffness * n.values(0, static_cast<Eigen::Index>(k)) * s.target.transpose();
    }
    return b;
  }

  void refactor() {
    Sparse s = free_block(stiffness(), poles_free) * (h * h);
    for (size_t k = 0; k < poles_free.free.size(); ++k)
      s.coeffRef(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k)) +=
          mass(poles_free.free[k]) + h * damping(poles_free.free[k]);
    SerialOpenMp serial;
#ifdef VARSURF_HAVE_CHOLMOD
    // Simplicial: a step is one back-substitution, and the supernodal factor's took longer
    // (measured at 60 x 60 poles: 0.57-0.70 ms a step against 0.93; its factorization, once a
    // grab, 108-146 ms against 105).
    factor.setMode(Eigen::CholmodSimplicialLLt);
#endif
    factor.compute(s);
    if (factor.info() != Eigen::Success)
      throw SolveFailure("dynamics: the step's matrix could not be factored");
  }
};

DynamicSheet::DynamicSheet(const SheetProblem& pb, const DynamicsParameters& par)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  pb.space.validate();
  m.space = pb.space;
  const int n = pb.space.size();
  if (pb.initial_poles.rows() != n || !pb.initial_poles.allFinite())
    throw InvalidInput("dynamics: the start poles do not match the space (or are not finite)");
  if (!pb.points.empty() || !pb.curves.empty() || !pb.tangents.empty() || !pb.normals.empty() ||
      !pb.plane_points.empty() || !pb.line_points.empty() || !pb.ribbons.empty() ||
      !pb.curvatures.empty() || !pb.point_curvatures.empty() || !pb.attractors.empty() ||
      !pb.directors.empty() || !pb.repellers.empty() || !pb.shape_attractors.empty() ||
      pb.pressure != 0.0 || pb.closed_u || pb.closed_v)
    throw InvalidInput(
        "dynamics: only fixed poles hold a dynamic sheet (its boundary conditions); "
        "remove its curve, point and operator constraints, or sculpt it statically");
  if (!(std::isfinite(par.time_step) && par.time_step > 0.0))
    throw InvalidInput("dynamics: the time step " + std::to_string(par.time_step) +
                       " must be a positive number of seconds");
  if (!(std::isfinite(par.stiffness) && par.stiffness > 0.0))
    throw InvalidInput("dynamics: the stiffness " + std::to_string(par.stiffness) +
                       " must be a positive number");
  try {
    par.mass.validate(pb.space);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string("dynamics: the mass must be positive everywhere: ") + e.what());
  }
  if (!zero_density(par.damping)) {
    try {
      validate_non_negative(par.damping, pb.space);
    } catch (const InvalidInput& e) {
      throw InvalidInput(std::string("dynamics: the damping must be 0 or positive: ") + e.what());
    }
  }
  m.energy = par.stiffness *
             (pb.pde ? assemble_pde(pb.space, *pb.pde) : assemble_thin_plate(pb.space, pb.energy));
  m.rest = Eigen::MatrixX3d::Zero(n, 3);
  if (pb.rest_poles.rows() != 0) {
    if (pb.rest_poles.rows() != n || !pb.rest_poles.allFinite())
      throw InvalidInput("dynamics: the rest poles do not match the space (or are not finite)");
    m.rest = m.energy * pb.rest_poles;
  }
  m.mass = lumped(pb.space, par.mass);
  m.damping = zero_density(par.damping) ? Eigen::VectorXd::Zero(n) : lumped(pb.space, par.damping);
  m.poles_free = free_unknowns(n, pb.fixed_poles, "dynamics");
  if (m.poles_free.free.empty())
    throw InvalidInput("dynamics: every pole is fixed; nothing can move");
  m.p = pb.initial_poles;
  m.v = Eigen::MatrixX3d::Zero(n, 3);
  m.spring_matrix = Sparse(n, n);
  m.h = par.time_step;
  m.refactor();
}

DynamicSheet::~DynamicSheet() = default;
DynamicSheet::DynamicSheet(DynamicSheet&&) noexcept = default;
DynamicSheet& DynamicSheet::operator=(DynamicSheet&&) noexcept = default;

void DynamicSheet::set_springs(const std::vector<Spring>& springs) {
  Impl& m = *impl_;
  std::vector<Eigen::Triplet<double>> trip;
  for (size_t i = 0; i < springs.size(); ++i) {
    const Spring& s = springs[i];
    if (!(s.u >= m.space.u_first() && s.u <= m.space.u_last() && s.v >= m.space.v_first() &&
          s.v <= m.space.v_last() && s.target.allFinite() && std::isfinite(s.stiffness) &&
          s.stiffness > 0.0))
      throw InvalidInput("dynamics: spring " + std::to_string(i) +
                         " must sit in the domain, pull toward a finite target and be stiff (> 0)");
    const BasisSample n = m.space.basis(s.u, s.v, 0);
    for (size_t a = 0; a < n.index.size(); ++a)
      for (size_t b = 0; b < n.index.size(); ++b)
        trip.emplace_back(n.index[a], n.index[b],
                          s.stiffness * n.values(0, static_cast<Eigen::Index>(a)) *
                              n.values(0, static_cast<Eigen::Index>(b)));
  }
  m.spring_matrix = Sparse(m.space.size(), m.space.size());
  m.spring_matrix.setFromTriplets(trip.begin(), trip.end());
  m.springs = springs;
  m.refactor();
}

void DynamicSheet::move_targets(const std::vector<Eigen::Vector3d>& targets) {
  Impl& m = *impl_;
  if (targets.size() != m.springs.size())
    throw InvalidInput("dynamics: give one target per spring");
  for (const Eigen::Vector3d& x : targets)
    if (!x.allFinite()) throw InvalidInput("dynamics: a spring's target is not finite");
  for (size_t i = 0; i < targets.size(); ++i) m.springs[i].target = targets[i];
}

void DynamicSheet::step(int count) {
  Impl& m = *impl_;
  if (count < 0 || count > 1000000) throw InvalidInput("dynamics: 0 to 1e6 steps at a time");
  // Backward Euler, (M + h D + h^2 A) V+ = M V - h (A P - b) with P+ = P + h V+, written for P+:
  // S P+ = (M + h D) P + h M V + h^2 (b - A_FX P_X). Per step: one back-substitution and diagonal
  // products, no product with A (measured at 60 x 60 poles: 1.31 ms a step with it).
  const Eigen::Index nf = static_cast<Eigen::Index>(m.poles_free.free.size());
  const Eigen::MatrixX3d b = m.forces();
  Eigen::MatrixX3d held = m.p;
  for (int k : m.poles_free.free) held.row(k).setZero();
  const Eigen::MatrixX3d outer = b - m.stiffness() * held;  // free rows: b_F - A_FX P_X
  Eigen::MatrixX3d pf(nf, 3), vf(nf, 3), load(nf, 3);
  Eigen::VectorXd keep(nf), push(nf);
  for (Eigen::Index k = 0; k < nf; ++k) {
    const int pole = m.poles_free.free[static_cast<size_t>(k)];
    pf.row(k) = m.p.row(pole);
    vf.row(k) = m.v.row(pole);
    load.row(k) = (m.h * m.h) * outer.row(pole);
    keep(k) = m.mass(pole) + m.h * m.damping(pole);
    push(k) = m.h * m.mass(pole);
  }
  SerialOpenMp serial;
  Eigen::MatrixX3d rhs(nf, 3), next(nf, 3);
  for (int it = 0; it < count; ++it) {
    rhs = keep.asDiagonal() * pf;
    rhs += push.asDiagonal() * vf;
    rhs += load;
    next = m.factor.solve(rhs);
    vf = (next - pf) / m.h;
    pf.swap(next);
    m.t += m.h;
  }
  for (Eigen::Index k = 0; k < nf; ++k) {
    const int pole = m.poles_free.free[static_cast<size_t>(k)];
    m.p.row(pole) = pf.row(k);
    m.v.row(pole) = vf.row(k);
  }
}

const Eigen::MatrixX3d& DynamicSheet::poles() const {
  return impl_->p;
}
const Eigen::MatrixX3d& DynamicSheet::velocities() const {
  return impl_->v;
}
double DynamicSheet::time() const {
  return impl_->t;
}

double DynamicSheet::kinetic_energy() const {
  const Impl& m = *impl_;
  return 0.5 * (m.v.array().square().rowwise().sum() * m.mass.array()).sum();
}

double DynamicSheet::potential_energy() const {
  const Impl& m = *impl_;
  double springs = 0.0;
  for (const Spring& s : m.springs) springs += 0.5 * s.stiffness * s.target.squaredNorm();
  return 0.5 * (m.p.transpose() * (m.stiffness() * m.p)).trace() -
         (m.forces().transpose() * m.p).trace() + springs;
}

const Eigen::VectorXd& DynamicSheet::masses() const {
  return impl_->mass;
}

Eigen::MatrixX3d DynamicSheet::equilibrium() const {
  const Impl& m = *impl_;
  const Sparse a = m.stiffness();
  const Eigen::MatrixX3d b = m.forces();
  // A_FF P_F = b_F - A_FX P_X: the fixed poles' share moved to the right.
  Eigen::MatrixX3d held = m.p;
  for (int k : m.poles_free.free) held.row(k).setZero();
  const Eigen::MatrixX3d right = b - a * held;
  Eigen::MatrixX3d rf(static_cast<Eigen::Index>(m.poles_free.free.size()), 3);
  for (size_t k = 0; k < m.poles_free.free.size(); ++k)
    rf.row(static_cast<Eigen::Index>(k)) = right.row(m.poles_free.free[k]);
  Eigen::SimplicialLDLT<Sparse> ldlt(free_block(a, m.poles_free));
  if (ldlt.info() != Eigen::Success)
    throw SolveFailure(
        "dynamics: the equilibrium is not determined (the fixed poles do not hold "
        "the sheet)");
  const Eigen::MatrixX3d pf = ldlt.solve(rf);
  Eigen::MatrixX3d out = m.p;
  for (size_t k = 0; k < m.poles_free.free.size(); ++k)
    out.row(m.poles_free.free[k]) = pf.row(static_cast<Eigen::Index>(k));
  return out;
}

PinStiffness pin_stiffness(const SheetProblem& problem, double u, double v) {
  DynamicsParameters unit;         // unit mass density: the lumped masses are the poles' shares
  SheetProblem at_rest = problem;  // the start is the rest shape: only the spring moves it
  at_rest.rest_poles = problem.initial_poles;
  DynamicSheet probe(at_rest, unit);
  const Eigen::MatrixXd d = evaluate_surface(problem.space, problem.initial_poles, u, v, 1);
  const Eigen::Vector3d at = d.row(0).transpose();
  const Eigen::Vector3d du = d.row(1).transpose(), dv = d.row(2).transpose();
  Eigen::Vector3d normal = du.cross(dv);
  if (!(normal.norm() > 0.0) || !normal.allFinite())
    throw SolveFailure("the surface has no normal at the pin");
  normal.normalize();
  probe.set_springs({{u, v, at + normal, 1.0}});
  const Eigen::MatrixX3d settled = probe.equilibrium();
  const Eigen::Vector3d moved =
      evaluate_surface(problem.space, settled, u, v, 0).row(0).transpose();
  const double delta = (moved - at).dot(normal);
  // Under a unit spring pulled one unit away, the pin moves delta: the sheet's own stiffness k
  // balances the spring's, k delta = 1 - delta.
  if (!(delta > 0.0 && delta < 1.0))
    throw SolveFailure(
        "the surface does not give at the pin (its boundary conditions hold it there)");
  const Eigen::VectorXd& share = probe.masses();
  double shape = 0.0;
  for (Eigen::Index k = 0; k < settled.rows(); ++k)
    shape += share(k) * ((settled.row(k) - problem.initial_poles.row(k)) / delta).squaredNorm();
  return {(1.0 - delta) / delta, std::max(shape, 1e-300)};
}

}  // namespace varsurf
