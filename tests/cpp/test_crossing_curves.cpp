// Curves that cross: two arcs crossing at one point and height over a flat 120 x 90 mm sheet
// (boundary held, the flat sheet as rest shape) are met without throwing poles, in every mode and
// at every resolution. The rows of the two arcs near the crossing and at the short arc's steep
// ends (53 degrees) ask for slightly different things; fitting their difference once put poles
// 260 mm below a 6 mm dome on 16 spans while the curves were met. A space too coarse to hold the
// arcs fairly now leaves them unmet (for a refining caller), never met by a wild sheet.
//
// Bounds: a thin plate without tension continues a steep arc end below the sheet before the held
// boundary brings it back; on 128 spans the scene undershoots 0.68 arc heights (bend only) and
// 0.11 (stretch 1), coarser spaces more. On 64 spans the sheet must stay above -1.75 and -0.5 arc
// heights; on 16 and 32 spans (too coarse: the arcs are left unmet there, measured down to -0.87
// arc heights with stretch 1) above -1.75 arc heights. The defect went 20 to 40 arc heights below.
// On 64 spans the arcs are met to 1.5 times the tolerance here (measured 0.0119 mm for 0.01: the
// core fits to the RMS fit tolerance; a Sheet's deviation check and refinement complete it, see
// tests/python/test_crossing_curves.py, which measures the finished sheet with OCCT).
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/sheet_solver.hpp"
#include "varsurf/core/thin_plate_energy.hpp"

using namespace varsurf;

namespace {

constexpr double kHeight = 6.0;
constexpr double kTolerance = 0.01;
const SolveMode kAllModes[] = {SolveMode::exact, SolveMode::penalty, SolveMode::cg,
                               SolveMode::tsvd,  SolveMode::mtsvd,   SolveMode::automatic};

Eigen::Vector2d uv_of(double x, double y) {
  return {(x + 60.0) / 120.0, (y + 45.0) / 90.0};
}

// The arc over the segment (x0, y0) -> (x1, y1) of the sheet rising to `top` at its middle, as
// a piecewise quintic (exact to ~1e-9 mm), with the segment's (u, v) line as pre-image.
CurveConstraint arc(double x0, double y0, double x1, double y1, double top) {
  const double half = 0.5 * std::hypot(x1 - x0, y1 - y0);
  const double centre = (top * top - half * half) / (2.0 * top) - top;  // below the chord: < 0
  const double radius = top - centre;
  CurveConstraint c;
  c.preimage = test::line_curve(uv_of(x0, y0), uv_of(x1, y1));
  std::vector<double> breaks;
  for (int i = 0; i <= 16; ++i) breaks.push_back(i / 16.0);
  c.target = test::fit_piecewise_curve(breaks, 5, 3, [=](double t) {
    const double s = (2.0 * t - 1.0) * half;  // from the chord's middle
    return Eigen::VectorXd(Eigen::Vector3d(x0 + t * (x1 - x0), y0 + t * (y1 - y0),
                                           std::sqrt(radius * radius - s * s) + centre));
  });
  return c;
}

SheetProblem flat_sheet(int spans, double stretch, const std::vector<CurveConstraint>& curves) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  // Linear functions have their Greville abscissae as poles: the flat sheet, exactly.
  const std::vector<double> gu = test::greville(pb.space.knots_u, 3);
  const std::vector<double> gv = test::greville(pb.space.knots_v, 3);
  pb.initial_poles.resize(pb.space.size(), 3);
  for (int a = 0; a < pb.space.nu(); ++a)
    for (int b = 0; b < pb.space.nv(); ++b)
      pb.initial_poles.row(pb.space.index(a, b)) << -60.0 + 120.0 * gu[static_cast<size_t>(a)],
          -45.0 + 90.0 * gv[static_cast<size_t>(b)], 0.0;
  pb.rest_poles = pb.initial_poles;
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(stretch, 1.0);
  pb.curves = curves;
  return pb;
}

SolveOptions options(SolveMode mode) {
  SolveOptions o;
  o.mode = mode;
  o.fit_tolerance = 0.25 * kTolerance;  // what a Sheet asks for its tolerance
  return o;
}

