"""Scripting API of the VarSurf workbench (App side: works headless, in macros and in the GUI).

    import varsurf
    sheet = varsurf.make_sheet((surface, "Face1"), [(sketch, ("Edge1", "Edge2"))], bend=1.0)
    App.ActiveDocument.recompute()
    print(sheet.MaxDeviations)
    varsurf.export_step([sheet], "/tmp/sheet.step")
"""

from __future__ import annotations

import os
from typing import Iterable, List, Optional, Sequence, Tuple

import FreeCAD

from varsurf import model

#: Name of the undo transaction the GUI command and the task panel open.
TRANSACTION_CREATE = "Create VarSurf sheet"


# --------------------------------------------------------------------------------------------
# references


def _as_names(subs) -> Tuple[str, ...]:
    if subs is None:
        return ()
    if isinstance(subs, str):
        return (subs,) if subs else ()
    return tuple(str(s) for s in subs if s)


def _shape_of(obj):
    shape = getattr(obj, "Shape", None)
    if shape is None or shape.isNull():
        raise ValueError(f"{obj.Label} has no shape")
    return shape


def single_element(ref, kind: str, what: str):
    """(object, "KindN") of a reference naming exactly one element of ``kind`` ("Face", "Edge");
    ValueError naming ``what`` otherwise."""
    if not isinstance(ref, (tuple, list)) or len(ref) != 2:
        raise ValueError(f'{what} must be (object, "{kind}N")')
    obj, subs = ref
    names = _as_names(subs)
    if len(names) != 1 or not names[0].startswith(kind):
        raise ValueError(f'{what} must name exactly one {kind.lower()} of {obj.Label}, e.g. (obj, "{kind}1")')
    return obj, names[0]


def _normalize_base(base):
    return single_element(base, "Face", "base")


def _normalize_curves(curves) -> List[Tuple[object, Tuple[str, ...]]]:
    """[(obj, ("Edge1", ...)), ...], merged per object, in order; a bare object means all its edges."""
    merged: List[Tuple[object, List[str]]] = []
    for item in curves or []:
        if isinstance(item, (tuple, list)):
            if len(item) != 2:
                raise ValueError('each curve must be (object, "EdgeN") or (object, ("EdgeN", ...))')
            obj, subs = item
            names = _as_names(subs)
        else:
            obj, names = item, ()
        if not names:
            names = tuple(f"Edge{i + 1}" for i in range(len(_shape_of(obj).Edges)))
        for name in names:
            if not name.startswith("Edge"):
                raise ValueError(f"{obj.Label}:{name} is not an edge")
        for entry in merged:
            if entry[0] is obj:
                entry[1].extend(n for n in names if n not in entry[1])
                break
        else:
            merged.append((obj, list(dict.fromkeys(names))))
    return [(obj, tuple(names)) for obj, names in merged]


# --------------------------------------------------------------------------------------------
# creation


def attach_view_provider(obj, class_name: str):
    """In the GUI, give ``obj`` its view provider (``varsurf.gui.view_providers.<class_name>``)
    and let it set itself up (e.g. hide the inputs the object consumes); headless, nothing."""
    if not FreeCAD.GuiUp:
        return
    from varsurf.gui import view_providers

    getattr(view_providers, class_name)(obj.ViewObject)
    on_created = getattr(obj.ViewObject.Proxy, "on_created", None)
    if on_created is not None:
        on_created(obj.ViewObject)


def _model_size(base, curves) -> float:
    """The diagonal (mm) of what a new sheet is made from: its base face, else its curves."""
    import Part

    boxes = []
    try:
        if base is not None:
            obj, sub = _normalize_base(base)
            boxes.append(Part.getShape(obj, sub, needSubElement=True).BoundBox)
        else:
            for obj, subs in _normalize_curves(curves):
                for sub in subs:
                    boxes.append(Part.getShape(obj, sub, needSubElement=True).BoundBox)
    except Exception:  # a broken link: the Sheet reports it when it recomputes
        return 0.0
    if not boxes:
        return 0.0
    box = boxes[0]
    for other in boxes[1:]:
        box.add(other)
    return box.DiagonalLength


