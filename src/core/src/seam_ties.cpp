// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/seam_ties.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

struct Seam {
  int degree = 0;  // along the closed direction
  int order = 0;   // highest derivative tied
  double first = 0.0, last = 0.0, scale = 1.0;
  std::vector<double> across;  // Greville abscissae of the other direction
};

Seam seam_of(const SplineSpace& space, int direction) {
  space.validate();
  if (direction != 0 && direction != 1)
    throw InvalidInput("seam: direction must be 0 (closed along u) or 1 (along v)");
  Seam s;
  const std::vector<double>& knots = direction == 0 ? space.knots_u : space.knots_v;
  const std::vector<double>& other = direction == 0 ? space.knots_v : space.knots_u;
  s.degree = direction == 0 ? space.degree_u : space.degree_v;
  const int other_degree = direction == 0 ? space.degree_v : space.degree_u;
  if (s.degree < 1) throw InvalidInput("seam: a closed direction needs degree 1 or more");
  // A polynomial space is tied like a periodic spline (C^(p-1), as at its simple knots), so the
  // seam is no different from any other knot line and the sheet does not depend on where it is;
  // a rational one (its rows from the bivariate basis) to C2.
  s.order = space.rational() ? std::min(2, s.degree - 1) : s.degree - 1;
  s.first = knots.front(), s.last = knots.back();
  std::vector<double> distinct(knots);
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  s.scale = (s.last - s.first) / std::max<size_t>(distinct.size() - 1, 1);
  const int n = static_cast<int>(other.size()) - other_degree - 1;
  for (int j = 0; j < n; ++j) {
    double g = 0.0;
    for (int k = 1; k <= other_degree; ++k) g += other[static_cast<size_t>(j + k)];
    s.across.push_back(other_degree > 0 ? g / other_degree : other[static_cast<size_t>(j)]);
  }
  return s;
}

// Row of BasisSample::values holding the k-th derivative along the closed direction.
int derivative_row(int direction, int k) {
  static const int rows[2][3] = {{0, 1, 3}, {0, 2, 5}};
  return rows[direction][k];
}

BasisSample basis_at(const SplineSpace& space, int direction, double along, double across) {
  return direction == 0 ? space.basis(along, across, 2) : space.basis(across, along, 2);
}

}  // namespace

namespace {

// One tie row: the coefficients of `row` (pole -> value), unless every pole in it is fixed.
void add_row(const std::map<int, double>& row, const std::vector<bool>& fixed,
             ConstraintSamples& out) {
  std::vector<int> cols;
  std::vector<double> values;
  bool movable = fixed.empty();
  for (const auto& [pole, value] : row) {
    if (value == 0.0) continue;
    cols.push_back(pole);
    values.push_back(value);
    if (!fixed.empty() && !fixed[static_cast<size_t>(pole)]) movable = true;
  }
  if (cols.empty() || !movable) return;
  // Unit rows: a degree-p tie of order k carries factors up to p! / (p - k)!, and beside a
  // degree-14 loft's order-13 rows the position rows fell under the reduction's rank tolerance
  // and were dropped (the seam opened by 2.6 mm).
  Eigen::VectorXd row_values =
      Eigen::Map<Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  const double norm = row_values.norm();
  if (!(norm > 0.0)) return;
  out.index.push_back(std::move(cols));
  out.coeff.push_back(row_values / norm);
  out.weight.push_back(1.0);
}

// Polynomial spaces: pole by pole of the other direction (a spline of the other direction is
// zero exactly when its poles are), the closure rows of the closed direction along each pole line.
struct PoleTies {
  const SplineSpace& space;
  int direction;
  std::vector<std::map<int, double>> rows;  // per order, along one pole line

  PoleTies(const SplineSpace& sp, int dir, const Seam& s)
      : space(sp),
        direction(dir),
        rows(closure_rows(dir == 0 ? sp.knots_u : sp.knots_v, s.degree, s.order)) {}
  int across() const { return direction == 0 ? space.nv() : space.nu(); }
  // pole -> coefficient of the k-th order row along the j-th pole line.
  std::map<int, double> row(int j, int k) const {
    std::map<int, double> out;
    for (const auto& [i, value] : rows[static_cast<size_t>(k)])
      out[direction == 0 ? space.index(i, j) : space.index(j, i)] = value;
    return out;
  }
};

void polynomial_ties(const SplineSpace& space, int direction, const Seam& s,
                     const std::vector<bool>& fixed, ConstraintSamples& out) {
  const PoleTies ties(space, direction, s);
  for (int j = 0; j < ties.across(); ++j)
    for (int k = 0; k <= s.order; ++k) add_row(ties.row(j, k), fixed, out);
}

}  // namespace

