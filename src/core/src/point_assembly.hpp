// SPDX-License-Identifier: LGPL-2.1-or-later
// A quadratic energy summed over quadrature points: each point's local matrix over the basis
// functions that do not vanish there, gathered into one sparse matrix.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "varsurf/core/region.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// add(sample, point, local) adds the point's contribution (its weight included) to `local` (indexed
// like sample.index); derivatives up to `order` are evaluated.
template <class AddLocal>
Eigen::SparseMatrix<double> assemble_at_points(const SplineSpace& space,
                                               const std::vector<QuadraturePoint>& points,
                                               int order, AddLocal&& add) {
  // Points come piece by piece: one local matrix per piece, flushed when the span changes, keeps
  // the triplets to one set per piece instead of one per point.
  std::vector<Eigen::Triplet<double>> trip;
  std::vector<int> index;
  Eigen::MatrixXd local;
  auto flush = [&] {
    for (size_t c = 0; c < index.size(); ++c)
      for (size_t r = 0; r < index.size(); ++r) {
        const double x = local(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
        if (x != 0.0) trip.emplace_back(index[r], index[c], x);
      }
  };
  for (const QuadraturePoint& q : points) {
    const BasisSample s = space.basis(q.u, q.v, order);
    if (s.index != index) {
      flush();
      index = s.index;
      local = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(index.size()),
                                    static_cast<Eigen::Index>(index.size()));
    }
    add(s, q, local);
  }
  flush();
  Eigen::SparseMatrix<double> out(space.size(), space.size());
  out.setFromTriplets(trip.begin(), trip.end());
  return out;
}

}  // namespace varsurf
