# SPDX-License-Identifier: LGPL-2.1-or-later
"""Benchmark 10: multiresolution Catmull-Clark surfaces (Boier-Martin, Ronfard & Bernardini). A
bumpy vase scanned as 65,536 triangles is captured onto a 40-face cage at 4 levels (10,240 faces);
a pin at the finest level is dragged with its influence at level 2: the approximate solve per move
(Catmull-Clark rules on the deformation) against the refined ones on release (the sparse direct
KKT solve, and the paper's SOR), the memory a surface takes per finest face, and its limit surface
as B-rep: merged C2 faces against a face per patch.

Run alone (python3 bench/multires_bench.py) or as part of tools/bench.sh."""

from __future__ import annotations

import math
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from varsurf.solve import multiresolution  # noqa: E402
from varsurf.solve.native import native  # noqa: E402

AROUND, HIGH, HEIGHT = 8, 5, 60.0


def radius(theta, z):
    return 20.0 + 6.0 * np.sin(np.pi * z / HEIGHT) + 0.6 * np.sin(12 * theta) * np.sin(2 * np.pi * z / 8.0)


def scan(n_theta=256, n_z=128):
    """The vase's surface as a triangle mesh (an open tube)."""
    theta = np.linspace(0, 2 * np.pi, n_theta, endpoint=False)
    z = np.linspace(-2.0, HEIGHT + 2.0, n_z)
    t, zz = np.meshgrid(theta, z, indexing="ij")
    r = radius(t, zz)
    points = np.stack([r * np.cos(t), r * np.sin(t), zz], axis=-1).reshape(-1, 3)
    tris = []
    for i in range(n_theta):
        for j in range(n_z - 1):
            a, b = i * n_z + j, ((i + 1) % n_theta) * n_z + j
            tris += [(a, b, b + 1), (a, b + 1, a + 1)]
    return points, tris


def cage():
    """An open tube of AROUND x HIGH quads around the vase, outward."""
    points = [(24.0 * math.cos(2 * math.pi * i / AROUND), 24.0 * math.sin(2 * math.pi * i / AROUND),
               HEIGHT * j / HIGH) for i in range(AROUND) for j in range(HIGH + 1)]
    faces = []
    for i in range(AROUND):
        for j in range(HIGH):
            a, b = i * (HIGH + 1) + j, ((i + 1) % AROUND) * (HIGH + 1) + j
            faces.append([a, b, b + 1, a + 1])
    return points, faces