std::vector<std::map<int, double>> closure_rows(const std::vector<double>& knots, int degree,
                                                int max_order) {
  if (degree < 1 || max_order < 0 || max_order > degree)
    throw InvalidInput("closure rows: need degree >= 1 and 0 <= order <= degree");
  const int n = static_cast<int>(knots.size()) - degree - 1;
  const double first = knots.front(), last = knots.back();
  const int first_span = find_span(knots, degree, first),
            last_span = find_span(knots, degree, last);
  Eigen::MatrixXd a(degree + 1, degree + 1), b(degree + 1, degree + 1);
  basis_derivatives(knots, degree, first_span, first, degree, a);
  basis_derivatives(knots, degree, last_span, last, degree, b);
  std::vector<std::map<int, double>> out;
  for (int k = 0; k <= max_order; ++k) {
    std::map<int, double> row;
    for (int i = 0; i <= degree; ++i) {
      const int ia = first_span - degree + i, ib = last_span - degree + i;
      if (ia >= 0 && ia < n) row[ia] += a(k, i);
      if (ib >= 0 && ib < n) row[ib] -= b(k, i);
    }
    double norm = 0.0;
    for (const auto& entry : row) norm += entry.second * entry.second;
    norm = std::sqrt(norm);
    for (auto& entry : row) entry.second = norm > 0.0 ? entry.second / norm : 0.0;
    out.push_back(std::move(row));
  }
  return out;
}

ConstraintSamples sample_seam(const SplineSpace& space, int direction,
                              const std::vector<bool>& fixed) {
  const Seam s = seam_of(space, direction);
  if (!fixed.empty() && static_cast<int>(fixed.size()) != space.size())
    throw InvalidInput("seam: one fixed flag per pole expected");
  ConstraintSamples out;
  out.exact = true;
  if (!space.rational()) {
    polynomial_ties(space, direction, s, fixed, out);
    out.rhs = Eigen::MatrixXd::Zero(out.rows(), 3);
    return out;
  }
  for (const double c : s.across) {
    const BasisSample a = basis_at(space, direction, s.first, c);
    const BasisSample b = basis_at(space, direction, s.last, c);
    for (int k = 0; k <= s.order; ++k) {
      const double scale = std::pow(s.scale, k);
      std::map<int, double> row;
      for (size_t i = 0; i < a.index.size(); ++i)
        row[a.index[i]] +=
            scale * a.values(derivative_row(direction, k), static_cast<Eigen::Index>(i));
      for (size_t i = 0; i < b.index.size(); ++i)
        row[b.index[i]] -=
            scale * b.values(derivative_row(direction, k), static_cast<Eigen::Index>(i));
      add_row(row, fixed, out);
    }
  }
  out.rhs = Eigen::MatrixXd::Zero(out.rows(), 3);
  return out;
}

namespace {

// Per order k = 0 .. min(order tied, 2): the largest scaled difference of the k-th derivative
// across the seam over `samples` points along it.
std::vector<double> mismatch_by_order(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                                      int direction, int samples) {
  const Seam s = seam_of(space, direction);
  BSplineSurface{space, poles}.validate();
  if (samples < 2 || samples > 1000000)
    throw InvalidInput("seam_mismatch takes 2 to 1,000,000 samples");
  const double lo = s.across.front(), hi = s.across.back();
  std::vector<double> worst(static_cast<size_t>(std::min(s.order, 2) + 1), 0.0);
  for (int i = 0; i < samples; ++i) {
    const double c = lo + (hi - lo) * i / (samples - 1);
    const Eigen::MatrixXd a = direction == 0 ? evaluate_surface(space, poles, s.first, c, 2)
                                             : evaluate_surface(space, poles, c, s.first, 2);
    const Eigen::MatrixXd b = direction == 0 ? evaluate_surface(space, poles, s.last, c, 2)
                                             : evaluate_surface(space, poles, c, s.last, 2);
    for (size_t k = 0; k < worst.size(); ++k) {
      const int r = derivative_row(direction, static_cast<int>(k));
      worst[k] = std::max(worst[k], std::pow(s.scale, k) * (a.row(r) - b.row(r)).norm());
    }
  }
  return worst;
}

}  // namespace

double seam_mismatch(const SplineSpace& space, const Eigen::MatrixX3d& poles, int direction,
                     int samples) {
  const std::vector<double> worst = mismatch_by_order(space, poles, direction, samples);
  return *std::max_element(worst.begin(), worst.end());
}

int seam_continuity(const SplineSpace& space, const Eigen::MatrixX3d& poles, int direction,
                    double tolerance, int samples) {
  if (!(tolerance >= 0.0 && std::isfinite(tolerance)))
    throw InvalidInput("seam_continuity: the tolerance must be a finite number >= 0");
  const std::vector<double> worst = mismatch_by_order(space, poles, direction, samples);
  const double extent =
      std::max((poles.colwise().maxCoeff() - poles.colwise().minCoeff()).norm(), 1e-300);
  int order = -1;
  while (order + 1 < static_cast<int>(worst.size()) &&
         worst[static_cast<size_t>(order + 1)] <= tolerance * extent)
    ++order;
  // Beyond second derivatives a polynomial space answers pole by pole (as it is tied).
  const Seam s = seam_of(space, direction);
  if (space.rational() || order < 2 || s.order <= 2) return order;
  const PoleTies ties(space, direction, s);
  for (int k = 3; k <= s.order; ++k) {
    for (int j = 0; j < ties.across(); ++j) {
      Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
      for (const auto& [pole, c] : ties.row(j, k)) d += c * poles.row(pole);
      if (d.norm() > tolerance * extent) return order;
    }
    order = k;
  }
  return order;
}

}  // namespace varsurf