def make_sheet(
    base,
    curves: Iterable = (),
    stretch: Optional[float] = None,
    bend: Optional[float] = None,
    fix_boundary: bool = True,
    tolerance: Optional[float] = None,
    min_spans: Optional[int] = None,
    max_spans: Optional[int] = None,
    doc=None,
    name: str = "Sheet",
    degree: Optional[int] = None,
    solve_mode: Optional[str] = None,
):
    """Add a VarSurf Sheet to the document (it is computed at the next recompute).

    base: (object, "FaceN"), the base surface; its boundary is kept when fix_boundary is True.
        None: the sheet starts from the best-fit plane of the curves, with a free boundary.
    curves: [(object, "EdgeN") or (object, ("EdgeN", ...)) or object (all its edges), ...], the
        curves the sheet must pass through; they must lie over the base face.
    stretch, bend: thin-plate weights alpha and beta (default: pure thin plate, 0 and 1).
    tolerance: distance (mm) at which a curve counts as met.
    min_spans, max_spans: spans per direction the base face is refined to, and the limit of the
        automatic refinement used when the curves cannot be met within the tolerance.
    degree: the sheet's smallest degree in u and v (the base is elevated to it).
    solve_mode: one of model.SOLVE_MODES.
    Omitted values come from the VarSurf preferences (built in: thin plate 0 and 1, 16 to 64
    spans, degree 3, Automatic); without a stored tolerance, 1e-4 of the base's (or curves')
    size, rounded down to 1, 2 or 5 x 10^k (0.01 mm for a 100 mm part).
    """
    from varsurf.app.sheet import SheetFeature
    from varsurf.preferences import sheet_defaults

    from varsurf import preferences

    given = dict(stretch=stretch, bend=bend, tolerance=tolerance, min_spans=min_spans,
                 max_spans=max_spans, degree=degree, solve_mode=solve_mode)
    values = {k: (v if v is not None else sheet_defaults()[k]) for k, v in given.items()}
    if tolerance is None and not preferences.is_set("Tolerance"):
        values["tolerance"] = model.tolerance_for_size(_model_size(base, curves))
    if values["solve_mode"] not in model.SOLVE_MODES:
        raise ValueError(f"solve_mode must be one of {', '.join(model.SOLVE_MODES)} (got {values['solve_mode']!r})")

    curve_links = _normalize_curves(curves)
    if base is not None:
        base_obj, face_name = _normalize_base(base)
    elif not curve_links:
        raise ValueError("a sheet without a base face needs curves")
    if doc is None:
        doc = (base_obj if base is not None else curve_links[0][0]).Document
    obj = doc.addObject("Part::FeaturePython", name)
    SheetFeature(obj)
    if base is not None:
        obj.Base = (base_obj, face_name)
    obj.Curves = [(o, names) for o, names in curve_links]
    obj.Stretch = float(values["stretch"])
    obj.Bend = float(values["bend"])
    obj.FixBoundary = bool(fix_boundary)
    obj.Tolerance = float(values["tolerance"])
    obj.MinSpans = int(values["min_spans"])
    obj.MaxSpans = int(values["max_spans"])
    obj.Degree = int(values["degree"])
    obj.SolveMode = values["solve_mode"]
    attach_view_provider(obj, "ViewProviderSheet")
    return obj


def make_constraint(
    sheet,
    kind: str,
    location=None,
    uv=None,
    vector=None,
    origin=None,
    region=None,
    weight: float = 1.0,
    name: str = "Constraint",
    curve=None,
    reference=None,
    angle: float = 0.0,
    region_loop=None,
):
    """Add a Constraint of ``kind`` (see ``varsurf.constraints.KINDS``) to ``sheet``.

    location: (object, "VertexN"), whose projection onto the base gives the (u, v) (and, for a
        Point, the target); or uv=(u, v), normalized to [0, 1].
    vector: tangent, normal, plane normal, line or director direction (FreeCAD.Vector or tuple).
    origin: plane, line or attractor point; for a Point, the target instead of the location.
    region: normalized (u0, u1, v0, v1) of an operator or a frozen region.
    weight: the constraint's weight or the operator's strength.
    curve, reference, angle: Ribbon and G1: (object, "EdgeN"), (object, "FaceN") and degrees; a
        Ribbon's reference may also be a second edge, or None for the base's own normal.
        CurveAttractor: curve is the edge pulled onto; SurfaceAttractor: reference is the face.
    region_loop: (object, ["Edge1", ...]) or (object, []) for all its edges: a closed loop whose
        projection onto the base is the region (instead of the rectangle `region`).
    """
    from varsurf import constraints
    from varsurf.app.constraint import ConstraintFeature

    if kind not in constraints.KINDS:
        raise ValueError(f"unknown constraint kind {kind!r}: one of {', '.join(constraints.KINDS)}")
    doc = sheet.Document
    obj = doc.addObject("App::FeaturePython", name)
    ConstraintFeature(obj)
    obj.Kind = kind
    if location is not None:
        link, sub = location
        obj.Location = (link, sub)
    if uv is not None:
        obj.U, obj.V = float(uv[0]), float(uv[1])
    if vector is not None:
        obj.Vector = FreeCAD.Vector(*vector)
    if origin is not None:
        obj.Origin = FreeCAD.Vector(*origin)
        obj.UseOrigin = location is not None or kind == "Point"
    if region is not None:
        obj.RegionU0, obj.RegionU1, obj.RegionV0, obj.RegionV1 = (float(x) for x in region)
    obj.Weight = float(weight)
    if curve is not None:
        obj.Curve = (curve[0], curve[1])
    if reference is not None:
        obj.Reference = (reference[0], reference[1])
    obj.Angle = float(angle)
    if region_loop is not None:
        link, subs = region_loop
        obj.RegionLoop = (link, list(subs) if not isinstance(subs, str) else [subs])
    sheet.Constraints = list(sheet.Constraints) + [obj]
    attach_view_provider(obj, "ViewProviderConstraint")
    return obj


