// SPDX-License-Identifier: LGPL-2.1-or-later
// PDE surfaces from Du & Qin's boundary conditions: Hermite, Coons and Gordon data taken from a
// closed-form solution of (d_uu + a^2 d_vv)^2 P = 0 give that solution back; bad curves are
// refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "varsurf/core/curve_fit.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/core/pde_surface.hpp"
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
    const SheetProblem pb = pde_surface_problem(hermite_data(), o, &fit);
    EXPECT_LT(fit, 1e-12);
    const SolveResult r = solve_sheet(pb);
    EXPECT_LT(worst(pb, r.poles), 1e-8) << spans << " spans";
    // Tangents half as long across the boundaries: another surface (the derivative curves act).
    PdeBoundary shorter = hermite_data();
    shorter.magnitude0 = shorter.magnitude1 = 1.0;
    const SheetProblem other = pde_surface_problem(shorter, o);
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
  b.a.plate_form = true;
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
  EXPECT_LT(worst_p(pde_surface_problem(b, o)), 1e-8);
  b.a.plate_form = false;
  EXPECT_GT(worst_p(pde_surface_problem(b, o)), 1e-2);
}

TEST(PdeSurface, ReversedCurvesAreOrientedByTheirEnds) {
  PdeBoundary b = hermite_data();
  b.u1 = reversed(b.u1);
  b.d0 = reversed(b.d0);
  PdeSurfaceOptions o;
  o.spans_u = o.spans_v = 6;
  const SheetProblem pb = pde_surface_problem(b, o);
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
