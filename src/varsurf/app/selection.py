# SPDX-License-Identifier: LGPL-2.1-or-later
"""What a selection (Gui.Selection.getSelectionEx()) asks for: the arguments of each
make-function, or a ValueError that says what to select."""

from __future__ import annotations

from typing import List, Optional, Sequence, Tuple

import Part

from varsurf.app import references
from varsurf.app.sheet import curve_keys
from varsurf.solve import constraints

SELECTION_HINT = (
    "Select exactly one face (the base surface) and, optionally, edges of sketches or other "
    "shapes (the curves the sheet must pass through)."
)


def selection_to_sheet_args(selection_ex: Sequence):
    """(base, curves) for make_sheet from Gui.Selection.getSelectionEx(), or ValueError.

    Each item needs ``.Object`` and ``.SubElementNames``. A whole object (no sub-element) counts
    as its face if it has exactly one, otherwise as all its edges if it has no face.
    """
    faces: List[Tuple[object, str]] = []
    edges: List[Tuple[object, str]] = []
    for sel in selection_ex or []:
        obj = sel.Object
        subs = [s for s in (getattr(sel, "SubElementNames", None) or ()) if s]
        if not subs:
            shape = getattr(obj, "Shape", None)
            if shape is None or shape.isNull():
                raise ValueError(f"{obj.Label} has no shape. {SELECTION_HINT}")
            if len(shape.Faces) == 1:
                faces.append((obj, "Face1"))
            elif len(shape.Faces) > 1:
                raise ValueError(
                    f"{obj.Label} has {len(shape.Faces)} faces: select one of them in the 3D "
                    f"view. {SELECTION_HINT}"
                )
            elif shape.Edges:
                edges.extend((obj, f"Edge{i + 1}") for i in range(len(shape.Edges)))
            else:
                raise ValueError(f"{obj.Label} has neither a face nor an edge. {SELECTION_HINT}")
            continue
        for sub in subs:
            element = sub.split(".")[-1]
            if element.startswith("Face"):
                faces.append((obj, element))
            elif element.startswith("Edge"):
                edges.append((obj, element))
            elif element.startswith("Vertex"):
                raise ValueError(
                    f"{obj.Label}:{element} is a vertex; a sheet takes one face and edges, "
                    f"not points. {SELECTION_HINT}"
                )
            else:
                raise ValueError(f"{obj.Label}:{element} is not a face or an edge. {SELECTION_HINT}")
    if not faces and not edges:
        raise ValueError(f"Nothing is selected. {SELECTION_HINT}")
    if not faces:
        raise ValueError(f"No face is selected. {SELECTION_HINT}")
    if len(faces) > 1:
        listed = ", ".join(f"{o.Label}:{n}" for o, n in faces)
        raise ValueError(f"{len(faces)} faces are selected ({listed}). {SELECTION_HINT}")
    curves = references.normalize_curves([(o, n) for o, n in edges])
    return faces[0], curves


def selection_problem(selection_ex) -> Optional[str]:
    """None when the selection makes a sheet, otherwise why not."""
    try:
        selection_to_sheet_args(selection_ex)
    except ValueError as error:
        return str(error)
    return None


SOLID_HINT = "Select the Sheets to join (two or more that share curves)."


def solid_selection_to_sheets(selection_ex) -> List:
    """The Sheets of a selection (whole objects or any of their elements), or ValueError."""
    sheets = []
    for sel in selection_ex or []:
        obj = sel.Object
        if not references.is_sheet(obj):
            raise ValueError(f"{obj.Label} is not a Sheet. {SOLID_HINT}")
        if obj not in sheets:
            sheets.append(obj)
    if len(sheets) < 2:
        found = "no Sheet is selected" if not sheets else f"only {sheets[0].Label} is selected"
        raise ValueError(f"A Solid joins two or more Sheets, and {found}. {SOLID_HINT}")
    return sheets


FILL_HOLE_HINT = ("Select the face of a part to replace, or the free edges around a hole (Ctrl+click), and "
                  "optionally curves inside it (e.g. a sketch).")


