// SPDX-License-Identifier: LGPL-2.1-or-later
// A sheet with mass and damping (Du & Qin sec. 3.4, 4.8, eq. 9 and 16):
// M P'' + D P' + A P = b + f, where A is the sheet's energy (the PDE's or the thin plate's) times
// a stiffness, b holds a rest shape, f the springs a user drags the sheet by. B-spline finite
// elements (their sec. 4.9): M and D are lumped (each pole's share of the mass and damping
// densities, the basis being a partition of unity), fixed poles hold the boundary conditions.
// Time steps are backward Euler, unconditionally stable and dissipative: one sparse factorization
// of M + h D + h^2 A per parameter set and set of grabbed points, one back-substitution a step.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "varsurf/core/pde_coefficient.hpp"
#include "varsurf/core/sheet_solver.hpp"

namespace varsurf {

struct DynamicsParameters {
  // Mass and damping densities over the (normalized) domain: constants, fields or painted
  // regions (the PdeCoefficient type serves as a scalar field: `a` is the value).
  PdeCoefficient mass;     // > 0 everywhere
  PdeCoefficient damping;  // >= 0 (a field value 0 is allowed)
  double stiffness = 1.0;  // multiplies the sheet's energy
  double time_step = 1.0 / 60.0;
};

// The sheet is pulled at (u, v) toward `target` with force stiffness * (target - P(u, v)).
struct Spring {
  double u = 0.0, v = 0.0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double stiffness = 1.0;
};

class DynamicSheet {
 public:
  // The problem's space, energy, rest shape and fixed poles (its start poles are the start
  // positions, at rest); other constraints are refused (InvalidInput): hold the sheet by its fixed
  // poles. Throws InvalidInput for non-positive mass, negative damping or stiffness, a time step
  // that is not a positive finite number.
  DynamicSheet(const SheetProblem& problem, const DynamicsParameters& parameters);
  ~DynamicSheet();
  DynamicSheet(DynamicSheet&&) noexcept;
  DynamicSheet& operator=(DynamicSheet&&) noexcept;

  // Grabbed points (none: released). A new set refactors; moving their targets (one per spring,
  // the drag) does not.
  void set_springs(const std::vector<Spring>& springs);
  void move_targets(const std::vector<Eigen::Vector3d>& targets);
  void step(int count = 1);

  const Eigen::MatrixX3d& poles() const;
  // Each pole's lumped mass (its share of the mass density; fixed poles included).
  const Eigen::VectorXd& masses() const;
  const Eigen::MatrixX3d& velocities() const;
  double kinetic_energy() const;    // 1/2 V^T M V
  double potential_energy() const;  // 1/2 P^T A P - b^T P with the springs' energy
  // Where the motion settles: A P = b with the springs, fixed poles held.
  Eigen::MatrixX3d equilibrium() const;
  double time() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// How stiff a sheet is where it is pinned: the force per unit of displacement a pull along its
// normal at (u, v) meets (the energy's response, measured by its equilibrium under a unit spring
// there), and the mass per unit density of the shape it deflects in (the deflection normalized to
// a unit move of the pin, weighted by each pole's lumped share of the domain). A dynamic drag sets
// its mass, damping and spring from these, so the same relative numbers feel alike on any sheet.
// The problem as DynamicSheet takes it, its start poles the shape and the rest shape (whatever
// rest shape it has: the pin measures the response to its own pull); SolveFailure when the sheet
// does not give at the pin (held there) or has no normal there.
struct PinStiffness {
  double stiffness = 0.0;
  double shape_mass = 0.0;
};
PinStiffness pin_stiffness(const SheetProblem& problem, double u, double v);

}  // namespace varsurf
