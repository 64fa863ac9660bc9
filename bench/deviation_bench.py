#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Time of the deviation measurement (varsurf._native.max_deviation) and its agreement with
FreeCAD's distToShape at the same number of points:

    /usr/bin/python3 bench/deviation_bench.py

1. Wild faces as the bridge's fuzzer builds them: degree 6, random knots and weights, poles
   scattered over +-20 mm, a random cubic curve over +-20 mm; 300 samples.
2. A face's own boundary edges on rational non-uniform faces of degree 2 .. 7.
3. A sheet of 67 x 67 poles through a curve of 25 waves (the result of a Sheet's refinement).
"""

import math
import random
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))
sys.path.append("/usr/lib/freecad-python3/lib")

import FreeCAD  # noqa: E402
import Part  # noqa: E402

from varsurf.solve.native import native  # noqa: E402
from varsurf.solve.sheet import solve_sheet_on_face  # noqa: E402

V = FreeCAD.Vector
nat = native()


def timed(f, *args):
    t0 = time.perf_counter()
    value = f(*args)
    return value, time.perf_counter() - t0


def dist_to_shape_max(face, edge, n):
    t0, t1 = edge.FirstParameter, edge.LastParameter
    return max(face.distToShape(Part.Vertex(edge.valueAt(t0 + (t1 - t0) * i / (n - 1))))[0] for i in range(n))


def random_bspline_face(rng, degree, nu, nv, spread):
    poles = [[V(*(rng.uniform(-spread, spread) for _ in range(3))) for _ in range(nv)] for _ in range(nu)]
    weights = [[rng.uniform(0.2, 5.0) for _ in range(nv)] for _ in range(nu)]

    def knots(n):
        inner = sorted(rng.uniform(0.0, 1.0) for _ in range(n - degree - 1))
        return [0.0] + inner + [1.0], [degree + 1] + [1] * len(inner) + [degree + 1]

    uk, um = knots(nu)
    vk, vm = knots(nv)
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, um, vm, uk, vk, False, False, degree, degree, weights)
    return surface.toShape()


def brep(face_or_edge, surface=True):
    text = face_or_edge.exportBrepToString()
    return nat.surface_from_face_brep(text) if surface else nat.curve_from_edge_brep(text)


def wild_faces(cases=8):
    print("1. wild degree-6 faces, 300 samples")
    print(f"{'case':>4} {'max_deviation (mm)':>19} {'time (s)':>9} {'distToShape@300 (mm)':>21} {'time (s)':>9}")
    rng = random.Random(3)
    for case in range(cases):
        face = random_bspline_face(rng, 6, rng.randint(7, 14), rng.randint(7, 14), 20.0)
        curve = Part.BSplineCurve()
        curve.buildFromPoles([V(*(rng.uniform(-20, 20) for _ in range(3))) for _ in range(8)], False, 3)
        edge = curve.toShape()
        measured, seconds = timed(nat.max_deviation, brep(face), brep(edge, False), 300)
        reference, ref_seconds = timed(dist_to_shape_max, face, edge, 300)
        print(f"{case:>4} {measured:>19.6f} {seconds:>9.3f} {reference:>21.6f} {ref_seconds:>9.2f}")


def own_edges():
    print("\n2. a face's own boundary edges (rational, non-uniform), 200 samples")
    print(f"{'degree':>6} {'largest figure (mm)':>20} {'time per edge (s)':>18}")
    rng = random.Random(5)
    for degree in range(2, 8):
        face = random_bspline_face(rng, degree, degree + 4, degree + 3, 50.0)
        sheet = brep(face)
        figures, seconds = [], 0.0
        for edge in face.Edges:
            value, dt = timed(nat.max_deviation, sheet, brep(edge, False), 200)
            figures.append(value)
            seconds += dt
        print(f"{degree:>6} {max(figures):>20.3g} {seconds / len(face.Edges):>18.4f}")


def fine_sheet():
    print("\n3. a 67 x 67 pole sheet through a curve of 25 waves")
    curve = Part.BSplineCurve()
    curve.interpolate(
        [V(5 + 90 * s, 50 + 10 * math.sin(2 * math.pi * s), 2 * math.sin(2 * math.pi * 25 * s))
         for s in (i / 500 for i in range(501))]
    )
    edge = curve.toShape()
    outcome = solve_sheet_on_face(Part.makePlane(100, 100), [edge])
    target = brep(edge, False)
    print(f"poles {outcome.pole_count_u} x {outcome.pole_count_v}")
    print(f"{'samples':>7} {'max_deviation (mm)':>19} {'time (s)':>9}")
    for samples in (50, 100, 200, 300, 1000, 2001):
        value, seconds = timed(nat.max_deviation, outcome.surface, target, samples)
        print(f"{samples:>7} {value:>19.9f} {seconds:>9.3f}")


if __name__ == "__main__":
    wild_faces()
    own_edges()
    fine_sheet()