def fill_hole_selection_to_args(selection_ex):
    """(part, its selected face or edges, interior curves as (object, element) links) of a selection:
    the first object with a selected face or edges is the part; everything selected after it are
    curves. ValueError saying what to select otherwise."""
    part, elements, curves = None, [], []
    for sel in selection_ex or []:
        obj, names = sel.Object, [n for n in (sel.SubElementNames or []) if n]
        if part is None and names and all(n.startswith(("Face", "Edge")) for n in names):
            if references.is_sheet(obj):
                raise ValueError(f"{obj.Label} is a Sheet: fill holes in parts. {FILL_HOLE_HINT}")
            part, elements = obj, names
            continue
        if part is None:
            raise ValueError(f"select the part's face or edges first. {FILL_HOLE_HINT}")
        curves += [(obj, n) for n in names] if names else [(obj, "")]
    if part is None:
        raise ValueError(f"nothing to fill is selected. {FILL_HOLE_HINT}")
    faces = [n for n in elements if n.startswith("Face")]
    if faces and (len(faces) > 1 or len(faces) != len(elements)):
        raise ValueError(f"select one face to replace, or edges only. {FILL_HOLE_HINT}")
    return part, elements, curves


SUBD_HINT = ("Select the cage (a Mesh, a shape whose faces make the control mesh, or a VarSurf sheet) and, "
             "optionally, a Mesh or shape whose detail to capture.")
SUBD_BREP_HINT = "Select one SubdSurface."
TRIANGULAR_HINT = "Select one Mesh (a coarse triangle mesh: each triangle becomes a patch) or a shape with faces."


def _has_mesh_or_faces(obj) -> bool:
    mesh = getattr(obj, "Mesh", None)
    if mesh is not None and hasattr(mesh, "CountFacets"):
        return mesh.CountFacets > 0
    shape = getattr(obj, "Shape", None)
    return shape is not None and not shape.isNull() and bool(shape.Faces)


def subd_surface_selection_to_args(selection_ex):
    """(cage, target or None) of a selection: whole objects with a mesh or faces. ValueError saying
    what to select otherwise."""
    objects = [sel.Object for sel in selection_ex or []]
    if not objects or len(objects) > 2:
        raise ValueError(f"{'nothing' if not objects else 'too much'} is selected. {SUBD_HINT}")
    for obj in objects:
        if not _has_mesh_or_faces(obj):
            raise ValueError(f"{obj.Label} has no mesh and no faces. {SUBD_HINT}")
    return objects[0], (objects[1] if len(objects) == 2 else None)


def subd_brep_selection_to_args(selection_ex):
    """The SubdSurface of a selection. ValueError saying what to select otherwise."""
    objects = [sel.Object for sel in selection_ex or []]
    if len(objects) != 1 or getattr(getattr(objects[0], "Proxy", None), "Type", "") != "VarSurf::SubdSurface":
        raise ValueError(f"no single SubdSurface is selected. {SUBD_BREP_HINT}")
    return objects[0]


def triangular_selection_to_args(selection_ex):
    """The Mesh (or shape with faces) of a selection. ValueError saying what to select otherwise."""
    objects = [sel.Object for sel in selection_ex or []]
    if len(objects) != 1 or not _has_mesh_or_faces(objects[0]):
        raise ValueError(f"no single mesh is selected. {TRIANGULAR_HINT}")
    return objects[0]


#: What to select for each kind, besides the Sheet.
SELECTION_HINTS = {
    "Point": "Select a Sheet and the vertex it must pass through.",
    "point": "Select a Sheet and, optionally, a vertex for the point's position.",
    "region": "Select a Sheet and, optionally, closed edges (e.g. a sketch) bounding the region.",
    "SurfaceAttractor": "Select a Sheet, the face to pull onto and, optionally, closed edges bounding the region.",
    "CurveAttractor": "Select a Sheet and the edge to pull onto.",
    "Ribbon": ("Select a Sheet, the edge along which its normal is set and, optionally, a face or a second edge "
               "to follow."),
    "G1": "Select a Sheet, the edge along which it joins, and the face it must follow there.",
    "G2": "Select a Sheet, the edge along which it joins, and the face whose curvature it must continue there.",
    "G0": "Select a Sheet and the edge it must contain (e.g. the edge of the neighbouring face).",
    "RegionMap": "Select a Sheet and the face (the destination patch) its region is mapped onto.",
    "CurveMap": ("Select a Sheet, then the source edge (a curve on the sheet) and then the destination edge it is "
                 "mapped onto."),
}
#: Kinds that need a picked vertex from the GUI (their target is a location).
VERTEX_KINDS = ("Point",)


