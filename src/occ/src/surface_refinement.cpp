// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/surface_refinement.hpp"

#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <algorithm>
#include <queue>
#include <string>
#include <vector>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

// Midpoints to insert so that the breakpoints form at least `spans` intervals, longest first.
std::vector<double> knots_to_insert(const std::vector<double>& flat, int degree, int spans) {
  std::vector<double> breaks = breakpoints(flat, degree);
  std::vector<double> added;
  using Interval = std::pair<double, double>;  // (length, start)
  std::priority_queue<Interval> longest;
  for (size_t i = 0; i + 1 < breaks.size(); ++i)
    longest.push({breaks[i + 1] - breaks[i], breaks[i]});
  for (int have = static_cast<int>(breaks.size()) - 1; have < spans; ++have) {
    const auto [length, start] = longest.top();
    longest.pop();
    const double mid = start + 0.5 * length;
    added.push_back(mid);
    longest.push({0.5 * length, start});
    longest.push({0.5 * length, mid});
  }
  std::sort(added.begin(), added.end());
  return added;
}

// OCCT (value, multiplicity) arrays for simple knots.
void simple_knots(const std::vector<double>& values, TColStd_Array1OfReal& knots,
                  TColStd_Array1OfInteger& mults) {
  for (size_t i = 0; i < values.size(); ++i) {
    knots.SetValue(static_cast<Standard_Integer>(i + 1), values[i]);
    mults.SetValue(static_cast<Standard_Integer>(i + 1), 1);
  }
}

void insert_knots(const Handle(Geom_BSplineSurface) & geom, const std::vector<double>& values,
                  bool along_u) {
  if (values.empty()) return;
  const Standard_Integer n = static_cast<Standard_Integer>(values.size());
  TColStd_Array1OfReal knots(1, n);
  TColStd_Array1OfInteger mults(1, n);
  simple_knots(values, knots, mults);
  if (along_u)
    geom->InsertUKnots(knots, mults, 0.0, Standard_True);
  else
    geom->InsertVKnots(knots, mults, 0.0, Standard_True);
}

}  // namespace

BSplineSurface refine_surface(const BSplineSurface& surface, int min_spans_u, int min_spans_v,
                              int min_degree) {
  if (min_spans_u < 1 || min_spans_v < 1 || min_spans_u > 4096 || min_spans_v > 4096)
    throw InvalidInput("refine_surface: span counts must be in 1..4096, got " +
                       std::to_string(min_spans_u) + " x " + std::to_string(min_spans_v));
  if (min_degree < 1 || min_degree > 9)
    throw InvalidInput("refine_surface: degree must be in 1..9, got " + std::to_string(min_degree));
  surface.validate();
  const bool raise = surface.space.degree_u < min_degree || surface.space.degree_v < min_degree;
  const std::vector<double> add_u =
      knots_to_insert(surface.space.knots_u, surface.space.degree_u, min_spans_u);
  const std::vector<double> add_v =
      knots_to_insert(surface.space.knots_v, surface.space.degree_v, min_spans_v);
  if (add_u.empty() && add_v.empty() && !raise) return surface;
  return guarded("refine_surface", [&] {
    Handle(Geom_BSplineSurface) geom = to_geom(surface);
    // Degree elevation keeps the breakpoints, so the span counts computed above still hold.
    if (raise)
      geom->IncreaseDegree(std::max(surface.space.degree_u, min_degree),
                           std::max(surface.space.degree_v, min_degree));
    insert_knots(geom, add_u, true);
    insert_knots(geom, add_v, false);
    return from_geom(geom);
  });
}

}  // namespace varsurf::occ
