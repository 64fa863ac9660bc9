# SPDX-License-Identifier: LGPL-2.1-or-later
"""Tubes: a closed Sheet through closed sections (a bottle neck between two rings) and curves
between them. The sections are ordered along the tube and lofted (FreeCAD's own Part Loft, so a
changed section recomputes the start shape); the Sheet on the loft's face is closed around its
seam, keeps the two end sections as its boundary and passes through the others and the curves.
App side only."""

from __future__ import annotations

from typing import Iterable

import Part

from varsurf.app.make import make_sheet
from varsurf.solve.errors import SheetError
from varsurf.solve.tube import section_order


def _closed_section(obj):
    """The one closed curve of a section object (as a wire), or ValueError naming it."""
    if "Touched" in obj.State or getattr(obj, "Shape", None) is None or obj.Shape.isNull():
        obj.recompute()  # a section added in the same script has no shape before its recompute
    shape = getattr(obj, "Shape", None)
    if shape is None or shape.isNull() or not shape.Edges:
        raise ValueError(f"tube section {obj.Label} has no curve")
    wires = shape.Wires or [Part.Wire(shape.Edges)]
    if len(wires) != 1 or not wires[0].isClosed():
        raise ValueError(f"tube section {obj.Label} is not one closed curve: give each section as a closed sketch, "
                         "circle or closed B-spline")
    if len(shape.Edges) != 1:
        raise ValueError(f"tube section {obj.Label} is made of {len(shape.Edges)} edges: the tube's loft would "
                         "be several faces; give it as one closed curve (a circle, an ellipse, a closed B-spline)")
    return wires[0]


def ordered_sections(sections):
    """The section objects in the tube's order, or ValueError (unclosed, or cannot be ordered)."""
    wires = [_closed_section(obj) for obj in sections]
    extent = max(w.BoundBox.DiagonalLength for w in wires)
    try:
        order = section_order([o.Label for o in sections], [w.CenterOfMass for w in wires], extent)
    except SheetError as error:
        raise ValueError(str(error)) from error
    return [sections[i] for i in order]


def make_tube(sections: Iterable, curves: Iterable = (), doc=None, name: str = "Tube", **sheet_options):
    """A closed Sheet through ``sections`` (two or more objects, each one closed curve: a circle,
    an ellipse, a closed B-spline or a sketch of one) and ``curves`` between them (as make_sheet
    takes them). Returns the Sheet; its Base is a Part Loft of the sections in their order along
    the tube (hidden). ``sheet_options`` go to make_sheet (tolerance, spans, degree, ...).
    ValueError, with nothing created, for sections that are not closed curves or cannot be
    ordered."""
    sections = list(sections)
    ordered = ordered_sections(sections)
    doc = doc or ordered[0].Document
    loft = doc.addObject("Part::Loft", f"{name}Loft")
    loft.Sections = ordered
    loft.Solid = False
    loft.Ruled = False
    loft.Closed = False
    if getattr(loft, "ViewObject", None) is not None:
        loft.ViewObject.Visibility = False
    return make_sheet((loft, "Face1"), list(ordered) + list(curves), doc=doc, name=name, **sheet_options)
