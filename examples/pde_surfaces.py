#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: PDE surfaces from boundary conditions, after Du & Qin's figures.

    /usr/bin/python3 examples/pde_surfaces.py [OUT_DIR [FIGURE...]]   (default: out/pde, every figure)

- fig7: Hermite-like conditions: two boundary curves and their derivative curves (7A, 7B), and
  three sets of them joining two surfaces with one tangent across the shared curve (7C, 7D).
- fig8: Coons-like conditions (four boundary curves, 8A, 8B) and a Gordon-like network (curves at
  u = 0, 0.5, 1 and v = 0, 0.5, 1, 8C, 8D).
- fig9: one surface from its boundary curves on finer and finer grids (about Du & Qin's 15 x 15,
  30 x 30 and 60 x 60 samples: 15, 35 and 67 poles a side); the finer two solved by multigrid.
- fig11: the coefficient a: 3 everywhere, 5 painted on a region, 5 everywhere.
- fig12, fig13: sculpting tools: a point moved, a normal set, a curvature set; a frozen region.
- fig14: a non-isoparametric curve constraint: a curve on the surface mapped onto another.
- fig15: region manipulation: a rectangle of the surface mapped onto a destination patch.
- fig16: PDE displacements of an existing face (a Sheet with Energy = PDE and its base as rest
  shape): a point, a point beside a frozen region, a curve (17A), a region mapped onto a patch
  (17C).
- blend: Bloor & Wilson's blend, closed along v, from a cylinder (G1 to its side) to a flange.
- vase: a Gordon network closed along v: a cylinder's top circle, a belt and a rim (Part circles),
  two sketch profiles (an arc and a B-spline) across them.

