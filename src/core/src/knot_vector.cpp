// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/knot_vector.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

std::vector<double> flat_knots(const std::vector<double>& knots, const std::vector<int>& mults) {
  if (knots.size() != mults.size()) throw InvalidInput("knots and multiplicities differ in length");
  std::vector<double> flat;
  for (size_t i = 0; i < knots.size(); ++i) {
    if (mults[i] < 1) throw InvalidInput("knot multiplicities must be positive");
    flat.insert(flat.end(), static_cast<size_t>(mults[i]), knots[i]);
  }
  return flat;
}

void split_knots(const std::vector<double>& flat, std::vector<double>& knots,
                 std::vector<int>& mults) {
  knots.clear();
  mults.clear();
  for (double t : flat) {
    if (!knots.empty() && t == knots.back()) {
      ++mults.back();
    } else {
      knots.push_back(t);
      mults.push_back(1);
    }
  }
}

std::vector<double> uniform_clamped_knots(int degree, int spans, double a, double b) {
  if (degree < 1 || spans < 1 || !(b > a))
    throw InvalidInput("uniform knots need degree, spans >= 1 and a < b");
  // Refused before allocating: 2^31 spans took 50 s to fail with a MemoryError.
  if (spans > kMaxSpans)
    throw InvalidInput("uniform knots take 1 to " + std::to_string(kMaxSpans) + " spans");
  std::vector<double> k(static_cast<size_t>(degree), a);
  for (int i = 0; i <= spans; ++i) k.push_back(a + (b - a) * i / spans);
  k.back() = b;
  k.insert(k.end(), static_cast<size_t>(degree), b);
  return k;
}

void validate_knots(const std::vector<double>& k, int degree, int pole_count, const char* what) {
  const std::string w(what);
  if (degree < 1) throw InvalidInput(w + ": degree must be at least 1");
  if (pole_count < degree + 1)
    throw InvalidInput(w + ": " + std::to_string(pole_count) + " poles are too few for degree " +
                       std::to_string(degree));
  if (static_cast<int>(k.size()) != pole_count + degree + 1)
    throw InvalidInput(w + ": expected " + std::to_string(pole_count + degree + 1) +
                       " flat knots, got " + std::to_string(k.size()));
  for (size_t i = 0; i < k.size(); ++i) {
    if (!std::isfinite(k[i])) throw InvalidInput(w + ": knot value is not finite");
    // Finite but huge knots overflow when differenced (1e308: a closest-point search ran for
    // minutes); no model needs parameters beyond this.
    if (std::abs(k[i]) > kMaxCoordinate)
      throw InvalidInput(w + ": knot values must lie within +-1e12");
    if (i > 0 && k[i] < k[i - 1]) throw InvalidInput(w + ": knots must be non-decreasing");
  }
  const size_t p = static_cast<size_t>(degree);
  for (size_t i = 1; i <= p; ++i) {
    if (k[i] != k[0] || k[k.size() - 1 - i] != k.back())
      throw InvalidInput(w + ": knot vector must be clamped (end multiplicity degree + 1)");
  }
  if (!(k.back() > k.front())) throw InvalidInput(w + ": parameter domain is empty");
  // Interior multiplicity above the degree would disconnect the surface.
  size_t run = 1;
  for (size_t i = p + 1; i + p + 1 < k.size(); ++i) {
    run = (k[i] == k[i - 1] && i > p + 1) ? run + 1 : 1;
    if (run > p) throw InvalidInput(w + ": interior knot multiplicity exceeds the degree");
  }
}

int find_span(const std::vector<double>& k, int degree, double t) {
  // A NaN would fall through every comparison and index outside the knot vector.
  if (!std::isfinite(t)) throw InvalidInput("parameter value is not finite");
  // An empty (default-constructed) spline would index before its knot vector.
  if (degree < 1 || k.size() < 2 * static_cast<size_t>(degree) + 2)
    throw InvalidInput("evaluating a spline whose knot vector is too short for its degree");
  const int n = static_cast<int>(k.size()) - degree - 2;  // index of last pole
  if (t >= k[static_cast<size_t>(n + 1)]) return n;
  if (t <= k[static_cast<size_t>(degree)]) {
    // First span with non-zero length.
    int s = degree;
    while (s < n && k[static_cast<size_t>(s + 1)] <= k[static_cast<size_t>(degree)]) ++s;
    return s;
  }
  // Binary search for k[s] <= t < k[s+1].
  auto it = std::upper_bound(k.begin() + degree, k.begin() + n + 2, t);
  return static_cast<int>(it - k.begin()) - 1;
}