def make_solid(sheets, tolerance=None, name: str = "Solid"):
    """Add a VarSurf Solid joining ``sheets`` along the curves they share (computed at the next
    recompute): each sheet is trimmed to the loop of its join curves and the faces are sewn into
    a shell, a solid when they close. tolerance: sewing tolerance (mm)."""
    from varsurf.app.solid import SolidFeature

    sheets = list(sheets)
    if not sheets:
        raise ValueError("a Solid needs Sheets")
    doc = sheets[0].Document
    obj = doc.addObject("Part::FeaturePython", name)
    SolidFeature(obj)
    obj.Sheets = sheets
    if tolerance is not None:
        obj.Tolerance = float(tolerance)
    attach_view_provider(obj, "ViewProviderSolid")
    return obj


def install_rest_shape(sheet):
    """Make the Sheet's current result its rest shape: later edits keep this shape's detail."""
    if sheet.Shape.isNull() or len(sheet.Shape.Faces) != 1:
        raise ValueError(f"{sheet.Label} has no result to install: recompute it first")
    sheet.InstalledRest = sheet.Shape.Faces[0].copy()
    sheet.RestShape = "Installed"
    return sheet


def melt(sheet):
    """Drop the Sheet's rest shape: back to pure fairness (the thin-plate energy of the shape)."""
    sheet.RestShape = "None"
    return sheet


def export_step(objects, path: str) -> str:
    """Write the shapes of ``objects`` (document objects or Part shapes) to an AP214 STEP file.

    Faces keep their exact B-spline surfaces and their pcurves. Returns the path.
    """
    import Part

    if not isinstance(objects, (list, tuple)):
        objects = [objects]
    shapes = []
    for item in objects:
        shape = item if isinstance(item, Part.Shape) else _shape_of(item)
        if shape.isNull():
            raise ValueError("cannot export an empty shape")
        shapes.append(shape)
    if not shapes:
        raise ValueError("nothing to export")
    shape = shapes[0] if len(shapes) == 1 else Part.makeCompound(shapes)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    model.native().write_step(shape.exportBrepToString(), path)
    return path


# --------------------------------------------------------------------------------------------
# selection (shared by the GUI command and the tests)

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
    curves = _normalize_curves([(o, n) for o, n in edges])
    return faces[0], curves


def selection_problem(selection_ex) -> Optional[str]:
    """None when the selection makes a sheet, otherwise why not."""
    try:
        selection_to_sheet_args(selection_ex)
    except ValueError as error:
        return str(error)
    return None


def _ref(obj) -> str:
    return f"App.getDocument({obj.Document.Name!r}).getObject({obj.Name!r})"


def sheet_command_lines(base, curves) -> List[str]:
    """The macro lines that create and compute a sheet (what the GUI command records)."""
    base_obj, face_name = _normalize_base(base)
    curve_links = _normalize_curves(curves)
    curve_text = ", ".join(f"({_ref(o)}, {tuple(names)!r})" for o, names in curve_links)
    doc = base_obj.Document
    return [
        "import varsurf",
        f"_sheet = varsurf.make_sheet(({_ref(base_obj)}, {face_name!r}), [{curve_text}])",
        f"App.getDocument({doc.Name!r}).recompute()",
    ]


def _exec_line(line: str, namespace={}):  # noqa: B006 - one namespace, like the GUI console
    if not namespace:
        namespace.update({"App": FreeCAD, "FreeCAD": FreeCAD, "__name__": "__varsurf_macro__"})
    exec(line, namespace)


