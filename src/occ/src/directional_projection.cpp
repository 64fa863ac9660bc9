// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/occ/directional_projection.hpp"

#include <GeomAPI_IntCS.hxx>
#include <Geom_Line.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <sstream>

#include "varsurf/core/errors.hpp"
#include "varsurf/occ/geom_convert.hpp"
#include "varsurf/occ/occ_error.hpp"

namespace varsurf::occ {

namespace {

// Below this |cos| between the direction and the sheet's normal (88.9 degrees) the line skims the
// sheet: its meeting point moves by 50 times any error along the line, so a pre-image there
// would be noise.
constexpr double kGrazing = 0.02;

std::string vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << "(" << v(0) << ", " << v(1) << ", " << v(2) << ")";
  return s.str();
}

}  // namespace

LineFoot::LineFoot(const BSplineSurface& base, const Eigen::Vector3d& direction)
    : base_(base),
      lo_(base.space.u_first(), base.space.v_first()),
      hi_(base.space.u_last(), base.space.v_last()) {
  base.validate();
  if (!direction.allFinite() || direction.norm() <= 0.0)
    throw InvalidInput("projection direction must be a finite, non-zero vector");
  direction_ = direction.normalized();
  // Two unit vectors across the line: the foot is where S - p has no component along them.
  Eigen::Vector3d helper =
      std::abs(direction_(0)) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d across1 = direction_.cross(helper).normalized();
  across_.row(0) = across1.transpose();
  across_.row(1) = direction_.cross(across1).transpose();
  scale_ =
      std::max(1.0, (base.poles.colwise().maxCoeff() - base.poles.colwise().minCoeff()).norm());
  geom_ = to_geom(base);
}

// Newton on the two components of S(u, v) - p across the line, the step clipped to the domain.
// False when it stalls off the line (the foot lies beyond the domain, or the start was poor).
bool LineFoot::newton(const Eigen::Vector3d& p, Eigen::Vector2d& uv) const {
  const auto off_line = [&](const Eigen::Vector2d& q) {
    return (across_ * (base_.evaluate(q(0), q(1)) - p)).norm();
  };
  for (int it = 0; it < 40; ++it) {
    const Eigen::MatrixXd s = evaluate_surface(base_.space, base_.poles, uv(0), uv(1), 1);
    const Eigen::Vector2d f = across_ * (s.row(0).transpose() - p);
    if (f.norm() <= 1e-12 * scale_) return true;
    Eigen::Matrix2d j;
    j.col(0) = across_ * s.row(1).transpose();
    j.col(1) = across_ * s.row(2).transpose();
    const double det = j.determinant();
    if (!std::isfinite(det) || std::abs(det) <= 1e-300) return false;
    Eigen::Vector2d step = -j.inverse() * f;
    // Halve the step until the residual drops: far from the foot a full step may overshoot.
    bool improved = false;
    for (int half = 0; half < 30 && !improved; ++half, step *= 0.5) {
      const Eigen::Vector2d next = (uv + step).cwiseMax(lo_).cwiseMin(hi_);
      const double fn = off_line(next);
      if (fn < f.norm()) {
        const bool stuck = (next - uv).cwiseAbs().maxCoeff() <= 1e-15 * (hi_ - lo_).maxCoeff();
        uv = next;
        improved = true;
        if (stuck) return fn <= 1e-9 * scale_;
      }
    }
    if (!improved) return false;
  }
  return off_line(uv) <= 1e-9 * scale_;
}

void LineFoot::check_incidence(const Eigen::Vector3d& p, const Eigen::Vector2d& uv) const {
  const Eigen::MatrixXd s = evaluate_surface(base_.space, base_.poles, uv(0), uv(1), 1);
  const Eigen::Vector3d n = Eigen::Vector3d(s.row(1)).cross(Eigen::Vector3d(s.row(2)));
  if (n.norm() <= 0.0) return;  // a degenerate point (a pole of a sphere): no tangent plane
  if (std::abs(n.normalized().dot(direction_)) < kGrazing) {
    std::ostringstream msg;
    msg << "along the projection direction " << vec(direction_) << " the line through " << vec(p)
        << " grazes the face (less than " << 90.0 - std::acos(kGrazing) * 180.0 / M_PI
        << " degrees from its tangent plane): project along a direction that meets the face "
           "more steeply";
    throw InvalidInput(msg.str());
  }
}

Eigen::Vector2d LineFoot::operator()(const Eigen::Vector3d& p, const Eigen::Vector2d* near) const {
  if (!p.allFinite()) throw InvalidInput("projection: the target point is not finite");
  if (near) {
    Eigen::Vector2d uv = *near;
    if (newton(p, uv)) {
      check_incidence(p, uv);
      return uv;
    }
  }
  // OCCT's line/surface intersection over the whole sheet decides the first point, and any
  // point where continuing from the neighbour failed.
  const Handle(Geom_Line) line =
      new Geom_Line(gp_Pnt(p(0), p(1), p(2)), gp_Dir(direction_(0), direction_(1), direction_(2)));
  Eigen::Vector2d best;
  double best_cost = std::numeric_limits<double>::infinity();
  guarded("intersecting the projection line with the face", [&] {
    GeomAPI_IntCS inter(line, geom_);
    if (!inter.IsDone()) return;
    for (int i = 1; i <= inter.NbPoints(); ++i) {
      double u = 0.0, v = 0.0, w = 0.0;
      inter.Parameters(i, u, v, w);
      const Eigen::Vector2d uv(u, v);
      if (!uv.allFinite()) continue;
      const double cost = near ? (uv - *near).cwiseQuotient(hi_ - lo_).norm() : std::abs(w);
      if (cost < best_cost) {
        best_cost = cost;
        best = uv;
      }
    }
  });
  if (!std::isfinite(best_cost)) {
    std::ostringstream msg;
    msg << "seen along the projection direction " << vec(direction_) << ", the point " << vec(p)
        << " lies beyond the face: the line through it misses the face";
    throw InvalidInput(msg.str());
  }
  best = best.cwiseMax(lo_).cwiseMin(hi_);
  newton(p, best);  // OCCT's intersection is accurate to its own tolerance; polish it
  check_incidence(p, best);
  return best;
}

}  // namespace varsurf::occ
