// SPDX-License-Identifier: LGPL-2.1-or-later
// Detail-preserving editing of multiresolution Catmull-Clark surfaces against independent
// answers: the divided differences are exact on quadratic fields; pins are met by every solve;
// the level a pin is propagated to sets how much of the surface moves; a captured relief keeps its
// detail vectors through a large bend while the same bend applied to the finest mesh turns them;
// the edit commutes with rigid motions and scalings.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "flat_grid.hpp"
#include "varsurf/core/detail_edit.hpp"
#include "varsurf/core/errors.hpp"

using namespace varsurf;

namespace {

constexpr double kSpacing = 10.0;
constexpr int kCells = 10;  // the base plane's quads per side
constexpr double kSize = kSpacing * kCells;

// A flat kCells x kCells quad grid in the xy plane, corners at 0 and kSize.
SubdivisionMesh plane() {
  return test::flat_grid(kCells, kSpacing);
}

// A relief of wavelength 2.5 (4 finest edges at 4 levels) and amplitude 0.4, captured by
// vertical projection: detail at the finest levels only.
Eigen::Vector3d relief(const Eigen::Vector3d& p) {
  const double k = 2.0 * M_PI / 2.5;
  return {p.x(), p.y(), 0.4 * std::sin(k * p.x()) * std::sin(k * p.y())};
}

// The finest level's vertex nearest to (x, y).
int nearest(const DetailEditor& editor, const Multiresolution& m, double x, double y) {
  const Eigen::MatrixX3d finest = editor.points(m).back();
  Eigen::Index best = 0;
  (finest.leftCols(2).rowwise() - Eigen::RowVector2d(x, y)).rowwise().squaredNorm().minCoeff(&best);
  return static_cast<int>(best);
}

double moved_fraction(const Eigen::MatrixX3d& before, const Eigen::MatrixX3d& after) {
  const Eigen::VectorXd moves = (after - before).rowwise().norm();
  return static_cast<double>((moves.array() > 1e-6 * kSize).count()) /
         static_cast<double>(moves.size());
}

// Pearson's correlation of two sets of vectors, all components together.
double correlation(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  const Eigen::VectorXd x =
      Eigen::Map<const Eigen::VectorXd>(a.data(), a.size()).array() - a.mean();
  const Eigen::VectorXd y =
      Eigen::Map<const Eigen::VectorXd>(b.data(), b.size()).array() - b.mean();
  return x.dot(y) / (x.norm() * y.norm());
}

}  // namespace

TEST(DetailEnergy, DividedDifferencesAreExactOnQuadraticFields) {
  // A height field z = a x^2 / 2 + b x y + c y^2 / 2 + d x + e y on the flat grid: at interior
  // vertices the fitted quadratic is the field itself, so the invariants |grad|^2 and the
  // Hessian's squared norm come out exactly whatever direction the local parameters take.
  const double a = 0.03, b = -0.02, c = 0.05, d = 0.4, e = -0.7;
  const SubdivisionMesh m = plane();
  Eigen::VectorXd z(m.points.rows());
  for (Eigen::Index v = 0; v < z.size(); ++v) {
    const double x = m.points(v, 0), y = m.points(v, 1);
    z(v) = 0.5 * a * x * x + b * x * y + 0.5 * c * y * y + d * x + e * y;
  }
  const Eigen::VectorXd q = divided_differences(m) * z;
  int checked = 0;
  for (Eigen::Index v = 0; v < z.size(); ++v) {
    const double x = m.points(v, 0), y = m.points(v, 1);
    if (x <= 0.0 || y <= 0.0 || x >= kSize || y >= kSize) continue;
    const double gx = a * x + b * y + d, gy = b * x + c * y + e;
    EXPECT_NEAR(q(5 * v) * q(5 * v) + q(5 * v + 1) * q(5 * v + 1), gx * gx + gy * gy, 1e-10);
    EXPECT_NEAR(
        q(5 * v + 2) * q(5 * v + 2) + 2 * q(5 * v + 3) * q(5 * v + 3) + q(5 * v + 4) * q(5 * v + 4),
        a * a + 2 * b * b + c * c, 1e-12);
    ++checked;
  }
  EXPECT_EQ(checked, (kCells - 1) * (kCells - 1));
  // The energy of a translation is zero; that of a linear field is its stretch alone.
  const Eigen::SparseMatrix<double> h = detail_energy(m, {1.0, 1.0});
  EXPECT_LT(std::abs(Eigen::VectorXd::Ones(z.size()).dot(h * Eigen::VectorXd::Ones(z.size()))),
            1e-12);
}

