// SPDX-License-Identifier: LGPL-2.1-or-later
// The stretch and bend energies of a triangular Bezier patch (Veltkamp & Wesselink eqs. 6-7 and
// 24-27), exactly: the patch is parameterized over an equilateral triangle (their eq. 25, so that
// the energy does not depend on which corner comes first), the derivatives along x and y are
// Bezier nets of lower degree, and the integrals of products of Bernstein polynomials over a
// triangle have a closed form.
#pragma once

#include <Eigen/Core>

namespace varsurf {

// The integrals over a triangle of area `area` of B_a B_b, a and b of degree m (numbered as
// triangle_index): 2 area C(m; a) C(m; b) / (C(2m; a + b) (2m + 1)(2m + 2)), C the multinomial.
// InvalidInput for a degree outside 0..40 or an area that is negative or not finite.
Eigen::MatrixXd bernstein_gram(int degree, double area);

struct TriangleEnergy {
  // Per coordinate: E = p^T stretch p with p the control points' x (or y, or z) values.
  Eigen::MatrixXd stretch;  // integral of |T_x|^2 + |T_y|^2
  Eigen::MatrixXd bend;     // integral of |T_xx|^2 + 2 |T_xy|^2 + |T_yy|^2
};

// The energies of a degree-n patch over an equilateral triangle of side `side`, corners (0, 0),
// (side, 0), (side / 2, side sqrt(3) / 2). InvalidInput for a degree outside 1..20 or a side that
// is not a positive finite number.
TriangleEnergy triangle_energy(int degree, double side = 1.0);

// The Cartesian directions x and y of the triangle a, b, c (counterclockwise) as barycentric
// directions: entry k is the derivative of corner k's coordinate along x (or y). No checks.
struct BarycentricAxes {
  Eigen::Vector3d x, y;
  double area = 0.0;
};
BarycentricAxes barycentric_axes(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                 const Eigen::Vector2d& c);

// The same over any triangle of the plane, corners a, b, c counterclockwise (corner 1, 2, 3 of
// the patch). InvalidInput for a degree outside 1..20 or a triangle without area.
TriangleEnergy triangle_energy(int degree, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& c);

}  // namespace varsurf
