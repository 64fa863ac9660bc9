// SPDX-License-Identifier: LGPL-2.1-or-later
// Clamped B-spline knot vectors and basis function evaluation (Piegl & Tiller, algorithms
// A2.1–A2.3).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace varsurf {

// Largest span count a uniform knot vector may ask for (per direction).
constexpr int kMaxSpans = 1000000;
// Largest magnitude of a knot or pole coordinate (model units): beyond it evaluation overflows.
constexpr double kMaxCoordinate = 1e12;

// Flat knot vector from distinct knots and multiplicities (OCCT/FreeCAD store them that way).
std::vector<double> flat_knots(const std::vector<double>& knots, const std::vector<int>& mults);

// Distinct knots and their multiplicities from a flat knot vector.
void split_knots(const std::vector<double>& flat, std::vector<double>& knots,
                 std::vector<int>& mults);

// Uniform clamped knot vector on [a, b] with `spans` polynomial pieces.
std::vector<double> uniform_clamped_knots(int degree, int spans, double a = 0.0, double b = 1.0);

// Throws InvalidInput unless `knots` is a finite, non-decreasing, clamped vector for `pole_count`
// poles of `degree` (>= 1) with no interior multiplicity above `degree`.
void validate_knots(const std::vector<double>& knots, int degree, int pole_count, const char* what);

// Index of the knot span containing t (t is clamped into the domain).
int find_span(const std::vector<double>& knots, int degree, double t);

// Degrees up to this evaluate with work arrays on the stack (higher ones on the heap).
constexpr int kStackDegree = 15;

// Non-zero basis functions and their derivatives at t: out(k, j) is the k-th derivative of
// N_{span-degree+j}, for k = 0..order, j = 0..degree.
void basis_derivatives(const std::vector<double>& knots, int degree, int span, double t, int order,
                       Eigen::Ref<Eigen::MatrixXd> out);

// Greville abscissae (knot averages) of the poles: where a spline whose poles lie on an affine
// function of them reproduces that function.
std::vector<double> greville(const std::vector<double>& knots, int degree);

// Distinct knot values (span breakpoints) of a clamped vector, domain ends included.
std::vector<double> breakpoints(const std::vector<double>& knots, int degree);

}  // namespace varsurf
