// SPDX-License-Identifier: LGPL-2.1-or-later
// Solver benchmarks, one case per run so that peak memory belongs to that case alone. Prints one
// JSON object per line; bench/run_bench.py runs the cases, fits exponents and prints the tables.
//
//   varsurf_sheet_bench scaling <poles per direction> <interior curves> [mode]
//   varsurf_sheet_bench mb        Michalik & Bruderlin's sizes (TSVD / MTSVD)
//   varsurf_sheet_bench duqin     Du & Qin's sheet sizes
//   varsurf_sheet_bench penalty-multigrid <poles per direction> <weight>
//                                 a sheet held by 14 curves: the direct penalty solve against
//                                 multigrid-preconditioned CG on the same penalty system
#include <sys/resource.h>

#include <Eigen/LU>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "varsurf/core/constraints.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/heap_policy.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/core/multigrid.hpp"
#include "varsurf/core/sheet_solver.hpp"
#include "varsurf/core/thin_plate_energy.hpp"

using namespace varsurf;

namespace {

constexpr double kSize = 100.0;  // mm

double peak_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // KiB on Linux
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A cubic B-spline through f at `n` + 1 parameters (interpolation at the Greville points of a
// uniform space), enough to carry smooth waves.
BSplineCurve curve_through(int dim, int spans, const std::function<Eigen::VectorXd(double)>& f) {
  BSplineCurve c;
  c.degree = 3;
  c.knots = uniform_clamped_knots(3, spans, 0.0, 1.0);
  const int n = static_cast<int>(c.knots.size()) - 4;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n), rhs(n, dim);
  for (int i = 0; i < n; ++i) {
    const double t = (c.knots[static_cast<size_t>(i + 1)] + c.knots[static_cast<size_t>(i + 2)] +
                      c.knots[static_cast<size_t>(i + 3)]) /
                     3.0;
    BSplineCurve unit = c;
    unit.poles = Eigen::MatrixXd::Identity(n, n);
    a.row(i) = unit.evaluate(t).transpose();
    rhs.row(i) = f(t).transpose();
  }
  c.poles = a.partialPivLu().solve(rhs);
  return c;
}

BSplineCurve line2(double u0, double v0, double u1, double v1) {
  BSplineCurve c;
  c.degree = 1;
  c.knots = {0, 0, 1, 1};
  c.poles.resize(2, 2);
  c.poles << u0, v0, u1, v1;
  return c;
}

// A flat 100 x 100 mm bicubic sheet with `poles` poles per direction, bounded by four wavy
// boundary curves (z = 5 sin(2 pi t), corners at z = 0) and crossed by `interior` slanted
// non-isoparametric wavy curves that do not meet each other.
SheetProblem scaling_problem(int poles, int interior) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, poles - 3, poles - 3);
  pb.initial_poles.resize(pb.space.size(), 3);
  for (int i = 0; i < pb.space.nu(); ++i)
    for (int j = 0; j < pb.space.nv(); ++j) {
      double gu = 0, gv = 0;
      for (int k = 1; k <= 3; ++k) {
        gu += pb.space.knots_u[static_cast<size_t>(i + k)] / 3.0;
        gv += pb.space.knots_v[static_cast<size_t>(j + k)] / 3.0;
      }
      pb.initial_poles.row(pb.space.index(i, j)) << kSize * gu, kSize * gv, 0.0;
    }
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  const int spans = 32;
  auto boundary = [&](double u0, double v0, double u1, double v1, double phase) {
    CurveConstraint c;
    c.preimage = line2(u0, v0, u1, v1);
    c.target = curve_through(3, spans, [=](double t) {
      const double u = u0 + t * (u1 - u0), v = v0 + t * (v1 - v0);
      return Eigen::VectorXd(
          Eigen::Vector3d(kSize * u, kSize * v, 5.0 * std::sin(2 * M_PI * t + phase)));
    });
    pb.curves.push_back(c);
  };
  boundary(0, 0, 1, 0, 0.0);
  boundary(1, 0, 1, 1, 0.0);
  boundary(1, 1, 0, 1, 0.0);
  boundary(0, 1, 0, 0, 0.0);
  for (int j = 0; j < interior; ++j) {
    const double a = 0.08 + 0.084 * j;
    CurveConstraint c;
    c.preimage = line2(a, 0.08, a + 0.06, 0.92);
    c.target = curve_through(3, spans, [=](double t) {
      const double u = a + 0.06 * t, v = 0.08 + 0.84 * t;
      return Eigen::VectorXd(
          Eigen::Vector3d(kSize * u, kSize * v, 8.0 + 4.0 * std::sin(3 * M_PI * t + j)));
    });
    pb.curves.push_back(c);
  }
  return pb;
}