def memory_per_face(cells, levels):
    """Peak bytes per finest face of a build with one pin, in a fresh process."""
    code = f"""
import resource, sys
sys.path.insert(0, {str(ROOT / 'src')!r})
from varsurf.solve import multiresolution as mr
n = {cells}
pts = [(i, j, 0.0) for i in range(n + 1) for j in range(n + 1)]
faces = [[i*(n+1)+j, (i+1)*(n+1)+j, (i+1)*(n+1)+j+1, i*(n+1)+j+1] for i in range(n) for j in range(n)]
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
mr.build(pts, faces, {levels}, pins=[mr.Pin({levels}, 5, (1, 2, 3), 0)])
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024, before * 1024)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={"OPENBLAS_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"})
    peak, before = map(int, out.stdout.split())
    faces = cells * cells * 4 ** levels
    return faces, peak / faces, (peak - before) / faces


def main():
    nat = native()
    print("\n## 10. Multiresolution subdivision surfaces: a scanned vase edited with detail kept\n")
    points, faces = cage()
    target = scan()
    start = time.perf_counter()
    built = multiresolution.build(points, faces, 4, target=target)
    capture_s = time.perf_counter() - start
    print(f"Cage {len(faces)} quads, 4 levels: {len(built.faces[-1]):,} faces; the scan {len(target[1]):,} "
          f"triangles captured in {capture_s:.2f} s, the limit within {built.fit_max:.3f} mm of it "
          f"(RMS {built.fit_rms:.4f}).\n")
    base = nat.SubdivisionMesh(np.asarray(points, float), faces)
    editor = nat.DetailEditor(base, 4)
    surface = nat.capture(base, 4, nat.TriangleSurface(np.asarray(target[0]), [list(t) for t in target[1]]))
    finest = np.asarray(editor.points(surface)[-1])
    pin = int(np.argmin(np.linalg.norm(finest - np.array([26.0, 0.0, 30.0]), axis=1)))
    outward = np.array([1.0, 0.0, 0.0])

    def options(solve):
        o = nat.DetailEditOptions()
        o.solve = solve
        return o

    rows = []
    held = [nat.DetailNormal(4, pin, outward, 2)]  # the vase's normal there, kept through the drag
    for name, solve, normals in (("approximate (a drag's move)", nat.DetailSolve.approximate, []),
                                 ("direct (release)", nat.DetailSolve.direct, []),
                                 ("SOR (release)", nat.DetailSolve.sor, []),
                                 ("approximate, normal held", nat.DetailSolve.approximate, held),
                                 ("direct, normal held", nat.DetailSolve.direct, held)):
        times, residual, sweeps = [], 0.0, 0
        moves = 30 if solve == nat.DetailSolve.approximate else 3
        for k in range(moves):
            goal = finest[pin] + outward * (10.0 * (k + 1) / moves)
            start = time.perf_counter()
            edited = editor.edit(surface, [nat.DetailPin(4, pin, goal, 2)], normals, options(solve))
            shown = editor.points(edited.surface)[-1]
            times.append(time.perf_counter() - start)
            residual = max(residual, edited.report.max_residual)
            sweeps = edited.report.sweeps
        rows.append((name, min(times), residual, sweeps, np.asarray(shown), edited.report.region_sizes))
    print("| solve | time per edit (ms) | per second | pin residual (mm) | SOR sweeps | farthest from direct (mm) "
          "| region (level-2 vertices) |")
    print("|---|---|---|---|---|---|---|")
    for name, seconds, residual, sweeps, shown, region in rows:
        direct = rows[4 if "normal" in name else 1][4]  # the direct solve with the same constraints
        far = float(np.max(np.linalg.norm(shown - direct, axis=1)))
        print(f"| {name} | {1e3 * seconds:.2f} | {1.0 / seconds:.0f} | {residual:.1e} | {sweeps or '-'} | "
              f"{far:.3f} | {region[0] if region else '-'} |")
    print(f"\nDirect vs SOR on release: {rows[2][1] / rows[1][1]:.1f}x the time for SOR. Holding the pin's "
          f"normal costs {rows[3][1] / rows[0][1]:.1f}x a move (the coupled 3N system, re-linearized each round).")
    print("\nMemory per finest face (peak of a fresh process building a flat grid and editing one pin):\n")
    print("| finest faces | peak per face (B) | growth per face (B) |")
    print("|---|---|---|")
    for cells, levels in ((10, 4), (10, 5), (20, 5)):
        count, per_face, growth = memory_per_face(cells, levels)
        print(f"| {count:,} | {per_face:.0f} | {growth:.0f} |")
    print(f"\nThe feature refuses a surface whose estimate ({multiresolution.BYTES_PER_FINEST_FACE} B a face) "
          f"exceeds {multiresolution.MAX_BYTES / 1e9:.1f} GB.")
    brep_table(nat, built)
    _ = resource  # the subprocess measures; imported for readers running it by hand


def quietly(call):
    """call() with the process's standard output closed (OCCT's STEP writer prints its statistics)."""
    sys.stdout.flush()
    saved, devnull = os.dup(1), os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    try:
        return call()
    finally:
        os.dup2(saved, 1)
        os.close(devnull)
        os.close(saved)


def brep_table(nat, built):
    """The limit surface as B-rep: the patches merged into C2 faces (what SubdBRep writes) against
    a face per patch (the peer, in the same process), on the vase and on a cube captured onto a
    sphere (valence-3 corners: end caps and refined faces)."""
    import tempfile

    box = [(x, y, z) for x in (-10.0, 10.0) for y in (-10.0, 10.0) for z in (-10.0, 10.0)]
    quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    u, v = np.meshgrid(np.linspace(0, np.pi, 64), np.linspace(0, 2 * np.pi, 128), indexing="ij")
    ball = np.stack([13 * np.sin(u) * np.cos(v), 13 * np.sin(u) * np.sin(v), 13 * np.cos(u)], -1).reshape(-1, 3)
    tris = [t for i in range(63) for j in range(128)
            for t in ((i * 128 + j, (i + 1) * 128 + j, (i + 1) * 128 + (j + 1) % 128),
                      (i * 128 + j, (i + 1) * 128 + (j + 1) % 128, i * 128 + (j + 1) % 128))]
    sphere = multiresolution.build(box, quads, 5, target=(ball, tris))
    print("\nThe limit surface as B-rep (SubdBRep, isolation 3): regular patches merged into C2 B-spline faces "
          "against a face per patch:\n")
    print("| surface | patches | faces merged / one each | build (s) merged / one each | ratio "
          "| STEP (MB) merged / one each |")
    print("|---|---|---|---|---|---|")
    for name, result in (("vase, 10,240 faces", built), ("sphere-captured cube, 6,144 faces", sphere)):
        start = time.perf_counter()
        merged = multiresolution.brep(result, 3)
        merged_s = time.perf_counter() - start
        finest = nat.SubdivisionMesh(np.asarray(result.levels[-1], float), [list(f) for f in result.faces[-1]])
        start = time.perf_counter()
        patches = nat.limit_patches(finest, 3).patches
        each = nat.patch_shell([p.surface for p in patches], [not p.regular for p in patches],
                               1e-7 * float(np.linalg.norm(np.ptp(result.points, axis=0))))
        each_s = time.perf_counter() - start
        sizes = []
        with tempfile.TemporaryDirectory() as folder:
            for k, brep in enumerate((merged.brep, each.shell.brep)):
                path = Path(folder) / f"{k}.step"
                quietly(lambda: nat.write_step(brep, str(path)))
                sizes.append(path.stat().st_size / 1e6)
        print(f"| {name} | {merged.patches:,} | {merged.faces:,} / {len(patches):,} | {merged_s:.2f} / {each_s:.2f} "
              f"| {each_s / merged_s:.1f}x | {sizes[0]:.1f} / {sizes[1]:.1f} |")


if __name__ == "__main__":
    main()