TEST(DetailEdit, EverySolveMeetsThePins) {
  const Multiresolution m = capture(plane(), 3, relief);
  const DetailEditor editor(m.base, 3);
  const Eigen::MatrixX3d before = editor.points(m).back();
  const int v = nearest(editor, m, 50.0, 50.0), w = nearest(editor, m, 20.0, 70.0);
  std::vector<DetailPin> pins{{3, v, before.row(v).transpose() + Eigen::Vector3d(0, 0, 20.0), 0},
                              {3, w, before.row(w).transpose() + Eigen::Vector3d(3, -2, 5.0), 2}};
  for (const DetailSolve solve :
       {DetailSolve::approximate, DetailSolve::direct, DetailSolve::sor}) {
    DetailEditOptions options;
    options.solve = solve;
    const DetailEditResult r = editor.edit(m, pins, options);
    const Eigen::MatrixX3d after = editor.points(r.surface).back();
    EXPECT_LT((after.row(v).transpose() - pins[0].target).norm(), 1e-9 * kSize * 2);
    EXPECT_LT((after.row(w).transpose() - pins[1].target).norm(), 1e-9 * kSize * 2);
    EXPECT_LE(r.report.max_residual, 1e-9 * kSize * 2);
    // The fast points are reconstruct's.
    const std::vector<SubdivisionMesh> slow = reconstruct(r.surface);
    EXPECT_LT((slow.back().points - after).cwiseAbs().maxCoeff(), 1e-9);
    // The cached limit stencil is OpenSubdiv's limit of the finest level.
    EXPECT_LT(
        (subdivide(slow.back(), 0).limit_points - editor.limit(r.surface)).cwiseAbs().maxCoeff(),
        1e-9);
  }
}

TEST(DetailEdit, TheInfluenceLevelSetsHowMuchOfTheSurfaceMoves) {
  // The same pin (the finest vertex at the middle raised by a tenth of the model) propagated to
  // the base moves most of the surface; propagated to level L - 2, a small patch around it.
  const int levels = 4;
  const Multiresolution m = capture(plane(), levels, relief);
  const DetailEditor editor(m.base, levels);
  const Eigen::MatrixX3d before = editor.points(m).back();
  const int v = nearest(editor, m, 50.0, 50.0);
  const Eigen::Vector3d target = before.row(v).transpose() + Eigen::Vector3d(0, 0, 0.1 * kSize);
  double fraction[levels + 1] = {};
  for (int influence = 0; influence <= levels; ++influence) {
    const DetailEditResult r = editor.edit(m, {{levels, v, target, influence}}, {});
    fraction[influence] = moved_fraction(before, editor.points(r.surface).back());
    EXPECT_LT(r.report.max_residual, 1e-9 * kSize * 2) << influence;
    if (influence > 0) {
      EXPECT_LT(fraction[influence], fraction[influence - 1]) << influence;
    }
  }
  EXPECT_GE(fraction[0], 0.5);
  EXPECT_LT(fraction[levels - 2], 0.05);
  std::printf("moved fraction by influence level: %.4f %.4f %.4f %.4f %.4f\n", fraction[0],
              fraction[1], fraction[2], fraction[3], fraction[4]);
}

