#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: multiresolution subdivision surfaces, after Boier-Martin, Ronfard & Bernardini.

    /usr/bin/python3 examples/subdivision_surfaces.py [OUT_DIR [FIGURE...]]   (default: out/subd)

- fig1: region of influence: one pin on a plane with a captured relief, propagated to level 0
  (the whole sheet bends), level 2 and level 4 (a small patch moves); the relief is kept.
- fig7: an organic model rich in detail: a bumpy vase scanned as a Mesh, captured onto a 40-face
  cage; pins bend its top over and pull its belly out, and the bumps ride along. Its limit
  surface as a B-rep (SubdBRep).
- fig8: the approximate answer (Catmull-Clark rules on the deformation, what a drag shows)
  beside the refined one (the energy's minimum) for the same pin.
- fig9: a planar sheet with a square hole whose inner boundary is turned (an arcball's 30
  degrees) and lifted, the outer boundary held: the surface follows smoothly.

Each figure writes figN.FCStd, figN.step (the SubdBReps) and figN.png (the FreeCAD GUI under
Xvfb, when present) into OUT_DIR and prints what it measured.
"""

import math
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Mesh  # noqa: E402
import Part  # noqa: E402

import varsurf  # noqa: E402
from varsurf.app import subd_pins  # noqa: E402
from figures import run_figures  # noqa: E402

V = FreeCAD.Vector


def quad_cage(doc, name, points, quads):
    """A Part shell of planar-or-not quads sharing their vertices (a control cage)."""
    faces = []
    for q in quads:
        loop = [V(*points[i]) for i in q]
        wire = Part.makePolygon(loop + [loop[0]])
        try:
            faces.append(Part.Face(wire))
        except Part.OCCError:  # a quad that is not planar: a ruled face through its sides
            faces.append(Part.makeRuledSurface(Part.makeLine(loop[0], loop[1]), Part.makeLine(loop[3], loop[2])))
    shell = Part.Shell(faces)
    shell.sewShape()
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = shell
    return obj


def grid_points(n, size, hole=0):
    """(points, quads) of an n x n grid of quads over [0, size]^2, without the middle hole x hole."""
    points = [(size * i / n, size * j / n, 0.0) for i in range(n + 1) for j in range(n + 1)]
    lo, hi = (n - hole) // 2, (n + hole) // 2
    quads = [[i * (n + 1) + j, (i + 1) * (n + 1) + j, (i + 1) * (n + 1) + j + 1, i * (n + 1) + j + 1]
             for i in range(n) for j in range(n) if not (hole and lo <= i < hi and lo <= j < hi)]
    return points, quads


def relief_mesh(doc, name, size, amplitude=0.6, wave=6.0, n=240):
    """A scanned plane with bumps, as a Mesh."""
    m = Mesh.Mesh()
    pts = [V(size * i / n, size * j / n, amplitude * math.sin(2 * math.pi * size * i / n / wave)
             * math.sin(2 * math.pi * size * j / n / wave)) for i in range(n + 1) for j in range(n + 1)]
    tris = []
    for i in range(n):
        for j in range(n):
            a, b = i * (n + 1) + j, (i + 1) * (n + 1) + j
            tris += [(a, b, b + 1), (a, b + 1, a + 1)]
    m.addFacets((pts, tris))
    obj = doc.addObject("Mesh::Feature", name)
    obj.Mesh = m
    return obj


def nearest(subd, level, point):
    pts = subd.Proxy.outcome.levels[level]
    return min(range(len(pts)), key=lambda k: (V(*pts[k]) - point).Length)


def fig1(doc):
    size, levels = 100.0, 4
    made = []
    for k, influence in enumerate((0, 2, 4)):
        points, quads = grid_points(10, size)
        shift = V(0, k * 130.0, 0)
        cage = quad_cage(doc, f"Cage{influence}", [(x, y + shift.y, z) for x, y, z in points], quads)
        scan = relief_mesh(doc, f"Scan{influence}", size)
        scan.Placement.Base = shift
        subd = varsurf.make_subd_surface(cage, levels=levels, target=scan, name=f"Influence{influence}")
        doc.recompute()
        v = nearest(subd, levels, V(50, 50, 0) + shift)
        target = V(*subd.Proxy.outcome.levels[levels][v]) + V(0, 0, 20)
        varsurf.set_pins(subd, [(levels, v, target, influence)])
        made.append(subd)
    doc.recompute()
    return made, []


def vase_mesh(doc, n_theta=200, n_z=100, height=60.0):
    m = Mesh.Mesh()

    def r(t, z):
        return 20 + 6 * math.sin(math.pi * z / height) + 0.8 * math.sin(12 * t) * math.sin(2 * math.pi * z / 7.5)

    pts = []
    for i in range(n_theta):
        t = 2 * math.pi * i / n_theta
        for j in range(n_z):
            z = -2 + (height + 4) * j / (n_z - 1)
            pts.append(V(r(t, z) * math.cos(t), r(t, z) * math.sin(t), z))
    tris = []
    for i in range(n_theta):
        for j in range(n_z - 1):
            a, b = i * n_z + j, ((i + 1) % n_theta) * n_z + j
            tris += [(a, b, b + 1), (a, b + 1, a + 1)]
    m.addFacets((pts, tris))
    obj = doc.addObject("Mesh::Feature", "VaseScan")
    obj.Mesh = m
    return obj


def vase_cage_points(around=8, high=5, height=60.0):
    """(points, quads) of an open tube of quads around the vase (40 faces)."""
    points = [(24 * math.cos(2 * math.pi * i / around), 24 * math.sin(2 * math.pi * i / around), height * j / high)
              for i in range(around) for j in range(high + 1)]
    quads = [[i * (high + 1) + j, ((i + 1) % around) * (high + 1) + j, ((i + 1) % around) * (high + 1) + j + 1,
              i * (high + 1) + j + 1] for i in range(around) for j in range(high)]
    return points, quads


def fig7(doc):
    cage = quad_cage(doc, "VaseCage", *vase_cage_points())
    scan = vase_mesh(doc)
    subd = varsurf.make_subd_surface(cage, levels=4, target=scan, name="Vase")
    doc.recompute()
    top = nearest(subd, 4, V(30, 0, 60))
    belly = nearest(subd, 4, V(-30, 0, 30))
    pts = subd.Proxy.outcome.levels[4]
    varsurf.set_pins(subd, [(4, top, V(*pts[top]) + V(12, 0, -6), 1), (4, belly, V(*pts[belly]) + V(-10, 0, 0), 1)])
    doc.recompute()
    brep = varsurf.make_subd_brep(subd, isolation=3)
    doc.recompute()
    return [subd], [brep]


def fig8(doc):
    made = []
    for k, solve in enumerate(("Approximate", "Direct")):
        points, quads = grid_points(8, 80.0)
        shift = 100.0 * k
        cage = quad_cage(doc, f"Cage{solve}", [(x + shift, y, z) for x, y, z in points], quads)
        subd = varsurf.make_subd_surface(cage, levels=3, name=solve)
        doc.recompute()
        v = nearest(subd, 3, V(40 + shift, 40, 0))
        varsurf.set_pins(subd, [(3, v, V(*subd.Proxy.outcome.levels[3][v]) + V(0, 0, 25), 1)])
        subd.Solve = solve
        made.append(subd)
    doc.recompute()
    return made, []


def fig9(doc):
    n, size, levels = 12, 120.0, 3
    points, quads = grid_points(n, size, hole=4)
    cage = quad_cage(doc, "SheetCage", points, quads)
    subd = varsurf.make_subd_surface(cage, levels=levels, name="TurnedHole")
    doc.recompute()
    centre = V(size / 2, size / 2, 0)
    # The hole's boundary loop turned 30 degrees about its centre (the arcball's turn) and lifted;
    # the outer loop held: their vertices at every level, exactly.
    inner, outer = subd_pins.loop_at(subd, centre), subd_pins.loop_at(subd, V(0, 0, 0))
    motion = FreeCAD.Placement(V(0, 0, 25), FreeCAD.Rotation(V(1, 1, 0), 30), centre)
    varsurf.set_curves(subd, [], motion, loops=[inner], held=[outer], influence=0)
    doc.recompute()
    brep = varsurf.make_subd_brep(subd, isolation=3)
    doc.recompute()
    return [subd], [brep]


def relief_height(x, y, amplitude=0.6, wave=6.0):
    """The scanned relief's height (relief_mesh's function)."""
    return amplitude * math.sin(2 * math.pi * x / wave) * math.sin(2 * math.pi * y / wave)


def fig7d(doc):
    """A curve drawn on the scanned relief (a closed B-spline through points of the scan) lifted
    12 mm and turned 20 degrees about its own centre: the surface follows it with its bumps."""
    size, levels = 100.0, 4  # 25,600 faces: its B-rep is 9 merged faces, sewn in 0.2 s
    points, quads = grid_points(10, size)
    cage = quad_cage(doc, "ReliefCage", points, quads)
    scan = relief_mesh(doc, "ReliefScan", size)
    subd = varsurf.make_subd_surface(cage, levels=levels, target=scan, name="CarriedRelief")
    centre = V(50, 50, 0)
    ring = [V(50 + 22 * math.cos(t), 50 + 16 * math.sin(t), 0.0)
            for t in (2 * math.pi * k / 48 for k in range(48))]
    curve = Part.BSplineCurve()
    curve.interpolate([V(p.x, p.y, relief_height(p.x, p.y)) for p in ring], PeriodicFlag=True)
    drawn = doc.addObject("Part::Feature", "DrawnCurve")
    drawn.Shape = curve.toShape()
    motion = FreeCAD.Placement(V(0, 0, 12), FreeCAD.Rotation(V(1, 0, 0), 20), centre)
    varsurf.set_curves(subd, [(drawn, "Edge1")], motion, influence=0)
    doc.recompute()
    brep = varsurf.make_subd_brep(subd, isolation=2)
    doc.recompute()
    return [subd], [brep]


FIGURES = {"fig1": fig1, "fig7": fig7, "fig7d": fig7d, "fig8": fig8, "fig9": fig9}


def _build_report(stem, doc):
    surfaces, breps = FIGURES[stem](doc)
    lines = [f"{stem} {s.Label}: {s.Status if s.isValid() else s.getStatusString()}" for s in surfaces + breps]
    return surfaces + breps, breps, lines


def main(out_dir="out/subd", *only):
    """Every figure, or those named after OUT_DIR (e.g. fig1 fig9)."""
    return run_figures(FIGURES, out_dir, only, _build_report)


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
