// SPDX-License-Identifier: LGPL-2.1-or-later
// PDE surfaces from Du & Qin's boundary conditions: Hermite, Coons and Gordon data taken from a
// closed-form solution of (d_uu + a^2 d_vv)^2 P = 0 give that solution back; bad curves are
// refused by name.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <functional>
#include <string>

#include "varsurf/core/curve_fit.hpp"
#include "varsurf/core/curve_orientation.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/core/pde_surface.hpp"
#include "varsurf/core/seam_ties.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

constexpr double kA = 1.6;

// z with z_uu + a^2 z_vv = 0 (so every natural boundary condition of the energy holds too).
Eigen::Vector3d exact(double u, double v) {
  const double a2 = kA * kA;
  const double z = u * u * u - 3.0 * u * v * v / a2 + u * u - v * v / a2 + u * v;
  return {20.0 * u, 15.0 * v + 2.0 * u * v, 5.0 * z};
}

Eigen::Vector3d exact_du(double u, double v) {
  const double a2 = kA * kA;
  return {20.0, 2.0 * v, 5.0 * (3.0 * u * u - 3.0 * v * v / a2 + 2.0 * u + v)};
}

// A cubic Bezier curve through f on [t0, t1] (exact for f of degree <= 3).
BSplineCurve cubic(const std::function<Eigen::Vector3d(double)>& f, double t0 = 0.0,
                   double t1 = 1.0) {
  std::vector<double> t;
  Eigen::MatrixXd pts(9, 3);
  for (int k = 0; k < 9; ++k) {
    t.push_back(t0 + (t1 - t0) * k / 8.0);
    pts.row(k) = f(k / 8.0).transpose();
  }
  return fit_clamped_curve(t, pts, 3, uniform_clamped_knots(3, 1, t0, t1));
}

double worst(const SheetProblem& pb, const Eigen::MatrixX3d& poles) {
  double out = 0.0;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const double u = i / 20.0, v = j / 20.0;
      out = std::max(out, (BSplineSurface{pb.space, poles}.evaluate(u, v) - exact(u, v)).norm());
    }
  return out;
}

PdeBoundary hermite_data() {
  PdeBoundary b;
  b.a.a = kA;
  b.u0 = cubic([](double v) { return exact(0.0, v); });
  b.u1 = cubic([](double v) { return exact(1.0, v); }, 2.0, 7.0);  // another parameter range
  b.d0 = cubic([](double v) { return Eigen::Vector3d(exact(0.0, v) + 0.5 * exact_du(0.0, v)); });
  b.d1 = cubic([](double v) { return Eigen::Vector3d(exact(1.0, v) + 0.5 * exact_du(1.0, v)); });
  b.magnitude0 = b.magnitude1 = 2.0;  // the derivative curves are half the tangent away
  return b;
}

// The problem with the operator's own square of energy: the harmonic solution meets every natural
// condition of it, on the free sides too (the plate form, the default there, asks P_vv = 0).
SheetProblem operator_form(SheetProblem pb) {
  pb.pde->plate_form = false;
  return pb;
}

