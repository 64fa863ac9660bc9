// SPDX-License-Identifier: LGPL-2.1-or-later
// A tensor-product B-spline space with fixed weights: the set of surfaces whose points are linear
// in the poles. Pole (i, j) -- i along u, j along v -- has the flat index i * nv() + j, the order
// of FreeCAD's getPoles() rows.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace varsurf {

// Values of the non-zero basis functions at one (u, v) point. values(d, k) is derivative d of
// function index[k], with d ordered 0:w, 1:w_u, 2:w_v, 3:w_uu, 4:w_uv, 5:w_vv (rows up to `order`).
struct BasisSample {
  std::vector<int> index;
  Eigen::MatrixXd values;
};

struct SplineSpace {
  int degree_u = 3;
  int degree_v = 3;
  std::vector<double> knots_u;  // flat, clamped
  std::vector<double> knots_v;  // flat, clamped
  Eigen::VectorXd weights;      // empty (non-rational) or size() positive values

  int nu() const { return static_cast<int>(knots_u.size()) - degree_u - 1; }
  int nv() const { return static_cast<int>(knots_v.size()) - degree_v - 1; }
  int size() const { return nu() * nv(); }
  int index(int i, int j) const { return i * nv() + j; }
  bool rational() const { return weights.size() > 0; }
  double u_first() const { return knots_u.front(); }
  double u_last() const { return knots_u.back(); }
  double v_first() const { return knots_v.front(); }
  double v_last() const { return knots_v.back(); }

  void validate() const;  // throws InvalidInput

  // Basis functions and their derivatives up to `order` (0, 1 or 2; 2 gives all six rows).
  BasisSample basis(double u, double v, int order) const;

  // Uniform bicubic-style space on [0,1]^2 with the given degrees and span counts.
  static SplineSpace uniform(int degree_u, int degree_v, int spans_u, int spans_v);

 private:
  // basis() from the two directions' basis derivatives at spans su, sv.
  template <class Basis>
  BasisSample tensor_basis(const Basis& nu_d, const Basis& nv_d, int su, int sv, int order) const;
};

// A surface of the space: its poles, size() x 3.
struct BSplineSurface {
  SplineSpace space;
  Eigen::MatrixX3d poles;
  void validate() const;  // throws InvalidInput
  Eigen::Vector3d evaluate(double u, double v) const;
};

// Flat indices of the poles on the four boundary rows of the space; the rows at the ends of a
// closed direction are a seam, not a boundary, and are left out.
std::vector<int> boundary_pole_indices(const SplineSpace& space, bool closed_u = false,
                                       bool closed_v = false);

// Surface point and derivatives (rows as in BasisSample) for the given poles (size() x 3).
Eigen::MatrixXd evaluate_surface(const SplineSpace& space, const Eigen::MatrixX3d& poles, double u,
                                 double v, int order);

}  // namespace varsurf
