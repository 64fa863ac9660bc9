#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf against FreeCAD's Surface Filling on N-sided holes, same edges, same run.

    /usr/bin/python3 bench/hole_bench.py

A smooth host face (a bicubic B-spline, 140 mm square, a few mm of waves) has a hole cut by a
prism: three, five and six sides, a concave L, and one with a 170 degree corner. Both fill the
hole from its edges with the host as the neighbour on every edge: Filling with BoundaryFaces and
order G1 (and one case G2), VarSurf with a G1 and, separately, a G2 constraint per edge and the
sheet trimmed to the loop. Measured on the results by OCCT (varsurf.solve.continuity, 200 points an edge), not by
either solver: the largest gap to the host, angle between the tangent planes and relative jump
of the normal curvature across the edges; degree and poles; and the fairness, the integral of
k1^2 + k2^2 over the trimmed face.
"""

import math
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
FREECAD_LIB = "/usr/lib/freecad-python3/lib"
for path in (FREECAD_LIB, str(REPO / "src"), str(REPO / "tests" / "python")):
    if path not in sys.path:
        sys.path.insert(0 if path != FREECAD_LIB else len(sys.path), path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

from brep_measure import bending_energy  # noqa: E402
from varsurf.solve import continuity  # noqa: E402
from varsurf.solve.constraints import ConstraintSpec  # noqa: E402
from varsurf.solve.sheet import solve_sheet_from_curves  # noqa: E402

V = FreeCAD.Vector
HALF = 70.0
SPANS = 8


def host_face():
    """A bicubic B-spline over [-70, 70]^2 parametrized by x and y (poles at the Greville points),
    its height a few millimetres of smooth waves."""
    knots = [-HALF + 2 * HALF * k / SPANS for k in range(SPANS + 1)]
    flat = [knots[0]] * 3 + knots + [knots[-1]] * 3
    greville = [sum(flat[i + 1:i + 4]) / 3.0 for i in range(len(flat) - 4)]
    height = lambda x, y: 6.0 * math.sin(x / 25.0) * math.cos(y / 30.0) + 0.002 * x * y  # noqa: E731
    surface = Part.BSplineSurface()
    mults = [4] + [1] * (SPANS - 1) + [4]
    surface.buildFromPolesMultsKnots([[V(x, y, height(x, y)) for y in greville] for x in greville],
                                     mults, mults, knots, knots, False, False, 3, 3)
    return surface.toShape()


def polygon(name):
    if name == "3 sides":
        return [(-30, -25), (35, -20), (0, 35)]
    if name in ("5 sides", "6 sides", "6 sides, G2"):
        n = 5 if name == "5 sides" else 6
        return [(32 * math.cos(2 * math.pi * k / n + 0.3), 32 * math.sin(2 * math.pi * k / n + 0.3)) for k in range(n)]
    if name == "concave L":
        return [(-30, -30), (30, -30), (30, -5), (-5, -5), (-5, 30), (-30, 30)]
    if name == "170 degree corner":
        return [(-30, -25), (30, -25), (30, 25), (0, 25 + 30 * math.tan(math.radians(5))), (-30, 25)]
    raise ValueError(name)


def holed(host, corners):
    """The host with the polygon's prism cut out: the face around the hole, and the hole's edges."""
    points = [V(x, y, -100) for x, y in corners]
    prism = Part.Face(Part.makePolygon(points + points[:1])).extrude(V(0, 0, 200))
    face = host.cut(prism).Faces[0]
    inner = [w for w in face.Wires if not w.isSame(face.OuterWire)][0]
    return face, list(inner.Edges)


def joins(face, edges, neighbour):
    found = [continuity.measure(f"edge {k}", face, e, neighbour) for k, e in enumerate(edges)]
    return max(j.gap for j in found), max(j.angle for j in found), max(j.curvature_jump for j in found)


def describe(face):
    s = face.Surface
    if hasattr(s, "NbUPoles"):
        return f"{s.UDegree}x{s.VDegree} / {s.NbUPoles}x{s.NbVPoles}"
    return s.TypeId


def run(doc, name, host):
    corners = polygon(name)
    around, edges = holed(host, corners)
    order = 2 if name.endswith("G2") else 1
    holder = doc.addObject("Part::Feature", "Around")
    holder.Shape = around
    doc.recompute()
    names = [f"Edge{next(i for i, a in enumerate(around.Edges) if a.isSame(e)) + 1}" for e in edges]
    filling = doc.addObject("Surface::Filling", "Filling")
    filling.BoundaryEdges = [(holder, n) for n in names]
    filling.BoundaryFaces = ["Face1"] * len(names)
    filling.BoundaryOrder = [order] * len(names)
    t = time.perf_counter()
    doc.recompute()
    fill_s = time.perf_counter() - t
    ok_f = filling.isValid() and not filling.Shape.isNull() and bool(filling.Shape.Faces)
    ours = {}
    for kind in ("G1", "G2"):  # every hole both ways: G2 is where the corners' curvature comes right
        specs = [ConstraintSpec(kind=kind, name=f"{kind} {k}", edge=e, reference=around) for k, e in enumerate(edges)]
        t = time.perf_counter()
        try:
            face = solve_sheet_from_curves(edges, tolerance=0.001, constraints=specs).shape
            ours[kind] = (time.perf_counter() - t, True, "", face)
        except Exception as error:  # the row says what failed
            ours[kind] = (time.perf_counter() - t, False, str(error)[:80], None)
    rows = []
    filled = [(f"VarSurf {kind}", ok, seconds, face, why) for kind, (seconds, ok, why, face) in ours.items()]
    filled.append((f"Filling {'G2' if order == 2 else 'G1'}", ok_f, fill_s, filling.Shape.Faces[0] if ok_f else None,
                   "" if ok_f else filling.getStatusString()))
    for label, ok, seconds, face, why in filled:
        if not ok:
            rows.append(f"| {name} | {label} | {seconds * 1e3:.0f} | failed: {why} "
                        "| | | | | |")
            continue
        gap, angle, jump = joins(face, edges, around)
        fairness, _area = bending_energy(face, 80)
        rows.append(f"| {name} | {label} | {seconds * 1e3:.0f} | yes | {gap:.2g} | {angle:.3g} | {jump:.3g} | "
                    f"{describe(face)} | {fairness:.4g} |")
    for o in (filling, holder):
        doc.removeObject(o.Name)
    return rows, (ours["G1"][0], ours["G2"][0], fill_s)


def main():
    print("\n## 7. N-sided holes: VarSurf against Surface Filling, same edges and neighbour, same run\n")
    print("Gap (mm), G1 angle (°) and G2 jump (%) are the largest along the hole's edges (200 points "
          "each); fairness is ∫(κ1²+κ2²) dA over the filled face.\n")
    print("| hole | filler | ms | success | max gap | max G1 angle | max G2 jump % | degree / poles | fairness |")
    print("|---|---|---|---|---|---|---|---|---|")
    doc = FreeCAD.newDocument("HoleBench")
    host = host_face()
    for name in ("3 sides", "5 sides", "6 sides", "concave L", "170 degree corner", "6 sides, G2"):
        rows, (g1_s, g2_s, fill_s) = run(doc, name, host)
        for row in rows:
            print(row)
        print(f"| {name} | time VarSurf G1, G2 / Filling | {g1_s / fill_s:.0f}x, {g2_s / fill_s:.0f}x | | | | | | |")
    FreeCAD.closeDocument(doc.Name)


if __name__ == "__main__":
    main()
