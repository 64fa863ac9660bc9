// SPDX-License-Identifier: LGPL-2.1-or-later
// A triangular surface's patches as domains: the Bernstein basis and its derivatives at a point,
// the flat triangle each patch is parameterized over, and quadrature over a set of patches for
// the external energy operators (operator_terms.hpp).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "varsurf/core/operator_terms.hpp"
#include "varsurf/core/triangle_net.hpp"

namespace varsurf {

// The degree-n Bernstein polynomials at barycentric b, in triangle_index order.
Eigen::VectorXd bernstein(int n, const Eigen::Vector3d& b);
// Their derivatives along barycentric direction d (entries summing to 0) at b.
Eigen::VectorXd bernstein_derivative(int n, const Eigen::Vector3d& b, const Eigen::Vector3d& d);

// The domain triangle of patch t: the equilateral triangle of its area (Veltkamp & Wesselink eq.
// 25) or the mesh triangle laid flat; corners counterclockwise, the first at the origin.
std::array<Eigen::Vector2d, 3> domain_corners(const TriangleNet& net, int t, bool equilateral);

// The patches `triangles` of `net` as an operator's domain: on each a collapsed Gauss rule of
// degree + 1 points a direction (exact for products of two of its Bernstein polynomials), with the
// basis values and their derivatives along the domain's x and y. The net must outlive the domain.
OperatorDomain triangles_domain(const TriangleNet& net, std::vector<int> triangles,
                                bool equilateral);

}  // namespace varsurf
