// SPDX-License-Identifier: LGPL-2.1-or-later
// The closest point of a bounded B-spline surface to a point in space (point inversion), global
// over the whole surface and its boundary: the measure behind a sheet's deviation from its curves.
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <gp_Pnt.hxx>

#include <memory>

namespace varsurf::occ {

struct SurfacePoint {
  double u = 0.0;
  double v = 0.0;
  double distance = 0.0;  // from the point to the surface at (u, v)
};

// Bounding boxes of the surface's Bezier patches (their poles' hull holds each patch, rational or
// not) in a tree pick every patch that may hold a closer point; Newton on the squared distance,
// kept inside the parameter box (so boundary points count), converges from the best start in each,
// again from any start nearer than its answer, and from the centres of the patch's quarters, their
// quarters in turn, as long as a piece's lower bound (its poles' box, and their slab along the
// direction to the best foot point) leaves room for a nearer point and the piece is not a convex
// bowl around the best point, up to a budget of pieces per patch. OCCT's global extremum search is
// the fallback where Newton does not settle.
class SurfaceInversion {
 public:
  // Throws Standard_Failure as OCCT does (callers wrap it with `guarded`).
  explicit SurfaceInversion(const Handle(Geom_BSplineSurface) & surface);
  ~SurfaceInversion();
  SurfaceInversion(const SurfaceInversion&) = delete;
  SurfaceInversion& operator=(const SurfaceInversion&) = delete;

  // The globally closest point. `start`, when given, is tried first (e.g. the previous sample's
  // answer along a curve): it only speeds the search up, it does not decide it.
  SurfacePoint closest(const gp_Pnt& point, const SurfacePoint* start = nullptr);

  // A nearest point by Newton from `start` alone (a local minimum of the distance): its distance
  // bounds the global one from above. `settled` says whether Newton converged.
  SurfacePoint local(const gp_Pnt& point, const SurfacePoint& start, bool& settled);

  // Where (u, v) lies on the patch grid: patch index plus the fraction across it (0 .. patches).
  double patch_coordinate_u(double u) const;
  double patch_coordinate_v(double v) const;

  // How many closest() calls fell back to OCCT's global search (Newton did not settle).
  long fallbacks() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace varsurf::occ