def selection_hint(kind: str) -> str:
    if kind in SELECTION_HINTS:
        return SELECTION_HINTS[kind]
    return SELECTION_HINTS["point" if kind in constraints.POINT_KINDS else "region"]


def _split_selection(selection_ex, hint):
    """(sheets, [(element type, (object, sub)), ...]) of a selection, in picking order."""
    sheets, picks = [], []
    for sel in selection_ex or []:
        obj = sel.Object
        subs = [s.split(".")[-1] for s in (getattr(sel, "SubElementNames", None) or ()) if s]
        if references.is_sculptable(obj):  # a Sheet or a PdeSurface
            if obj not in sheets:
                sheets.append(obj)
            continue
        if not subs and references.is_point_object(obj):
            subs = ["Vertex1"]  # a Draft point or Part vertex picked as a whole
        if not subs:
            raise ValueError(f"{obj.Label} is not a Sheet: pick one of its elements instead. {hint}")
        for sub in subs:
            element = next((e for e in ("Vertex", "Edge", "Face") if sub.startswith(e)), None)
            if element is None:
                raise ValueError(f"{obj.Label}:{sub} cannot be used here. {hint}")
            picks.append((element, (obj, sub)))
    if len(sheets) != 1:
        raise ValueError(f"{len(sheets)} Sheets selected: select exactly one. {hint}")
    return sheets[0], picks


def constraint_selection_to_args(kind: str, selection_ex: Sequence):
    """(sheet, keyword arguments for make_constraint) from a selection, or ValueError.

    Exactly one Sheet (the whole object or any of its elements), plus per kind: a vertex (Point:
    required; other point kinds: optional); an edge to follow and an optional face or second
    edge (Ribbon), an edge and a face (G1); an edge (CurveAttractor); a face (SurfaceAttractor);
    and for region kinds optionally closed edges of one object bounding the region.
    """
    if kind not in constraints.KINDS:
        raise ValueError(f"unknown constraint kind {kind!r}: give one of {', '.join(constraints.KINDS)}")
    hint = selection_hint(kind)
    sheet, picks = _split_selection(selection_ex, hint)
    of = {e: [ref for element, ref in picks if element == e] for e in ("Vertex", "Edge", "Face")}

    def refuse(element, why=None):
        if of[element]:
            obj, sub = of[element][0]
            raise ValueError(why or f"{obj.Label}:{sub} cannot be used here. {hint}")

    args = {}
    if kind in constraints.POINT_KINDS:
        refuse("Edge")
        refuse("Face")
        if len(of["Vertex"]) > 1:
            raise ValueError(f"{len(of['Vertex'])} vertices selected: select at most one. {hint}")
        if kind in VERTEX_KINDS and not of["Vertex"]:
            raise ValueError(f"a {kind} constraint needs a vertex. {hint}")
        if of["Vertex"]:
            args["location"] = of["Vertex"][0]
        return sheet, args
    refuse("Vertex")
    if kind == "RegionMap":
        if len(of["Face"]) != 1 or of["Edge"]:
            raise ValueError(f"a RegionMap needs exactly one face: the destination patch. {hint}")
        args["reference"] = of["Face"][0]
        return sheet, args
    if kind == "CurveMap":
        if len(of["Edge"]) != 2 or of["Face"]:
            raise ValueError(f"a CurveMap needs exactly two edges: the source, then the destination. {hint}")
        args["curve"], args["reference"] = of["Edge"]
        return sheet, args
    if kind in constraints.CURVE_KINDS or kind in ("CurveAttractor", "G0"):
        edges, faces = of["Edge"], of["Face"]
        if kind in constraints.JOIN_KINDS and (len(edges) != 1 or len(faces) != 1):
            raise ValueError(f"a {kind} needs exactly one edge and one face. {hint}")
        if kind in ("CurveAttractor", "G0") and (len(edges) != 1 or faces):
            raise ValueError(f"a {kind} needs exactly one edge. {hint}")
        if kind == "Ribbon" and (not edges or len(edges) + len(faces) > 2 or len(faces) > 1):
            raise ValueError(f"a Ribbon needs one edge and at most one face or second edge. {hint}")
        args["curve"] = edges[0]
        rest = faces + edges[1:]
        if rest:
            args["reference"] = rest[0]
        return sheet, args
    if kind == "SurfaceAttractor":
        if len(of["Face"]) != 1:
            raise ValueError(f"a SurfaceAttractor needs exactly one face. {hint}")
        args["reference"] = of["Face"][0]
    else:
        refuse("Face")
    if of["Edge"]:
        owners = {obj.Name for obj, _sub in of["Edge"]}
        if len(owners) != 1:
            raise ValueError(f"the region's edges must all belong to one object. {hint}")
        args["region_loop"] = (of["Edge"][0][0], [sub for _obj, sub in of["Edge"]])
    return sheet, args


