#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf benchmarks: prints the tables of the README's "Benchmarks" section.

    /usr/bin/python3 bench/run_bench.py [--quick]

1. Scaling of the solver (bench/sheet_bench.cpp, one process per size so that peak memory is that
   size's own): bicubic sheets of 16^2 .. 256^2 poles, 4 wavy boundary curves and 10 interior
   non-isoparametric curves; assembly, factorization, full solve and drag update, the fitted
   exponent of time against pole count.
2. VarSurf against FreeCAD's Surface Filling (OCCT GeomPlate) on the same curves in the same
   process: time, largest distance from every curve to the result (sampled densely and measured
   by OCCT projection, independently of either solver), degree, poles and a fairness figure
   (the integral of k1^2 + k2^2 over the face, sampled).
3. Michalik & Bruderlin's sizes (TSVD / MTSVD) and 4. Du & Qin's sheet sizes.
6. Local refinement (hierarchical spaces) against uniform refinement: degrees of freedom to meet a
   tolerance on one interior curve (bench/hierarchical_bench.cpp).
7. N-sided holes against Surface Filling with G1 (and G2) to the face around them
   (bench/hole_bench.py).
11. Triangular Bezier surfaces over closed meshes of 24 to 20,000 triangles: direct against CG,
   G1 measured, the exact B-rep export (bench/triangular_bench.py).
5. Live dragging in a FreeCAD document (varsurf.app.drag.PointDrag): a 64 x 64 pole Sheet through 10
   curves with a Point constraint; each move's back-substitution and result face against a fresh
   recompute of the same Sheet in the same process.
"""

import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
BENCH = REPO / "build" / "bench" / "varsurf_sheet_bench"
FREECAD_LIB = "/usr/lib/freecad-python3/lib"


def run_case(*args):
    out = subprocess.run([str(BENCH), *map(str, args)], check=True, capture_output=True, text=True)
    return [json.loads(line) for line in out.stdout.splitlines() if line.startswith("{")]


def fitted_exponent(xs, ys):
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def ms(seconds):
    return f"{1000.0 * seconds:.1f}"


def scaling(sizes):
    print("\n## 1. Scaling: 4 wavy boundary curves + 10 interior curves, automatic mode\n")
    # full: the fastest of three solves in the process (stages are that solve's); first: the
    # process's first solve, which also touches its memory for the first time.
    print("| poles | unknowns | mode | assemble ms | factor ms | solve ms | full ms | first ms | drag ms "
          "| add a pin ms | change / full | peak MiB | max dev mm |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []

    def line(r):
        kept = " (factor kept)" if r.get("change_kept") else ""
        return (f"| {r['poles']}x{r['poles']} | {r['unknowns']} | {r['mode']} | {ms(r['assemble'])} | "
                f"{ms(r['factor'])} | {ms(r['solve'])} | {ms(r['full'])} | {ms(r['first'])} | {ms(r['drag'])} | "
                f"{ms(r['change'])}{kept} | {r['change'] / r['full']:.0%} | {r['peak_mib']:.0f} | "
                f"{r['max_dev']:.2g} |")

    for n in sizes:
        (r,) = run_case("scaling", n, 10)
        rows.append(r)
        print(line(r))
    # The penalty mode's QR form, for comparison at 64 x 64.
    (r,) = run_case("scaling", 64, 10, "penalty-qr")
    print(line(r))
    big = [r for r in rows if r["poles"] >= 32]
    if len(big) >= 2:
        counts = [r["poles"] ** 2 for r in big]
        print(f"\nFitted exponent of full-solve time against pole count ({big[0]['poles']}^2 .. "
              f"{big[-1]['poles']}^2): {fitted_exponent(counts, [r['full'] for r in big]):.2f}; "
              f"of drag time: {fitted_exponent(counts, [r['drag'] for r in big]):.2f}")
    return rows


def michalik_bruderlin():
    print("\n## 3. Michalik & Bruderlin's cases\n")
    print("| case | poles | constraint rows | mode | ms | reduce / factor / solve ms "
          "| L-curve corner / directions | max dev mm |")
    print("|---|---|---|---|---|---|---|---|")
    for r in run_case("mb"):
        corner = f"{r['corner']} / {r['directions']}" if r["directions"] else "-"
        stages = " / ".join(ms(r[k]) for k in ("reduce", "factor", "solve"))
        print(f"| {r['name']} | {r['poles']} | {r['rows']} | {r['mode']} | {ms(r['seconds'])} | {stages} "
              f"| {corner} | {r['max_dev']:.2g} |")
    # A constraint group too large for a dense SVD: the Krylov (CGLS) truncation.
    for mode in ("tsvd", "mtsvd"):
        (r,) = run_case("scaling", 128, 10, mode)
        stages = " / ".join(ms(r[k]) for k in ("reduce", "factor", "solve"))
        print(f"| 128x128, 14 curves (Krylov) | {r['poles'] ** 2} | - | {mode} | {ms(r['full'])} | {stages} | "
              f"CGLS | {r['max_dev']:.2g} |")


def du_qin():
    print("\n## 4. Du & Qin's sheet sizes (4 boundary + 3 interior curves)\n")
    print("| poles | unknowns | ms | max dev mm |")
    print("|---|---|---|---|")
    for r in run_case("duqin"):
        print(f"| {r['poles']}x{r['poles']} | {r['unknowns']} | {ms(r['seconds'])} | {r['max_dev']:.2g} |")


# ------------------------------------------------------------------------------------------------
# 2. against Surface Filling


# Benchmark 2's cases: (name, boundary wave amplitude, interior curves, VarSurf tolerance in mm)
FILLING_CASES = [("flat boundary, 1 interior", 0.0, 1, 0.01), ("wavy boundary, 1 interior", 5.0, 1, 0.01),
                 ("wavy boundary, 3 interior", 5.0, 3, 0.01), ("wavy boundary, 6 interior", 5.0, 6, 0.01),
                 ("wavy boundary, 3 interior, tolerance 1e-3", 5.0, 3, 0.001),
                 ("wavy boundary, 6 interior, tolerance 1e-3", 5.0, 6, 0.001)]


def _freecad():
    if FREECAD_LIB not in sys.path:
        sys.path.append(FREECAD_LIB)
    if str(REPO / "src") not in sys.path:
        sys.path.insert(0, str(REPO / "src"))
    import FreeCAD  # noqa: F401
    import Part  # noqa: F401

    return FreeCAD, Part


def _curve(Part, V, fn, n=65):
    points = [V(*fn(k / (n - 1))) for k in range(n)]
    c = Part.BSplineCurve()
    c.interpolate(points)
    return c.toShape()


def _case_curves(Part, V, amplitude, interior):
    """Four boundary curves of a 100 mm square (z = amplitude sin(2 pi t), corners at 0) and
    `interior` slanted wavy curves inside."""
    L = 100.0
    wave = lambda t: amplitude * math.sin(2 * math.pi * t)  # noqa: E731
    boundary = [
        _curve(Part, V, lambda t: (L * t, 0.0, wave(t))),
        _curve(Part, V, lambda t: (L, L * t, wave(t))),
        _curve(Part, V, lambda t: (L * (1 - t), L, wave(t))),
        _curve(Part, V, lambda t: (0.0, L * (1 - t), wave(t))),
    ]
    inner = []
    for j in range(interior):
        a = 0.2 + 0.6 * (j + 0.5) / interior - 0.05
        inner.append(_curve(Part, V, lambda t, a=a, j=j: (L * (a + 0.1 * t), L * (0.15 + 0.7 * t),
                                                          6.0 + 3.0 * math.sin(3 * math.pi * t + j))))
    return boundary, inner


def _flat_square(Part, V, spans=16):
    knots = [k / spans for k in range(spans + 1)]
    mults = [4] + [1] * (spans - 1) + [4]
    flat = [0.0] * 4 + knots[1:-1] + [1.0] * 4
    g = [sum(flat[i + 1:i + 4]) / 3.0 for i in range(len(flat) - 4)]
    s = Part.BSplineSurface()
    s.buildFromPolesMultsKnots([[V(100 * a, 100 * b, 0) for b in g] for a in g], mults, mults, knots, knots,
                               False, False, 3, 3)
    return s.toShape()


def _max_distance(face, edges, samples=200):
    """Largest distance from points sampled on the edges to the face's surface (OCCT projection)."""
    surface = face.Surface
    worst = 0.0
    for edge in edges:
        for p in edge.discretize(samples):
            u, v = surface.parameter(p)
            worst = max(worst, (surface.value(u, v) - p).Length)
    return worst


def _fairness(face, n=60):
    """Integral of k1^2 + k2^2 over the face's parameter box, by the midpoint rule."""
    surface = face.Surface
    u0, u1, v0, v1 = face.ParameterRange
    du, dv = (u1 - u0) / n, (v1 - v0) / n
    total = 0.0
    for i in range(n):
        for j in range(n):
            u, v = u0 + (i + 0.5) * du, v0 + (j + 0.5) * dv
            try:
                k1 = surface.curvature(u, v, "Max")
                k2 = surface.curvature(u, v, "Min")
            except Exception:  # undefined normal: skip the sample
                continue
            d1 = surface.getD1(u, v) if hasattr(surface, "getD1") else None
            if d1 is not None:
                su, sv = d1[1], d1[2]
            else:
                su = (surface.value(min(u + 1e-6, u1), v) - surface.value(u, v)) * (1e6)
                sv = (surface.value(u, min(v + 1e-6, v1)) - surface.value(u, v)) * (1e6)
            total += (k1 * k1 + k2 * k2) * su.cross(sv).Length * du * dv
    return total


class _StageClock:
    """Wall time spent in the native stages of a sheet's recompute: each wrapped function of
    varsurf._native adds its time to its stage while the clock is installed."""

    STAGES = {"project_curve": "projection", "solve_sheet": "solve", "max_deviations": "measurement"}

    def __init__(self, nat):
        self.nat, self.seconds, self.saved = nat, {}, {}

    def __enter__(self):
        for name, stage in self.STAGES.items():
            original = getattr(self.nat, name)
            self.saved[name] = original

            def timed(*args, _original=original, _stage=stage, **kwargs):
                began = time.perf_counter()
                try:
                    return _original(*args, **kwargs)
                finally:
                    self.seconds[_stage] = self.seconds.get(_stage, 0.0) + time.perf_counter() - began
            setattr(self.nat, name, timed)
        return self

    def __exit__(self, *_exc):
        for name, original in self.saved.items():
            setattr(self.nat, name, original)


class _FloorProxy:
    """The least a Python surface feature does in a recompute: read its linked edges' shapes and
    assign a face built beforehand (the Sheet's own result). Its recompute time is FreeCAD's
    floor for any Python feature in this document, VarSurf's Sheet included."""

    def __init__(self, obj, face):
        obj.addProperty("App::PropertyLinkSubList", "Edges")
        obj.Proxy = self
        self.face = face

    def execute(self, obj):
        for linked, subs in obj.Edges:
            for sub in subs:
                linked.Shape.getElement(sub)
        obj.Shape = self.face


def _floor_recompute(doc, objs, face):
    """Seconds of one recompute of a _FloorProxy feature over `objs`' edges."""
    floor = doc.addObject("Part::FeaturePython", "Floor")
    _FloorProxy(floor, face.copy())
    floor.Edges = [(o, "Edge1") for o in objs]
    t = time.perf_counter()
    doc.recompute()
    seconds = time.perf_counter() - t
    doc.removeObject(floor.Name)
    return seconds


def filling_comparison():
    FreeCAD, Part = _freecad()
    V = FreeCAD.Vector
    from varsurf.solve.settings import SheetSettings
    from varsurf.solve.sheet import solve_sheet_on_face

    import varsurf
    from varsurf.solve.native import native

    print("\n## 2. VarSurf against FreeCAD's Surface Filling (GeomPlate), same curves, same run\n")
    print("| case | VarSurf ms | Filling ms | time ratio | VarSurf max dev mm | Filling max dev mm | dev ratio "
          "| VarSurf degree / poles | Filling degree / poles | fairness VarSurf / Filling |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    features = []  # (case, VarSurf feature recompute s, Filling recompute s, stages)
    doc = FreeCAD.newDocument("Bench")
    for name, amplitude, interior, tolerance in FILLING_CASES:
        boundary, inner = _case_curves(Part, V, amplitude, interior)
        edges = boundary + inner
        base = _flat_square(Part, V)
        t = time.perf_counter()
        ours = solve_sheet_on_face(base, edges, SheetSettings(fix_boundary=False, tolerance=tolerance))
        ours_s = time.perf_counter() - t
        objs = []
        for k, e in enumerate(edges):
            o = doc.addObject("Part::Feature", f"C{k}")
            o.Shape = e
            objs.append(o)
        doc.recompute()
        filling = doc.addObject("Surface::Filling", "Filling")
        filling.BoundaryEdges = [(o, "Edge1") for o in objs[:4]]
        if inner:
            filling.UnboundEdges = [(o, "Edge1") for o in objs[4:]]
        t = time.perf_counter()
        doc.recompute()
        fill_s = time.perf_counter() - t
        if not filling.isValid() or filling.Shape.isNull() or not filling.Shape.Faces:
            print(f"| {name} | {ms(ours_s)} | failed: {filling.getStatusString()} | | | | | | | |")
            continue
        # The whole feature, as a user recomputes it: a Sheet over the base through the curves.
        base_obj = doc.addObject("Part::Feature", "Base")
        base_obj.Shape = base
        doc.recompute()
        sheet = varsurf.make_sheet((base_obj, "Face1"), [(o, "Edge1") for o in objs], fix_boundary=False,
                                   tolerance=tolerance, name="Sheet")
        with _StageClock(native()) as clock:
            t = time.perf_counter()
            doc.recompute()
            feature_s = time.perf_counter() - t
        floor_s = _floor_recompute(doc, objs, sheet.Shape.Faces[0]) if sheet.Shape.Faces else float("nan")
        features.append((name, feature_s, fill_s, dict(clock.seconds), sheet.isValid(), floor_s))
        ff = filling.Shape.Faces[0]
        of = ours.shape
        dev_o, dev_f = _max_distance(of, edges), _max_distance(ff, edges)
        fair_o, fair_f = _fairness(of), _fairness(ff)
        so, sf = of.Surface, ff.Surface
        print(f"| {name} | {ms(ours_s)} | {ms(fill_s)} | {fill_s / ours_s:.1f}x | {dev_o:.2g} | {dev_f:.2g} | "
              f"{dev_f / max(dev_o, 1e-300):.0f}x | {so.UDegree}x{so.VDegree} / {so.NbUPoles}x{so.NbVPoles} | "
              f"{getattr(sf, 'UDegree', '?')}x{getattr(sf, 'VDegree', '?')} / "
              f"{getattr(sf, 'NbUPoles', '?')}x{getattr(sf, 'NbVPoles', '?')} | {fair_o:.3g} / {fair_f:.3g} |")
        for o in [sheet, base_obj, filling] + objs:
            doc.removeObject(o.Name)
    FreeCAD.closeDocument(doc.Name)
    print("\nThe same cases as document recomputes (a Sheet feature against the Filling feature), and where the "
          "Sheet's time goes (native stages; the rest is Python, face building and FreeCAD):\n")
    print("| case | Sheet recompute ms | Filling recompute ms | time ratio | projection ms | solve ms "
          "| measurement ms | rest ms | floor ms | 10x Filling needs ms |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, feature_s, fill_s, stages, valid, floor_s in features:
        staged = sum(stages.values())
        cells = " | ".join(ms(stages.get(s, 0.0)) for s in ("projection", "solve", "measurement"))
        print(f"| {name}{'' if valid else ' (in error)'} | {ms(feature_s)} | {ms(fill_s)} | "
              f"{fill_s / feature_s:.1f}x | {cells} | {ms(feature_s - staged)} | {ms(floor_s)} | {ms(fill_s / 10)} |")
    print("\nfloor: the recompute of a Python feature that only reads the same edges and assigns the Sheet's "
          "finished face (FreeCAD's own cost for any Python feature here).")


def drag_scene():
    """A document with a 64 x 64 pole Sheet through 10 curves and a Point constraint, recomputed:
    (doc, sheet, point constraint)."""
    FreeCAD, Part = _freecad()
    import varsurf

    V = FreeCAD.Vector
    doc = FreeCAD.newDocument("DragBench")
    base = doc.addObject("Part::Feature", "Base")
    base.Shape = _flat_square(Part, V, spans=61)
    _boundary, inner = _case_curves(Part, V, 0.0, 10)
    curves = []
    for k, edge in enumerate(inner):
        obj = doc.addObject("Part::Feature", f"Curve{k}")
        obj.Shape = edge
        curves.append((obj, "Edge1"))
    sheet = varsurf.make_sheet((base, "Face1"), curves, max_spans=61)
    pin = varsurf.make_constraint(sheet, "Point", uv=(0.1, 0.9), origin=(10.0, 90.0, 5.0))
    doc.recompute()
    return doc, sheet, pin


def live_drag(moves=60):
    print("\n## 5. Live drag: a 64 x 64 pole Sheet through 10 curves, one Point dragged\n")
    FreeCAD, _Part = _freecad()
    from varsurf.app import drag

    V = FreeCAD.Vector
    began = time.perf_counter()
    doc, sheet, pin = drag_scene()
    fresh = time.perf_counter() - began
    if not sheet.isValid():
        print(f"(the sheet did not solve: {sheet.Status})")
        return
    # a fresh recompute of the sheet alone (the scene's first one also built the document)
    sheet.touch()
    began = time.perf_counter()
    doc.recompute()
    fresh = time.perf_counter() - began
    session = drag.PointDrag(sheet, pin)
    began = time.perf_counter()
    for k in range(moves):
        session.move(V(10.0, 90.0, 5.0 + 10.0 * math.sin(math.pi * k / moves)))
    per_move = (time.perf_counter() - began) / moves
    session.cancel()
    gui = gui_drag()
    print("| poles | fresh recompute ms | per move ms (solve + face) | moves per second | speed-up "
          "| in the GUI, view redrawn each move |")
    print("|---|---|---|---|---|---|")
    print(f"| {sheet.PoleCountU} x {sheet.PoleCountV} | {ms(fresh)} | {ms(per_move)} | "
          f"{1.0 / per_move:.0f} | {fresh / per_move:.0f}x | {gui} |")
    FreeCAD.closeDocument(doc.Name)


def gui_drag():
    """Moves per second with the view redrawn, measured in the FreeCAD GUI under Xvfb (a text)."""
    import shutil
    import tempfile

    if not (shutil.which("xvfb-run") and shutil.which("freecad")):
        return "(no xvfb-run/freecad)"
    with tempfile.TemporaryDirectory() as home:
        mod = Path(home) / ".local" / "share" / "FreeCAD" / "Mod"
        mod.mkdir(parents=True)
        (mod / "VarSurf").symlink_to(REPO)
        out = Path(home) / "gui_drag.json"
        env = dict(os.environ, HOME=home, VARSURF_BENCH_OUT=str(out), VARSURF_NO_DIALOGS="1",
                   QTWEBENGINE_CHROMIUM_FLAGS="--no-sandbox")
        env.pop("QT_QPA_PLATFORM", None)
        subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "freecad",
                        str(REPO / "bench" / "gui_drag_bench.py")], env=env, capture_output=True,
                       timeout=600, cwd=home)
        if not out.is_file():
            return "(the GUI run wrote nothing)"
        result = json.loads(out.read_text())
    if "error" in result:
        return f"(failed: {result['error'].splitlines()[-1]})"
    return (f"{result['redrawn']:.0f} moves/s (move alone in that process: {result['move_only']:.0f}; "
            f"redraw alone, nothing moved: {result['redraw_only']:.0f}; an empty view's redraw: "
            f"{result['empty_view']:.0f})")


def local_refinement():
    print("\n## 6. Local against uniform refinement: one interior wavy curve, boundary kept\n")
    bench = REPO / "build" / "bench" / "varsurf_hierarchical_bench"
    out = subprocess.run([str(bench)], check=True, capture_output=True, text=True)
    print("| tolerance | depth | hierarchical DOFs (poles) | export poles | uniform poles that meet it | ratio "
          "| hierarchical ms | uniform ms |")
    print("|---|---|---|---|---|---|---|---|")
    for line in out.stdout.splitlines():
        r = json.loads(line)
        ratio = r["uniform_poles"] / r["dofs"] if r["dofs"] else float("nan")
        print(f"| {r['tolerance']:g} | {r['depth']} | {r['dofs']} | {r['export_poles']} | {r['uniform_poles']} | "
              f"{ratio:.1f} | {ms(r['hier_seconds'])} | {ms(r['uniform_seconds'])} |")


# ------------------------------------------------------------------------------------------------
# 8. dynamic PDE sheets


def dynamics(sides=(15, 30, 60), steps=300):
    """Du & Qin's grid sizes as PDE sheets held by Hermite data all round, one point pulled by a
    spring: the factorization a grab costs, one backward Euler step, and the static solve of the
    same sheet in the same process (the peer a step replaces while the sheet moves)."""
    sys.path.insert(0, str(REPO / "src"))
    import numpy as np
    from varsurf.solve.native import native

    nat = native()
    print("\n## 8. Dynamic PDE sheets: Hermite data all round, one point pulled by a spring\n")
    print("| poles | free poles | factor per grab ms | step ms | steps per second | static solve ms | "
          "static solve / step |")
    print("|---|---|---|---|---|---|---|")
    for n in sides:
        space = nat.SplineSpace.uniform(3, 3, n - 3, n - 3)
        g = np.linspace(0.0, 1.0, n)
        poles = np.array([[100 * a, 100 * b, 10 * (a - 0.5) * (b - 0.5)] for a in g for b in g])
        fixed = [i * n + j for i in range(n) for j in range(n) if min(i, j) < 2 or max(i, j) >= n - 2]
        problem = nat.SheetProblem(space=space, initial_poles=poles, fixed_poles=fixed)
        problem.pde = nat.PdeCoefficient(a=1.5)
        parameters = nat.DynamicsParameters()
        parameters.damping = nat.PdeCoefficient(a=5.0)
        sheet = nat.DynamicSheet(problem, parameters)
        started = time.perf_counter()
        sheet.set_springs([nat.Spring(0.5, 0.5, np.array([50.0, 50.0, 30.0]), 200.0)])
        factor = time.perf_counter() - started
        sheet.step(10)
        started = time.perf_counter()
        sheet.step(steps)
        step = (time.perf_counter() - started) / steps
        started = time.perf_counter()
        nat.solve_sheet(problem)
        static = time.perf_counter() - started
        print(f"| {n}x{n} | {n * n - len(fixed)} | {ms(factor)} | {step * 1e3:.3f} | {1.0 / step:.0f} | "
              f"{ms(static)} | {static / step:.0f}x |")


# ------------------------------------------------------------------------------------------------
# 9. multigrid against the direct solve


def _held_sheet(nat, np, spans):
    """A PDE sheet (a = 1.7) held by Hermite data all round (its two outer rings of poles), its
    interior lifted 20 mm off the answer."""
    n = spans + 3
    g = np.linspace(0.0, 1.0, n)
    poles = np.array([[100 * a, 80 * b, 10 * math.sin(3 * a) * math.cos(2 * b) + 5 * a * b] for a in g for b in g])
    fixed = [i * n + j for i in range(n) for j in range(n) if min(i, j) < 2 or max(i, j) >= n - 2]
    inner = np.ones(n * n, dtype=bool)
    inner[fixed] = False
    poles[inner, 2] += 20.0
    problem = nat.SheetProblem(space=nat.SplineSpace.uniform(3, 3, spans, spans), initial_poles=poles,
                               fixed_poles=fixed)
    problem.pde = nat.PdeCoefficient(a=1.7)
    return problem


def multigrid(spans_list=(12, 32, 64, 128, 256, 512), direct_limit=256):
    """Du & Qin's Tables 1-2 solve one PDE surface on grids of 15^2, 30^2, 60^2 samples (Gaussian
    elimination 0.094 / 3.19 / 122 s, SOR 0.59 / 6 / 34 s, their multigrid-SOR 0.109 / 0.079 /
    0.156 s on 2004 hardware). Here the B-spline sheet of about those sizes and on to 515^2 poles:
    VarSurf's direct solve (solve_sheet in the exact mode: sparse factorization) against
    multigrid-preconditioned conjugate gradients, with the peak memory each took (a process per
    case), and the mode Automatic chooses."""
    print("\n## 9. Multigrid against the direct solve: a PDE sheet held by Hermite data all round\n")
    print("| poles | free poles | direct ms | direct peak MiB | multigrid ms (setup + solve) | levels | CG steps | "
          "multigrid peak MiB | direct / multigrid | max pole difference mm | Automatic |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    script = (
        "import sys, json, math, time, resource\n"
        f"sys.path.insert(0, {str(REPO / 'src')!r}); sys.path.insert(0, {str(REPO / 'bench')!r})\n"
        "import numpy as np\n"
        "from varsurf.solve.native import native\n"
        "import run_bench\n"
        "nat = native()\n"
        "spans, how = int(sys.argv[1]), sys.argv[2]\n"
        "problem = run_bench._held_sheet(nat, np, spans)\n"
        "t = time.perf_counter()\n"
        "if how == 'direct':\n"
        "    options = nat.SolveOptions(); options.mode = nat.SolveMode.exact\n"
        "    poles = np.array(nat.solve_sheet(problem, options).poles); extra = {}\n"
        "else:\n"
        "    result, rep = nat.solve_sheet_multigrid(problem)\n"
        "    poles = np.array(result.poles)\n"
        "    extra = dict(levels=rep.levels, steps=rep.iterations)\n"
        "seconds = time.perf_counter() - t\n"
        "np.save(sys.argv[3], poles)\n"
        "print(json.dumps(dict(seconds=seconds, peak=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,"
        " free=len(problem.initial_poles) - len(problem.fixed_poles), **extra)))\n"
    )
    import tempfile

    import numpy as np

    from varsurf.solve.native import native

    nat = native()
    with tempfile.TemporaryDirectory() as tmp:
        for spans in spans_list:
            runs = {}
            for how in (("direct", "multigrid") if spans <= direct_limit else ("multigrid",)):
                out = subprocess.run([sys.executable, "-c", script, str(spans), how, f"{tmp}/{how}.npy"],
                                     capture_output=True, text=True, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
                if out.returncode != 0:
                    sys.exit(f"multigrid bench {spans} {how}: {out.stderr[-2000:]}")
                runs[how] = json.loads(out.stdout.strip().splitlines()[-1])
            mg = runs["multigrid"]
            if "direct" in runs:
                d = runs["direct"]
                diff = float(np.abs(np.load(f"{tmp}/direct.npy") - np.load(f"{tmp}/multigrid.npy")).max())
                direct = f"{ms(d['seconds'])} | {d['peak']:.0f}"
                ratio, diff_text = f"{d['seconds'] / mg['seconds']:.1f}x", f"{diff:.1g}"
            else:
                direct, ratio, diff_text = "not run | -", "-", "-"
            n = spans + 3
            chosen = nat.solve_sheet(_held_sheet(nat, np, spans)).report.mode.name if spans <= 256 else "-"
            print(f"| {n}x{n} | {mg['free']} | {direct} | {ms(mg['seconds'])} | {mg['levels']} | {mg['steps']} | "
                  f"{mg['peak']:.0f} | {ratio} | {diff_text} | {chosen} |")


def main():
    quick = "--quick" in sys.argv
    if not BENCH.exists():
        sys.exit(f"{BENCH} is missing: build first (bash tools/build.sh)")
    print("# VarSurf benchmarks")
    print(f"\nMachine: {os.cpu_count()} cores, {platform_line()}")
    scaling([16, 32, 64] if quick else [16, 32, 64, 128, 256])
    filling_comparison()
    michalik_bruderlin()
    du_qin()
    live_drag()
    local_refinement()
    import hole_bench  # here: it puts FreeCAD on the path, which sections 1, 3, 4 and 6 do not need

    hole_bench.main()
    dynamics()
    multigrid((12, 32, 64) if quick else (12, 32, 64, 128, 256, 512))
    import multires_bench

    multires_bench.main()
    import triangular_bench

    triangular_bench.main(quick)


def platform_line():
    import platform

    cpu = ""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu or platform.processor()}, {platform.platform()}"


if __name__ == "__main__":
    main()
