# SPDX-License-Identifier: LGPL-2.1-or-later
"""A Sheet's analysis data: the face its deviation is measured from, and its L-curve plot
(recorded macros call ``varsurf.app.analysis.plot_lcurve``; those of release 0.1.0,
``varsurf.analysis.plot_lcurve``). The fields themselves are computed by
varsurf.solve.analysis."""

from __future__ import annotations

from typing import Optional

import Part


def reference_of(sheet) -> Optional[object]:
    """The face a Sheet's deviation is measured from: its installed rest shape, else its base."""
    if str(getattr(sheet, "RestShape", "None")) == "Installed":
        rest = getattr(sheet, "InstalledRest", None)
        if rest is not None and not rest.isNull() and len(rest.Faces) == 1:
            return rest
    base = getattr(sheet, "Base", None)
    if base and base[0] is not None:
        subs = [s for s in base[1] if s]
        if subs:
            return Part.getShape(base[0], subs[0], needSubElement=True)
    return None


def plot_lcurve(sheet, path: str) -> str:
    """The L-curve of a Sheet's TSVD/MTSVD solve (residual norm against solution change norm per
    truncation k, log-log) with the chosen corner marked, written as a PNG; its path. ValueError
    when the last solve drew no L-curve (other solve modes)."""
    residuals, norms = list(sheet.LCurveResiduals), list(sheet.LCurveNorms)
    corner = int(sheet.LCurveCorner)
    if not residuals or len(residuals) != len(norms) or not 1 <= corner <= len(residuals):
        raise ValueError(f"{sheet.Label} has no L-curve: solve it in TSVD or MTSVD mode")
    import matplotlib  # here: optional (Recommends), and 0.4 s to import; only for this plot

    matplotlib.use("Agg", force=False)  # a file, whatever the GUI uses
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    keep = [(r, e) for r, e in zip(residuals, norms) if r > 0.0 and e > 0.0]
    figure = Figure(figsize=(6.0, 4.5), dpi=100)
    FigureCanvasAgg(figure)
    axes = figure.add_subplot(1, 1, 1)
    axes.loglog([r for r, _ in keep], [e for _, e in keep], "o-", markersize=3, color="#2060c0")
    r, e = residuals[corner - 1], norms[corner - 1]
    if r > 0.0 and e > 0.0:
        axes.loglog([r], [e], "o", markersize=10, markerfacecolor="none", markeredgecolor="#d02020",
                    markeredgewidth=2, label=f"corner: k = {corner}")
        axes.legend()
    axes.set_xlabel("constraint residual norm ‖B x − d‖")
    axes.set_ylabel("solution change norm ‖x − x₀‖")
    axes.set_title(f"L-curve of {sheet.Label} ({len(residuals)} truncations)")
    axes.grid(True, which="both", alpha=0.3)
    figure.tight_layout()
    figure.savefig(path)
    return path