TUBE_HINT = ("Select two or more closed sections (sketches, circles, closed splines: each one closed curve) "
             "and, optionally, edges of the curves the tube passes through between them.")


def _one_closed_curve(obj) -> bool:
    shape = getattr(obj, "Shape", None)
    if shape is None or shape.isNull() or not shape.Edges or references.is_sheet(obj):
        return False
    wires = shape.Wires or [Part.Wire(Part.__sortEdges__(shape.Edges))]
    return len(wires) == 1 and wires[0].isClosed() and len(wires[0].Edges) == len(shape.Edges)


def tube_selection_to_args(selection_ex):
    """(sections, curves) of a selection: every object that is one closed curve, picked whole or
    by any of its edges, is a section (whole); edges of other objects are curves, as
    (object, "EdgeN"). ValueError saying what to select otherwise."""
    sections, curves = [], []
    for sel in selection_ex or []:
        obj, names = sel.Object, [n.split(".")[-1] for n in (sel.SubElementNames or []) if n]
        if _one_closed_curve(obj):
            if obj not in sections:
                sections.append(obj)
            continue
        if references.is_sheet(obj):
            raise ValueError(f"{obj.Label} is a Sheet, not a section. {TUBE_HINT}")
        if not names:
            raise ValueError(f"{obj.Label} is not one closed curve: pick the edges the tube must pass "
                             f"through instead. {TUBE_HINT}")
        for name in names:
            if not name.startswith("Edge"):
                raise ValueError(f"{obj.Label}:{name} is not an edge. {TUBE_HINT}")
            curves.append((obj, name))
    if len(sections) < 2:
        raise ValueError(f"{len(sections)} closed sections selected: a tube needs two or more. {TUBE_HINT}")
    return sections, curves


PDE_SURFACE_HINT = ("Select the two boundary curves (edges), then optionally a derivative curve beside each, in the "
                    "same order (Hermite); or four edges that close a loop (Coons).")


def _ends(obj, sub):
    import Part

    edge = Part.getShape(obj, sub, needSubElement=True)
    return edge.valueAt(edge.FirstParameter), edge.valueAt(edge.LastParameter), edge.BoundBox.DiagonalLength


def pde_surface_selection_to_args(selection_ex):
    """make_pde_surface's keyword arguments for a selection of edges, or ValueError: two boundary
    curves (u = 0, u = 1) and up to two derivative curves after them; or four edges closing a loop:
    the first at u = 0, the one not touching it at u = 1, the sides between them."""
    picked = [(sel.Object, sub) for sel in selection_ex or [] for sub in sel.SubElementNames]
    edges = [(o, s) for o, s in picked if s.startswith("Edge")]
    if len(edges) != len(picked) or not 2 <= len(edges) <= 4:
        raise ValueError(f"{len(edges)} edges selected ({len(picked) - len(edges)} other elements). {PDE_SURFACE_HINT}")
    if len(edges) == 4:
        ends = [_ends(o, s) for o, s in edges]
        size = max(e[2] for e in ends)
        close = 1e-6 * max(size, 1.0)

        def touch(a, b):
            return min((p - q).Length for p in ends[a][:2] for q in ends[b][:2]) <= close

        others = [k for k in (1, 2, 3) if not touch(0, k)]
        if len(others) == 1 and all(touch(k, m) for k in (1, 2, 3) if k != others[0] for m in (0, others[0])):
            opposite = others[0]
            sides = [k for k in (1, 2, 3) if k != opposite]
            start = ends[0][0]
            first = min(sides, key=lambda k: min((start - p).Length for p in ends[k][:2]))
            second = [k for k in sides if k != first][0]
            return dict(u0=edges[0], u1=edges[opposite], v0=edges[first], v1=edges[second])
    args = dict(u0=edges[0], u1=edges[1])
    if len(edges) > 2:
        args["derivative0"] = edges[2]
    if len(edges) > 3:
        args["derivative1"] = edges[3]
    return args