def run_in_transaction(doc, name: str, lines, do_command=None, keep=lambda obj: True):
    """Run macro lines (through do_command, e.g. FreeCADGui.doCommand so they are recorded, or
    exec()) as one undoable transaction; a failing line aborts it. Returns the last object the
    lines created that ``keep`` accepts, or None."""
    run = do_command or _exec_line
    before = set(o.Name for o in doc.Objects)
    doc.openTransaction(name)
    try:
        for line in lines:
            run(line)
    except Exception:
        doc.abortTransaction()
        raise
    doc.commitTransaction()
    created = [o for o in doc.Objects if o.Name not in before and keep(o)]
    return created[-1] if created else None


def create_sheet_from_selection(selection_ex, do_command=None):
    """Validate the selection and create a sheet through macro lines, in one undo transaction.

    do_command runs one line (FreeCADGui.doCommand in the GUI, so the lines are recorded in
    macros); without it the lines are exec()'d. Raises ValueError for an unusable selection,
    creating nothing. Returns the new Sheet object.
    """
    base, curves = selection_to_sheet_args(selection_ex)
    return run_in_transaction(base[0].Document, TRANSACTION_CREATE, sheet_command_lines(base, curves),
                              do_command, keep=_is_sheet)


def run_sheet_command(selection_ex, do_command=None, on_error=None):
    """What the VarSurf_Sheet command does when activated (also usable headless).

    A usable selection creates the sheet through recorded macro lines in one transaction; an
    unusable one is reported in the report view (and through ``on_error``, e.g. a dialog) and
    creates nothing. Returns the new Sheet or None.
    """
    try:
        return create_sheet_from_selection(selection_ex, do_command=do_command)
    except ValueError as error:
        message = str(error)
        FreeCAD.Console.PrintError(f"VarSurf: {message}\n")
        if on_error is not None:
            on_error(message)
        return None


TRANSACTION_SOLID = "Add VarSurf solid"
SOLID_HINT = "Select the Sheets to join (two or more that share curves)."


def solid_selection_to_sheets(selection_ex) -> List:
    """The Sheets of a selection (whole objects or any of their elements), or ValueError."""
    sheets = []
    for sel in selection_ex or []:
        obj = sel.Object
        if not _is_sheet(obj):
            raise ValueError(f"{obj.Label} is not a Sheet. {SOLID_HINT}")
        if obj not in sheets:
            sheets.append(obj)
    if len(sheets) < 2:
        raise ValueError(f"{len(sheets)} Sheets selected: select two or more. {SOLID_HINT}")
    return sheets


def run_solid_command(selection_ex, do_command=None, on_error=None):
    """What the VarSurf_Solid command does (also usable headless): join the selected Sheets
    through recorded macro lines in one transaction. Returns the new Solid or None."""
    try:
        sheets = solid_selection_to_sheets(selection_ex)
    except ValueError as error:
        FreeCAD.Console.PrintError(f"VarSurf: {error}\n")
        if on_error is not None:
            on_error(str(error))
        return None
    doc = sheets[0].Document
    lines = [
        "import varsurf",
        f"_solid = varsurf.make_solid([{', '.join(_ref(s) for s in sheets)}])",
        f"App.getDocument({doc.Name!r}).recompute()",
    ]
    return run_in_transaction(doc, TRANSACTION_SOLID, lines, do_command)


def _is_sheet(obj) -> bool:
    proxy = getattr(obj, "Proxy", None)
    return getattr(proxy, "Type", None) == "VarSurf::Sheet"


def is_sheet(obj) -> bool:
    """True for VarSurf Sheet objects."""
    return _is_sheet(obj)


# --------------------------------------------------------------------------------------------
# constraints from a selection (what the constraint commands run)

TRANSACTION_CONSTRAINT = "Add VarSurf constraint"
#: What to select for each kind, besides the Sheet.
SELECTION_HINTS = {
    "Point": "Select a Sheet and the vertex it must pass through.",
    "point": "Select a Sheet and, optionally, a vertex for the point's position.",
    "region": "Select a Sheet and, optionally, closed edges (e.g. a sketch) bounding the region.",
    "SurfaceAttractor": "Select a Sheet, the face to pull onto and, optionally, closed edges bounding the region.",
    "CurveAttractor": "Select a Sheet and the edge to pull onto.",
    "Ribbon": "Select a Sheet, the edge along which its normal is set and, optionally, a face or a second edge to follow.",
    "G1": "Select a Sheet, the edge along which it joins, and the face it must follow there.",
    "G0": "Select a Sheet and the edge it must contain (e.g. the edge of the neighbouring face).",
}
#: Kinds that need a picked vertex from the GUI (their target is a location).
VERTEX_KINDS = ("Point",)


