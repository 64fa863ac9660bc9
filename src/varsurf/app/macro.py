# SPDX-License-Identifier: LGPL-2.1-or-later
"""The macro lines each command records (and runs, so a recorded macro replays it exactly)."""

from __future__ import annotations

from typing import List

import FreeCAD

from varsurf.app import references
from varsurf.solve import constraints


def ref(obj) -> str:
    """The expression that finds ``obj`` again when a macro replays."""
    return f"App.getDocument({obj.Document.Name!r}).getObject({obj.Name!r})"


def exec_line(line: str, namespace={}):  # noqa: B006 - one namespace, like the GUI console
    if not namespace:
        namespace.update({"App": FreeCAD, "FreeCAD": FreeCAD, "__name__": "__varsurf_macro__"})
    exec(line, namespace)


def sheet_command_lines(base, curves) -> List[str]:
    """The macro lines that create and compute a sheet (what the GUI command records)."""
    base_obj, face_name = references.normalize_base(base)
    curve_links = references.normalize_curves(curves)
    curve_text = ", ".join(f"({ref(o)}, {tuple(names)!r})" for o, names in curve_links)
    doc = base_obj.Document
    return [
        "import varsurf",
        f"_sheet = varsurf.make_sheet(({ref(base_obj)}, {face_name!r}), [{curve_text}])",
        f"App.getDocument({doc.Name!r}).recompute()",
    ]


def solid_command_lines(sheets) -> List[str]:
    """Macro lines that join Sheets into a Solid and recompute."""
    return [
        "import varsurf",
        f"_solid = varsurf.make_solid([{', '.join(ref(s) for s in sheets)}])",
        f"App.getDocument({sheets[0].Document.Name!r}).recompute()",
    ]


def fill_hole_command_lines(part, elements, curves) -> List[str]:
    """Macro lines that fill a hole in (or replace a face of) a part and recompute."""
    curve_text = ", ".join(f"({ref(o)}, {sub!r})" for o, sub in curves)
    return [
        "import varsurf",
        f"_fill = varsurf.make_fill_hole({ref(part)}, {list(elements)!r}, curves=[{curve_text}])",
        f"App.getDocument({part.Document.Name!r}).recompute()",
    ]


def subd_surface_command_lines(cage, target) -> List[str]:
    """Macro lines that add a SubdSurface of a cage (and a target to capture) and recompute."""
    target_text = f", target={ref(target)}" if target is not None else ""
    return [
        "import varsurf",
        f"_subd = varsurf.make_subd_surface({ref(cage)}, levels=3{target_text})",
        f"App.getDocument({cage.Document.Name!r}).recompute()",
    ]


def subd_brep_command_lines(subd) -> List[str]:
    """Macro lines that add a SubdBRep of a SubdSurface and recompute."""
    return [
        "import varsurf",
        f"_brep = varsurf.make_subd_brep({ref(subd)})",
        f"App.getDocument({subd.Document.Name!r}).recompute()",
    ]


def triangular_command_lines(source) -> List[str]:
    """Macro lines that add a TriangularSurface over a mesh and recompute."""
    return [
        "import varsurf",
        f"_surface = varsurf.make_triangular_surface({ref(source)})",
        f"App.getDocument({source.Document.Name!r}).recompute()",
    ]


def constraint_command_lines(kind: str, sheet, args) -> List[str]:
    """Macro lines that add a constraint with editable defaults and recompute."""
    parts = [ref(sheet), repr(kind)]
    for key in ("location", "curve", "reference"):
        if key in args:
            obj, sub = args[key]
            parts.append(f"{key}=({ref(obj)}, {sub!r})")
    if "region_loop" in args:
        obj, subs = args["region_loop"]
        parts.append(f"region_loop=({ref(obj)}, {list(subs)!r})")
    if kind in constraints.POINT_KINDS and "location" not in args:
        parts.append("uv=(0.5, 0.5)")
    if kind in ("PointInPlane", "PointOnLine", "PointAttractor", "PlaneAttractor", "LineAttractor", "Repeller"):
        # planes, lines and attracting points start through the sheet's middle
        centre = _sheet_centre(sheet)
        parts.append(f"origin=({centre[0]:.6g}, {centre[1]:.6g}, {centre[2]:.6g})")
    if (kind in constraints.REGION_KINDS or kind == "RegionMap") and "region_loop" not in args:
        parts.append("region=(0.25, 0.75, 0.25, 0.75)")  # the sheet's middle
    if kind == "Curvature":
        # The sheet's own normal and curvatures at the point: nothing changes until they are edited.
        normal, kappa = _curvature_now(sheet, args)
        parts.append(f"vector=({normal[0]:.6g}, {normal[1]:.6g}, {normal[2]:.6g})")
        parts.append(f"curvature=({kappa[0]:.6g}, {kappa[1]:.6g})")
    return [
        "import varsurf",
        f"_constraint = varsurf.make_constraint({', '.join(parts)})",
        f"App.getDocument({sheet.Document.Name!r}).recompute()",
    ]


