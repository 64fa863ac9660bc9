// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/detail_energy.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

// The ring of vertex v in turning order: each incident face contributes its vertices after v
// (edge neighbour, the others, edge neighbour); faces chain where one's last vertex is the next
// one's first. `closed` is false at a boundary vertex, whose chain has two ends.
struct Ring {
  std::vector<int> vertices;
  bool closed = true;
};

Ring ring_of(const SubdivisionMesh& mesh, const std::vector<int>& faces, int v) {
  std::vector<std::vector<int>> fan;
  for (const int index : faces) {
    const std::vector<int>& face = mesh.faces[static_cast<size_t>(index)];
    const size_t k = static_cast<size_t>(std::find(face.begin(), face.end(), v) - face.begin());
    std::vector<int> seq;
    for (size_t m = 1; m < face.size(); ++m) seq.push_back(face[(k + m) % face.size()]);
    fan.push_back(std::move(seq));
  }
  Ring ring;
  if (fan.empty()) return ring;
  std::map<int, size_t> by_first;
  std::map<int, int> ends;  // how often a vertex ends a sequence
  for (size_t f = 0; f < fan.size(); ++f) by_first[fan[f].front()] = f;
  for (const auto& seq : fan) ++ends[seq.back()];
  // A boundary vertex starts from the face whose first vertex ends no other face's sequence.
  size_t start = 0;
  for (size_t f = 0; f < fan.size(); ++f)
    if (!ends.count(fan[f].front())) {
      start = f;
      ring.closed = false;
      break;
    }
  const std::string broken = "vertex " + std::to_string(v) +
                             ": its faces do not make one fan (the mesh is not manifold there)";
  std::vector<bool> used(fan.size(), false);
  size_t f = start;
  for (size_t step = 0; step < fan.size(); ++step) {
    if (used[f]) throw InvalidInput(broken);
    used[f] = true;
    const std::vector<int>& seq = fan[f];
    ring.vertices.insert(ring.vertices.end(), seq.begin() + (step == 0 ? 0 : 1), seq.end());
    if (step + 1 < fan.size()) {
      const auto next = by_first.find(seq.back());
      if (next == by_first.end()) throw InvalidInput(broken);
      f = next->second;
    }
  }
  // A closed ring repeats its first vertex at the end.
  if (ring.closed && ring.vertices.size() > 1 && ring.vertices.back() == ring.vertices.front())
    ring.vertices.pop_back();
  return ring;
}

double mean_edge_length(const SubdivisionMesh& mesh) {
  double total = 0.0;
  size_t count = 0;
  for (const std::vector<int>& face : mesh.faces)
    for (size_t k = 0; k < face.size(); ++k) {
      total += (mesh.points.row(face[k]) - mesh.points.row(face[(k + 1) % face.size()])).norm();
      ++count;
    }
  return count ? total / static_cast<double>(count) : 1.0;
}

}  // namespace

VertexFaces vertex_faces(const SubdivisionMesh& mesh) {
  subdivide(mesh, 0);  // the mesh's checks
  VertexFaces incident(static_cast<size_t>(mesh.points.rows()));
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (const int v : mesh.faces[f])
      incident[static_cast<size_t>(v)].push_back(static_cast<int>(f));
  return incident;
}

Eigen::SparseMatrix<double> divided_differences(const SubdivisionMesh& mesh,
                                                const std::vector<int>& vertices) {
  return divided_differences_checked(mesh, vertex_faces(mesh), vertices);
}

Eigen::SparseMatrix<double> divided_differences_checked(const SubdivisionMesh& mesh,
                                                        const VertexFaces& incident,
                                                        const std::vector<int>& vertices) {
  const Eigen::Index n = mesh.points.rows();
  if (incident.size() != static_cast<size_t>(n))
    throw InvalidInput("the incidence is not the mesh's: build it by vertex_faces");
  std::vector<int> all;
  if (vertices.empty())
    for (int v = 0; v < n; ++v) all.push_back(v);
  for (const int v : vertices)
    if (v < 0 || v >= n) throw InvalidInput("vertex " + std::to_string(v) + " is not in the mesh");
  std::vector<Eigen::Triplet<double>> entries;
  for (const int v : vertices.empty() ? all : vertices) {
    const Ring ring = ring_of(mesh, incident[static_cast<size_t>(v)], v);
    const size_t m = ring.vertices.size();
    if (m == 0) continue;
    const Eigen::Vector3d p0 = mesh.points.row(v);
    // The angles between consecutive ring vertices, spread over a full turn (half at a boundary).
    std::vector<double> angle(m, 0.0);
    double total = 0.0;
    const size_t gaps = ring.closed ? m : m - 1;
    for (size_t j = 0; j < gaps; ++j) {
      const Eigen::Vector3d a = mesh.points.row(ring.vertices[j]).transpose() - p0;
      const Eigen::Vector3d b = mesh.points.row(ring.vertices[(j + 1) % m]).transpose() - p0;
      angle[j] = std::atan2(a.cross(b).norm(), a.dot(b));
      total += angle[j];
    }
    const double turn = ring.closed ? 2.0 * M_PI : M_PI;
    Eigen::MatrixXd phi(static_cast<Eigen::Index>(m), 5);
    double theta = 0.0;
    for (size_t j = 0; j < m; ++j) {
      const double r = (mesh.points.row(ring.vertices[j]).transpose() - p0).norm();
      const double u = r * std::cos(theta), w = r * std::sin(theta);
      phi.row(static_cast<Eigen::Index>(j)) << u, w, 0.5 * u * u, u * w, 0.5 * w * w;
      if (total > 0.0) theta += turn * angle[j] / total;
    }
    // Least squares, or least norm where the ring is too small (a corner's three neighbours).
    const Eigen::MatrixXd d =
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(phi).pseudoInverse();
    for (Eigen::Index row = 0; row < 5; ++row) {
      double sum = 0.0;
      for (size_t j = 0; j < m; ++j) {
        entries.emplace_back(5 * v + row, ring.vertices[j], d(row, static_cast<Eigen::Index>(j)));
        sum += d(row, static_cast<Eigen::Index>(j));
      }
      entries.emplace_back(5 * v + row, v, -sum);
    }
  }
  Eigen::SparseMatrix<double> out(5 * n, n);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

Eigen::SparseMatrix<double> detail_energy(const SubdivisionMesh& mesh,
                                          const DetailEnergyWeights& weights,
                                          const std::vector<int>& vertices) {
  return detail_energy_checked(mesh, vertex_faces(mesh), weights, vertices);
}

Eigen::SparseMatrix<double> detail_energy_checked(const SubdivisionMesh& mesh,
                                                  const VertexFaces& incident,
                                                  const DetailEnergyWeights& weights,
                                                  const std::vector<int>& vertices) {
  if (!(weights.stretch >= 0.0) || !(weights.bend >= 0.0) ||
      !std::isfinite(weights.stretch + weights.bend) || weights.stretch + weights.bend <= 0.0)
    throw InvalidInput("the stretch and bend weights must be finite, >= 0 and not both 0");
  const Eigen::SparseMatrix<double> d = divided_differences_checked(mesh, incident, vertices);
  const double l = mean_edge_length(mesh);
  Eigen::VectorXd w(d.rows());
  for (Eigen::Index v = 0; 5 * v < d.rows(); ++v)
    w.segment<5>(5 * v) << weights.stretch / (l * l), weights.stretch / (l * l), weights.bend,
        2.0 * weights.bend, weights.bend;
  return Eigen::SparseMatrix<double>(d.transpose() * w.asDiagonal() * d);
}

}  // namespace varsurf
