// SPDX-License-Identifier: LGPL-2.1-or-later
// A locally refinable spline space (Welch & Witkin sec. 3): a sum of layers, layer k+1 on the
// knots of layer k with every span halved, each layer holding poles only where it was refined.
//
// Which poles of a layer are degrees of freedom follows the hierarchical B-spline construction
// (Forsey & Bartels; Kraft): a level-k basis function is used when its support lies inside the
// region refined to level k and not wholly inside the region refined further. A layer's function
// is then zero with its derivatives along the border of its region (Welch & Witkin's r-wide band
// of poles held at zero), the sum stays C^(p-1), and the functions used are linearly independent,
// so an energy stays positive definite on them. Refined patches that meet simply merge: the
// region is a set of spans.
//
// A rational base keeps its weight function w(u, v): every layer carries it exactly (knot
// insertion of the weights), and the layers add up in homogeneous coordinates, so the surface is
// (sum over layers of w_k P N_k) / w. A degree of freedom's value is a point (its homogeneous
// coefficient divided by its own weight): with only the base's functions, the values are the
// base's poles and the surface is the base's (a cylinder stays a cylinder).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "varsurf/core/spline_space.hpp"

namespace varsurf {

struct HierarchicalDof {
  int level, i, j;  // pole (i, j) of layer `level`
};

class HierarchicalSpace {
 public:
  // Level 0: the whole of `base` (validated; rational or not).
  explicit HierarchicalSpace(SplineSpace base);

  int levels() const { return static_cast<int>(layers_.size()); }
  const SplineSpace& layer(int level) const;
  int spans_u(int level) const;
  int spans_v(int level) const;

  // Whether span (su, sv) of `level` belongs to the region of that level, and whether it has
  // been refined into the next level.
  bool in_region(int level, int su, int sv) const;
  bool refined(int level, int su, int sv) const;

  // Refine one span of the region of `level` (creating level + 1 if needed). InvalidInput for a
  // span outside the region or out of range; refining a refined span changes nothing.
  void refine(int level, int su, int sv);
  // Refine every span of the region of `level` that overlaps [u0, u1] x [v0, v1]; returns how
  // many were newly refined.
  int refine_box(int level, double u0, double u1, double v0, double v1);

  // The degrees of freedom, level by level, and their count.
  const std::vector<HierarchicalDof>& dofs() const { return dofs_; }
  int dof_count() const { return static_cast<int>(dofs_.size()); }

  // The finest layer's space (every layer written in it is exact: its knots contain all others).
  const SplineSpace& finest() const { return layers_.back().space; }
  // A level's basis in the finest one, per direction (finest count x level count): knot
  // insertion from that level's knots to the finest level's.
  Eigen::SparseMatrix<double> level_to_finest_u(int level) const;
  Eigen::SparseMatrix<double> level_to_finest_v(int level) const;
  // finest poles = to_finest() * dof values (finest size x dof_count), per coordinate.
  Eigen::SparseMatrix<double> to_finest() const;
  // Poles of a surface of the base space (layer 0) written exactly on the finest space.
  Eigen::MatrixX3d base_to_finest(const Eigen::MatrixX3d& poles) const;
  // The surface at (u, v) summed layer by layer from dof values (dof_count x 3): independent of
  // to_finest, for checking it.
  Eigen::Vector3d evaluate(const Eigen::MatrixX3d& values, double u, double v) const;

 private:
  struct Layer {
    SplineSpace space;
    std::vector<char> region, refined;  // per span, row-major (su * spans_v + sv)
    std::vector<int> first_u, last_u;   // span range of each basis function's support
    std::vector<int> first_v, last_v;
  };
  Layer make_layer(SplineSpace space) const;
  void add_level();
  void collect_dofs();
  const Layer& at(int level) const;
  double layer_weight(int level, int i, int j) const;  // 1 for polynomial layers
  std::vector<Layer> layers_;
  std::vector<HierarchicalDof> dofs_;
};

}  // namespace varsurf
