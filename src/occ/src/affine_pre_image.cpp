// SPDX-License-Identifier: LGPL-2.1-or-later
#include "affine_pre_image.hpp"

#include <Geom2d_BSplineCurve.hxx>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "varsurf/core/knot_vector.hpp"
#include "varsurf/occ/geom_convert.hpp"

namespace varsurf::occ {

namespace {

struct Affine {
  Eigen::Vector3d a, b, c;  // S(u, v) = a + u b + v c
};

// The base as an affine map, if its poles are one to within 1e-13 of its size.
std::optional<Affine> affine_of(const BSplineSurface& base, double size) {
  const SplineSpace& space = base.space;
  if (space.rational()) return std::nullopt;
  const std::vector<double> gu = greville(space.knots_u, space.degree_u);
  const std::vector<double> gv = greville(space.knots_v, space.degree_v);
  const int nu = space.nu(), nv = space.nv();
  const double du = gu.back() - gu.front(), dv = gv.back() - gv.front();
  if (!(du > 0.0) || !(dv > 0.0)) return std::nullopt;
  const auto pole = [&](int i, int j) -> Eigen::Vector3d {
    return base.poles.row(space.index(i, j)).transpose();
  };
  Affine f;
  f.b = (pole(nu - 1, 0) - pole(0, 0)) / du;
  f.c = (pole(0, nv - 1) - pole(0, 0)) / dv;
  f.a = pole(0, 0) - gu.front() * f.b - gv.front() * f.c;
  const double tolerance = 1e-13 * size;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Vector3d expected =
          f.a + gu[static_cast<size_t>(i)] * f.b + gv[static_cast<size_t>(j)] * f.c;
      if ((pole(i, j) - expected).norm() > tolerance) return std::nullopt;
    }
  }
  return f;
}

}  // namespace

std::optional<PreImage> affine_pre_image(const BSplineSurface& base, const SheetDomain& domain,
                                         const BSplineCurve& target,
                                         const Eigen::Vector3d& direction,
                                         const std::vector<double>& ts, int degree) {
  const double size = domain.model_size();
  const std::optional<Affine> f = affine_of(base, size);
  if (!f) return std::nullopt;
  const Eigen::Vector3d normal = f->b.cross(f->c);
  if (!(normal.norm() > 0.0)) return std::nullopt;
  const Eigen::Vector3d along =
      direction.isZero(0.0) ? normal.normalized() : direction.normalized();
  // A direction within a degree of the sheet's plane: the general projection and its messages.
  if (std::abs(along.dot(normal.normalized())) < std::sin(M_PI / 180.0)) return std::nullopt;
  Eigen::Matrix3d frame;
  frame << f->b, f->c, along;
  const Eigen::Matrix<double, 2, 3> to_uv = frame.inverse().topRows<2>();

  PreImage out;
  out.curve.degree = target.degree;
  out.curve.knots = target.knots;
  out.curve.weights = target.weights;
  out.curve.poles = (to_uv * (target.poles.transpose().colwise() - f->a)).transpose();

  // Where the general projection samples: the target must stay on the sheet and not run along
  // the projection direction; the distances are measured there.
  const Eigen::Vector2d lo = domain.lo(), hi = domain.hi();
  const Eigen::Vector2d margin = SheetDomain::snap_margin * domain.width();
  double target_length = 0.0, image_length = 0.0;
  Eigen::Vector3d last_target = Eigen::Vector3d::Zero();
  Eigen::Vector2d last_uv = Eigen::Vector2d::Zero();
  out.boundary_t = target.first();
  for (size_t k = 0; k < ts.size(); ++k) {
    const Eigen::Vector3d p = target.evaluate(ts[k]);
    Eigen::Vector2d uv = to_uv * (p - f->a);
    if ((uv.array() < (lo - margin).array()).any() || (uv.array() > (hi + margin).array()).any())
      return std::nullopt;
    uv = uv.cwiseMax(lo).cwiseMin(hi);
    const double distance = (f->a + uv(0) * f->b + uv(1) * f->c - p).norm();
    out.max_distance = std::max(out.max_distance, distance);
    out.fit_error = std::max(out.fit_error, (out.curve.evaluate(ts[k]) - uv).norm());
    if ((domain.side(uv, 0) != 0 || domain.side(uv, 1) != 0) && distance >= out.boundary_distance) {
      out.boundary_distance = distance;
      out.boundary_t = ts[k];
    }
    if (k > 0) {
      target_length += (p - last_target).norm();
      image_length += (f->b * (uv(0) - last_uv(0)) + f->c * (uv(1) - last_uv(1))).norm();
    }
    last_target = p;
    last_uv = uv;
  }
  if (target_length > 0.0 && image_length < 1e-3 * target_length) return std::nullopt;

  // Poles within the snap margin of a bound go onto it, as the general projection's do: a
  // target along the sheet's edge has its pre-image exactly on the domain's side.
  for (int i = 0; i < out.curve.pole_count(); ++i) {
    for (int c = 0; c < 2; ++c) {
      double& x = out.curve.poles(i, c);
      if (std::abs(x - lo(c)) <= margin(c)) x = lo(c);
      if (std::abs(x - hi(c)) <= margin(c)) x = hi(c);
    }
  }
  // Raised to the degree the general projection fits (exactly: knot multiplicities grow with
  // it): the solver's quadrature along a curve takes its point count from the pre-image's degree,
  // and a degree-1 line's was too few to hold a G0 join or an exact curve.
  if (out.curve.degree < degree) {
    const Handle(Geom2d_BSplineCurve) raised = to_geom2d_curve(out.curve);
    raised->IncreaseDegree(degree);
    out.curve = from_geom(raised);
  }
  out.curve.validate("pre-image");
  return out;
}

}  // namespace varsurf::occ