namespace {

// Piegl & Tiller A2.3 on caller-provided work arrays (ndu: (p+1) x (p+1), a: 2 x (p+1)).
template <class Work>
void basis_derivatives_in(const double* U, int p, int span, double t, int order, Work& ndu, Work& a,
                          Eigen::Ref<Eigen::MatrixXd> out) {
  double left[kStackDegree + 2], right[kStackDegree + 2];
  std::vector<double> heap_left, heap_right;
  double* L = left;
  double* R = right;
  if (p > kStackDegree) {
    heap_left.resize(static_cast<size_t>(p + 1));
    heap_right.resize(static_cast<size_t>(p + 1));
    L = heap_left.data();
    R = heap_right.data();
  }
  ndu(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    L[j] = t - U[span + 1 - j];
    R[j] = U[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu(j, r) = R[r + 1] + L[j - r];
      const double temp = ndu(r, j - 1) / ndu(j, r);
      ndu(r, j) = saved + R[r + 1] * temp;
      saved = L[j - r] * temp;
    }
    ndu(j, j) = saved;
  }
  out.setZero();
  for (int j = 0; j <= p; ++j) out(0, j) = ndu(j, p);
  const int nd = std::min(order, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a(0, 0) = 1.0;
    for (int k = 1; k <= nd; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a(s2, 0) = a(s1, 0) / ndu(pk + 1, rk);
        d = a(s2, 0) * ndu(rk, pk);
      }
      const int j1 = (rk >= -1) ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a(s2, j) = (a(s1, j) - a(s1, j - 1)) / ndu(pk + 1, rk + j);
        d += a(s2, j) * ndu(rk + j, pk);
      }
      if (r <= pk) {
        a(s2, k) = -a(s1, k - 1) / ndu(pk + 1, r);
        d += a(s2, k) * ndu(r, pk);
      }
      out(k, r) = d;
      std::swap(s1, s2);
    }
  }
  int factor = p;
  for (int k = 1; k <= nd; ++k) {
    out.row(k) *= factor;
    factor *= (p - k);
  }
}

}  // namespace

void basis_derivatives(const std::vector<double>& knots, int p, int span, double t, int order,
                       Eigen::Ref<Eigen::MatrixXd> out) {
  // Work arrays on the stack for the usual degrees: this runs for every sample of every
  // projection, measurement and constraint, and two heap blocks per call were a third of a
  // sheet's evaluation time (perf, 19 x 19 sheet through 7 curves).
  if (p <= kStackDegree) {
    using Work = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kStackDegree + 1,
                               kStackDegree + 1>;
    Work ndu(p + 1, p + 1), a(2, p + 1);
    basis_derivatives_in(knots.data(), p, span, t, order, ndu, a, out);
  } else {
    Eigen::MatrixXd ndu(p + 1, p + 1), a(2, p + 1);
    basis_derivatives_in(knots.data(), p, span, t, order, ndu, a, out);
  }
}

std::vector<double> greville(const std::vector<double>& knots, int degree) {
  const int n = static_cast<int>(knots.size()) - degree - 1;
  std::vector<double> g(static_cast<size_t>(std::max(n, 0)));
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    for (int k = 1; k <= degree; ++k) s += knots[static_cast<size_t>(i + k)];
    g[static_cast<size_t>(i)] = s / degree;
  }
  return g;
}

std::vector<double> breakpoints(const std::vector<double>& k, int degree) {
  std::vector<double> b;
  for (size_t i = static_cast<size_t>(degree); i + static_cast<size_t>(degree) < k.size(); ++i) {
    if (b.empty() || k[i] > b.back()) b.push_back(k[i]);
  }
  return b;
}

}  // namespace varsurf
