#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Instruction counts (valgrind's callgrind) of benchmark 2's document recomputes: a Sheet feature
against the Surface Filling feature on the same curves. Wall time on shared 2-core machines varies
by +-20 %; executed instructions do not, so the ratio of these counts is the stable figure.

    /usr/bin/python3 bench/callgrind_filling.py      # prints one table row per case

Each filler runs in one FreeCAD process under callgrind, counting only inside
App::Document::recompute and writing a profile after each one: per case the scene's curves are
recomputed, the feature is added and recomputed (first run: start-up costs), then touched and
recomputed again; that last, warm recompute is the figure.
"""

import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
RECOMPUTE = "*App::Document::recompute*"


def child(filler):
    """Run every case's scene with `filler` ("sheet" or "filling"), three recomputes each."""
    sys.path.insert(0, str(HERE))
    import run_bench as rb

    FreeCAD, Part = rb._freecad()
    import varsurf

    V = FreeCAD.Vector
    for name, amplitude, interior, tolerance in rb.FILLING_CASES:
        doc = FreeCAD.newDocument("Callgrind")
        boundary, inner = rb._case_curves(Part, V, amplitude, interior)
        objs = []
        for k, e in enumerate(boundary + inner):
            o = doc.addObject("Part::Feature", f"C{k}")
            o.Shape = e
            objs.append(o)
        base = doc.addObject("Part::Feature", "Base")
        base.Shape = rb._flat_square(Part, V)
        doc.recompute()
        if filler == "sheet":
            feature = varsurf.make_sheet((base, "Face1"), [(o, "Edge1") for o in objs], fix_boundary=False,
                                         tolerance=tolerance, name="Sheet")
        else:
            feature = doc.addObject("Surface::Filling", "Filling")
            feature.BoundaryEdges = [(o, "Edge1") for o in objs[:4]]
            if inner:
                feature.UnboundEdges = [(o, "Edge1") for o in objs[4:]]
        doc.recompute()
        feature.touch()
        doc.recompute()
        FreeCAD.closeDocument(doc.Name)


def _dump_totals(folder):
    """The instruction totals of the profiles callgrind wrote, in the order written."""
    dumps = []
    for path in folder.glob("callgrind.out.*"):
        part = re.search(r"\.(\d+)$", path.name)
        total = None
        for line in path.read_text(errors="replace").splitlines():
            if line.startswith(("summary:", "totals:")):
                total = int(line.split()[1])
        if part and total is not None:
            dumps.append((int(part.group(1)), total))
    return [total for _, total in sorted(dumps)]


def counts(filler):
    """Warm-recompute instruction counts of every case for one filler."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        cmd = ["valgrind", "--tool=callgrind", f"--toggle-collect={RECOMPUTE}", f"--dump-after={RECOMPUTE}",
               f"--callgrind-out-file={out}/callgrind.out", "/usr/bin/python3", __file__, "--child", filler]
        env = dict(os.environ, PYTHONHASHSEED="0", OPENBLAS_NUM_THREADS="1")
        subprocess.run(cmd, check=True, env=env, capture_output=True, cwd=tmp)
        totals = _dump_totals(out)
    return totals[2::3]  # per case: curves, first recompute, warm recompute


def main():
    sys.path.insert(0, str(HERE))
    import run_bench as rb

    sheet, filling = counts("sheet"), counts("filling")
    print("| case | Sheet recompute Ir (millions) | Filling recompute Ir (millions) | ratio |")
    print("|---|---|---|---|")
    for (name, *_), s, f in zip(rb.FILLING_CASES, sheet, filling):
        print(f"| {name} | {s / 1e6:.1f} | {f / 1e6:.1f} | {f / s:.2f}x |")


if __name__ == "__main__":
    if "--child" in sys.argv:
        child(sys.argv[sys.argv.index("--child") + 1])
    else:
        main()
