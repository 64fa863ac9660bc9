// SPDX-License-Identifier: LGPL-2.1-or-later
// The Bezier poles of a bicubic from its points at (i / 3, j / 3): the inverse of the Bernstein
// collocation matrix on each side, exact for a bicubic (a limit patch, or a piece of one).
#pragma once

#include <Eigen/Dense>

namespace varsurf {

// Poles 4 i + j (i along u) of the bicubic whose point at (i / 3, j / 3) is point(i / 3, j / 3).
template <class Point>
Eigen::Matrix<double, 16, 3> bicubic_bezier(const Point& point) {
  static const Eigen::Matrix4d inverse = [] {
    Eigen::Matrix4d c;
    for (int i = 0; i < 4; ++i) {
      const double t = i / 3.0, s = 1.0 - t;
      c.row(i) << s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t;
    }
    return Eigen::Matrix4d(c.inverse());
  }();
  Eigen::Matrix4d x, y, z;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const Eigen::Vector3d q = point(i / 3.0, j / 3.0);
      x(i, j) = q.x();
      y(i, j) = q.y();
      z(i, j) = q.z();
    }
  const Eigen::Matrix4d bx = inverse * x * inverse.transpose();
  const Eigen::Matrix4d by = inverse * y * inverse.transpose();
  const Eigen::Matrix4d bz = inverse * z * inverse.transpose();
  Eigen::Matrix<double, 16, 3> poles;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) poles.row(4 * i + j) << bx(i, j), by(i, j), bz(i, j);
  return poles;
}

}  // namespace varsurf
