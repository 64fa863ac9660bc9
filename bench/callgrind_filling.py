#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Instruction counts (valgrind's callgrind) of benchmark 2's document recomputes: a Sheet feature
against the Surface Filling feature on the same curves. Wall time on shared 2-core machines varies
by +-20 %; executed instructions do not, so the ratio of these counts is the stable figure.

    /usr/bin/python3 bench/callgrind_filling.py      # prints one table row per case

Each filler runs in one FreeCAD process under callgrind. Per case the scene is built, the feature
added and recomputed twice (start-up costs, then warm); the third recompute is counted. Callgrind
zeroes its counters when the child calls getppid() and writes a profile when it calls getpgrp():
two C functions nothing in a recompute calls, so each profile holds exactly one recompute (with
the Python call around it, as a user's recompute has).
"""

import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def _scene(rb, FreeCAD, Part, doc, amplitude, interior):
    V = FreeCAD.Vector
    boundary, inner = rb._case_curves(Part, V, amplitude, interior)
    objs = []
    for k, e in enumerate(boundary + inner):
        o = doc.addObject("Part::Feature", f"C{k}")
        o.Shape = e
        objs.append(o)
    base = doc.addObject("Part::Feature", "Base")
    base.Shape = rb._flat_square(Part, V)
    doc.recompute()
    return base, objs


def child(filler):
    """Every case's scene with `filler` ("sheet" or "filling"); one counted warm recompute each."""
    sys.path.insert(0, str(HERE))
    import run_bench as rb

    FreeCAD, Part = rb._freecad()
    import varsurf

    for _name, amplitude, interior, tolerance in rb.FILLING_CASES:
        doc = FreeCAD.newDocument("Callgrind")
        base, objs = _scene(rb, FreeCAD, Part, doc, amplitude, interior)
        if filler == "sheet":
            feature = varsurf.make_sheet((base, "Face1"), [(o, "Edge1") for o in objs], fix_boundary=False,
                                         tolerance=tolerance, name="Sheet")
        else:
            feature = doc.addObject("Surface::Filling", "Filling")
            feature.BoundaryEdges = [(o, "Edge1") for o in objs[:4]]
            if len(objs) > 4:
                feature.UnboundEdges = [(o, "Edge1") for o in objs[4:]]
        doc.recompute()
        feature.touch()
        doc.recompute()
        feature.touch()
        os.getppid()  # callgrind: zero the counters
        doc.recompute()
        os.getpgrp()  # callgrind: write this recompute's profile
        if not feature.isValid():
            sys.exit(f"{feature.Name} in error: {feature.getStatusString()}")
        FreeCAD.closeDocument(doc.Name)


def _dump_totals(folder):
    """The instruction totals of the numbered profiles callgrind wrote, in the order written."""
    dumps = []
    for path in folder.glob("callgrind.out.*"):
        part = re.search(r"\.(\d+)$", path.name)
        if not part:
            continue
        for line in path.read_text(errors="replace").splitlines():
            if line.startswith("summary:"):
                dumps.append((int(part.group(1)), int(line.split()[1])))
                break
    return [total for _, total in sorted(dumps)]


def counts(filler):
    """Warm-recompute instruction counts of every case for one filler."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        cmd = ["valgrind", "--tool=callgrind", "--zero-before=*getppid*", "--dump-before=*getpgrp*",
               f"--callgrind-out-file={out}/callgrind.out", "/usr/bin/python3", __file__, "--child", filler]
        env = dict(os.environ, PYTHONHASHSEED="0", OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
        done = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=tmp)
        if done.returncode != 0:
            sys.exit(f"callgrind run of {filler} failed:\n{done.stderr[-3000:]}")
        return _dump_totals(out)


def main():
    sys.path.insert(0, str(HERE))
    import run_bench as rb

    sheet, filling = counts("sheet"), counts("filling")
    if len(sheet) != len(rb.FILLING_CASES) or len(filling) != len(rb.FILLING_CASES):
        sys.exit(f"expected one profile per case, got {len(sheet)} (Sheet) and {len(filling)} (Filling)")
    print("| case | Sheet recompute (million instructions) | Filling recompute (million instructions) "
          "| Filling / Sheet |")
    print("|---|---|---|---|")
    for (name, *_), s, f in zip(rb.FILLING_CASES, sheet, filling):
        print(f"| {name} | {s / 1e6:.1f} | {f / 1e6:.1f} | {f / s:.2f}x |")


if __name__ == "__main__":
    if "--child" in sys.argv:
        child(sys.argv[sys.argv.index("--child") + 1])
    else:
        main()