Each figure writes figN.FCStd, figN.step and figN.png (the FreeCAD GUI under Xvfb, when present)
into OUT_DIR and prints what each surface measured.
"""

import math
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import varsurf  # noqa: E402
from figures import run_figures  # noqa: E402

V = FreeCAD.Vector


def curve(doc, name, points):
    """A Part feature with one B-spline edge through the points at evenly spaced parameters (the
    surface pairs its curves' points by parameter)."""
    spline = Part.BSplineCurve()
    spline.interpolate(points, Parameters=[k / (len(points) - 1) for k in range(len(points))])
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = spline.toShape()
    return obj


def along(f, n=9):
    return [f(k / (n - 1)) for k in range(n)]


def fig7(doc):
    """A wavy boundary at x = 0 and a straight one at x = 80, their derivative curves pointing up
    and along (7A-B); then a third boundary at x = 160 whose surface joins the first along x = 80,
    sharing that curve's derivative curve (7C-D: one tangent plane across the seam)."""
    c0 = curve(doc, "Boundary0", along(lambda t: V(0, 100 * t, 10 * math.sin(2 * math.pi * t))))
    c1 = curve(doc, "Boundary1", along(lambda t: V(80, 100 * t, 0)))
    c2 = curve(doc, "Boundary2", along(lambda t: V(160, 100 * t, 15 * t * (1 - t))))
    d0 = curve(doc, "Derivative0", along(lambda t: V(15, 100 * t, 10 * math.sin(2 * math.pi * t) + 25)))
    d1 = curve(doc, "Derivative1", along(lambda t: V(100, 100 * t, 10)))  # shared by both surfaces
    d2 = curve(doc, "Derivative2", along(lambda t: V(175, 100 * t, 15 * t * (1 - t) - 20)))
    doc.recompute()
    first = varsurf.make_pde_surface((c0, "Edge1"), (c1, "Edge1"), derivative0=(d0, "Edge1"),
                                     derivative1=(d1, "Edge1"), a=1.0, name="HermiteA")
    second = varsurf.make_pde_surface((c1, "Edge1"), (c2, "Edge1"), derivative0=(d1, "Edge1"),
                                      derivative1=(d2, "Edge1"), a=1.0, name="HermiteB")
    doc.recompute()
    return [first, second]


def fig8(doc):
    """A Coons patch on four curves, and a Gordon surface on a 3 x 3 network, side by side."""
    def surface_point(u, v, dx=0.0):
        return V(dx + 90 * u, 90 * v, 12 * math.sin(math.pi * u) * math.cos(math.pi * v) + 8 * u * v)

    coons = [curve(doc, name, along(f)) for name, f in (
        ("CoonsU0", lambda t: surface_point(0, t)), ("CoonsU1", lambda t: surface_point(1, t)),
        ("CoonsV0", lambda t: surface_point(t, 0)), ("CoonsV1", lambda t: surface_point(t, 1)))]
    net = {}
    for name, f in (("GordonU0", lambda t: surface_point(0, t, 120)), ("GordonU1", lambda t: surface_point(1, t, 120)),
                    ("GordonV0", lambda t: surface_point(t, 0, 120)), ("GordonV1", lambda t: surface_point(t, 1, 120)),
                    ("GordonUMid", lambda t: surface_point(0.5, t, 120) + V(0, 0, 10 * math.sin(math.pi * t))),
                    ("GordonVMid", lambda t: surface_point(t, 0.5, 120) + V(0, 0, 10 * math.sin(math.pi * t)))):
        net[name] = curve(doc, name, along(f, 17))
    doc.recompute()
    a = varsurf.make_pde_surface(*[(c, "Edge1") for c in coons[:2]], v0=(coons[2], "Edge1"), v1=(coons[3], "Edge1"),
                                 a=1.0, name="Coons")
    b = varsurf.make_pde_surface((net["GordonU0"], "Edge1"), (net["GordonU1"], "Edge1"), v0=(net["GordonV0"], "Edge1"),
                                 v1=(net["GordonV1"], "Edge1"), u_curves=[((net["GordonUMid"], "Edge1"), 0.5)],
                                 v_curves=[((net["GordonVMid"], "Edge1"), 0.5)], a=1.0, name="Gordon")
    doc.recompute()
    return [a, b]


def fig9(doc):
    """Du & Qin's Fig. 9: the boundary curves through a few points each (9A), and the PDE surface
    they bound on 12, 32 and 64 spans (9B-D), side by side; SolveModeUsed says how each was
    solved (the finer two by multigrid on their B-spline levels)."""
    def edge(u, v, dx):
        a, b = math.pi * u, math.pi * v
        return V(dx + 100 * u, 100 * v, 15 * math.cos(a) * math.sin(2 * b) + 12 * math.sin(a) * math.cos(b))

    out = []
    for k, spans in enumerate((12, 32, 64)):
        dx = 130.0 * k
        sides = [curve(doc, f"Grid{spans}{name}", along(f, 7)) for name, f in (
            ("U0", lambda t: edge(0, t, dx)), ("U1", lambda t: edge(1, t, dx)),
            ("V0", lambda t: edge(t, 0, dx)), ("V1", lambda t: edge(t, 1, dx)))]
        doc.recompute()
        pde = varsurf.make_pde_surface((sides[0], "Edge1"), (sides[1], "Edge1"), v0=(sides[2], "Edge1"),
                                       v1=(sides[3], "Edge1"), a=1.0, name=f"Grid{spans}")
        pde.MinSpans = pde.MaxSpans = spans
        out.append(pde)
    doc.recompute()
    return out


def fig11(doc):
    """The same Hermite data three times: a = 3; a = 3 with 5 painted on a region; a = 5."""
    out = []
    for k, (name, a, regions) in enumerate((("A3", 3.0, ()), ("Painted", 3.0, ((5.0, 0.3, 0.7, 0.5, 0.9),)),
                                            ("A5", 5.0, ()))):
        dy = 130.0 * k
        c0 = curve(doc, f"{name}U0", along(lambda t: V(0, dy + 100 * t, 20 * math.sin(math.pi * t))))
        c1 = curve(doc, f"{name}U1", along(lambda t: V(60, dy + 100 * t, 0)))
        d0 = curve(doc, f"{name}Derivative0", along(lambda t: V(20, dy + 100 * t, 20 * math.sin(math.pi * t) + 30)))
        d1 = curve(doc, f"{name}Derivative1", along(lambda t: V(80, dy + 100 * t, -30)))
        doc.recompute()
        out.append(varsurf.make_pde_surface((c0, "Edge1"), (c1, "Edge1"), derivative0=(d0, "Edge1"),
                                            derivative1=(d1, "Edge1"), a=a, regions=regions, blend=0.1,
                                            name=name))
    doc.recompute()
    return out


def blend(doc):
    """Bloor & Wilson's blend, closed along v: from a cylinder's top, tangent to its side, to a wider
    circle the surface reaches horizontally, with a = 0.5."""
    cylinder = doc.addObject("Part::Cylinder", "Cylinder")
    cylinder.Radius, cylinder.Height = 10.0, 20.0
    rim = doc.addObject("Part::Circle", "Rim")
    rim.Radius = 25.0
    rim.Placement = FreeCAD.Placement(V(0, 0, 35), FreeCAD.Rotation())
    flange = doc.addObject("Part::Circle", "Derivative1")
    flange.Radius = 40.0
    flange.Placement = rim.Placement
    doc.recompute()
    top = next(f"Edge{k + 1}" for k, e in enumerate(cylinder.Shape.Edges)
               if e.Curve.TypeId == "Part::GeomCircle" and abs(e.Vertexes[0].Point.z - 20.0) < 1e-9)
    side = next(f"Face{k + 1}" for k, f in enumerate(cylinder.Shape.Faces)
                if f.Surface.TypeId == "Part::GeomCylinder")
    surface = varsurf.make_pde_surface((cylinder, top), (rim, "Edge1"), face0=(cylinder, side),
                                       derivative1=(flange, "Edge1"), a=0.5, tolerance=1e-3, name="Blend")
    doc.recompute()
    return [surface]


def _profile_sketch(doc, name, angle, geometry):
    """A Sketcher profile in the vertical plane at `angle` degrees about z (sketch x = radius,
    sketch y = height)."""
    import Sketcher  # noqa: F401  (registers the type)

    sketch = doc.addObject("Sketcher::SketchObject", name)
    upright = FreeCAD.Rotation(V(1, 0, 0), 90)
    sketch.Placement = FreeCAD.Placement(V(0, 0, 0), FreeCAD.Rotation(V(0, 0, 1), angle) * upright)
    sketch.addGeometry(geometry)
    return sketch


def vase_scene(doc, flip_belt=False):
    """A vase closed along v from real inputs: a Part Cylinder's top circle (u0), a Part Circle
    rim (u1), a belt circle between them (a u-curve) and two sketch profiles from the cylinder
    through the belt to the rim, a three-point arc and an interpolated B-spline (v-curves at v = 0
    and 0.25: where the cylinder's circle starts and a quarter turn on)."""
    cylinder = doc.addObject("Part::Cylinder", "Cylinder")
    cylinder.Radius, cylinder.Height = 10.0, 20.0
    rim = doc.addObject("Part::Circle", "Rim")
    rim.Radius = 15.0
    rim.Placement = FreeCAD.Placement(V(0, 0, 60), FreeCAD.Rotation(V(0, 0, 1), 50))
    belt = doc.addObject("Part::Circle", "Belt")
    belt.Radius = 24.0
    # Its seam elsewhere; flipped over, it runs the other way round.
    turn = FreeCAD.Rotation(V(0, 0, 1), 130)
    belt.Placement = FreeCAD.Placement(V(0, 0, 40), turn * FreeCAD.Rotation(V(1, 0, 0), 180) if flip_belt else turn)
    p0 = _profile_sketch(doc, "Profile0", 0.0, Part.Arc(V(10, 20, 0), V(24, 40, 0), V(15, 60, 0)))
    spline = Part.BSplineCurve()
    spline.interpolate([V(10, 20, 0), V(17, 28, 0), V(24, 40, 0), V(21, 52, 0), V(15, 60, 0)])
    p1 = _profile_sketch(doc, "Profile1", 90.0, spline)
    doc.recompute()
    top = next(f"Edge{k + 1}" for k, e in enumerate(cylinder.Shape.Edges)
               if e.Curve.TypeId == "Part::GeomCircle" and abs(e.Vertexes[0].Point.z - 20.0) < 1e-9)
    return cylinder, top, rim, belt, p0, p1


def vase(doc):
    """A Gordon network closed along v: a vase from a cylinder's top circle through a belt to a
    rim, its profiles a sketch arc and a sketch B-spline (v = 0 and 0.25)."""
    cylinder, top, rim, belt, p0, p1 = vase_scene(doc)
    surface = varsurf.make_pde_surface((cylinder, top), (rim, "Edge1"), u_curves=[((belt, "Edge1"), 0.5)],
                                       v_curves=[((p0, "Edge1"), 0.0), ((p1, "Edge1"), 0.25)], a=0.5,
                                       tolerance=1e-2, name="Vase")
    doc.recompute()
    return [surface]


def _hermite_patch(doc, prefix, dx=0.0, a=2.0, place=None):
    """Fig. 7's kind of surface, used by the sculpting figures: a wavy and a straight boundary with
    their derivative curves, 100 mm long, at x = dx .. dx + 80 (each point mapped by `place`, when
    given: the same scene moved or scaled)."""
    def at(f):
        return [place(p) for p in along(f)] if place else along(f)

    c0 = curve(doc, f"{prefix}Boundary0", at(lambda t: V(dx, 100 * t, 10 * math.sin(2 * math.pi * t))))
    c1 = curve(doc, f"{prefix}Boundary1", at(lambda t: V(dx + 80, 100 * t, 0)))
    d0 = curve(doc, f"{prefix}Derivative0", at(lambda t: V(dx + 15, 100 * t, 10 * math.sin(2 * math.pi * t) + 25)))
    d1 = curve(doc, f"{prefix}Derivative1", at(lambda t: V(dx + 100, 100 * t, 10)))
    doc.recompute()
    return varsurf.make_pde_surface((c0, "Edge1"), (c1, "Edge1"), derivative0=(d0, "Edge1"),
                                    derivative1=(d1, "Edge1"), a=a, name=prefix)


def fig12(doc):
    """Point, normal and curvature sculpting (12A, 12B, 12C): a surface point moved 15 mm up; the
    normal there tilted by 30 degrees; the curvature there across the surface (along u) set to
    1/25 mm, bending toward +z, and along v to 0."""
    moved = _hermite_patch(doc, "PointMoved")
    tilted = _hermite_patch(doc, "NormalSet", dx=130.0)
    bent = _hermite_patch(doc, "CurvatureSet", dx=260.0)
    doc.recompute()
    varsurf.make_constraint(bent, "Curvature", uv=(0.5, 0.5), vector=(0, 0, 1), curvature=(1 / 25.0, 0.0))
    target = moved.Shape.Faces[0].Surface.value(0.5, 0.5) + V(0, 0, 15)
    varsurf.make_constraint(moved, "Point", uv=(0.5, 0.5), origin=(target.x, target.y, target.z))
    varsurf.make_constraint(tilted, "Normal", uv=(0.5, 0.5), vector=(math.sin(math.radians(30)), 0,
                                                                     math.cos(math.radians(30))))
    doc.recompute()
    return [moved, tilted, bent]


def fig13(doc):
    """A frozen region (13A): the surface outside it is pulled 15 mm up, the region keeps its shape."""
    frozen = _hermite_patch(doc, "Frozen")
    doc.recompute()
    target = frozen.Shape.Faces[0].Surface.value(0.5, 0.3) + V(0, 0, 15)
    varsurf.make_constraint(frozen, "Point", uv=(0.5, 0.3), origin=(target.x, target.y, target.z))
    varsurf.make_constraint(frozen, "FrozenRegion", region=(0.3, 0.8, 0.6, 0.95))
    doc.recompute()
    return [frozen]


def fig14(doc):
    """A non-isoparametric curve constraint (Fig. 14): a diagonal curve drawn on the surface is
    mapped onto a destination curve that rises 20 mm in its middle (a CurveMap); the boundary
    conditions hold."""
    patch = _hermite_patch(doc, "Mapped")
    doc.recompute()
    surface = patch.Shape.Faces[0].Surface
    u0, u1, v0, v1 = surface.bounds()
    diagonal = [surface.value(u0 + (u1 - u0) * (0.2 + 0.6 * t), v0 + (v1 - v0) * (0.15 + 0.7 * t))
                for t in (i / 8 for i in range(9))]
    source = curve(doc, "MappedSource", diagonal)
    destination = curve(doc, "MappedDestination",
                        [p + V(0, 0, 20 * math.sin(math.pi * i / 8)) for i, p in enumerate(diagonal)])
    doc.recompute()
    varsurf.make_constraint(patch, "CurveMap", curve=(source, "Edge1"), reference=(destination, "Edge1"))
    doc.recompute()
    return [patch]


def fig15(doc):
    """Region manipulation (Fig. 15): a rectangle of the surface's (u, v) mapped onto a destination
    B-spline patch, a dome 25 mm above the surface's middle."""
    patch = _hermite_patch(doc, "RegionMapped")
    doc.recompute()
    poles = [[V(20 + 40 * i / 3, 30 + 40 * j / 3, 25 + (12 if 0 < i < 3 and 0 < j < 3 else 0)) for j in range(4)]
             for i in range(4)]
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, [4, 4], [4, 4], [0.0, 1.0], [0.0, 1.0], False, False, 3, 3)
    dome = doc.addObject("Part::Feature", "RegionMappedDome")
    dome.Shape = surface.toShape()
    doc.recompute()
    varsurf.make_constraint(patch, "RegionMap", reference=(dome, "Face1"), region=(0.3, 0.7, 0.3, 0.7))
    doc.recompute()
    return [patch]