std::string message_of(const PdeBoundary& b, const PdeSurfaceOptions& o = {}) {
  try {
    pde_surface_problem(b, o);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(PdeSurface, HermiteConditionsGiveTheClosedFormSolution) {
  for (int spans : {3, 8}) {
    PdeSurfaceOptions o;
    o.spans_u = spans;
    o.spans_v = spans + 1;
    double fit = -1.0;
    const SheetProblem pb = operator_form(pde_surface_problem(hermite_data(), o, &fit));
    EXPECT_LT(fit, 1e-12);
    const SolveResult r = solve_sheet(pb);
    EXPECT_LT(worst(pb, r.poles), 1e-8) << spans << " spans";
    // Tangents half as long across the boundaries: another surface (the derivative curves act).
    PdeBoundary shorter = hermite_data();
    shorter.magnitude0 = shorter.magnitude1 = 1.0;
    const SheetProblem other = operator_form(pde_surface_problem(shorter, o));
    EXPECT_GT(worst(other, solve_sheet(other).poles), 1e-2);
  }
}

// With the v sides free, the plate form's natural conditions there are a free plate's (P_vv = 0 and
// no shear): P = (20 u, 15 v + 4 u v, cubic(u) + v linear(u)) meets them and L^2 P = 0, so Hermite
// data alone give it back. The operator's own square cannot: its natural conditions ask
// L P = P_uu = 0 on the free sides, which this P does not meet.
TEST(PdeSurface, FreeSidesOfThePlateFormGiveTheClosedFormSolution) {
  auto p = [](double u, double v) {
    return Eigen::Vector3d(20.0 * u, 15.0 * v + 4.0 * u * v,
                           5.0 * u * u * u - 2.0 * u * u + 3.0 * u * v + 1.5 * v);
  };
  auto pu = [](double u, double v) {
    return Eigen::Vector3d(20.0, 4.0 * v, 15.0 * u * u - 4.0 * u + 3.0 * v);
  };
  PdeBoundary b;
  b.a.a = 2.2;
  b.u0 = cubic([&](double v) { return p(0.0, v); });
  b.u1 = cubic([&](double v) { return p(1.0, v); });
  b.d0 = cubic([&](double v) { return Eigen::Vector3d(p(0.0, v) + pu(0.0, v)); });
  b.d1 = cubic([&](double v) { return Eigen::Vector3d(p(1.0, v) + pu(1.0, v)); });
  PdeSurfaceOptions o;
  o.spans_u = o.spans_v = 5;
  auto worst_p = [&](const SheetProblem& pb) {
    const Eigen::MatrixX3d poles = solve_sheet(pb).poles;
    double out = 0.0;
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j)
        out = std::max(out, (BSplineSurface{pb.space, poles}.evaluate(i / 20.0, j / 20.0) -
                             p(i / 20.0, j / 20.0))
                                .norm());
    return out;
  };
  SheetProblem pb = pde_surface_problem(b, o);
  ASSERT_TRUE(pb.pde->plate_form);  // the v sides are free
  EXPECT_LT(worst_p(pb), 1e-8);
  pb.pde->plate_form = false;
  EXPECT_GT(worst_p(pb), 1e-2);
}

TEST(PdeSurface, ReversedCurvesAreOrientedByTheirEnds) {
  PdeBoundary b = hermite_data();
  b.u1 = reversed(b.u1);
  b.d0 = reversed(b.d0);
  PdeSurfaceOptions o;
  o.spans_u = o.spans_v = 6;
  const SheetProblem pb = operator_form(pde_surface_problem(b, o));
  EXPECT_LT(worst(pb, solve_sheet(pb).poles), 1e-8);
}

TEST(PdeSurface, CoonsAndGordonNetworksGiveTheClosedFormSolution) {
  PdeBoundary b;
  b.a.a = kA;
  b.u0 = cubic([](double v) { return exact(0.0, v); });
  b.u1 = cubic([](double v) { return exact(1.0, v); });
  b.v0 = reversed(cubic([](double u) { return exact(u, 0.0); }));  // drawn the other way
  b.v1 = cubic([](double u) { return exact(u, 1.0); });
  PdeSurfaceOptions o;
  o.spans_u = o.spans_v = 6;
  SheetProblem pb = pde_surface_problem(b, o);
  EXPECT_LT(worst(pb, solve_sheet(pb).poles), 1e-8);
  // Gordon: interior isoparametric curves at u = 0.3 and v = 0.4, one reversed and on another
  // parameter range (placed through its crossings with the curves across it).
  b.u_curves.push_back({0.3, cubic([](double v) { return exact(0.3, v); })});
  b.v_curves.push_back({0.4, reversed(cubic([](double u) { return exact(u, 0.4); }, -3.0, 5.0))});
  pb = pde_surface_problem(b, o);
  ASSERT_EQ(pb.curves.size(), 2u);
  SolveOptions opt;
  opt.fit_tolerance = 0.0;
  EXPECT_LT(worst(pb, solve_sheet(pb, opt).poles), 1e-8);
}

TEST(PdeSurface, BadCurvesAreRefusedByName) {
  PdeBoundary b = hermite_data();
  b.d0 =
      cubic([](double v) { return Eigen::Vector3d(exact(0.0, v) + Eigen::Vector3d(0, 0, 1000)); });
  EXPECT_NE(message_of(b).find("d0 does not run beside u0"), std::string::npos) << message_of(b);
  b = hermite_data();
  b.v0 = cubic([](double u) { return Eigen::Vector3d(exact(u, 0.0) + Eigen::Vector3d(0, 3, 0)); });
  EXPECT_NE(message_of(b).find("v0's start is 3"), std::string::npos) << message_of(b);
  b = hermite_data();
  b.v_curves.push_back({0.5, cubic([](double u) {
                          return Eigen::Vector3d(exact(u, 0.5) + Eigen::Vector3d(0, 0, 4));
                        })});
  EXPECT_NE(message_of(b).find("u0 and v-curve 1 do not meet"), std::string::npos) << message_of(b);
  b = hermite_data();
  b.u_curves.push_back({1.2, b.u0});
  EXPECT_NE(message_of(b).find("u-curve 1 lies at 1.2"), std::string::npos) << message_of(b);
  b = hermite_data();
  b.u0 = cubic([](double) { return Eigen::Vector3d(1, 2, 3); });
  EXPECT_NE(message_of(b).find("u0 has no length"), std::string::npos) << message_of(b);
  b = hermite_data();
  b.a.a = -1.0;
  PdeSurfaceOptions o;
  EXPECT_THROW(solve_sheet(pde_surface_problem(b, o)), InvalidInput);
}

namespace {

// A circle of radius r at height z about the z axis, parametrized by angle / 2 pi (a closed cubic
// spline through 256 points of it, within 1e-8 of it for the radii used).
BSplineCurve circle(double r, double z, double turn = 0.0, bool backwards = false) {
  std::vector<double> t;
  Eigen::MatrixXd pts(257, 3);
  for (int k = 0; k <= 256; ++k) {
    t.push_back(k / 256.0);
    const double a = 2.0 * M_PI * (turn + (backwards ? -1.0 : 1.0) * k / 256.0);
    pts.row(k) << r * std::cos(a), r * std::sin(a), z;
  }
  return fit_clamped_curve(t, pts, 3, uniform_clamped_knots(3, 128));
}

}  // namespace

// Bloor & Wilson's classic closed-form solution: P = (f(u) cos 2 pi v, f(u) sin 2 pi v, H u)
// solves (d_uu + a^2 d_vv)^2 P = 0 when f = (A + B u) e^(k u) + (C + D u) e^(-k u), k = 2 pi a.
// Hermite data on two circles give it back on a surface closed along v, whatever the circles'
// seams and directions.
TEST(PdeSurface, ClosedAlongVGivesBloorWilsonsSolution) {
  const double a = 0.3, k = 2.0 * M_PI * a, height = 25.0;
  const double r0 = 20.0, s0 = -10.0, r1 = 12.0, s1 = 6.0;  // f and f' at u = 0 and 1
  // f = (A + B u) e^(k u) + (C + D u) e^(-k u): four conditions.
  Eigen::Matrix4d m;
  const double e = std::exp(k), ie = std::exp(-k);
  m << 1, 0, 1, 0,   //
      k, 1, -k, 1,   //
      e, e, ie, ie,  //
      k * e, e + k * e, -k * ie, ie - k * ie;
  const Eigen::Vector4d c = m.fullPivLu().solve(Eigen::Vector4d(r0, s0, r1, s1));
  auto f = [&](double u) {
    return (c(0) + c(1) * u) * std::exp(k * u) + (c(2) + c(3) * u) * std::exp(-k * u);
  };
  PdeBoundary b;
  b.a.a = a;
  b.u0 = circle(r0, 0.0);
  b.u1 = circle(r1, height, 0.3, true);  // its seam elsewhere, drawn the other way
  b.d0 = circle(r0 + s0, height, 0.1);   // P_u(0, v) = (s0 cos, s0 sin, height)
  b.d1 = circle(r1 + s1, 2.0 * height, 0.7);
  PdeSurfaceOptions o;
  o.spans_u = 12;
  o.spans_v = 32;
  double fit = 0.0;
  const SheetProblem pb = pde_surface_problem(b, o, &fit);
  EXPECT_TRUE(pb.closed_v);
  EXPECT_LT(fit, 1e-4);  // a circle by 32 cubic spans: 4e-5 of 20 mm
  const Eigen::MatrixX3d poles = solve_sheet(pb).poles;
  const BSplineSurface surface{pb.space, poles};
  double worst_radius = 0.0, worst_height = 0.0;
  for (int i = 0; i <= 24; ++i)
    for (int j = 0; j <= 24; ++j) {
      const double u = i / 24.0, v = j / 24.0;
      const Eigen::Vector3d p = surface.evaluate(u, v);
      worst_radius = std::max(worst_radius, std::abs(std::hypot(p.x(), p.y()) - f(u)));
      worst_height = std::max(worst_height, std::abs(p.z() - height * u));
    }
  EXPECT_LT(worst_radius, 1e-3 * r0);
  EXPECT_LT(worst_height, 1e-3 * height);
  // The seam is as smooth as a knot line.
  EXPECT_LT(seam_mismatch(pb.space, poles, 1), 1e-6 * r0);
}

namespace {

// Bloor & Wilson's closed-form solution of ClosedAlongVGivesBloorWilsonsSolution:
// P = (f(u) cos 2 pi v, f(u) sin 2 pi v, H u), f = (A + B u) e^(k u) + (C + D u) e^(-k u).
struct BloorWilson {
  double a = 0.3, height = 25.0, r0 = 20.0, s0 = -10.0, r1 = 12.0, s1 = 6.0;
  Eigen::Vector4d c;
  BloorWilson() {
    const double k = 2.0 * M_PI * a, e = std::exp(k), ie = std::exp(-k);
    Eigen::Matrix4d m;
    m << 1, 0, 1, 0, k, 1, -k, 1, e, e, ie, ie, k * e, e + k * e, -k * ie, ie - k * ie;
    c = m.fullPivLu().solve(Eigen::Vector4d(r0, s0, r1, s1));
  }
  double f(double u) const {
    const double k = 2.0 * M_PI * a;
    return (c(0) + c(1) * u) * std::exp(k * u) + (c(2) + c(3) * u) * std::exp(-k * u);
  }
  Eigen::Vector3d operator()(double u, double v) const {
    return {f(u) * std::cos(2.0 * M_PI * v), f(u) * std::sin(2.0 * M_PI * v), height * u};
  }
  // The profile at v: a cubic spline through 65 of its points (within 1e-6 of it).
  BSplineCurve profile(double v) const {
    std::vector<double> t;
    Eigen::MatrixXd pts(65, 3);
    for (int k = 0; k <= 64; ++k) {
      t.push_back(k / 64.0);
      pts.row(k) = (*this)(k / 64.0, v).transpose();
    }
    return fit_clamped_curve(t, pts, 3, uniform_clamped_knots(3, 32));
  }
  PdeBoundary hermite() const {
    PdeBoundary b;
    b.a.a = a;
    b.u0 = circle(r0, 0.0);
    b.u1 = circle(r1, height, 0.3, true);
    b.d0 = circle(r0 + s0, height, 0.1);
    b.d1 = circle(r1 + s1, 2.0 * height, 0.7);
    return b;
  }
};

double worst_against(const SheetProblem& pb, const Eigen::MatrixX3d& poles,
                     const std::function<Eigen::Vector3d(double, double)>& f) {
  const BSplineSurface surface{pb.space, poles};
  double out = 0.0;
  for (int i = 0; i <= 24; ++i)
    for (int j = 0; j <= 24; ++j)
      out = std::max(out, (surface.evaluate(i / 24.0, j / 24.0) - f(i / 24.0, j / 24.0)).norm());
  return out;
}

}  // namespace

// A Gordon network on a surface closed along v: interior circles of the closed-form solution (their
// seams anywhere, one drawn backwards) and profiles at v = 0, 0.2, 0.55 (one reversed) are
// curves the solution contains, so the surface is the solution, v placed by the profiles.
TEST(PdeSurface, ClosedNetworkGivesTheClosedFormSolution) {
  const BloorWilson bw;
  PdeBoundary b = bw.hermite();
  b.u_curves.push_back({0.35, circle(bw.f(0.35), 0.35 * bw.height, 0.45, true)});
  b.u_curves.push_back({0.7, circle(bw.f(0.7), 0.7 * bw.height, 0.8)});
  for (double v : {0.0, 0.2, 0.55}) b.v_curves.push_back({v, bw.profile(v)});
  b.v_curves[1].curve = reversed(b.v_curves[1].curve);
  PdeSurfaceOptions o;
  o.spans_u = 12;
  o.spans_v = 32;
  const SheetProblem pb = pde_surface_problem(b, o);
  EXPECT_TRUE(pb.closed_v);
  // Each circle is held on both sides of its own seam (two pieces), each profile whole.
  EXPECT_EQ(pb.curves.size(), 7u);
  SolveOptions opt;
  opt.fit_tolerance = 1e-5;
  const Eigen::MatrixX3d poles = solve_sheet(pb, opt).poles;
  EXPECT_LT(worst_against(pb, poles, bw), 1e-3 * bw.r0);
  EXPECT_LT(seam_mismatch(pb.space, poles, 1), 1e-6 * bw.r0);
}

// Network curves change a closed surface: a circle bulging out at u = 0.5 between two boundary
// circles (no Hermite data) is contained by the surface, whatever its seam and direction.
TEST(PdeSurface, ClosedNetworkCurvesAreContained) {
  PdeBoundary b;
  b.a.a = 0.4;
  b.u0 = circle(20.0, 0.0);
  b.u1 = circle(12.0, 30.0, 0.6);
  PdeSurfaceOptions o;
  o.spans_u = 10;
  o.spans_v = 24;
  SolveOptions opt;  // exact incidence: the answer does not depend on where the penalty stops
  opt.fit_tolerance = 0.0;
  const SheetProblem plain = pde_surface_problem(b, o);
  const Eigen::MatrixX3d plain_poles = solve_sheet(plain, opt).poles;
  Eigen::MatrixX3d first;
  for (const auto& [turn, backwards] : {std::pair{0.0, false}, {0.37, true}, {0.81, false}}) {
    b.u_curves = {{0.5, circle(26.0, 15.0, turn, backwards)}};
    const SheetProblem pb = pde_surface_problem(b, o);
    const Eigen::MatrixX3d poles = solve_sheet(pb, opt).poles;
    const BSplineSurface surface{pb.space, poles};
    double off = 0.0, plain_off = 0.0;
    for (int j = 0; j <= 96; ++j) {
      const Eigen::Vector3d p = surface.evaluate(0.5, j / 96.0);
      off = std::max(off, std::hypot(std::hypot(p.x(), p.y()) - 26.0, p.z() - 15.0));
      const Eigen::Vector3d q = BSplineSurface{plain.space, plain_poles}.evaluate(0.5, j / 96.0);
      plain_off = std::max(plain_off, std::hypot(std::hypot(q.x(), q.y()) - 26.0, q.z() - 15.0));
    }
    EXPECT_LT(off, 1e-3) << turn;
    EXPECT_GT(plain_off, 5.0);  // without the curve the surface passes far from it
    if (first.size() == 0)
      first = poles;
    else  // the same surface, whichever way the circle was drawn, to the sheet's own error of
          // a circle (24 cubic spans hold one of radius 26 to about 3e-4: where the circle's
          // pieces meet moves with its seam, and so does the least-squares fit)
      EXPECT_LT((poles - first).cwiseAbs().maxCoeff(), 1e-3) << turn;
  }
}

TEST(PdeSurface, BadClosedNetworksAreRefusedByName) {
  const BloorWilson bw;
  PdeBoundary b = bw.hermite();
  b.u_curves.push_back({0.5, bw.profile(0.3)});
  EXPECT_NE(message_of(b).find("u-curve 1 is open"), std::string::npos) << message_of(b);
  b = bw.hermite();
  b.v_curves.push_back({1.0, bw.profile(0.3)});
  EXPECT_NE(message_of(b).find("v-curve 1 lies at 1"), std::string::npos) << message_of(b);
  b = bw.hermite();
  b.v_curves.push_back({0.3, bw.profile(0.3)});
  b.v_curves[0].curve.poles.col(2).array() += 40.0;  // lifted off both circles
  EXPECT_NE(message_of(b).find("u0 and v-curve 1 do not meet"), std::string::npos) << message_of(b);
  b = bw.hermite();
  for (double v : {0.1, 0.4, 0.7}) b.v_curves.push_back({v, bw.profile(v)});
  std::swap(b.v_curves[0].at, b.v_curves[1].at);  // 0.4, 0.1, 0.7: not the way they lie
  EXPECT_NE(message_of(b).find("crosses the v-curves out of their order"), std::string::npos)
      << message_of(b);
}

TEST(PdeSurface, ClosedAndOpenBoundariesAreRefused) {
  PdeBoundary b;
  b.u0 = circle(10.0, 0.0);
  b.u1 = cubic([](double v) { return Eigen::Vector3d(10.0, 20.0 * v, 5.0); });
  EXPECT_NE(message_of(b).find("u0 is closed but u1 is open"), std::string::npos) << message_of(b);
  b.u1 = circle(8.0, 5.0);
  b.d0 = cubic([](double v) { return Eigen::Vector3d(12.0, 20.0 * v, 1.0); });
  EXPECT_NE(message_of(b).find("d0 is open"), std::string::npos) << message_of(b);
}
