# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the figure examples share: build each named figure in its own document, print what it
measured, write its FCStd, its STEP and its picture (the FreeCAD GUI under Xvfb, when present)."""

from pathlib import Path

import freecad_env  # noqa: F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402

import varsurf  # noqa: E402


def run_figures(figures, out_dir, only, build_report):
    """Build the figures named in `only` (all when empty) into `out_dir`. `build_report(stem, doc)`
    builds one and returns (objects to check, objects to write to STEP, lines to print); returns
    1 if an object is in error, 2 for an unknown name, else 0."""
    from demo import render

    unknown = [name for name in only if name not in figures]
    if unknown:
        print(f"no figure {', '.join(unknown)}: name some of {', '.join(figures)}")
        return 2
    out = Path(out_dir).resolve()
    out.mkdir(parents=True, exist_ok=True)
    failed = 0
    for stem in figures:
        if only and stem not in only:
            continue
        doc = FreeCAD.newDocument(stem)
        checked, to_step, lines = build_report(stem, doc)
        failed += sum(not obj.isValid() for obj in checked)
        for line in lines:
            print(line)
        fcstd = out / f"{stem}.FCStd"
        doc.saveAs(str(fcstd))
        written = [fcstd.name]
        if to_step:
            varsurf.export_step(to_step, str(out / f"{stem}.step"))
            written.append(f"{stem}.step")
        why = render(fcstd, out / f"{stem}.png")
        print(f"{stem}: {', '.join(written)}" + (f", no picture ({why})" if why else f", {stem}.png"))
        FreeCAD.closeDocument(doc.Name)
    return 1 if failed else 0
