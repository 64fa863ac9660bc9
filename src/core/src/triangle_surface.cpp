// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/triangle_surface.hpp"

#include <unsupported/Eigen/BVH>

#include <Eigen/Geometry>
#include <limits>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

using Box = Eigen::AlignedBox3d;

struct TriangleSurface::Tree {
  Eigen::KdBVH<double, 3, int> bvh;
};

namespace {

// Eigen's minimizer protocol: the squared distance to a box bounds the triangles inside it.
// Triangles nearest within this relative margin of the squared distance are ties, broken by the
// lowest index: a point on the medial axis (a cube cage's face centre inside a tessellated sphere,
// on its axis) has several nearest facets, and which one rounding picked made captures of the
// same scene at 0.05x and 500x differ by 0.23 mm of 20 at level 1 (measured).
constexpr double kTie = 1e-10;

struct Nearest {
  typedef double Scalar;
  const Eigen::MatrixX3d* points;
  const std::vector<std::array<int, 3>>* triangles;
  Eigen::Vector3d query, best;
  double best_distance = std::numeric_limits<double>::infinity();
  int best_triangle = -1;
  double minimumOnVolume(const Box& box) const { return box.squaredExteriorDistance(query); }
  double minimumOnObject(int t) {
    const std::array<int, 3>& tri = (*triangles)[static_cast<size_t>(t)];
    const Eigen::Vector3d q =
        closest_on_triangle(query, points->row(tri[0]).transpose(), points->row(tri[1]).transpose(),
                            points->row(tri[2]).transpose());
    const double d = (q - query).squaredNorm();
    const bool nearer = d < best_distance * (1.0 - kTie);
    const bool tie = !nearer && d <= best_distance * (1.0 + kTie) && t < best_triangle;
    if (nearer || tie) best = q, best_distance = d, best_triangle = t;
    // Reported a little farther, so that boxes holding a tie are still visited.
    return d * (1.0 + 2.0 * kTie);
  }
};

}  // namespace

TriangleSurface::TriangleSurface(Eigen::MatrixX3d points, std::vector<std::array<int, 3>> triangles)
    : points_(std::move(points)), triangles_(std::move(triangles)), tree_(new Tree) {
  if (triangles_.empty()) throw InvalidInput("the target has no triangles");
  if (!points_.allFinite()) throw InvalidInput("the target has points that are not finite");
  std::vector<int> ids;
  std::vector<Box> boxes;
  for (size_t t = 0; t < triangles_.size(); ++t) {
    Box box;
    for (const int v : triangles_[t]) {
      if (v < 0 || v >= points_.rows())
        throw InvalidInput("target triangle " + std::to_string(t) + " names vertex " +
                           std::to_string(v) + ", not one of its " +
                           std::to_string(points_.rows()));
      box.extend(points_.row(v).transpose());
    }
    ids.push_back(static_cast<int>(t));
    boxes.push_back(box);
  }
  tree_->bvh.init(ids.begin(), ids.end(), boxes.begin(), boxes.end());
}

TriangleSurface::~TriangleSurface() = default;

Eigen::Vector3d TriangleSurface::closest(const Eigen::Vector3d& p) const {
  const double inf = std::numeric_limits<double>::infinity();
  Nearest n{&points_, &triangles_, p, Eigen::Vector3d(inf, inf, inf)};
  Eigen::BVMinimize(tree_->bvh, n);
  return n.best;
}

double TriangleSurface::size() const {
  return (points_.colwise().maxCoeff() - points_.colwise().minCoeff()).norm();
}

Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace varsurf
