"""Scripting API for what couples sheets in a Solid: variational space curves and hinges
(App side: headless, macros and the GUI commands).

    curve = varsurf.make_space_curve((sketch, "Edge1"))         # handles at both ends and midway
    ... sheets list (curve, "Edge1") among their curves ...
    solid = varsurf.make_solid(sheets)
    varsurf.make_hinge(solid, sheet_a, sheet_b, (sketch, "Edge2"), angle=180)
    varsurf.move_handle(curve, 1, App.Vector(0, 0, 10)); App.ActiveDocument.recompute()
"""

from __future__ import annotations

from typing import Optional, Sequence

import FreeCAD

from varsurf.api import _is_sheet, _ref, attach_view_provider, run_in_transaction, single_element

TRANSACTION_SPACE_CURVE = "Add VarSurf space curve"
TRANSACTION_HINGE = "Add VarSurf hinge"
SPACE_CURVE_HINT = "Select one edge (of a sketch or a Part object): the curve's start shape."
HINGE_HINT = ("Select two Sheets of a Solid and the edge they share, or the edge of a Solid "
              "where two of its faces meet.")
#: Where a new space curve's handles sit (0..1 along the base edge).
DEFAULT_HANDLE_PARAMETERS = (0.0, 0.5, 1.0)


def _edge_ref(ref):
    return single_element(ref, "Edge", "an edge")


def make_space_curve(base, handle_parameters: Optional[Sequence[float]] = None,
                     handles: Optional[Sequence] = None, spans: Optional[int] = None,
                     name: str = "SpaceCurve"):
    """Add a variational SpaceCurve starting from the edge ``base`` = (object, "EdgeN").

    handle_parameters: where its handles sit, 0..1 along the edge (default both ends and the
    middle); handles: their positions (default: on the edge, so nothing moves until one is moved).
    """
    import Part

    from varsurf.app.space_curve import SpaceCurveFeature

    obj_ref, sub = _edge_ref(base)
    edge = Part.getShape(obj_ref, sub, needSubElement=True)
    params = [float(s) for s in (handle_parameters if handle_parameters is not None else DEFAULT_HANDLE_PARAMETERS)]
    if handles is None:
        a, b = edge.FirstParameter, edge.LastParameter
        handles = [edge.valueAt(a + (b - a) * s) for s in params]
    obj = obj_ref.Document.addObject("Part::FeaturePython", name)
    SpaceCurveFeature(obj)
    obj.Base = (obj_ref, [sub])
    obj.HandleParameters = params
    obj.Handles = [FreeCAD.Vector(*p) for p in handles]
    if spans is not None:
        obj.Spans = int(spans)
    attach_view_provider(obj, "ViewProviderSpaceCurve")
    return obj


def move_handle(curve, index: int, position) -> None:
    """Move handle ``index`` of a SpaceCurve to ``position`` (recompute to see the sheets follow)."""
    handles = list(curve.Handles)
    if not 0 <= int(index) < len(handles):
        raise ValueError(f"{curve.Label} has {len(handles)} handles, no handle {index}")
    handles[int(index)] = FreeCAD.Vector(position)
    curve.Handles = handles


def make_hinge(solid, sheet_a, sheet_b, curve, angle: float = 180.0, name: str = "Hinge"):
    """Add a Hinge to ``solid``: the angle (degrees, (0, 180]; 180 smooth) between ``sheet_a``
    and ``sheet_b`` across ``curve`` = (object, "EdgeN"), an edge both Sheets list."""
    from varsurf.app.hinge import HingeFeature

    for s in (sheet_a, sheet_b):
        if s not in list(solid.Sheets or []):
            raise ValueError(f"{s.Label} is not one of {solid.Label}'s Sheets")
    obj_ref, sub = _edge_ref(curve)
    obj = solid.Document.addObject("App::FeaturePython", name)
    HingeFeature(obj)
    obj.Sheets = [sheet_a, sheet_b]
    obj.Curve = (obj_ref, [sub])
    obj.Angle = float(angle)
    solid.Hinges = list(solid.Hinges or []) + [obj]
    attach_view_provider(obj, "ViewProviderHinge")
    return obj


# --------------------------------------------------------------------------------------------
# from a selection (what the commands run)


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
        if getattr(getattr(obj, "Proxy", None), "Type", None) == "VarSurf::Solid" and \
                all(s in list(obj.Sheets or []) for s in sheets):
            return obj
    raise ValueError(f"{sheets[0].Label} and {sheets[1].Label} are not in one Solid: make a Solid of "
                     "them first (VarSurf Solid)")


def _shared_curve_near(sheets, point):
    """The curve key both sheets list that passes nearest ``point``."""
    import Part

    from varsurf.app.sheet import curve_keys

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
    import Part

    sheets, edges, solid_edges = [], [], []
    for sel in selection_ex or []:
        obj = sel.Object
        subs = [s for s in sel.SubElementNames if s]
        if _is_sheet(obj):
            if obj not in sheets:
                sheets.append(obj)
        elif getattr(getattr(obj, "Proxy", None), "Type", None) == "VarSurf::Solid":
            solid_edges += [(obj, s) for s in subs if s.startswith("Edge")]
        else:
            edges += [(obj, s) for s in subs if s.startswith("Edge")]
    if len(sheets) == 2 and len(edges) == 1 and not solid_edges:
        from varsurf.app.sheet import curve_keys

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


def _report(error, on_error):
    FreeCAD.Console.PrintError(f"VarSurf: {error}\n")
    if on_error is not None:
        on_error(str(error))


def run_space_curve_command(selection_ex, do_command=None, on_error=None):
    """What VarSurf_SpaceCurve does: a SpaceCurve on the selected edge, one undoable step."""
    try:
        obj, sub = space_curve_selection_to_base(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    lines = [
        "import varsurf",
        f"_curve = varsurf.make_space_curve(({_ref(obj)}, {sub!r}))",
        f"App.getDocument({obj.Document.Name!r}).recompute()",
    ]
    return run_in_transaction(obj.Document, TRANSACTION_SPACE_CURVE, lines, do_command)


def run_hinge_command(selection_ex, do_command=None, on_error=None, angle: float = 180.0):
    """What VarSurf_Hinge does: a Hinge between the selected Sheets, one undoable step."""
    try:
        solid, a, b, (obj, sub) = hinge_selection_to_args(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    lines = [
        "import varsurf",
        f"_hinge = varsurf.make_hinge({_ref(solid)}, {_ref(a)}, {_ref(b)}, ({_ref(obj)}, {sub!r}), "
        f"angle={float(angle)!r})",
        f"App.getDocument({solid.Document.Name!r}).recompute()",
    ]
    return run_in_transaction(solid.Document, TRANSACTION_HINGE, lines, do_command,
                              keep=lambda o: getattr(getattr(o, "Proxy", None), "Type", None) == "VarSurf::Hinge")