TEST(DetailEdit, ABendKeepsTheDetailVectorsWhileMovingTheFinestMeshTurnsThem) {
  // A relief captured on the plane, then the plane's middle raised by a third of its size at the
  // base level: the surface bends steeply. The detail vectors of the levels finer than the base,
  // measured again from the edited levels in their new frames, are the captured ones. The same
  // move given to the finest mesh's vertices directly (the naive edit: every vertex of the finest
  // level translated by the smooth deformation) leaves the relief pointing the old way, and its
  // detail vectors measured in the bent surface's frames no longer match.
  const int levels = 4;
  const Multiresolution m = capture(plane(), levels, relief);
  const DetailEditor editor(m.base, levels);
  const std::vector<Eigen::MatrixX3d> before = editor.points(m);
  const int v = nearest(editor, m, 50.0, 50.0);
  const Eigen::Vector3d target =
      before.back().row(v).transpose() + Eigen::Vector3d(0, 0, kSize / 3.0);
  const DetailEditResult r = editor.edit(m, {{levels, v, target, 0}}, {});
  ASSERT_LT(r.report.max_residual, 1e-9 * kSize * 2);
  const std::vector<Eigen::MatrixX3d> after = editor.points(r.surface);

  // The smooth deformation alone: the edited base, no details.
  Multiresolution smooth_before = m, smooth_after = r.surface;
  for (size_t k = 0; k < m.details.size(); ++k) {
    smooth_before.details[k].setZero();
    smooth_after.details[k].setZero();
  }
  const Eigen::MatrixX3d deformation =
      editor.points(smooth_after).back() - editor.points(smooth_before).back();
  const Eigen::MatrixX3d naive = before.back() + deformation;

  // The finest level's details measured against the level above, in that level's frames.
  auto measured = [&](const std::vector<Eigen::MatrixX3d>& pts, const Eigen::MatrixX3d& finest) {
    SubdivisionMesh coarse = editor.topology(levels - 1);
    coarse.points = pts[levels - 1];
    const SubdivisionLevels s = subdivide(coarse, 1);
    const Eigen::MatrixX3d frames = local_frames(s);
    Eigen::MatrixX3d d(finest.rows(), 3);
    for (Eigen::Index k = 0; k < d.rows(); ++k)
      d.row(k) =
          (frames.middleRows(3 * k, 3) * (finest.row(k) - s.levels[1].points.row(k)).transpose())
              .transpose();
    return d;
  };
  // Compared where the edit acted: the vertices the deformation moved by over 1 % of the model.
  std::vector<Eigen::Index> acted;
  for (Eigen::Index k = 0; k < deformation.rows(); ++k)
    if (deformation.row(k).norm() > 0.01 * kSize) acted.push_back(k);
  ASSERT_GT(acted.size(), deformation.rows() / 10);
  auto on_acted = [&](const Eigen::MatrixX3d& d) {
    Eigen::MatrixX3d out(static_cast<Eigen::Index>(acted.size()), 3);
    for (size_t k = 0; k < acted.size(); ++k)
      out.row(static_cast<Eigen::Index>(k)) = d.row(acted[k]);
    return out;
  };
  const Eigen::MatrixX3d original = on_acted(m.details.back());
  const double kept = correlation(on_acted(measured(after, after.back())), original);
  const double turned = correlation(on_acted(measured(after, naive)), original);
  EXPECT_GE(kept, 0.99);
  EXPECT_LT(turned, 0.9);
  // The bend is large: the surface's normal turns by more than 30 degrees somewhere.
  EXPECT_GT(deformation.col(2).maxCoeff(), kSize / 3.0 * 0.9);
  std::printf("detail correlation where the edit acted: kept %.6f, naive %.4f\n", kept, turned);
}

