// SPDX-License-Identifier: LGPL-2.1-or-later
// Random model input drawn from a fuzzer's bytes: mostly sane values (so the solver gets deep),
// sometimes the values users and files produce by mistake (NaN, inf, negative, huge, reversed or
// over-repeated knots, parameters off the domain).
#pragma once

#include <fuzzer/FuzzedDataProvider.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::fuzz {

// A number in [lo, hi], or one time in 16 a hostile one.
inline double number(FuzzedDataProvider& in, double lo, double hi) {
  if (in.ConsumeIntegralInRange<int>(0, 15) == 0) {
    switch (in.ConsumeIntegralInRange<int>(0, 6)) {
      case 0:
        return std::numeric_limits<double>::quiet_NaN();
      case 1:
        return std::numeric_limits<double>::infinity();
      case 2:
        return -std::numeric_limits<double>::infinity();
      case 3:
        return -1e300;
      case 4:
        return 1e300;
      case 5:
        return 0.0;
      default:
        return std::numeric_limits<double>::denorm_min();
    }
  }
  return in.ConsumeFloatingPointInRange<double>(lo, hi);
}

inline Eigen::Vector3d vector3(FuzzedDataProvider& in, double size) {
  return {number(in, -size, size), number(in, -size, size), number(in, -size, size)};
}

// A clamped knot vector on [0, 1] for `spans` pieces: uniform, random, or broken on purpose.
inline std::vector<double> knots(FuzzedDataProvider& in, int degree, int spans) {
  std::vector<double> k(degree + 1, 0.0);
  const int style = in.ConsumeIntegralInRange<int>(0, 7);
  std::vector<double> inner;
  for (int s = 1; s < spans; ++s) {
    if (style < 5)
      inner.push_back(double(s) / spans);
    else
      inner.push_back(number(in, 0.0, 1.0));
  }
  if (style != 6) std::sort(inner.begin(), inner.end());  // style 6: maybe not monotone
  k.insert(k.end(), inner.begin(), inner.end());
  k.insert(k.end(), degree + 1, 1.0);
  if (style == 7 && !k.empty()) k.pop_back();  // inconsistent with the pole count
  return k;
}

inline SplineSpace space(FuzzedDataProvider& in) {
  SplineSpace s;
  s.degree_u = in.ConsumeIntegralInRange<int>(0, 6);
  s.degree_v = in.ConsumeIntegralInRange<int>(1, 5);
  s.knots_u = knots(in, s.degree_u, in.ConsumeIntegralInRange<int>(1, 6));
  s.knots_v = knots(in, s.degree_v, in.ConsumeIntegralInRange<int>(0, 6));
  if (in.ConsumeBool() && s.nu() > 0 && s.nv() > 0) {
    s.weights.resize(s.size());
    for (int k = 0; k < s.size(); ++k) s.weights[k] = number(in, 0.2, 3.0);
  }
  return s;
}

// A curve of dimension `dim` whose poles lie in [lo, hi] per coordinate (mostly).
inline BSplineCurve curve(FuzzedDataProvider& in, int dim, double lo, double hi) {
  BSplineCurve c;
  c.degree = in.ConsumeIntegralInRange<int>(0, 4);
  const int spans = in.ConsumeIntegralInRange<int>(1, 4);
  c.knots = knots(in, std::max(c.degree, 0), spans);
  const int poles = std::max(1, static_cast<int>(c.knots.size()) - c.degree - 1);
  c.poles.resize(poles, dim);
  for (int i = 0; i < poles; ++i)
    for (int d = 0; d < dim; ++d) c.poles(i, d) = number(in, lo, hi);
  if (in.ConsumeIntegralInRange<int>(0, 5) == 0) {
    c.weights.resize(poles);
    for (int i = 0; i < poles; ++i) c.weights[i] = number(in, 0.2, 3.0);
  }
  return c;
}

}  // namespace varsurf::fuzz
