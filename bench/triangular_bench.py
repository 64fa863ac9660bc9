#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Triangular Bezier surfaces (Veltkamp & Wesselink) over closed meshes of 24 to 20,000 triangles.

    /usr/bin/python3 bench/triangular_bench.py [--quick]

Each mesh is a torus (a handle: every vertex of valence 6) of nu x nv quads cut into triangles,
its vertices interpolated by cubic patches, G1 across every edge. Per size: patches, unknowns,
the solve by sparse Cholesky and by conjugate gradients (the same system; their control points
compared), the worst angle between two patches' normals along their shared edge (50 points an
edge, measured on the patches), and the export: each patch written as three Bezier faces of
degree 3 x 3 and all faces sewn into one solid (OCCT), with the largest tangent-plane angle across
any seam of the B-rep. CG stops at a relative residual of 1e-12; above 2,000 triangles it is not
run (it takes minutes; see the README)."""

import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))
sys.path.insert(0, str(REPO / "examples"))

from triangular_surfaces import torus_mesh  # noqa: E402  (also puts FreeCAD on the path)
from varsurf.solve.native import native  # noqa: E402

SIZES = ((4, 3), (10, 10), (40, 25), (200, 50))  # 24, 200, 2,000 and 20,000 triangles
EXPORT_UP_TO = 2000
CG_UP_TO = 2000


def torus(nu, nv):
    points, triangles = torus_mesh(nu, nv)
    return np.asarray(points, float), triangles


def solve(nat, points, triangles, solver):
    problem = nat.TriangularProblem()
    problem.vertices = points
    problem.triangles = triangles
    problem.degree = 3
    problem.solver = solver
    started = time.perf_counter()
    result = nat.solve_triangular(problem)
    return result, time.perf_counter() - started


def main(quick=False):
    nat = native()
    print("## Triangular Bezier surfaces over closed meshes (tori, cubic patches, G1)")
    print()
    print("| triangles | unknowns | G1 rows | direct s | CG s (iterations) | CG vs direct | worst angle ° "
          "| export s (faces) | B-rep seam ° |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for nu, nv in SIZES[:3] if quick else SIZES:
        points, triangles = torus(nu, nv)
        direct, direct_seconds = solve(nat, points, triangles, nat.TriangularSolver.direct)
        report = direct.report
        cg_text = compare = "—"
        if len(triangles) <= CG_UP_TO:
            cg, cg_seconds = solve(nat, points, triangles, nat.TriangularSolver.cg)
            cg_text = f"{cg.report.assembly_seconds + cg.report.solve_seconds:.3f} ({cg.report.cg_iterations})"
            compare = f"{np.abs(cg.control - direct.control).max():.1e}"
        export_text = seam = "—"
        if len(triangles) <= EXPORT_UP_TO:
            started = time.perf_counter()
            quads = [q for patch in direct.patches for q in nat.triangle_quads(patch)]
            shell = nat.patch_shell(quads, [False] * len(quads), 1e-7 * 54.0, 11)
            export_text = f"{time.perf_counter() - started:.2f} ({len(quads)})"
            seam = f"{shell.regular_angle:.1e}" + ("" if shell.shell.valid and shell.shell.closed else " (not a solid)")
        print(f"| {len(triangles)} | {report.unknowns} | {3 * report.g1_rows} "
              f"| {report.assembly_seconds + report.solve_seconds:.3f} | {cg_text} | {compare} "
              f"| {report.worst_angle:.1e} | {export_text} | {seam} |")
    print()
    print("Solve times include assembly; the worst angle is measured on the patches afterwards "
          "(its own time, not counted). 1.5e-6° is the angle measurement's floor (acos near 1).")


if __name__ == "__main__":
    main("--quick" in sys.argv)