TEST(DetailEdit, TheEditCommutesWithRigidMotionsAndScalings) {
  const int levels = 3;
  const Multiresolution m = capture(plane(), levels, relief);
  const DetailEditor editor(m.base, levels);
  const Eigen::MatrixX3d finest = editor.points(m).back();
  const int v = nearest(editor, m, 40.0, 60.0), w = nearest(editor, m, 75.0, 25.0);
  const std::vector<DetailPin> pins{
      {levels, v, finest.row(v).transpose() + Eigen::Vector3d(2, 1, 15.0), 0},
      {levels, w, finest.row(w).transpose() + Eigen::Vector3d(0, 0, -4.0), 1}};
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(300, -120, 45);
  for (const double scale : {1.0, 0.01, 100.0}) {
    auto moved = [&](const Eigen::Vector3d& p) {
      return Eigen::Vector3d(scale * (turn * p) + shift);
    };
    Multiresolution mm = m;
    for (Eigen::Index k = 0; k < mm.base.points.rows(); ++k)
      mm.base.points.row(k) = moved(m.base.points.row(k).transpose()).transpose();
    for (auto& d : mm.details) d *= scale;  // details are in local frames: only the scale
    std::vector<DetailPin> moved_pins = pins;
    for (DetailPin& p : moved_pins) p.target = moved(p.target);
    for (const DetailSolve solve : {DetailSolve::approximate, DetailSolve::direct}) {
      DetailEditOptions options;
      options.solve = solve;
      const Eigen::MatrixX3d a = editor.points(editor.edit(m, pins, options).surface).back();
      const Eigen::MatrixX3d b = editor.points(editor.edit(mm, moved_pins, options).surface).back();
      double worst = 0.0;
      for (Eigen::Index k = 0; k < a.rows(); ++k)
        worst = std::max(worst, (moved(a.row(k).transpose()) - b.row(k).transpose()).norm());
      EXPECT_LT(worst, 1e-8 * scale * kSize) << scale;
    }
  }
}