// Lowest and highest point of the sheet on a 121 x 91 parameter grid.
std::pair<double, double> height_range(const SheetProblem& pb, const Eigen::MatrixX3d& poles) {
  double low = 1e300, high = -1e300;
  for (int i = 0; i <= 120; ++i)
    for (int j = 0; j <= 90; ++j) {
      const double z = evaluate_surface(pb.space, poles, i / 120.0, j / 90.0, 0)(0, 2);
      low = std::min(low, z);
      high = std::max(high, z);
    }
  return {low, high};
}

std::vector<CurveConstraint> crossing_arcs(double second_top = kHeight) {
  return {arc(-20, 0, 20, 0, kHeight), arc(0, -12, 0, 12, second_top)};
}

}  // namespace

TEST(CrossingCurves, ArcsCrossingAtOneHeightStayFairAtEveryResolution) {
  for (double stretch : {0.0, 1.0}) {
    for (int spans : {16, 32, 64})
      for (SolveMode mode : kAllModes) {
        const double undershoot = (stretch == 0.0 || spans < 64 ? 1.75 : 0.5) * kHeight;
        const SheetProblem pb = flat_sheet(spans, stretch, crossing_arcs());
        const SolveResult r = solve_sheet(pb, options(mode));
        const auto [low, high] = height_range(pb, r.poles);
        EXPECT_GE(low, -undershoot)
            << to_string(mode) << " spans " << spans << " stretch " << stretch;
        EXPECT_LE(high, kHeight + kTolerance) << to_string(mode) << " spans " << spans;
        if (spans == 64)  // fine enough to hold the arcs: met, as the refining caller needs
          for (const CurveConstraint& c : pb.curves)
            EXPECT_LE(incidence_error(pb.space, r.poles, c, 400), 1.5 * kTolerance)
                << to_string(mode) << " stretch " << stretch;
      }
  }
}

TEST(CrossingCurves, ThreeArcsThroughOnePointAndCrossingLines) {
  std::vector<CurveConstraint> three = crossing_arcs();
  three.push_back(arc(-10, -10, 10, 10, kHeight));
  CurveConstraint along = arc(-20, 0, 20, 0, kHeight), across = arc(0, -12, 0, 12, kHeight);
  along.target = test::line_curve(Eigen::Vector3d(-20, 0, 5), Eigen::Vector3d(20, 0, 5));
  across.target = test::line_curve(Eigen::Vector3d(0, -12, 5), Eigen::Vector3d(0, 12, 5));
  for (const auto& [curves, top] :
       {std::make_pair(three, kHeight), std::make_pair(std::vector{along, across}, 5.0)})
    for (SolveMode mode : {SolveMode::exact, SolveMode::penalty, SolveMode::cg}) {
      const SheetProblem pb = flat_sheet(64, 1.0, curves);
      const SolveResult r = solve_sheet(pb, options(mode));
      const auto [low, high] = height_range(pb, r.poles);
      EXPECT_GE(low, -0.5 * kHeight) << to_string(mode) << " " << curves.size() << " curves";
      EXPECT_LE(high, top + kTolerance) << to_string(mode);
      for (const CurveConstraint& c : pb.curves)
        EXPECT_LE(incidence_error(pb.space, r.poles, c, 400), 1.5 * kTolerance) << to_string(mode);
    }
}

TEST(CrossingCurves, HeightsDifferingByLessThanTheToleranceAreMetByMoreContradict) {
  for (SolveMode mode : {SolveMode::exact, SolveMode::penalty, SolveMode::cg}) {
    const SheetProblem near = flat_sheet(64, 1.0, crossing_arcs(kHeight + 0.4 * kTolerance));
    const SolveResult met = solve_sheet(near, options(mode));
    EXPECT_LE(met.report.conflict, kTolerance) << to_string(mode);
    const auto [low, high] = height_range(near, met.poles);
    EXPECT_GE(low, -0.5 * kHeight) << to_string(mode);
    for (const CurveConstraint& c : near.curves)
      EXPECT_LE(incidence_error(near.space, met.poles, c, 400), 1.5 * kTolerance)
          << to_string(mode);
    // Half a millimetre apart where they cross: no sheet meets both, and the solve says by how
    // much (the RMS over the arcs of a 0.5 mm disagreement at one point) instead of hiding it.
    const SheetProblem far = flat_sheet(64, 1.0, crossing_arcs(kHeight + 0.5));
    const SolveResult apart = solve_sheet(far, options(mode));
    EXPECT_GT(apart.report.conflict, kTolerance) << to_string(mode);
  }
}