double max_parametric_deviation(const SheetProblem& pb, const Eigen::MatrixX3d& poles) {
  double worst = 0.0;
  for (const CurveConstraint& c : pb.curves)
    for (int k = 0; k <= 200; ++k) {
      const double t = k / 200.0;
      const Eigen::VectorXd uv = c.preimage.evaluate(t);
      const Eigen::Vector3d p =
          evaluate_surface(pb.space, poles, uv(0), uv(1), 0).row(0).transpose();
      worst = std::max(worst, (p - c.target.evaluate(t)).norm());
    }
  return worst;
}

SolveMode parse_mode(std::string name, bool& qr) {
  qr = name == "penalty-qr";
  if (qr) name = "penalty";
  for (SolveMode m : {SolveMode::automatic, SolveMode::exact, SolveMode::penalty, SolveMode::cg,
                      SolveMode::tsvd, SolveMode::mtsvd})
    if (name == to_string(m)) return m;
  throw std::runtime_error("unknown mode " + name);
}

int scaling(int poles, int interior, SolveMode mode, bool qr) {
  const SheetProblem pb = scaling_problem(poles, interior);
  SolveOptions opt;
  opt.mode = mode;
  opt.penalty_qr = qr;
  opt.fit_tolerance = 0.0025;  // what a Sheet uses at its default tolerance (0.01 mm / 4)
  // The first solve in a fresh process also pays for touching its memory for the first time;
  // FreeCAD's is warm after its first recompute. Both are printed: "first", and "full" as the
  // fastest of three (its stages are that solve's).
  double t0 = now();
  PreparedSheet prepared(pb, opt);
  const double first = now() - t0;
  double full = first;
  SolveReport r = prepared.result().report;  // a copy: change() below replaces it
  for (int rep = 0; rep < 2; ++rep) {
    t0 = now();
    PreparedSheet again(pb, opt);
    if (now() - t0 < full) {
      full = now() - t0;
      r = again.result().report;
    }
  }
  // Drag: one interior curve (or a boundary curve) moved up 2 mm, same pre-image.
  SheetProblem moved = pb;
  const size_t which = pb.curves.size() > 4 ? 4 : 0;
  moved.curves[which].target.poles.col(2).array() += 2.0;
  double drag = 1e300;
  for (int rep = 0; rep < 5; ++rep) {
    const double t = now();
    const SolveResult u = prepared.update(moved);
    drag = std::min(drag, now() - t);
    moved.curves[which].target.poles.col(2).array() += (rep % 2 ? 2.0 : -2.0);
    if (u.poles.rows() == 0) return 1;
  }
  const double max_dev = max_parametric_deviation(pb, prepared.result().poles);
  // A pin added: the constraint side rebuilt, the energy's assembly kept.
  SheetProblem pinned = pb;
  PointConstraint pin;
  pin.u = 0.5;
  pin.v = 0.5;
  pin.target = Eigen::Vector3d(0.5 * kSize, 0.5 * kSize, 10.0);
  pinned.points.push_back(pin);
  const double tc = now();
  const bool kept = prepared.change(pinned).report.factor_kept;
  const double change = now() - tc;
  std::printf(
      "{\"case\": \"scaling\", \"poles\": %d, \"interior\": %d, \"unknowns\": %d, "
      "\"mode\": \"%s%s\", \"assemble\": %.6f, \"reduce\": %.6f, \"factor\": %.6f, \"solve\": "
      "%.6f, "
      "\"full\": %.6f, \"first\": %.6f, \"drag\": %.6f, \"change\": %.6f, \"rank\": %d, \"inner\": "
      "%d, "
      "\"change_kept\": %s, \"peak_mib\": %.1f, "
      "\"max_dev\": %.3g}\n",
      poles, interior, r.unknowns, to_string(r.mode), qr ? " (QR)" : "", r.assemble_seconds,
      r.reduce_seconds, r.factor_seconds, r.solve_seconds, full, first, drag, change,
      r.constraint_rank, r.inner_iterations, kept ? "true" : "false", peak_mib(), max_dev);
  return 0;
}