SPACE_CURVE_HINT = "Select one edge (of a sketch or a Part object): the curve's start shape."
HINGE_HINT = ("Select two Sheets of a Solid and the edge they share, or the edge of a Solid "
              "where two of its faces meet.")


def space_curve_selection_to_base(selection_ex):
    """(object, "EdgeN") of a selection of exactly one edge, or ValueError."""
    picked = [(sel.Object, sub) for sel in selection_ex or [] for sub in sel.SubElementNames]
    edges = [(o, s) for o, s in picked if s.startswith("Edge")]
    if len(edges) != 1 or len(picked) != 1:
        raise ValueError(f"{len(edges)} edges selected. {SPACE_CURVE_HINT}")
    return edges[0]


def _solid_of(sheets):
    doc = sheets[0].Document
    for obj in doc.Objects:
        if references.is_solid(obj) and all(s in list(obj.Sheets or []) for s in sheets):
            return obj
    raise ValueError(f"{sheets[0].Label} and {sheets[1].Label} are not in one Solid: make a Solid of "
                     "them first (VarSurf Solid)")


def _shared_curve_near(sheets, point):
    """The curve key both sheets list that passes nearest ``point``."""
    shared = [k for k in curve_keys(sheets[0]) if k in set(curve_keys(sheets[1]))]
    if not shared:
        raise ValueError(f"{sheets[0].Label} and {sheets[1].Label} share no curve. {HINGE_HINT}")
    doc = sheets[0].Document

    def distance(key):
        name, sub = key.split(":")
        edge = Part.getShape(doc.getObject(name), sub, needSubElement=True)
        return edge.distToShape(Part.Vertex(point))[0]

    best = min(shared, key=distance)
    name, sub = best.split(":")
    return doc.getObject(name), sub


def hinge_selection_to_args(selection_ex):
    """(solid, sheet_a, sheet_b, (object, "EdgeN")) of a hinge selection, or ValueError."""
    sheets, edges, solid_edges = [], [], []
    for sel in selection_ex or []:
        obj = sel.Object
        subs = [s for s in sel.SubElementNames if s]
        if references.is_sheet(obj):
            if obj not in sheets:
                sheets.append(obj)
        elif references.is_solid(obj):
            solid_edges += [(obj, s) for s in subs if s.startswith("Edge")]
        else:
            edges += [(obj, s) for s in subs if s.startswith("Edge")]
    if len(sheets) == 2 and len(edges) == 1 and not solid_edges:
        key = f"{edges[0][0].Name}:{edges[0][1]}"
        for s in sheets:
            if key not in curve_keys(s):
                raise ValueError(f"{edges[0][0].Label}:{edges[0][1]} is not a curve of {s.Label}: a hinge "
                                 "needs a curve both Sheets pass through")
        return (_solid_of(sheets), sheets[0], sheets[1], edges[0])
    if len(solid_edges) == 1 and not sheets and not edges:
        solid, sub = solid_edges[0]
        edge = Part.getShape(solid, sub, needSubElement=True)
        mid = edge.valueAt(0.5 * (edge.FirstParameter + edge.LastParameter))
        tol = max(float(solid.Tolerance), 1e-6) * 10
        near = [s for s in solid.Sheets if s.Shape.distToShape(Part.Vertex(mid))[0] <= tol]
        if len(near) != 2:
            raise ValueError(f"{solid.Label}:{sub} is not where two of its Sheets meet. {HINGE_HINT}")
        return (solid, near[0], near[1], _shared_curve_near(near, mid))
    raise ValueError(HINGE_HINT)
