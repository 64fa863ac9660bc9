// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/ribbon_constraint.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "curve_pieces.hpp"
#include "unit_vector.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"

namespace varsurf {

namespace {

void validate(const RibbonConstraint& c) {
  c.preimage.validate("ribbon pre-image");
  c.normals.validate("ribbon normal field");
  if (c.preimage.dim() != 2) throw InvalidInput("ribbon pre-image must be a 2D (u, v) curve");
  if (c.normals.dim() != 3) throw InvalidInput("ribbon normal field must be 3D");
  if (!std::isfinite(c.weight) || c.weight <= 0.0)
    throw InvalidInput("ribbon: weight must be positive and finite");
  const double tol = 1e-9 * (c.preimage.last() - c.preimage.first());
  if (std::abs(c.preimage.first() - c.normals.first()) > tol ||
      std::abs(c.preimage.last() - c.normals.last()) > tol)
    throw InvalidInput("ribbon pre-image and normal field must share their parameter range");
}

}  // namespace

ConstraintSamples sample_ribbon(const SplineSpace& space, const RibbonConstraint& c,
                                std::vector<double>* at) {
  validate(c);
  if (at) at->clear();
  const double t0 = c.preimage.first(), t1 = c.preimage.last();
  const std::vector<double> pieces = curve_pieces(space, c.preimage, &c.normals);
  const GaussRule& g = gauss_legendre(gauss_points_along(space, c.preimage));
  ConstraintSamples out;
  out.rhs.resize(0, 1);
  std::vector<double> rhs;
  for (size_t i = 0; i + 1 < pieces.size(); ++i) {
    const double a = pieces[i], h = 0.5 * (pieces[i + 1] - pieces[i]);
    for (size_t q = 0; q < g.nodes.size(); ++q) {
      const double t = a + h * (g.nodes[q] + 1.0);
      const Eigen::MatrixXd pre = c.preimage.derivatives(t, 1);
      const Eigen::Vector2d uv = clamp_to_domain(space, pre.row(0).transpose(), t);
      const Eigen::Vector3d n = unit_vector(c.normals.evaluate(t), "ribbon: the normal field");
      const BasisSample s = space.basis(uv(0), uv(1), 1);
      // Rows: w_u . N and w_v . N, or the derivative across the pre-image alone. Each carries its
      // share of the sample's weight.
      const int rows = c.across_only ? 1 : 2;
      const double w = c.weight * g.weights[q] * h / (t1 - t0) / rows, sw = std::sqrt(w);
      for (int r = 0; r < rows; ++r) {
        std::vector<int> cols;
        Eigen::VectorXd coeff(3 * static_cast<Eigen::Index>(s.index.size()));
        for (size_t k = 0; k < s.index.size(); ++k) {
          const Eigen::Index kk = static_cast<Eigen::Index>(k);
          const double dk = c.across_only
                                ? -pre(1, 1) * s.values(1, kk) + pre(1, 0) * s.values(2, kk)
                                : s.values(r + 1, kk);
          for (int e = 0; e < 3; ++e) {
            cols.push_back(3 * s.index[k] + e);
            coeff(3 * kk + e) = sw * dk * n(e);
          }
        }
        out.index.push_back(std::move(cols));
        out.coeff.push_back(std::move(coeff));
        out.weight.push_back(w);
        rhs.push_back(0.0);
        if (at) at->push_back(t);
      }
    }
  }
  out.rhs = Eigen::Map<Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  return out;
}

double ribbon_angle_error(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                          const RibbonConstraint& c, int samples) {
  validate(c);
  BSplineSurface{space, poles}.validate();
  if (samples < 2 || samples > 1000000)
    throw InvalidInput("ribbon_angle_error takes 2 to 1,000,000 samples");
  double worst = 0.0;
  const double t0 = c.preimage.first(), t1 = c.preimage.last();
  for (int i = 0; i < samples; ++i) {
    const double t = t0 + (t1 - t0) * i / (samples - 1);
    const Eigen::Vector2d uv = clamp_to_domain(space, c.preimage.evaluate(t), t);
    const Eigen::MatrixXd d = evaluate_surface(space, poles, uv(0), uv(1), 1);
    const Eigen::Vector3d normal = Eigen::Vector3d(d.row(1)).cross(Eigen::Vector3d(d.row(2)));
    const Eigen::Vector3d n = unit_vector(c.normals.evaluate(t), "ribbon: the normal field");
    // Unsigned: a ribbon fixes the tangent plane, not which side is up.
    worst = std::max(worst, std::atan2(normal.cross(n).norm(), std::abs(normal.dot(n))));
  }
  return worst;
}

}  // namespace varsurf