TEST(DetailEdit, BadPinsAreRefusedByName) {
  const Multiresolution m = capture(plane(), 2, relief);
  const DetailEditor editor(m.base, 2);
  auto message = [&](const std::vector<DetailPin>& pins, DetailEditOptions options = {}) {
    try {
      editor.edit(m, pins, options);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const Eigen::Vector3d p(1, 2, 3);
  EXPECT_NE(message({{3, 0, p, 0}}).find("level 3 does not exist"), std::string::npos);
  EXPECT_NE(message({{1, 99999, p, 0}}).find("vertex 99999 of level 1"), std::string::npos);
  EXPECT_NE(message({{1, 5, p, 2}}).find("influence level must lie in 0..1"), std::string::npos);
  EXPECT_NE(message({{2, 5, p, 1}, {2, 5, p, 0}}).find("given twice"), std::string::npos);
  EXPECT_NE(message({{2, 5, Eigen::Vector3d(NAN, 0, 0), 1}}).find("not finite"), std::string::npos);
  DetailEditOptions bad;
  bad.omega = 2.5;
  EXPECT_NE(message({}, bad).find("(0, 2)"), std::string::npos);
  Multiresolution other = m;
  other.details[1].conservativeResize(7, 3);
  EXPECT_THROW(editor.edit(other, {}, {}), InvalidInput);
  EXPECT_THROW(DetailEditor(m.base, 0), InvalidInput);
  EXPECT_TRUE(message({}).empty());  // no pins: nothing to do
}

TEST(DetailEdit, PinsPropagateThroughTheCatmullClarkMasksOfTable1) {
  // The one-level refinement rows are the masks of the paper's Table 1 (with beta = 3 / 2k,
  // gamma = 1 / 4k): at an interior vertex of valence k, (1 - beta - gamma) on itself, beta / k on
  // each edge neighbour and gamma / k on each diagonal one; at a boundary vertex 3/4 and 1/8.
  auto check_vertex = [](const SubdivisionMesh& m, int v, int k, const std::vector<int>& edge,
                         const std::vector<int>& diagonal) {
    const Eigen::SparseMatrix<double> s = subdivision_step(m).refine;
    const double beta = 3.0 / (2.0 * k), gamma = 1.0 / (4.0 * k);
    EXPECT_NEAR(s.coeff(v, v), 1.0 - beta - gamma, 1e-15);
    for (int e : edge) EXPECT_NEAR(s.coeff(v, e), beta / k, 1e-15);
    for (int d : diagonal) EXPECT_NEAR(s.coeff(v, d), gamma / k, 1e-15);
    EXPECT_NEAR(Eigen::VectorXd(s.row(v).transpose()).sum(), 1.0, 1e-15);
  };
  const SubdivisionMesh p = plane();
  const int n = kCells + 1, c = 5 * n + 5;
  check_vertex(p, c, 4, {c - 1, c + 1, c - n, c + n}, {c - n - 1, c - n + 1, c + n - 1, c + n + 1});
  const Eigen::SparseMatrix<double> s = subdivision_step(p).refine;
  EXPECT_NEAR(s.coeff(5, 5), 0.75, 1e-15);  // a boundary vertex (x = 0)
  EXPECT_NEAR(s.coeff(5, 4), 0.125, 1e-15);
  EXPECT_NEAR(s.coeff(5, 6), 0.125, 1e-15);
  SubdivisionMesh cube;
  cube.points.resize(8, 3);
  for (int k = 0; k < 8; ++k) cube.points.row(k) << (k & 1), (k & 2) / 2, (k & 4) / 4;
  cube.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  check_vertex(cube, 0, 3, {1, 2, 4}, {3, 5, 6});
}

namespace {

// The angle between the normal of `level`'s mesh at `vertex`, from fresh divided differences,
// and the line of n; and the same for OpenSubdiv's limit normal there (finest level only).
double mesh_normal_angle(const DetailEditor& editor, const Multiresolution& m, int level,
                         int vertex, const Eigen::Vector3d& n) {
  SubdivisionMesh shape = editor.topology(level);
  shape.points = editor.points(m)[static_cast<size_t>(level)];
  const Eigen::MatrixXd q =
      Eigen::MatrixXd(divided_differences(shape, {vertex})).middleRows(5 * vertex, 2) *
      shape.points;
  const Eigen::Vector3d qu = q.row(0).transpose(), qv = q.row(1).transpose();
  const Eigen::Vector3d normal = qu.cross(qv);
  return std::atan2(normal.cross(n).norm(), std::abs(normal.dot(n)));
}

double limit_normal_angle(const Multiresolution& m, int vertex, const Eigen::Vector3d& n) {
  const SubdivisionLevels limit = subdivide(reconstruct(m).back(), 0);
  const Eigen::Vector3d tu = limit.limit_tangent_u.row(vertex).transpose();
  const Eigen::Vector3d tv = limit.limit_tangent_v.row(vertex).transpose();
  const Eigen::Vector3d normal = tu.cross(tv);
  return std::atan2(normal.cross(n).norm(), std::abs(normal.dot(n)));
}

Eigen::Vector3d no_relief(const Eigen::Vector3d& p) {
  return p;
}

}  // namespace

TEST(DetailEdit, NormalsAreMetByEverySolve) {
  // The middle of a flat plane raised by a fifth of its size with its normal held tilted 30
  // degrees about x, and a second normal tilted about y at a vertex of level 2: the tangents of
  // each constrained vertex end perpendicular to its normal, measured by fresh divided
  // differences of the edited mesh, and the pin is met.
  const int levels = 3;
  const Multiresolution m = capture(plane(), levels, no_relief);
  const DetailEditor editor(m.base, levels);
  const Eigen::MatrixX3d before = editor.points(m).back();
  const int v = nearest(editor, m, 50.0, 50.0);
  const Eigen::Vector3d tilt_x(0.0, std::sin(M_PI / 6), std::cos(M_PI / 6));
  const Eigen::Vector3d tilt_y(std::sin(0.2), 0.0, std::cos(0.2));
  const Eigen::MatrixX3d level2 = editor.points(m)[2];
  Eigen::Index w = 0;
  (level2.leftCols(2).rowwise() - Eigen::RowVector2d(25.0, 70.0))
      .rowwise()
      .squaredNorm()
      .minCoeff(&w);
  const std::vector<DetailPin> pins{
      {levels, v, before.row(v).transpose() + Eigen::Vector3d(0, 0, 20.0), 0}};
  const std::vector<DetailNormal> normals{{levels, v, tilt_x, 0},
                                          {2, static_cast<int>(w), 3.0 * tilt_y, 1}};
  for (const DetailSolve solve :
       {DetailSolve::approximate, DetailSolve::direct, DetailSolve::sor}) {
    DetailEditOptions options;
    options.solve = solve;
    const DetailEditResult r = editor.edit(m, pins, normals, options);
    EXPECT_LT(mesh_normal_angle(editor, r.surface, levels, v, tilt_x), 1e-6);
    EXPECT_LT(mesh_normal_angle(editor, r.surface, 2, static_cast<int>(w), tilt_y), 1e-6);
    EXPECT_LT(r.report.max_normal_angle, 1e-6);
    EXPECT_LE(r.report.max_residual, 1e-9 * kSize * 2);
    // The editor's normal there is the one held (up to its sign).
    EXPECT_GT(std::abs(editor.normal(r.surface, levels, v).dot(tilt_x)), 1.0 - 1e-12);
    // The limit surface's own normal there follows to a fraction of the tilt (the limit mask
    // averages the ring the constraint holds).
    if (solve == DetailSolve::direct)
      EXPECT_LT(limit_normal_angle(r.surface, v, tilt_x), 0.05 * M_PI / 6);
  }
  // Without the normals the raised middle stays level (symmetry): the constraint did the tilt.
  const DetailEditResult free = editor.edit(m, pins, {}, {});
  EXPECT_NEAR(mesh_normal_angle(editor, free.surface, levels, v, tilt_x), M_PI / 6, 1e-6);
}

TEST(DetailEdit, ANormalAlreadyMetLeavesThePinsSolutionAlone) {
  // Pins sliding vertices within a flat plane leave it flat, so a normal along z elsewhere holds
  // already: the coupled system (one unknown per coordinate) gives the three separate systems'
  // answer, for every solve (on the whole level: the normal's mask would widen a grown region).
  const int levels = 2;
  const Multiresolution m = capture(plane(), levels, no_relief);
  const DetailEditor editor(m.base, levels);
  const Eigen::MatrixX3d before = editor.points(m).back();
  const int v = nearest(editor, m, 40.0, 50.0), w = nearest(editor, m, 60.0, 55.0);
  const std::vector<DetailPin> pins{
      {levels, v, before.row(v).transpose() + Eigen::Vector3d(4, -3, 0), 0},
      {1, 30, editor.points(m)[1].row(30).transpose() + Eigen::Vector3d(-2, 1, 0), 0}};
  const std::vector<DetailNormal> normals{{levels, w, Eigen::Vector3d::UnitZ(), 0}};
  for (const DetailSolve solve :
       {DetailSolve::approximate, DetailSolve::direct, DetailSolve::sor}) {
    DetailEditOptions options;
    options.solve = solve;
    options.rings = 16;
    const Eigen::MatrixX3d separate = editor.points(editor.edit(m, pins, options).surface).back();
    const DetailEditResult coupled = editor.edit(m, pins, normals, options);
    EXPECT_LT((editor.points(coupled.surface).back() - separate).cwiseAbs().maxCoeff(),
              1e-7 * kSize);
    EXPECT_LT(separate.col(2).cwiseAbs().maxCoeff(), 1e-9 * kSize);
    EXPECT_GT((separate - before).cwiseAbs().maxCoeff(), 1.0);  // the pins did move it
  }
}

TEST(DetailEdit, NormalsCommuteWithRigidMotionsAndScalings) {
  const int levels = 3;
  const Multiresolution m = capture(plane(), levels, relief);
  const DetailEditor editor(m.base, levels);
  const Eigen::MatrixX3d finest = editor.points(m).back();
  const int v = nearest(editor, m, 40.0, 60.0), w = nearest(editor, m, 70.0, 30.0);
  const std::vector<DetailPin> pins{
      {levels, v, finest.row(v).transpose() + Eigen::Vector3d(2, 1, 15.0), 0}};
  const std::vector<DetailNormal> normals{{levels, v, Eigen::Vector3d(0.3, -0.2, 1.0), 0},
                                          {levels, w, Eigen::Vector3d(-0.4, 0.0, 1.0), 1}};
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(-1.1, Eigen::Vector3d(0.2, 1, -0.7).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(-50, 800, 12);
  for (const double scale : {1.0, 0.01, 100.0}) {
    auto moved = [&](const Eigen::Vector3d& p) {
      return Eigen::Vector3d(scale * (turn * p) + shift);
    };
    Multiresolution mm = m;
    for (Eigen::Index k = 0; k < mm.base.points.rows(); ++k)
      mm.base.points.row(k) = moved(m.base.points.row(k).transpose()).transpose();
    for (auto& d : mm.details) d *= scale;
    std::vector<DetailPin> moved_pins = pins;
    for (DetailPin& p : moved_pins) p.target = moved(p.target);
    std::vector<DetailNormal> moved_normals = normals;
    for (DetailNormal& n : moved_normals) n.normal = turn * n.normal;
    for (const DetailSolve solve : {DetailSolve::approximate, DetailSolve::direct}) {
      DetailEditOptions options;
      options.solve = solve;
      const DetailEditResult ra = editor.edit(m, pins, normals, options);
      const DetailEditResult rb = editor.edit(mm, moved_pins, moved_normals, options);
      const Eigen::MatrixX3d a = editor.points(ra.surface).back();
      const Eigen::MatrixX3d b = editor.points(rb.surface).back();
      double worst = 0.0;
      for (Eigen::Index k = 0; k < a.rows(); ++k)
        worst = std::max(worst, (moved(a.row(k).transpose()) - b.row(k).transpose()).norm());
      EXPECT_LT(worst, 1e-8 * scale * kSize) << scale;
      EXPECT_LT(rb.report.max_normal_angle, 1e-6) << scale;
    }
  }
}

TEST(DetailEdit, BadNormalsAreRefusedByName) {
  const Multiresolution m = capture(plane(), 2, relief);
  const DetailEditor editor(m.base, 2);
  auto message = [&](const std::vector<DetailNormal>& normals) {
    try {
      editor.edit(m, {}, normals, {});
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  EXPECT_NE(message({{3, 0, z, 0}}).find("the normal on vertex 0 of level 3"), std::string::npos);
  EXPECT_NE(message({{1, 99999, z, 0}}).find("has vertices 0.."), std::string::npos);
  EXPECT_NE(message({{1, 5, z, 2}}).find("influence level must lie in 0..1"), std::string::npos);
  EXPECT_NE(message({{2, 5, z, 1}, {2, 5, -z, 0}}).find("given twice"), std::string::npos);
  EXPECT_NE(message({{2, 5, Eigen::Vector3d::Zero(), 1}}).find("zero or not finite"),
            std::string::npos);
  EXPECT_NE(message({{2, 5, Eigen::Vector3d(0, INFINITY, 1), 1}}).find("zero or not finite"),
            std::string::npos);
  EXPECT_TRUE(message({{2, 5, z, 1}}).empty());
  EXPECT_THROW(editor.normal(m, 2, -1), InvalidInput);
  EXPECT_THROW(editor.normal(m, 3, 0), InvalidInput);
  // A flat plane's vertices all have the normal along z, corners included.
  const Multiresolution flat = capture(plane(), 2, no_relief);
  for (const int v : {0, 7, 40}) EXPECT_GT(std::abs(editor.normal(flat, 2, v).z()), 1.0 - 1e-12);
}
