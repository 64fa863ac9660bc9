// SPDX-License-Identifier: LGPL-2.1-or-later
#include "collapsed_sides.hpp"

#include <gp_Pnt.hxx>
#include <gp_XYZ.hxx>
#include <vector>

namespace varsurf::occ {

void collapse_degenerate_sides(const Handle(Geom_BSplineSurface) & s, double tolerance) {
  const int nu = s->NbUPoles(), nv = s->NbVPoles();
  struct Side {
    bool along_v;  // the row runs along v at a fixed u index
    int fixed;
  };
  for (const Side side : {Side{true, 1}, Side{true, nu}, Side{false, 1}, Side{false, nv}}) {
    const int count = side.along_v ? nv : nu;
    std::vector<gp_Pnt> row;
    row.reserve(static_cast<size_t>(count));
    for (int k = 1; k <= count; ++k)
      row.push_back(side.along_v ? s->Pole(side.fixed, k) : s->Pole(k, side.fixed));
    gp_XYZ sum(0.0, 0.0, 0.0);
    for (const gp_Pnt& p : row) sum += p.XYZ();
    const gp_Pnt mean(sum / count);
    bool collapsed = true;
    bool exact = true;
    for (const gp_Pnt& p : row) {
      collapsed = collapsed && p.Distance(mean) <= tolerance;
      exact = exact && p.IsEqual(row.front(), 0.0);
    }
    if (!collapsed || exact) continue;
    for (int k = 1; k <= count; ++k) {
      if (side.along_v)
        s->SetPole(side.fixed, k, mean);  // keeps the pole's weight
      else
        s->SetPole(k, side.fixed, mean);
    }
  }
}

}  // namespace varsurf::occ
