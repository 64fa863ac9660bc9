// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/subdivision.hpp"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include "osd_refiner.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

using namespace OpenSubdiv;
using Descriptor = Far::TopologyDescriptor;
using Factory = Far::TopologyRefinerFactory<Descriptor>;

using Point = OsdPoint;

// OpenSubdiv reports topology errors through a global callback: the last message is kept (under
// a lock, the callback being process-wide) and raised as InvalidInput.
std::mutex error_lock;
std::string last_error;
void keep_error(Far::ErrorType, const char* message) {
  last_error = message ? message : "topology refused";
}

}  // namespace

void validate_mesh(const SubdivisionMesh& mesh, int levels) {
  if (levels < 0 || levels > 8) throw InvalidInput("subdivision levels must be in 0..8");
  const int n = static_cast<int>(mesh.points.rows());
  if (n == 0 || mesh.faces.empty()) throw InvalidInput("the control mesh has no faces");
  if (!mesh.points.allFinite())
    throw InvalidInput("the control mesh has points that are not finite");
  std::set<std::pair<int, int>> edges;
  // Each directed edge names the face running it: a second face running it the same way is an
  // inconsistent orientation, a third face on an edge a non-manifold edge (OpenSubdiv would
  // accept both and refine a surface whose normals flip).
  std::map<std::pair<int, int>, size_t> directed;
  std::map<std::pair<int, int>, int> uses;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const std::vector<int>& face = mesh.faces[f];
    if (face.size() < 3)
      throw InvalidInput("face " + std::to_string(f) +
                         " of the control mesh has fewer than 3 vertices");
    for (size_t k = 0; k < face.size(); ++k) {
      if (face[k] < 0 || face[k] >= n)
        throw InvalidInput("face " + std::to_string(f) + " names vertex " +
                           std::to_string(face[k]) + ", not one of the mesh's " +
                           std::to_string(n));
      const int a = face[k], b = face[(k + 1) % face.size()];
      if (a == b)
        throw InvalidInput("face " + std::to_string(f) + " repeats vertex " + std::to_string(a) +
                           " along an edge");
      edges.insert({std::min(a, b), std::max(a, b)});
      if (++uses[{std::min(a, b), std::max(a, b)}] > 2)
        throw InvalidInput(
            "edge " + std::to_string(a) + "-" + std::to_string(b) +
            " has more than two faces: the mesh is not manifold (remove the extra faces)");
      const auto [other, fresh] = directed.insert({{a, b}, f});
      if (!fresh)
        throw InvalidInput("faces " + std::to_string(other->second) + " and " + std::to_string(f) +
                           " both run edge " + std::to_string(a) + "-" + std::to_string(b) +
                           " the same way: the mesh is inconsistently oriented (turn one of "
                           "them over)");
    }
  }
  for (const auto& [edge, sharpness] : mesh.creases) {
    const auto [a, b] = edge;
    if (!edges.count({std::min(a, b), std::max(a, b)}))
      throw InvalidInput("crease " + std::to_string(a) + "-" + std::to_string(b) +
                         " is not an edge of the control mesh");
    if (!(sharpness >= 0.0) || !std::isfinite(sharpness))
      throw InvalidInput("a crease's sharpness must be a finite number >= 0");
  }
}

std::unique_ptr<Far::TopologyRefiner> make_refiner(const SubdivisionMesh& mesh) {
  std::vector<int> counts, indices, crease_pairs;
  std::vector<float> crease_weights;
  for (const std::vector<int>& face : mesh.faces) {
    counts.push_back(static_cast<int>(face.size()));
    indices.insert(indices.end(), face.begin(), face.end());
  }
  for (const auto& [edge, sharpness] : mesh.creases) {
    crease_pairs.push_back(edge.first);
    crease_pairs.push_back(edge.second);
    crease_weights.push_back(static_cast<float>(sharpness));
  }
  Descriptor desc;
  desc.numVertices = static_cast<int>(mesh.points.rows());
  desc.numFaces = static_cast<int>(mesh.faces.size());
  desc.numVertsPerFace = counts.data();
  desc.vertIndicesPerFace = indices.data();
  desc.numCreases = static_cast<int>(crease_weights.size());
  desc.creaseVertexIndexPairs = crease_pairs.data();
  desc.creaseWeights = crease_weights.data();
  Sdc::Options options;
  options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::lock_guard<std::mutex> lock(error_lock);
  last_error.clear();
  Far::SetErrorCallback(keep_error);
  refiner.reset(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, options)));
  Far::SetErrorCallback(nullptr);
  if (!refiner)
    throw InvalidInput("OpenSubdiv refused the control mesh: " +
                       (last_error.empty() ? std::string("invalid topology") : last_error));
  return refiner;
}

