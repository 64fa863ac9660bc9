// SPDX-License-Identifier: LGPL-2.1-or-later
// Ribbon (Welch & Witkin 4.2.2): the sheet's orientation along a curve. A normal field N(t) is
// prescribed along the pre-image c(t); w_u . N = 0 and w_v . N = 0 hold in least squares over the
// curve. Linear in the poles, coupled in x, y, z.
#pragma once

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/constraints.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

struct RibbonConstraint {
  BSplineCurve preimage;  // 2D (u, v)
  BSplineCurve normals;   // 3D field N(t) over the same parameter range; only its direction counts
  double weight = 1.0;
  // Only the derivative across the pre-image, (-v' w_u + u' w_v) . N = 0, one row per sample: for
  // a ribbon along a curve the sheet also contains. The row along the pre-image then repeats the
  // incidence, which holds only to its tolerance, and the two disagreeing a little make the sheet
  // ripple beside the curve (seen on hinged seams).
  bool across_only = false;
};

// Gauss samples on the pieces of the pre-image (as for curve incidence), weighted by parameter
// length so that the whole ribbon weighs `weight`. InvalidInput for a pre-image leaving the domain,
// mismatched ranges or a vanishing normal. `at`, if given, receives each row's curve parameter.
ConstraintSamples sample_ribbon(const SplineSpace& space, const RibbonConstraint& c,
                                std::vector<double>* at = nullptr);

// Largest angle (radians) between the sheet's normal and N(t) over `samples` parameters.
double ribbon_angle_error(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                          const RibbonConstraint& c, int samples = 200);

}  // namespace varsurf
