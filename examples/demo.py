#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf demo: a variational sheet over a curved B-spline face, through three sketches.

    /usr/bin/python3 examples/demo.py [OUT_DIR]        (default: out/demo)

Builds a document with a gently curved bicubic base face (11 x 11 poles over 100 x 80 mm) and three
sketches (a diagonal ridge line above it, an arc and a short rail below it), makes a Sheet, recomputes, and
writes into OUT_DIR:

    demo.FCStd   the FreeCAD document (open it with the VarSurf workbench installed)
    demo.step    the sheet as an AP214 STEP file
    demo.png     an isometric picture, rendered by the FreeCAD GUI under Xvfb
    report.txt   poles, degree, max deviation per curve, solve time
"""

import math
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from freecad_env import REPO  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402
import Sketcher  # noqa: E402

import varsurf  # noqa: E402

V = FreeCAD.Vector


def base_face(width=100.0, depth=80.0, spans=8):
    """Gently curved, non-planar bicubic face over width x depth mm: a low dome with a slight
    twist, (spans + 3)^2 poles placed at the Greville abscissae (x, y linear in u, v)."""
    knots = [k / spans for k in range(spans + 1)]
    mults = [4] + [1] * (spans - 1) + [4]
    flat = [0.0] * 4 + knots[1:-1] + [1.0] * 4
    greville = [sum(flat[i + 1:i + 4]) / 3.0 for i in range(len(flat) - 4)]
    poles = []
    for s in greville:
        row = []
        for t in greville:
            z = 4.0 * math.sin(math.pi * s) * math.sin(math.pi * t) - 2.0 * (s - 0.5) * (t - 0.5)
            row.append(V(width * s, depth * t, z))
        poles.append(row)
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, 3, 3)
    return surface.toShape()


def sketch_at(doc, name, z):
    sketch = doc.addObject("Sketcher::SketchObject", name)
    sketch.Placement = FreeCAD.Placement(V(0, 0, z), FreeCAD.Rotation())
    return sketch


def build(doc):
    surface = doc.addObject("Part::Feature", "Surface")
    surface.Label = "BaseSurface"
    surface.Shape = base_face()

    # 1. a diagonal ridge well above the base: pulls the sheet up (not isoparametric)
    ridge = sketch_at(doc, "Ridge", 22.0)
    ridge.addGeometry(Part.LineSegment(V(22, 18, 0), V(46, 64, 0)), False)
    ridge.addConstraint(Sketcher.Constraint("DistanceX", 0, 1, 22.0))
    ridge.addConstraint(Sketcher.Constraint("DistanceY", 0, 1, 18.0))
    ridge.addConstraint(Sketcher.Constraint("DistanceX", 0, 2, 46.0))
    ridge.addConstraint(Sketcher.Constraint("DistanceY", 0, 2, 64.0))

    # 2. an arc on the right, a little above the base
    arc = sketch_at(doc, "Arc", 10.0)
    circle = Part.Circle(V(72, 40, 0), V(0, 0, 1), 15.0)
    arc.addGeometry(Part.ArcOfCircle(circle, math.radians(-80), math.radians(80)), False)
    arc.addConstraint(Sketcher.Constraint("Radius", 0, 15.0))

    # 3. a short rail near the front edge, below the base: pulls the sheet down
    rail = sketch_at(doc, "Rail", -3.0)
    rail.addGeometry(Part.LineSegment(V(55, 12, 0), V(85, 16, 0)), False)

    doc.recompute()
    sheet = varsurf.make_sheet(
        (surface, "Face1"), [(ridge, "Edge1"), (arc, "Edge1"), (rail, "Edge1")], stretch=0.0,
        bend=1.0, fix_boundary=True, tolerance=0.01,
    )
    doc.recompute()
    return surface, sheet


RENDER_SCRIPT = REPO / "examples" / "render_demo.py"


def render(fcstd: Path, png: Path) -> str:
    """Render the saved document with the real FreeCAD GUI under Xvfb; '' or why it failed."""
    for tool in ("xvfb-run", "freecad"):
        if shutil.which(tool) is None:
            return f"{tool} not found"
    home = Path(tempfile.mkdtemp(prefix="varsurf-demo-home-"))
    try:
        mod = home / ".local" / "share" / "FreeCAD" / "Mod"
        mod.mkdir(parents=True)
        (mod / "VarSurf").symlink_to(REPO, target_is_directory=True)
        env = dict(os.environ)
        env.update(
            HOME=str(home),
            QTWEBENGINE_CHROMIUM_FLAGS="--no-sandbox",
            VARSURF_DEMO_FCSTD=str(fcstd),
            VARSURF_DEMO_PNG=str(png),
            VARSURF_NO_DIALOGS="1",
        )
        env.pop("QT_QPA_PLATFORM", None)
        if png.exists():
            png.unlink()
        cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "freecad", str(RENDER_SCRIPT)]
        try:
            run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=240)
        except subprocess.TimeoutExpired:
            return "the FreeCAD GUI did not finish within 240 s"
        if not png.is_file():
            return "no image written\n" + run.stdout[-1500:] + run.stderr[-1500:]
        return ""
    finally:
        shutil.rmtree(home, ignore_errors=True)


def main(argv):
    out = Path(argv[1]) if len(argv) > 1 else REPO / "out" / "demo"
    out = out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    doc = FreeCAD.newDocument("VarSurfDemo")
    surface, sheet = build(doc)
    if not sheet.isValid():
        print(f"demo: the sheet failed: {sheet.getStatusString()}", file=sys.stderr)
        return 1

    fcstd = out / "demo.FCStd"
    step = out / "demo.step"
    png = out / "demo.png"
    doc.saveAs(str(fcstd))
    varsurf.export_step([sheet], str(step))
    problem = render(fcstd, png)

    base_bb, sheet_bb = surface.Shape.BoundBox, sheet.Shape.BoundBox
    lines = [
        f"VarSurf {varsurf.__version__} demo",
        f"base face      : bicubic B-spline, {surface.Shape.Faces[0].Surface.NbUPoles} x "
        f"{surface.Shape.Faces[0].Surface.NbVPoles} poles, "
        f"{base_bb.XLength:.0f} x {base_bb.YLength:.0f} mm, z {base_bb.ZMin:.2f} .. {base_bb.ZMax:.2f} mm",
        f"energy         : stretch {sheet.Stretch:g}, bend {sheet.Bend:g}, "
        f"boundary {'kept' if sheet.FixBoundary else 'free'}, tolerance {float(sheet.Tolerance):g} mm",
        f"sheet poles    : {sheet.PoleCountU} x {sheet.PoleCountV}",
        f"sheet degree   : {sheet.DegreeU} x {sheet.DegreeV}",
        f"sheet z range  : {sheet_bb.ZMin:.2f} .. {sheet_bb.ZMax:.2f} mm",
        f"constraint rank: {sheet.ConstraintRank}",
        f"solve time     : {sheet.SolveTime * 1000.0:.1f} ms",
        "max deviation per curve (distance from the curve to the sheet):",
    ]
    for name, dev in zip(sheet.CurveNames, sheet.MaxDeviations):
        lines.append(f"  {name:<12} {dev:.3g} mm")
    lines.append(f"status         : {sheet.Status}")
    lines.append("files          : demo.FCStd, demo.step" + (", demo.png" if not problem else ""))
    report = "\n".join(lines) + "\n"
    (out / "report.txt").write_text(report)
    print(report, end="")
    print(f"written to {out}")
    FreeCAD.closeDocument(doc.Name)
    if problem:
        print(f"demo: could not render demo.png: {problem}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
