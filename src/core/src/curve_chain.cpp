// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/curve_chain.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <set>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

// The closest point of segment ab to p: its parameter in 0..1.
double segment_parameter(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = b - a;
  const double length2 = d.squaredNorm();
  return length2 > 0.0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0.0;
}

// Every vertex's neighbours across its faces (edge and diagonal): the moves the approximation
// property allows between consecutive chain vertices.
std::vector<std::vector<int>> face_neighbours(const SubdivisionMesh& mesh) {
  std::vector<std::set<int>> sets(static_cast<size_t>(mesh.points.rows()));
  for (const std::vector<int>& face : mesh.faces)
    for (const int a : face)
      for (const int b : face)
        if (a != b) sets[static_cast<size_t>(a)].insert(b);
  std::vector<std::vector<int>> out;
  for (const std::set<int>& s : sets) out.emplace_back(s.begin(), s.end());
  return out;
}

}  // namespace

CurveChain curve_chain(const SubdivisionMesh& mesh, const Eigen::MatrixX3d& curve) {
  subdivide(mesh, 0);  // the mesh's checks
  if (!curve.allFinite()) throw InvalidInput("the curve has points that are not finite");
  std::vector<Eigen::Vector3d> polyline;
  for (Eigen::Index k = 0; k < curve.rows(); ++k)
    if (polyline.empty() || (curve.row(k).transpose() - polyline.back()).norm() > 0.0)
      polyline.push_back(curve.row(k).transpose());
  if (polyline.size() < 2) throw InvalidInput("the curve needs two distinct points");
  std::vector<double> arc{0.0};
  for (size_t k = 1; k < polyline.size(); ++k)
    arc.push_back(arc.back() + (polyline[k] - polyline[k - 1]).norm());
  const double length = arc.back();
  CurveChain out;
  out.closed = (polyline.front() - polyline.back()).norm() <= 1e-3 * length;

  double longest = 0.0, total = 0.0;
  size_t edges = 0;
  for (const std::vector<int>& face : mesh.faces)
    for (size_t k = 0; k < face.size(); ++k) {
      const double e =
          (mesh.points.row(face[k]) - mesh.points.row(face[(k + 1) % face.size()])).norm();
      longest = std::max(longest, e);
      total += e;
      ++edges;
    }
  // Samples a quarter of the mean edge apart: consecutive nearest vertices then share a face
  // except where the mesh is much finer than its mean (a path is searched there).
  const double step = 0.25 * total / static_cast<double>(std::max<size_t>(edges, 1));
  const std::vector<std::vector<int>> neighbours = face_neighbours(mesh);
  const auto distance2 = [&](int v, const Eigen::Vector3d& p) {
    return (mesh.points.row(v).transpose() - p).squaredNorm();
  };
  // "Nearer", kept by rigid motions: squared distances within 1e-9 of the longest edge squared
  // are a tie, broken by the lower index. Rounding alone chose between the vertices a symmetric
  // curve passes at equal distances, and the moved scene's chain differed.
  const double tie = 1e-9 * longest * longest;
  const auto nearer = [&](int w, int v, const Eigen::Vector3d& p) {
    const double dw = distance2(w, p), dv = distance2(v, p);
    return dw < dv - tie || (std::abs(dw - dv) <= tie && w < v);
  };
  // The nearest vertex to p: a descent over face neighbours from `start` (samples are close, so
  // it is short), checked against the whole mesh only for the first sample.
  const auto nearest_from = [&](int start, const Eigen::Vector3d& p) {
    int best = start;
    // Ties make "nearer" intransitive: the moves are capped (a cycle is then cut, not followed).
    for (Eigen::Index moves = 0, bound = mesh.points.rows(); moves < bound; ++moves) {
      bool moved = false;
      for (const int w : neighbours[static_cast<size_t>(best)])
        if (nearer(w, best, p)) best = w, moved = true;
      if (!moved) break;
    }
    return best;
  };
  // A shortest path of face neighbours from a to b (breadth first), a excluded, b included.
  const auto path = [&](int a, int b) {
    std::vector<int> parent(static_cast<size_t>(mesh.points.rows()), -1);
    std::deque<int> queue{a};
    parent[static_cast<size_t>(a)] = a;
    while (!queue.empty() && parent[static_cast<size_t>(b)] < 0) {
      const int v = queue.front();
      queue.pop_front();
      for (const int w : neighbours[static_cast<size_t>(v)])
        if (parent[static_cast<size_t>(w)] < 0)
          parent[static_cast<size_t>(w)] = v, queue.push_back(w);
    }
    std::vector<int> steps;
    if (parent[static_cast<size_t>(b)] < 0) return steps;  // another component: none
    for (int v = b; v != a; v = parent[static_cast<size_t>(v)]) steps.push_back(v);
    std::reverse(steps.begin(), steps.end());
    return steps;
  };

  int current = 0;
  for (int v = 1; v < static_cast<int>(mesh.points.rows()); ++v)
    if (nearer(v, current, polyline.front())) current = v;
  std::vector<int> chain{current};
  for (size_t k = 1; k < polyline.size(); ++k) {
    const int pieces = std::max(1, static_cast<int>(std::ceil((arc[k] - arc[k - 1]) / step)));
    for (int s = 1; s <= pieces; ++s) {
      const Eigen::Vector3d p =
          polyline[k - 1] + (polyline[k] - polyline[k - 1]) * (double(s) / pieces);
      const int next = nearest_from(current, p);
      if (std::sqrt(distance2(next, p)) > longest)
        throw InvalidInput("the curve leaves the surface near (" + std::to_string(p.x()) + ", " +
                           std::to_string(p.y()) + ", " + std::to_string(p.z()) +
                           "): give a curve lying on it");
      if (next == current) continue;
      const std::vector<int>& around = neighbours[static_cast<size_t>(current)];
      if (std::binary_search(around.begin(), around.end(), next))
        chain.push_back(next);
      else
        for (const int v : path(current, next)) chain.push_back(v);
      current = next;
    }
  }
  // A vertex met twice (the curve doubling back within a face) is kept at its first visit.
  std::set<int> seen;
  for (const int v : chain)
    if (seen.insert(v).second) out.vertices.push_back(v);
  // Parameters and distances: each vertex's closest point on the polyline.
  out.points.resize(static_cast<Eigen::Index>(out.vertices.size()), 3);
  for (size_t i = 0; i < out.vertices.size(); ++i) {
    const Eigen::Vector3d p = mesh.points.row(out.vertices[i]).transpose();
    double best = std::numeric_limits<double>::infinity(), at = 0.0;
    Eigen::Vector3d foot = p;
    for (size_t k = 1; k < polyline.size(); ++k) {
      const double t = segment_parameter(polyline[k - 1], polyline[k], p);
      const Eigen::Vector3d q = polyline[k - 1] + t * (polyline[k] - polyline[k - 1]);
      const double d = (q - p).norm();
      if (d < best) best = d, at = (arc[k - 1] + t * (arc[k] - arc[k - 1])) / length, foot = q;
    }
    out.parameters.push_back(at);
    out.points.row(static_cast<Eigen::Index>(i)) = foot.transpose();
    out.max_distance = std::max(out.max_distance, best);
  }
  // How far the curve strays from the chain's polyline (at the samples).
  const size_t n = out.vertices.size();
  for (size_t k = 0; k < polyline.size(); ++k) {
    double best = std::numeric_limits<double>::infinity();
    const size_t segments = out.closed ? n : n - 1;
    for (size_t j = 0; j < std::max<size_t>(segments, 1); ++j) {
      const Eigen::Vector3d a = mesh.points.row(out.vertices[j]).transpose();
      const Eigen::Vector3d b = mesh.points.row(out.vertices[(j + 1) % n]).transpose();
      best =
          std::min(best, (a + segment_parameter(a, b, polyline[k]) * (b - a) - polyline[k]).norm());
    }
    out.max_gap = std::max(out.max_gap, best);
  }
  return out;
}

}  // namespace varsurf
