// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/surface_grid.hpp"

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

// Basis values and first derivatives at each grid parameter of one direction.
struct DirectionBasis {
  std::vector<int> first;           // index of the first non-zero basis function
  std::vector<Eigen::MatrixXd> nd;  // 2 x (degree + 1): values, derivatives
};

DirectionBasis direction_basis(const std::vector<double>& knots, int degree, int cells) {
  DirectionBasis b;
  const double a = knots.front(), z = knots.back();
  for (int i = 0; i <= cells; ++i) {
    const double t = a + (z - a) * i / cells;
    const int span = find_span(knots, degree, t);
    Eigen::MatrixXd nd(2, degree + 1);
    basis_derivatives(knots, degree, span, t, 1, nd);
    b.first.push_back(span - degree);
    b.nd.push_back(nd);
  }
  return b;
}

}  // namespace

SurfaceGrid sample_grid(const BSplineSurface& surface, int nu, int nv) {
  surface.validate();
  if (nu < 1 || nv < 1 || nu > 2000 || nv > 2000)
    throw InvalidInput("a surface grid needs 1 to 2000 cells per direction (got " +
                       std::to_string(nu) + " x " + std::to_string(nv) + ")");
  const SplineSpace& sp = surface.space;
  SurfaceGrid g;
  g.nu = nu;
  g.nv = nv;
  const Eigen::Index count = static_cast<Eigen::Index>(nu + 1) * (nv + 1);
  g.points.resize(count, 3);
  g.normals.resize(count, 3);
  if (sp.weights.size() > 0) {  // rational: the space's own (rational) basis, point by point
    for (int i = 0; i <= nu; ++i)
      for (int j = 0; j <= nv; ++j) {
        const double u = sp.u_first() + (sp.u_last() - sp.u_first()) * i / nu;
        const double v = sp.v_first() + (sp.v_last() - sp.v_first()) * j / nv;
        const Eigen::MatrixXd d = evaluate_surface(sp, surface.poles, u, v, 1);
        const Eigen::Index r = static_cast<Eigen::Index>(i) * (nv + 1) + j;
        g.points.row(r) = d.row(0);
        g.normals.row(r) = Eigen::Vector3d(d.row(1)).cross(Eigen::Vector3d(d.row(2))).transpose();
      }
  } else {  // a tensor product: each direction's basis once
    const DirectionBasis bu = direction_basis(sp.knots_u, sp.degree_u, nu);
    const DirectionBasis bv = direction_basis(sp.knots_v, sp.degree_v, nv);
    for (int i = 0; i <= nu; ++i)
      for (int j = 0; j <= nv; ++j) {
        Eigen::RowVector3d p = Eigen::RowVector3d::Zero(), su = p, sv = p;
        for (int a = 0; a <= sp.degree_u; ++a) {
          Eigen::RowVector3d row = Eigen::RowVector3d::Zero(), row_v = row;
          for (int b = 0; b <= sp.degree_v; ++b) {
            const Eigen::RowVector3d pole = surface.poles.row(sp.index(
                bu.first[static_cast<size_t>(i)] + a, bv.first[static_cast<size_t>(j)] + b));
            row += bv.nd[static_cast<size_t>(j)](0, b) * pole;
            row_v += bv.nd[static_cast<size_t>(j)](1, b) * pole;
          }
          p += bu.nd[static_cast<size_t>(i)](0, a) * row;
          su += bu.nd[static_cast<size_t>(i)](1, a) * row;
          sv += bu.nd[static_cast<size_t>(i)](0, a) * row_v;
        }
        const Eigen::Index r = static_cast<Eigen::Index>(i) * (nv + 1) + j;
        g.points.row(r) = p;
        g.normals.row(r) = su.cross(sv);
      }
  }
  for (Eigen::Index r = 0; r < count; ++r) {
    const double len = g.normals.row(r).norm();
    if (len > 0.0)
      g.normals.row(r) /= len;
    else
      g.normals.row(r) =
          r > 0 ? Eigen::RowVector3d(g.normals.row(r - 1)) : Eigen::RowVector3d(0.0, 0.0, 1.0);
  }
  return g;
}

}  // namespace varsurf