def _curvature_now(sheet, args):
    """The sheet's unit normal and its normal curvatures along u and v (1/mm) at the constraint's
    place (the location's projection, else the middle); (0, 0, 1) and (0, 0) without a face."""
    face = sheet.Shape.Faces[0] if not sheet.Shape.isNull() and sheet.Shape.Faces else None
    if face is None:
        return (0.0, 0.0, 1.0), (0.0, 0.0)
    surface = face.Surface
    u0, u1, v0, v1 = surface.bounds()
    u, v = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    if "location" in args:
        obj, sub = args["location"]
        point = obj.getSubObject(sub).Vertexes[0].Point
        u, v = surface.parameter(point)
    du, dv = surface.getDN(u, v, 1, 0), surface.getDN(u, v, 0, 1)
    normal = du.cross(dv)
    if normal.Length < 1e-12 or du.Length < 1e-12 or dv.Length < 1e-12:
        return (0.0, 0.0, 1.0), (0.0, 0.0)
    normal.normalize()
    kappa = (normal.dot(surface.getDN(u, v, 2, 0)) / du.Length ** 2,
             normal.dot(surface.getDN(u, v, 0, 2)) / dv.Length ** 2)
    return (normal.x, normal.y, normal.z), kappa


def _sheet_centre(sheet):
    face = sheet.Shape.Faces[0] if not sheet.Shape.isNull() and sheet.Shape.Faces else None
    if face is None:
        return (0.0, 0.0, 0.0)
    u0, u1, v0, v1 = face.ParameterRange
    p = face.Surface.value(0.5 * (u0 + u1), 0.5 * (v0 + v1))
    return (p.x, p.y, p.z)


def space_curve_command_lines(obj, sub) -> List[str]:
    """Macro lines that add a SpaceCurve on an edge and recompute."""
    return [
        "import varsurf",
        f"_curve = varsurf.make_space_curve(({ref(obj)}, {sub!r}))",
        f"App.getDocument({obj.Document.Name!r}).recompute()",
    ]


def pde_surface_command_lines(args) -> List[str]:
    """Macro lines that add a PdeSurface (make_pde_surface's keyword arguments of edge links) and
    recompute."""
    doc = args["u0"][0].Document
    given = ", ".join(f"{key}=({ref(obj)}, {sub!r})" for key, (obj, sub) in args.items())
    return [
        "import varsurf",
        f"_pde = varsurf.make_pde_surface({given})",
        f"App.getDocument({doc.Name!r}).recompute()",
    ]


def hinge_command_lines(solid, a, b, obj, sub, angle) -> List[str]:
    """Macro lines that add a Hinge to a Solid and recompute."""
    return [
        "import varsurf",
        f"_hinge = varsurf.make_hinge({ref(solid)}, {ref(a)}, {ref(b)}, ({ref(obj)}, {sub!r}), "
        f"angle={float(angle)!r})",
        f"App.getDocument({solid.Document.Name!r}).recompute()",
    ]


def tube_command_lines(sections, curves) -> List[str]:
    """Macro lines that add a tube through closed sections and curves, and recompute."""
    listed = ", ".join(f"({ref(obj)}, {sub!r})" for obj, sub in curves)
    return [
        "import varsurf",
        f"_tube = varsurf.make_tube([{', '.join(ref(obj) for obj in sections)}], [{listed}])",
        f"App.getDocument({sections[0].Document.Name!r}).recompute()",
    ]
