// SPDX-License-Identifier: LGPL-2.1-or-later
// The fairest surface of triangular Bezier patches over a triangulation (Veltkamp & Wesselink
// secs. 3, 4 and 6): the patches' stretch and bend energies (eqs. 6-7, exactly) minimized over
// all control points, the mesh's vertices interpolated, G1 across every inner edge by the linear
// conditions of sec. 4.3 as default constraints, and the user's point, normal, point-in-plane and
// point-on-line constraints.
//
// Interpolation overrules continuity (their sec. 4.3): fixed points are eliminated, the user's
// constraints are held exactly (Lagrange multipliers through the factored energy), and the G1
// conditions by an augmented Lagrangian (a penalty well above the energy's plus multiplier
// updates). Where they can be met they are met to rounding; where they cannot (an even valence's
// vertex enclosure, interpolation that forbids them) the rounds stop at the compromise, and the
// report names every edge whose measured angle stays above the tolerance.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "varsurf/core/external_energy.hpp"
#include "varsurf/core/triangle_net.hpp"
#include "varsurf/core/triangular_bezier.hpp"

namespace varsurf {

// A constraint at barycentric point `at` of triangle `triangle` (as given, before orientation).
struct TriangularConstraint {
  enum class Kind {
    point,   // T = target
    normal,  // the normal is `direction` (its two tangents are perpendicular to it)
    plane,   // (T - target) . direction = 0
    line,    // T on the line through target along direction
  };
  Kind kind = Kind::point;
  int triangle = 0;
  Eigen::Vector3d at = Eigen::Vector3d::Constant(1.0 / 3.0);
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};

// An external energy operator (their sec. 5) on some of the surface's triangles, through the
// same terms as a sheet's (operator_terms.hpp): attractors pull toward a point, plane or line,
// a director turns the normals toward a direction, a repeller pushes away from a point, a shape
// attractor pulls onto another surface or curve. Strengths are relative as a sheet's: 1 pulls
// about as hard as the surface resists.
struct TriangularOperator {
  enum class Kind {
    point_attractor,
    plane_attractor,
    line_attractor,
    director,
    repeller,
    shape_attractor
  };
  Kind kind = Kind::point_attractor;
  std::vector<int> triangles;  // where it acts (numbered as given); empty: everywhere
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // plane normal, line, director
  double strength = 1.0;
  ClosestPointFunction closest;  // shape attractor: the target
};

// A curve the surface must contain along a chain of mesh edges (their sec. 4.2: patch edges carry
// the curve): the edge from vertex `from` to vertex `to` gets the degree + 1 control points
// `points`, in that order; the first and last are where the two vertices go.
struct FixedEdge {
  int from = 0, to = 1;
  Eigen::MatrixX3d points;
};

enum class TriangularSolver {
  // Direct up to `cg_above` unknowns, CG above. The G1 rows' weight makes CG slow: measured on a
  // torus of 1600 cubic patches (19200 unknowns), 2092 iterations and 1.4 s against the direct
  // solve's 0.02 s; so CG is kept for systems whose factor would not fit in memory.
  automatic,
  direct,  // sparse Cholesky (CHOLMOD)
  cg,      // conjugate gradients, incomplete-Cholesky preconditioned
};

struct TriangularProblem {
  Eigen::MatrixX3d vertices;
  std::vector<std::array<int, 3>> triangles;
  int degree = 3;
  double stretch = 0.0;  // weights of eq. 1's internal energy
  double bend = 1.0;
  bool interpolate_vertices = true;  // the mesh's vertices are points of the surface
  // Vertices not interpolated even so: those a split added off the curves, which only shape the
  // control structure (their sec. 4.2), so the energy places them.
  std::vector<int> free_vertices;
  // Each patch's energy over the equilateral triangle of its area (their eq. 25), or over the mesh
  // triangle itself laid flat, which follows the mesh's own proportions.
  bool equilateral_domain = true;
  // The energy of the displacement from the mesh's own flat patches instead of the points' own
  // (as a sheet's rest shape): what nothing pulls stays where the mesh is, so operators and
  // constraints sculpt the mesh rather than replace it.
  bool energy_of_displacement = false;
  bool g1 = true;
  bool approximate_g1 = false;  // their weaker variant (one row between the vertex rows)
  // Border vertices: the angle the surface turns through there. Negative: the angle the mesh's
  // own triangles span (a corner of the mesh stays a corner); their default is pi.
  double border_angle = -1.0;
  std::vector<TriangularConstraint> constraints;
  std::vector<TriangularOperator> operators;
  std::vector<FixedEdge> fixed_edges;
  // Repellers and shape attractors are not quadratic: Gauss-Newton steps until no control point
  // moves by more than nonlinear_tolerance times the mesh's size, or this many.
  int nonlinear_iterations = 30;
  double nonlinear_tolerance = 1e-9;
  // The G1 conditions' penalty weight over the energy's (both scaled to unit mean diagonal), and
  // the most rounds of multiplier updates that drive the rows that can be met to zero.
  double g1_weight = 1e6;
  int g1_rounds = 30;
  TriangularSolver solver = TriangularSolver::automatic;
  int cg_above = 3000000;
  double cg_tolerance = 1e-12;  // relative residual
  int cg_iterations = 20000;
  double angle_tolerance = 0.01;  // degrees: an edge above it is reported as overruled
  int angle_samples = 50;
};

struct TriangularReport {
  int patches = 0;
  int control_points = 0;
  int unknowns = 0;             // free coordinates
  int g1_rows = 0;              // per coordinate
  int g1_rounds = 0;            // multiplier updates made (the last solve's)
  int operator_iterations = 0;  // Gauss-Newton steps of the non-quadratic operators
  int constraint_rows = 0;
  std::string solver;  // "direct" or "cg"
  int cg_iterations = 0;
  double cg_error = 0.0;
  double worst_angle = 0.0;  // degrees, over every inner edge
  int edges_measured = 0;
  // Inner edges (vertex pairs) whose normals still differ by more than angle_tolerance, and by how
  // much (degrees): where interpolation overruled continuity or the space could not meet it.
  std::vector<std::array<int, 2>> overruled_edges;
  std::vector<double> overruled_angles;
  // The shortest tangent at a vertex, |M_1 - M_0| over the edge's length, over all edges (1 / n
  // for a straight edge evenly parameterized): near 0 the surface is close to a singular point
  // there, where the normal is ill-defined; `singular_vertices` lists those below 0.01.
  double shortest_tangent = 0.0;
  std::vector<int> singular_vertices;
  // Largest residual of the user's constraints (model units; normals: sine of the angle): what a
  // conflict among them leaves.
  double constraint_residual = 0.0;
  std::vector<int> flipped;  // triangles whose corners were reversed to orient the surface alike
  double assembly_seconds = 0.0, solve_seconds = 0.0, measure_seconds = 0.0;
};

struct TriangularResult {
  std::vector<TriangularBezier> patches;  // per triangle, in the oriented corner order
  Eigen::MatrixX3d control;               // the global control points
  TriangularReport report;
};

// InvalidInput naming the triangle, edge, vertex, constraint or operator at fault (see
// make_triangle_net; a constraint's triangle out of range, a point outside its triangle, a zero
// direction, a vertex whose G1 weights do not exist); SolveFailure when the system cannot be
// factored.
TriangularResult solve_triangular(const TriangularProblem& problem);

// The largest angle (degrees) between the normals of the two patches at each inner edge of `net`.
std::vector<double> edge_angles(const TriangleNet& net,
                                const std::vector<TriangularBezier>& patches, int samples);

}  // namespace varsurf