def fig16(doc):
    """PDE displacements (Figs. 16-17): a Sheet on an existing face with Energy = PDE and the face
    as rest shape; a point lifts it (16A), another with a frozen region beside it (16C), and a
    curve above the face sculpts it (17A). The face itself is untouched."""
    out = []
    for k, name in enumerate(("DisplacedPoint", "DisplacedFrozen", "DisplacedCurve", "DisplacedRegion")):
        base = doc.addObject("Part::Feature", f"{name}Base")
        poles = [[V(130 * k + 20 * i, 20 * j, 6 * math.sin(math.pi * i / 5) * math.sin(math.pi * j / 5))
                  for j in range(6)] for i in range(6)]
        surface = Part.BSplineSurface()
        knots, mults = [0.0, 1 / 3, 2 / 3, 1.0], [4, 1, 1, 4]
        surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, 3, 3)
        base.Shape = surface.toShape()
        curves = []
        if name == "DisplacedCurve":
            arc = doc.addObject("Part::Feature", f"{name}Arc")
            arc.Shape = Part.Arc(V(130 * k + 20, 50, 15), V(130 * k + 50, 60, 22), V(130 * k + 80, 50, 15)).toShape()
            curves = [(arc, "Edge1")]
        doc.recompute()
        sheet = varsurf.make_sheet((base, "Face1"), curves, energy="PDE", pde_a=2.0, name=name)
        if name in ("DisplacedPoint", "DisplacedFrozen"):
            at = (0.35, 0.5) if name == "DisplacedFrozen" else (0.5, 0.5)
            target = surface.value(*at) + V(0, 0, 12)
            varsurf.make_constraint(sheet, "Point", uv=at, origin=(target.x, target.y, target.z))
        if name == "DisplacedFrozen":
            varsurf.make_constraint(sheet, "FrozenRegion", region=(0.65, 0.95, 0.1, 0.9))
        if name == "DisplacedRegion":  # 17C: the middle of the face mapped onto a raised, tilted patch
            corners = [[V(130 * k + 35 + 10 * i, 35 + 10 * j, 14 + 2 * i + (5 if 0 < i < 3 and 0 < j < 3 else 0))
                        for j in range(4)] for i in range(4)]
            patch = Part.BSplineSurface()
            patch.buildFromPolesMultsKnots(corners, [4, 4], [4, 4], [0.0, 1.0], [0.0, 1.0], False, False, 3, 3)
            target = doc.addObject("Part::Feature", f"{name}Patch")
            target.Shape = patch.toShape()
            doc.recompute()
            varsurf.make_constraint(sheet, "RegionMap", reference=(target, "Face1"), region=(0.35, 0.65, 0.35, 0.65))
        base.Visibility = False
        out.append(sheet)
    doc.recompute()
    return out


FIGURES = {"fig7": fig7, "fig8": fig8, "fig9": fig9, "fig11": fig11, "fig12": fig12, "fig13": fig13, "fig14": fig14,
           "fig15": fig15, "fig16": fig16,
           "blend": blend, "vase": vase}


def _build_report(stem, doc):
    surfaces = FIGURES[stem](doc)
    lines = [f"{stem} {s.Label}: {s.Status if s.isValid() else s.getStatusString()}; "
             f"deviations {', '.join(f'{d:.2g}' for d in s.MaxDeviations)} mm; {s.SolveTime * 1000:.0f} ms; "
             f"{s.SolveModeUsed}" for s in surfaces]
    return surfaces, surfaces, lines


def main(out_dir="out/pde", *only):
    """Every figure, or those named after OUT_DIR (e.g. fig9 fig16)."""
    return run_figures(FIGURES, out_dir, only, _build_report)


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