// The fastest of three solves (seconds); `result` is the last one.
double best_of_three(const SheetProblem& pb, const SolveOptions& opt, SolveResult& result) {
  double best = 1e300;
  for (int rep = 0; rep < 3; ++rep) {
    const double t = now();
    result = solve_sheet(pb, opt);
    best = std::min(best, now() - t);
  }
  return best;
}

// Michalik & Bruderlin: a bicubic 8 x 10 sheet with one non-isoparametric curve, and a sheet of
// about 500 poles with more than 1000 constraint rows, solved by TSVD and MTSVD.
int mb() {
  struct Case {
    const char* name;
    int nu, nv, curves;
  };
  for (const Case& cs : {Case{"8x10, 1 curve", 8, 10, 1}, Case{"20x25, 6 curves", 20, 25, 6}}) {
    SheetProblem pb;
    pb.space = SplineSpace::uniform(3, 3, cs.nu - 3, cs.nv - 3);
    pb.initial_poles.resize(pb.space.size(), 3);
    for (int i = 0; i < pb.space.nu(); ++i)
      for (int j = 0; j < pb.space.nv(); ++j)
        pb.initial_poles.row(pb.space.index(i, j)) << kSize * i / (pb.space.nu() - 1),
            kSize * j / (pb.space.nv() - 1), 0.0;
    pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
    for (int k = 0; k < cs.curves; ++k) {
      const double a = 0.05 + 0.15 * k;
      CurveConstraint c;
      c.preimage = line2(a, 0.05, std::min(a + 0.2, 0.98), 0.95);
      c.target = curve_through(3, 48, [=](double t) {
        const double u = a + (std::min(a + 0.2, 0.98) - a) * t, v = 0.05 + 0.9 * t;
        return Eigen::VectorXd(Eigen::Vector3d(
            kSize * u, kSize * v, 10.0 * std::sin(4 * t + k) + 0.1 * std::sin(80 * t)));
      });
      pb.curves.push_back(c);
    }
    for (SolveMode mode : {SolveMode::tsvd, SolveMode::mtsvd, SolveMode::exact}) {
      SolveOptions opt;
      opt.mode = mode;
      SolveResult res;
      const double best = best_of_three(pb, opt, res);
      std::printf(
          "{\"case\": \"mb\", \"name\": \"%s\", \"poles\": %d, \"rows\": %d, \"mode\": \"%s\", "
          "\"seconds\": %.6f, \"assemble\": %.6f, \"reduce\": %.6f, \"factor\": %.6f, "
          "\"solve\": %.6f, \"corner\": %d, \"directions\": %zu, \"max_dev\": %.3g}\n",
          cs.name, pb.space.size(), res.report.constraint_samples, to_string(mode), best,
          res.report.assemble_seconds, res.report.reduce_seconds, res.report.factor_seconds,
          res.report.solve_seconds, res.report.lcurve.corner, res.report.lcurve.k.size(),
          max_parametric_deviation(pb, res.poles));
    }
  }
  return 0;
}

int duqin() {
  for (int n : {15, 30, 60}) {
    const SheetProblem pb = scaling_problem(n, 3);
    SolveOptions opt;
    opt.fit_tolerance = 0.0025;
    SolveResult res;
    const double best = best_of_three(pb, opt, res);
    std::printf(
        "{\"case\": \"duqin\", \"poles\": %d, \"unknowns\": %d, \"seconds\": %.6f, "
        "\"max_dev\": %.3g}\n",
        n, res.report.unknowns, best, max_parametric_deviation(pb, res.poles));
  }
  return 0;
}

