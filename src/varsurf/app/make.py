# SPDX-License-Identifier: LGPL-2.1-or-later
"""The make-functions of the scripting API (headless, in macros and behind the GUI commands):
each adds one VarSurf object to a document, computed at the next recompute.

    import varsurf
    sheet = varsurf.make_sheet((surface, "Face1"), [(sketch, ("Edge1", "Edge2"))], bend=1.0)
    App.ActiveDocument.recompute()
    print(sheet.MaxDeviations)
    varsurf.export_step([sheet], "/tmp/sheet.step")
"""

from __future__ import annotations

import os
from typing import Iterable, Optional

import FreeCAD
import Part

from varsurf.app import preferences, references
from varsurf.app.constraint import ConstraintFeature
from varsurf.app.fill_hole import FillHoleFeature
from varsurf.app.sheet import SheetFeature, apply_settings
from varsurf.app.solid import SolidFeature
from varsurf.solve import constraints, settings
from varsurf.solve.native import native

from varsurf.app.view_link import attach as attach_view_provider


def _model_size(base, curves) -> float:
    """The diagonal (mm) of what a new sheet is made from: its base face, else (or while the base
    has no shape yet: a tube's skin is built on the first recompute) its curves."""
    boxes = []
    try:
        if base is not None:
            obj, sub = references.normalize_base(base)
            boxes.append(Part.getShape(obj, sub, needSubElement=True).BoundBox)
        if not any(b.isValid() for b in boxes):
            for obj, subs in references.normalize_curves(curves):
                for sub in subs:
                    boxes.append(Part.getShape(obj, sub, needSubElement=True).BoundBox)
    except Exception:  # a broken link: the Sheet reports it when it recomputes
        return 0.0
    boxes = [b for b in boxes if b.isValid()]
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
    energy: str = "ThinPlate",
    pde_a: float = 1.0,
    pde_regions: Iterable = (),
    pde_blend: float = 0.0,
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
    solve_mode: one of settings.SOLVE_MODES.
    energy: "ThinPlate" (stretch, bend) or "PDE": Du & Qin's (d2/du2 + a^2 d2/dv2)^2 P = 0 with
        a = pde_a, painted on pde_regions ((a, u0, u1, v0, v1) each, u and v normalized to 0..1)
        and blended across their borders over pde_blend (a fraction of the domain; 0: sharp).
    Omitted values come from the VarSurf preferences (built in: thin plate 0 and 1, 16 to 64
    spans, degree 3, Automatic); without a stored tolerance, 1e-4 of the base's (or curves')
    size, rounded down to 1, 2 or 5 x 10^k (0.01 mm for a 100 mm part).
    """
    given = dict(stretch=stretch, bend=bend, tolerance=tolerance, min_spans=min_spans,
                 max_spans=max_spans, degree=degree, solve_mode=solve_mode)
    values = {k: (v if v is not None else preferences.sheet_defaults()[k]) for k, v in given.items()}
    if tolerance is None and preferences.tolerance_is_automatic():
        values["tolerance"] = settings.tolerance_for_size(_model_size(base, curves))
    if values["solve_mode"] not in settings.SOLVE_MODES:
        raise ValueError(f"solve_mode must be one of {', '.join(settings.SOLVE_MODES)} (got {values['solve_mode']!r})")
    chosen = settings.SheetSettings(fix_boundary=bool(fix_boundary), energy=str(energy), pde_a=float(pde_a),
                                    pde_regions=tuple(tuple(float(x) for x in r) for r in pde_regions),
                                    pde_blend=float(pde_blend), **values)

    curve_links = references.normalize_curves(curves)
    if base is not None:
        base_obj, face_name = references.normalize_base(base)
    elif not curve_links:
        raise ValueError("a sheet without a base face needs curves: give a base face, or the curves it must pass "
                         "through")
    if doc is None:
        doc = (base_obj if base is not None else curve_links[0][0]).Document
    obj = doc.addObject("Part::FeaturePython", name)
    SheetFeature(obj)
    if base is not None:
        obj.Base = (base_obj, face_name)
    obj.Curves = [(o, names) for o, names in curve_links]
    apply_settings(obj, chosen)
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
    curvature=None,
    curvature_directions: str = "U and V",
):
    """Add a Constraint of ``kind`` (see ``varsurf.solve.constraints.KINDS``) to ``sheet``.

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
    curvature, curvature_directions: Curvature: (kappa_u, kappa_v) in 1/mm (positive: the sheet bends
        toward the side `vector` points to) and which of them are asked ("U and V", "U" or "V").
    """
    if kind not in constraints.KINDS:
        raise ValueError(f"unknown constraint kind {kind!r}: give one of {', '.join(constraints.KINDS)}")
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
    if curvature is not None:
        obj.CurvatureU, obj.CurvatureV = float(curvature[0]), float(curvature[1])
    obj.CurvatureDirections = curvature_directions
    sheet.Constraints = list(sheet.Constraints) + [obj]
    attach_view_provider(obj, "ViewProviderConstraint")
    return obj


def make_solid(sheets, tolerance=None, name: str = "Solid"):
    """Add a VarSurf Solid joining ``sheets`` along the curves they share (computed at the next
    recompute): each sheet is trimmed to the loop of its join curves and the faces are sewn into
    a shell, a solid when they close. tolerance: sewing tolerance (mm)."""
    sheets = list(sheets)
    if not sheets:
        raise ValueError("a Solid needs Sheets: give two or more Sheets that share their join curves")
    doc = sheets[0].Document
    obj = doc.addObject("Part::FeaturePython", name)
    SolidFeature(obj)
    obj.Sheets = sheets
    if tolerance is not None:
        obj.Tolerance = float(tolerance)
    attach_view_provider(obj, "ViewProviderSolid")
    return obj


def make_fill_hole(part, elements, curves=(), continuity="G1", tolerance=None, name: str = "FillHole"):
    """Add a VarSurf FillHole: ``part`` (a document object) with the face ``elements`` names
    ("FaceN") replaced by a sheet, or the hole its free edges ("EdgeN", ...) bound filled by one,
    G1 (or G0) to the faces around; ``curves``: (object, "EdgeN") links or objects inside the hole
    that the sheet contains. Its Shape is the whole new part; the part is hidden."""
    elements = [elements] if isinstance(elements, str) else list(elements)
    if not elements:
        raise ValueError("a FillHole needs the face to replace or the free edges of the hole: give \"FaceN\" or "
                         "the hole's \"EdgeN\" names")
    doc = part.Document
    obj = doc.addObject("Part::FeaturePython", name)
    FillHoleFeature(obj)
    obj.Base = (part, elements)
    obj.Curves = [c if isinstance(c, tuple) else (c, "") for c in curves]
    obj.Continuity = continuity
    if tolerance is not None:
        obj.Tolerance = float(tolerance)
    attach_view_provider(obj, "ViewProviderFillHole")
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
    if not isinstance(objects, (list, tuple)):
        objects = [objects]
    found = []
    for item in objects:
        shape = item if isinstance(item, Part.Shape) else references.shape_of(item)
        if shape.isNull():
            raise ValueError("cannot export an empty shape: recompute the objects first, or leave out those in error")
        found.append(shape)
    if not found:
        raise ValueError("nothing to export: give the objects or shapes to write")
    shape = found[0] if len(found) == 1 else Part.makeCompound(found)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    native().write_step(shape.exportBrepToString(), path)
    return path
