// SPDX-License-Identifier: LGPL-2.1-or-later
// Pre-images of target curves: the (u, v) curve c(t) on a base sheet whose surface point S(c(t))
// is the orthogonal projection of the target D(t), with the same parameter t (the solver's curve
// constraint needs the shared parameter).
#pragma once

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

struct ProjectionOptions {
  int samples = 0;           // total samples along the target; 0 = automatic:
  int samples_per_span = 8;  //   at least this many per polynomial span of the target
  int min_samples = 64;      //   and at least this many in all
  // How far (model units) the target may pass beyond the sheet's boundary, measured in the
  // sheet's tangent plane at the closest boundary point.
  double tolerance = 1e-6;
  // Wanted max |c(t_k) - uv_k| of the fit, each direction relative to its side of the (u, v)
  // domain (u and v may be in different units: radians and mm on a cylinder). The
  // solver makes the new sheet pass through the target at c(t) whatever c is, so this shapes the
  // parametrization more than the result; tighter costs poles (and constraint samples). At 1e-7
  // the fit's own decisions (where to split) flipped under a rigid motion's rounding and moved a
  // sheet through lifted curves by 7e-5 mm; at 1e-9 the same scenes agree to 1e-5 mm and the
  // test suite takes no longer.
  double fit_tolerance = 1e-9;
  int degree = 3;        // degree of the pre-image (raised to the target's if that is higher)
  int max_poles = 1000;  // refinement stops here and reports the fit error it reached
  // Non-zero: each target point goes where the line through it along this direction meets the
  // sheet (a sketch seen along its normal: directional_projection.hpp) instead of to its closest
  // point.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};

// A target on the sheet's boundary (its own edges, a seam) has its pre-image exactly on the
// domain's side (see SheetDomain); one touching the boundary may pass beyond it by up to 1e-8 of
// the domain, which the solver clamps.
struct PreImage {
  BSplineCurve curve;         // 2D, parameter range exactly that of the target
  double max_distance = 0.0;  // max |D(t_k) - S(uv_k)|: how far the target is from the sheet
  double fit_error = 0.0;     // max |c(t_k) - uv_k| over the projected samples
  // Max |D(t_k) - S(uv_k)| over the samples whose foot point is on the sheet's boundary (a closed
  // direction's seam is not), and its t_k (-1 and the first parameter if none is): how far a
  // kept boundary would have to move.
  double boundary_distance = -1.0;
  double boundary_t = 0.0;
};

// InvalidInput for invalid data, a target leaving the sheet (no orthogonal projection) or a
// projection jumping across the sheet (a closed sheet's seam, a fold); GeometryError if OCCT fails.
PreImage project_curve(const BSplineSurface& base, const BSplineCurve& target,
                       const ProjectionOptions& options = {});

}  // namespace varsurf::occ