// Why Automatic keeps multigrid to sheets held by fixed poles: a sheet held by curves is a
// penalty system Q + mu^2 B^T B whose heavy term the B-spline levels' smoothing does not reach.
// The same refinement as the solver's penalty mode (W&W's: x = K^-1 (f + mu^2 B^T d_k), d_k+1 =
// d_k + d - B x, until every curve's RMS is within the tolerance), each step by multigrid-
// preconditioned conjugate gradients (to 1e-6), against solve_sheet's direct penalty solve.
// `weight` is mu^2 relative to the energy's and the samples' scales (the solver's is 1e4: CG
// then stalls; lighter weights take more steps).
int penalty_multigrid(int poles, double weight) {
  using Sparse = Eigen::SparseMatrix<double>;
  const SheetProblem pb = scaling_problem(poles, 10);
  SolveOptions opt;
  opt.fit_tolerance = 0.0025;
  double t = now();
  const SolveResult direct = solve_sheet(pb, opt);
  const double direct_seconds = now() - t;
  t = now();
  const Sparse q = assemble_thin_plate(pb.space, pb.energy);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<int> block_end;
  std::vector<double> block_weight;
  std::vector<Eigen::RowVector3d> data;
  for (const CurveConstraint& c : pb.curves) {
    const ConstraintSamples s = sample_curve(pb.space, c);
    double w = 0.0;
    for (int r = 0; r < s.rows(); ++r) {
      const int row = static_cast<int>(data.size());
      for (size_t k = 0; k < s.index[static_cast<size_t>(r)].size(); ++k)
        entries.emplace_back(row, s.index[static_cast<size_t>(r)][k],
                             s.coeff[static_cast<size_t>(r)](static_cast<Eigen::Index>(k)));
      data.push_back(s.rhs.row(r));
      w += s.weight[static_cast<size_t>(r)];
    }
    block_end.push_back(static_cast<int>(data.size()));
    block_weight.push_back(w);
  }
  Sparse b(static_cast<Eigen::Index>(data.size()), pb.space.size());
  b.setFromTriplets(entries.begin(), entries.end());
  Eigen::MatrixX3d d(b.rows(), 3);
  for (Eigen::Index r = 0; r < b.rows(); ++r) d.row(r) = data[static_cast<size_t>(r)];
  const Sparse btb = Sparse(b.transpose()) * b;
  const double mu2 = weight * q.diagonal().mean() / btb.diagonal().mean();
  const Sparse k = q + mu2 * btb;
  MultigridOptions mo;
  mo.tolerance = 1e-6;
  Eigen::MatrixX3d x = pb.initial_poles, dk = d;
  int steps = 0, iterations = 0;
  bool met = false;
  try {
    while (!met && steps < 50) {
      MultigridReport rep;
      x = solve_multigrid(pb.space, k, mu2 * (b.transpose() * dk), x, {}, mo, &rep);
      iterations += rep.iterations;
      ++steps;
      const Eigen::MatrixX3d res = d - b * x;
      met = true;
      for (size_t i = 0, start = 0; i < block_end.size(); start = block_end[i++])
        if (std::sqrt(res.middleRows(static_cast<Eigen::Index>(start),
                                     block_end[i] - static_cast<Eigen::Index>(start))
                          .squaredNorm() /
                      block_weight[i]) > opt.fit_tolerance)
          met = false;
      dk += res;
    }
  } catch (const SolveFailure&) {
    met = false;  // conjugate gradients stalled
  }
  std::printf(
      "{\"case\": \"penalty-multigrid\", \"poles\": %d, \"weight\": %g, \"direct\": %.4f, "
      "\"direct_max_dev\": %.3g, \"multigrid\": %.4f, \"steps\": %d, \"cg_iterations\": %d, "
      "\"met\": %s, \"multigrid_max_dev\": %.3g, \"multigrid_over_direct\": %.2f}\n",
      poles, weight, direct_seconds, max_parametric_deviation(pb, direct.poles), now() - t, steps,
      iterations, met ? "true" : "false", max_parametric_deviation(pb, x),
      (now() - t) / direct_seconds);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // The heap policy the Python module sets when it loads: measured as FreeCAD runs the solver.
  varsurf::keep_freed_heap();
  try {
    const std::string what = argc > 1 ? argv[1] : "";
    if (what == "scaling" && (argc == 4 || argc == 5)) {
      bool qr = false;
      const SolveMode mode = parse_mode(argc == 5 ? argv[4] : "automatic", qr);
      return scaling(std::atoi(argv[2]), std::atoi(argv[3]), mode, qr);
    }
    if (what == "mb") return mb();
    if (what == "duqin") return duqin();
    if (what == "penalty-multigrid" && argc == 4)
      return penalty_multigrid(std::atoi(argv[2]), std::atof(argv[3]));
    std::fprintf(stderr,
                 "usage: %s scaling <poles> <interior> [mode] | mb | duqin | penalty-multigrid "
                 "<poles> <weight>\n",
                 argv[0]);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
