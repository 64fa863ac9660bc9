// SPDX-License-Identifier: LGPL-2.1-or-later
// The coefficient a(u, v) of the generalized Bloor-Wilson operator (d^2/du^2 + a^2 d^2/dv^2)^2
// (Du & Qin eq. 1): a constant, a scalar B-spline field, and values painted on regions of the
// domain, blended across their borders.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "varsurf/core/region.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// `a` over `region` (in the sheet's parameters).
struct PaintedCoefficient {
  Region region;
  double a = 1.0;
};

// Du & Qin measure u and v on [0, 1]: a is the ratio of the length scales along v and u in those
// normalized parameters (a = 1 is the biharmonic-like isotropic case; a large a confines changes
// along u to a short length scale). The value at (u, v): the field where one is given, else
// `a`; then each painted region, later ones over earlier ones, replaces it inside (blended over a
// band of `blend` -- a fraction of the domain, centred on the region's border -- by a C2
// smoothstep of the distance to the border; 0: a sharp border).
struct PdeCoefficient {
  double a = 1.0;
  // A scalar B-spline over the sheet's domain: field_values has field_space.size() entries
  // (flat pole order). Empty: no field.
  SplineSpace field_space;
  Eigen::VectorXd field_values;
  std::vector<PaintedCoefficient> painted;
  double blend = 0.0;
  // The energy's form. false: int (P_ss + a^2 P_tt)^2, the operator's own square. true: the
  // plate form int P_ss^2 + 2 a^2 P_st^2 + a^4 P_tt^2. For constant a the two differ by a null
  // Lagrangian: the same equation inside (eq. 1) and the same surface wherever positions and cross
  // derivatives are held all round. They differ on a side that nothing holds: there the operator's
  // own natural conditions (L P = 0 and its normal derivative) over-determine P with Hermite data
  // on the other sides and the side flares (measured on Du & Qin's Fig. 7 scene: poles 17 mm
  // beyond an 80 mm surface), while the plate form's are a free plate's and hold it.
  bool plate_form = false;

  bool has_field() const { return field_values.size() > 0; }
  bool uniform() const { return !has_field() && painted.empty(); }
  // Throws InvalidInput naming the field or region for a <= 0 or non-finite anywhere, a field
  // whose space does not cover the sheet's domain, regions outside it, a blend outside [0, 0.5].
  void validate(const SplineSpace& sheet) const;
  // a(u, v) on `sheet`'s domain (validate() first).
  double value(const SplineSpace& sheet, double u, double v) const;
  // The field's value, or `a`: what the painted regions are painted over.
  double base_value(double u, double v) const;
  // The last painted region containing (u, v) (its border included), or -1.
  int top_region(const SplineSpace& sheet, double u, double v) const;
  // Largest degree of the field (0 without one): the quadrature's exactness depends on it.
  int field_degree() const;
};

bool operator==(const PdeCoefficient& x, const PdeCoefficient& y);
inline bool operator!=(const PdeCoefficient& x, const PdeCoefficient& y) {
  return !(x == y);
}

}  // namespace varsurf
