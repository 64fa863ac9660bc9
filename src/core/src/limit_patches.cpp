// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/limit_patches.hpp"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>

#include <Eigen/Dense>
#include <algorithm>
#include <memory>
#include <string>

#include "bicubic_bezier.hpp"
#include "osd_refiner.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

using namespace OpenSubdiv;

// A mesh refined adaptively, its patch table and every point its patches use: the refined
// vertices of all levels, then the end caps' local points.
struct Evaluator {
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::unique_ptr<Far::PatchTable> table;
  std::unique_ptr<Far::PatchMap> map;
  std::vector<OsdPoint> points;

  Evaluator(const SubdivisionMesh& mesh, int isolation,
            Far::PatchTableFactory::Options::EndCapType end_caps) {
    refiner = make_refiner(mesh);
    Far::TopologyRefiner::AdaptiveOptions adaptive(isolation);
    adaptive.useInfSharpPatch = true;
    refiner->RefineAdaptive(adaptive);
    Far::PatchTableFactory::Options options(isolation);
    options.SetEndCapType(end_caps);
    options.useInfSharpPatch = true;
    options.SetPatchPrecision<double>();
    table.reset(Far::PatchTableFactory::Create(*refiner, options));
    const int total = refiner->GetNumVerticesTotal();
    points.resize(static_cast<size_t>(total + table->GetNumLocalPoints()));
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i)
      for (int c = 0; c < 3; ++c) points[static_cast<size_t>(i)].p[c] = mesh.points(i, c);
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    OsdPoint* src = points.data();
    for (int level = 1; level <= refiner->GetMaxLevel(); ++level) {
      OsdPoint* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
      primvar.Interpolate(level, src, dst);
      src = dst;
    }
    // The end caps' points from their stencils (ComputeLocalPointValues assumes float ones).
    if (table->GetNumLocalPoints() > 0)
      table->GetLocalPointStencilTable<double>()->UpdateValues(points.data(),
                                                               points.data() + total);
    map.reset(new Far::PatchMap(*table));
  }

  // The point at (u, v) of a face, in the face's own coordinates.
  Eigen::Vector3d at(int face, double u, double v) const { return derivatives(face, u, v).col(0); }

  // Columns: the point, d/du, d/dv, d2/du2, d2/dudv, d2/dv2 at (u, v) of a face.
  Eigen::Matrix<double, 3, 6> derivatives(int face, double u, double v) const {
    const Far::PatchTable::PatchHandle* handle = map->FindPatch(face, u, v);
    if (!handle) throw SolveFailure("OpenSubdiv has no patch at a face's point");
    double w[6][20];
    table->EvaluateBasis(*handle, u, v, w[0], w[1], w[2], w[3], w[4], w[5]);
    const Far::ConstIndexArray cvs = table->GetPatchVertices(*handle);
    Eigen::Matrix<double, 3, 6> d = Eigen::Matrix<double, 3, 6>::Zero();
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < cvs.size(); ++k)
        for (int c = 0; c < 3; ++c) d(c, j) += w[j][k] * points[static_cast<size_t>(cvs[k])].p[c];
    return d;
  }
};

void require_quads(const SubdivisionMesh& mesh) {
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    if (mesh.faces[f].size() != 4)
      throw InvalidInput("face " + std::to_string(f) + " has " +
                         std::to_string(mesh.faces[f].size()) +
                         " sides: limit patches need a quad mesh (refine it once)");
}

}  // namespace

LimitPatches limit_patches(const SubdivisionMesh& mesh, int isolation) {
  validate_mesh(mesh, 0);
  require_quads(mesh);
  if (isolation < 1 || isolation > 10) throw InvalidInput("the isolation level must be 1..10");
  const Evaluator e(mesh, isolation, Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS);
  LimitPatches out;
  for (int array = 0; array < e.table->GetNumPatchArrays(); ++array)
    for (int patch = 0; patch < e.table->GetNumPatches(array); ++patch) {
      const Far::PatchParam param = e.table->GetPatchParam(array, patch);
      LimitPatch p;
      p.face = param.GetFaceId();
      p.regular = param.IsRegular();
      double u0 = 0.0, v0 = 0.0, u1 = 1.0, v1 = 1.0;
      param.Unnormalize(u0, v0);
      param.Unnormalize(u1, v1);
      p.u0 = u0;
      p.v0 = v0;
      p.size = u1 - u0;
      p.surface.space = SplineSpace::uniform(3, 3, 1, 1);
      p.surface.poles = bicubic_bezier(
          [&](double s, double t) { return e.at(p.face, u0 + p.size * s, v0 + p.size * t); });
      (p.regular ? out.regular : out.end_caps) += 1;
      out.patches.push_back(std::move(p));
    }
  return out;
}

double end_cap_deviation(const SubdivisionMesh& mesh, const LimitPatches& patches,
                         int reference_isolation, int samples) {
  validate_mesh(mesh, 0);
  require_quads(mesh);
  if (reference_isolation < 1 || reference_isolation > 10 || samples < 2 || samples > 100)
    throw InvalidInput("the reference isolation must be 1..10 and the samples 2..100");
  const Evaluator reference(mesh, reference_isolation,
                            Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  double worst = 0.0;
  const int faces = static_cast<int>(mesh.faces.size());
  for (const LimitPatch& p : patches.patches) {
    if (p.regular) continue;
    if (p.face < 0 || p.face >= faces || !(p.size > 0.0) || !(p.u0 >= 0.0) || !(p.v0 >= 0.0) ||
        p.u0 + p.size > 1.0 || p.v0 + p.size > 1.0)
      throw InvalidInput("the patches are not this mesh's: make them of it");
    for (int i = 0; i < samples; ++i)
      for (int j = 0; j < samples; ++j) {
        const double s = i / (samples - 1.0), t = j / (samples - 1.0);
        const Eigen::Vector3d mine = p.surface.evaluate(s, t);
        const Eigen::Vector3d exact = reference.at(p.face, p.u0 + p.size * s, p.v0 + p.size * t);
        worst = std::max(worst, (mine - exact).norm());
      }
  }
  return worst;
}

double limit_curvature(const SubdivisionMesh& mesh, int face, double u, double v, int isolation) {
  validate_mesh(mesh, 0);
  require_quads(mesh);
  if (isolation < 1 || isolation > 10) throw InvalidInput("the isolation level must be 1..10");
  if (face < 0 || face >= static_cast<int>(mesh.faces.size()) || !(u >= 0.0 && u <= 1.0) ||
      !(v >= 0.0 && v <= 1.0))
    throw InvalidInput("no such face or (u, v) outside [0, 1]^2");
  const Evaluator e(mesh, isolation, Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  const Eigen::Matrix<double, 3, 6> d = e.derivatives(face, u, v);
  const Eigen::Vector3d su = d.col(1), sv = d.col(2), n = su.cross(sv).normalized();
  Eigen::Matrix2d first, second;
  first << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
  second << d.col(3).dot(n), d.col(4).dot(n), d.col(4).dot(n), d.col(5).dot(n);
  // The shape operator's eigenvalues are the principal curvatures: trace(S^2) their squares' sum.
  const Eigen::Matrix2d shape = first.inverse() * second;
  return (shape * shape).trace();
}

}  // namespace varsurf