def selection_hint(kind: str) -> str:
    from varsurf import constraints

    if kind in SELECTION_HINTS:
        return SELECTION_HINTS[kind]
    return SELECTION_HINTS["point" if kind in constraints.POINT_KINDS else "region"]


def _split_selection(selection_ex, hint):
    """(sheets, [(element type, (object, sub)), ...]) of a selection, in picking order."""
    sheets, picks = [], []
    for sel in selection_ex or []:
        obj = sel.Object
        subs = [s.split(".")[-1] for s in (getattr(sel, "SubElementNames", None) or ()) if s]
        if _is_sheet(obj):
            if obj not in sheets:
                sheets.append(obj)
            continue
        if not subs and _is_point_object(obj):
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


def _is_point_object(obj) -> bool:
    shape = getattr(obj, "Shape", None)
    return shape is not None and not shape.isNull() and len(shape.Vertexes) == 1 and not shape.Edges


def constraint_selection_to_args(kind: str, selection_ex: Sequence):
    """(sheet, keyword arguments for make_constraint) from a selection, or ValueError.

    Exactly one Sheet (the whole object or any of its elements), plus per kind: a vertex (Point:
    required; other point kinds: optional); an edge to follow and an optional face or second
    edge (Ribbon), an edge and a face (G1); an edge (CurveAttractor); a face (SurfaceAttractor);
    and for region kinds optionally closed edges of one object bounding the region.
    """
    from varsurf import constraints

    if kind not in constraints.KINDS:
        raise ValueError(f"unknown constraint kind {kind!r}")
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
    if kind in constraints.CURVE_KINDS or kind in ("CurveAttractor", "G0"):
        edges, faces = of["Edge"], of["Face"]
        if kind == "G1" and (len(edges) != 1 or len(faces) != 1):
            raise ValueError(f"a G1 needs exactly one edge and one face. {hint}")
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


def constraint_command_lines(kind: str, sheet, args) -> List[str]:
    """Macro lines that add a constraint with editable defaults and recompute."""
    from varsurf import constraints

    parts = [_ref(sheet), repr(kind)]
    for key in ("location", "curve", "reference"):
        if key in args:
            obj, sub = args[key]
            parts.append(f"{key}=({_ref(obj)}, {sub!r})")
    if "region_loop" in args:
        obj, subs = args["region_loop"]
        parts.append(f"region_loop=({_ref(obj)}, {list(subs)!r})")
    if kind in constraints.POINT_KINDS and "location" not in args:
        parts.append("uv=(0.5, 0.5)")
    if kind in ("PointInPlane", "PointOnLine", "PointAttractor", "PlaneAttractor", "LineAttractor", "Repeller"):
        # planes, lines and attracting points start through the sheet's middle
        centre = _sheet_centre(sheet)
        parts.append(f"origin=({centre[0]:.6g}, {centre[1]:.6g}, {centre[2]:.6g})")
    if kind in constraints.REGION_KINDS and "region_loop" not in args:
        parts.append("region=(0.25, 0.75, 0.25, 0.75)")  # the sheet's middle
    return [
        "import varsurf",
        f"_constraint = varsurf.make_constraint({', '.join(parts)})",
        f"App.getDocument({sheet.Document.Name!r}).recompute()",
    ]


def _sheet_centre(sheet):
    face = sheet.Shape.Faces[0] if not sheet.Shape.isNull() and sheet.Shape.Faces else None
    if face is None:
        return (0.0, 0.0, 0.0)
    u0, u1, v0, v1 = face.ParameterRange
    p = face.Surface.value(0.5 * (u0 + u1), 0.5 * (v0 + v1))
    return (p.x, p.y, p.z)


def run_constraint_command(kind: str, selection_ex, do_command=None, on_error=None):
    """What a constraint command does when activated (also usable headless): validate the
    selection, then add the constraint through recorded macro lines in one transaction. An
    unusable selection is reported and creates nothing. Returns the new Constraint or None."""
    try:
        sheet, args = constraint_selection_to_args(kind, selection_ex)
    except ValueError as error:
        FreeCAD.Console.PrintError(f"VarSurf: {error}\n")
        if on_error is not None:
            on_error(str(error))
        return None
    return run_in_transaction(sheet.Document, TRANSACTION_CONSTRAINT,
                              constraint_command_lines(kind, sheet, args), do_command)
