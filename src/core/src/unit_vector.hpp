// SPDX-License-Identifier: LGPL-2.1-or-later
// Direction arguments (normals, line and attractor directions) as unit vectors.
#pragma once

#include <Eigen/Core>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

// d / |d|; InvalidInput naming `what` for a zero or non-finite vector.
inline Eigen::Vector3d unit_vector(const Eigen::Vector3d& d, const char* what) {
  const double n = d.norm();
  if (!d.allFinite() || !(n > 1e-300))
    throw InvalidInput(std::string(what) + " must be a finite non-zero vector");
  return d / n;
}

}  // namespace varsurf