SubdivisionLevels subdivide(const SubdivisionMesh& mesh, int levels) {
  validate_mesh(mesh, levels);
  std::unique_ptr<Far::TopologyRefiner> refiner = make_refiner(mesh);
  Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);

  SubdivisionLevels out;
  out.levels.push_back({mesh.points, mesh.faces, mesh.creases});
  std::vector<Point> current(static_cast<size_t>(mesh.points.rows()));
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i)
    for (int c = 0; c < 3; ++c) current[static_cast<size_t>(i)].p[c] = mesh.points(i, c);
  Far::PrimvarRefinerReal<double> primvar(*refiner);
  for (int level = 1; level <= levels; ++level) {
    const Far::TopologyLevel& topo = refiner->GetLevel(level);
    std::vector<Point> next(static_cast<size_t>(topo.GetNumVertices()));
    primvar.Interpolate(level, current, next);
    SubdivisionMesh refined;
    refined.points.resize(topo.GetNumVertices(), 3);
    for (int i = 0; i < topo.GetNumVertices(); ++i)
      for (int c = 0; c < 3; ++c) refined.points(i, c) = next[static_cast<size_t>(i)].p[c];
    for (int f = 0; f < topo.GetNumFaces(); ++f) {
      const Far::ConstIndexArray verts = topo.GetFaceVertices(f);
      refined.faces.emplace_back(verts.begin(), verts.end());
    }
    // The creases' sharpness as refinement left it (boundary edges are sharp by the boundary
    // rule already), so that refining this level again continues the base's creases.
    for (int e = 0; e < topo.GetNumEdges(); ++e)
      if (topo.GetEdgeSharpness(e) > 0.0f && topo.GetEdgeFaces(e).size() == 2) {
        const Far::ConstIndexArray ends = topo.GetEdgeVertices(e);
        refined.creases.push_back({{ends[0], ends[1]}, topo.GetEdgeSharpness(e)});
      }
    out.levels.push_back(std::move(refined));
    current = std::move(next);
  }
  const size_t count = current.size();
  std::vector<Point> pos(count), du(count), dv(count);
  primvar.Limit(current, pos, du, dv);
  out.limit_points.resize(static_cast<Eigen::Index>(count), 3);
  out.limit_tangent_u.resize(static_cast<Eigen::Index>(count), 3);
  out.limit_tangent_v.resize(static_cast<Eigen::Index>(count), 3);
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      out.limit_points(static_cast<Eigen::Index>(i), c) = pos[i].p[c];
      out.limit_tangent_u(static_cast<Eigen::Index>(i), c) = du[i].p[c];
      out.limit_tangent_v(static_cast<Eigen::Index>(i), c) = dv[i].p[c];
    }
  return out;
}

namespace {

// A point as a combination of the next level's points: OpenSubdiv's limit evaluation applied to
// these gives the limit stencils as rows of a matrix.
struct Combination {
  std::vector<std::pair<int, double>> terms;
  void Clear() { terms.clear(); }
  void AddWithWeight(const Combination& src, double w) {
    for (const auto& [index, weight] : src.terms) terms.push_back({index, w * weight});
  }
};

Eigen::SparseMatrix<double> to_matrix(const std::vector<Combination>& rows, Eigen::Index cols) {
  std::vector<Eigen::Triplet<double>> entries;
  for (size_t r = 0; r < rows.size(); ++r)
    for (const auto& [index, weight] : rows[r].terms)
      entries.emplace_back(static_cast<int>(r), index, weight);
  Eigen::SparseMatrix<double> m(static_cast<Eigen::Index>(rows.size()), cols);
  m.setFromTriplets(entries.begin(), entries.end());  // sums repeated terms
  return m;
}

}  // namespace

SubdivisionStep subdivision_step(const SubdivisionMesh& mesh) {
  validate_mesh(mesh, 1);
  std::unique_ptr<Far::TopologyRefiner> refiner = make_refiner(mesh);
  Far::TopologyRefiner::UniformOptions uniform(1);
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);
  Far::StencilTableFactoryReal<double>::Options options;
  options.generateIntermediateLevels = false;
  options.generateOffsets = true;
  options.maxLevel = 1;
  std::unique_ptr<const Far::StencilTableReal<double>> table(
      Far::StencilTableFactoryReal<double>::Create(*refiner, options));
  const int rows = table->GetNumStencils();
  std::vector<Combination> refine(static_cast<size_t>(rows));
  for (int r = 0; r < rows; ++r) {
    const auto stencil = table->GetStencil(r);
    for (int k = 0; k < stencil.GetSize(); ++k)
      refine[static_cast<size_t>(r)].terms.push_back(
          {stencil.GetVertexIndices()[k], stencil.GetWeights()[k]});
  }
  SubdivisionStep out;
  out.refine = to_matrix(refine, mesh.points.rows());
  std::vector<Combination> unit(static_cast<size_t>(rows)), pos(unit.size()), du(unit.size()),
      dv(unit.size());
  for (int r = 0; r < rows; ++r) unit[static_cast<size_t>(r)].terms.push_back({r, 1.0});
  Far::PrimvarRefinerReal<double>(*refiner).Limit(unit, pos, du, dv);
  out.limit = to_matrix(pos, rows);
  out.limit_u = to_matrix(du, rows);
  out.limit_v = to_matrix(dv, rows);
  return out;
}

}  // namespace varsurf
