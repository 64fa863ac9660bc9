# SPDX-License-Identifier: LGPL-2.1-or-later
"""The SubdSurface feature: a multiresolution Catmull-Clark surface (Boier-Martin, Ronfard &
Bernardini) of a cage (a Mesh, a Part shape's faces, a VarSurf sheet's pole net), with the detail
of a Target captured level by level and pins that move vertices of any level with a region of
influence set by the level they are propagated to; its Mesh is the limit surface. Parametric:
editing the cage, the target or a pin recomputes it. The computation is
varsurf.solve.multiresolution."""

from __future__ import annotations

import math

import FreeCAD

from varsurf.app import subdivision
from varsurf.app.feature import FeatureProxy, mark_failed, value
from varsurf.app.references import as_names, normalize_curves, shape_of
from varsurf.app.view_link import attach as attach_view_provider
from varsurf.solve import errors, multiresolution
from varsurf.solve.shapes import shape_from_brep

TYPE = "VarSurf::SubdSurface"

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Source", "App::PropertyLink", "SubdSurface", "The cage: a Mesh, a shape whose faces are the control mesh (a box, a cage of planar faces), or a VarSurf sheet's pole net", False),
    ("Target", "App::PropertyLink", "SubdSurface", "Optional: a Mesh (a scan) or a shape whose detail is captured onto the levels", False),
    ("TargetTolerance", "App::PropertyLength", "SubdSurface", "How finely a shape Target is tessellated for the capture (mm; 0: 5e-4 of its size)", False),
    ("Levels", "App::PropertyIntegerConstraint", "SubdSurface", "Catmull-Clark refinements of the cage: each makes four faces of one", False),
    ("PinVertices", "App::PropertyIntegerList", "Pins", "Per pin: the vertex it moves, numbered at its level", False),
    ("PinLevels", "App::PropertyIntegerList", "Pins", "Per pin: the level of its vertex (0: the cage)", False),
    ("PinInfluence", "App::PropertyIntegerList", "Pins", "Per pin: the level it is propagated to, its region of influence: 0 moves the whole shape, finer levels a smaller patch", False),
    ("PinTargets", "App::PropertyVectorList", "Pins", "Per pin: where its vertex goes", False),
    ("NormalVertices", "App::PropertyIntegerList", "Normals", "Per normal: the vertex whose normal is prescribed, numbered at its level", False),
    ("NormalLevels", "App::PropertyIntegerList", "Normals", "Per normal: the level of its vertex (0: the cage)", False),
    ("NormalInfluence", "App::PropertyIntegerList", "Normals", "Per normal: the level it is propagated to, its region of influence", False),
    ("NormalDirections", "App::PropertyVectorList", "Normals", "Per normal: the direction the surface's normal takes there (either sign)", False),
    ("Curves", "App::PropertyLinkSubList", "Curves", "Edges lying on the surface (sketch edges, a hole's boundary): the vertices of CurveLevel along each are moved rigidly by CurveMotion", False),
    ("CurveMotion", "App::PropertyPlacement", "Curves", "The rigid motion of the Curves (about the document's origin)", False),
    ("CurveLevel", "App::PropertyIntegerConstraint", "Curves", "The finest level whose vertices follow the curves: finer follows them more closely", False),
    ("CurveInfluence", "App::PropertyIntegerConstraint", "Curves", "The coarsest level whose vertices follow the curves (a chain at each level from it to CurveLevel, each pinned at its own level): their region of influence", False),
    ("CurveLoops", "App::PropertyIntegerList", "Curves", "Boundary loops of the cage (numbered by their lowest vertex) moved rigidly with the Curves by CurveMotion: their vertices at each level from CurveInfluence to CurveLevel", False),
    ("HeldLoops", "App::PropertyIntegerList", "Curves", "Boundary loops of the cage held where they are, at the same levels", False),
    ("Solve", "App::PropertyEnumeration", "Pins", "Direct: the energy's minimum on each region; SOR: the paper's relaxation; Approximate: Catmull-Clark smoothing of the pins' moves (what a drag shows)", False),
    ("Rings", "App::PropertyIntegerConstraint", "Pins", "How far each region reaches beyond the pins' masks, in rings of faces at its level", False),
    ("FitMax", "App::PropertyFloat", "Result", "The limit surface's largest distance from the Target (mm)", True),
    ("FitRms", "App::PropertyFloat", "Result", "The limit surface's RMS distance from the Target (mm)", True),
    ("PinResidual", "App::PropertyFloat", "Result", "The worst pin's distance from its target (mm)", True),
    ("NormalAngle", "App::PropertyFloat", "Result", "The worst prescribed normal's angle from the surface's normal there (degrees, from the edited mesh's divided differences)", True),
    ("CurvePins", "App::PropertyInteger", "Result", "Pins placed along the Curves, at all their levels", True),
    ("BoundaryLoops", "App::PropertyInteger", "Result", "The cage's boundary loops (CurveLoops and HeldLoops number them 0..BoundaryLoops-1)", True),
    ("CurveDistance", "App::PropertyFloat", "Result", "The farthest of the moved curves' points from the result (mm, on its bicubic limit patches near them): how closely the surface follows them", True),
    ("FaceCount", "App::PropertyInteger", "Result", "Faces of the finest level", True),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]


def _set_enumeration(obj):
    obj.Solve = list(multiresolution.SOLVES)
    obj.Solve = "Direct"


class SubdSurfaceFeature(FeatureProxy):
    """Proxy of a VarSurf SubdSurface (Mesh::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderSubdSurface"
    PROPERTIES = _PROPERTIES
    DEFAULTS = {"Levels": (3, 1, 8, 1), "Rings": (1, 0, 8, 1), "Solve": _set_enumeration,
                "CurveLevel": (3, 0, 8, 1), "CurveInfluence": (0, 0, 8, 1)}

    def consumed(self, obj):
        return [o for o in (getattr(obj, "Source", None), getattr(obj, "Target", None)) if o is not None]

    def execute(self, obj):
        try:
            result = compute(obj)
        except Exception as error:
            raise mark_failed(obj, error) from error
        self.outcome = result  # first: the view's handles, rebuilt as Mesh changes, read it
        obj.Mesh = subdivision.mesh_of(result.points, result.triangles)
        obj.FitMax = result.fit_max if result.fit_max is not None else 0.0
        obj.FitRms = result.fit_rms if result.fit_rms is not None else 0.0
        obj.PinResidual = result.residual
        obj.NormalAngle = math.degrees(result.normal_angle)
        obj.CurvePins, obj.CurveDistance = result.curve_pins, result.curve_distance
        obj.BoundaryLoops = len(multiresolution.boundary_loops(result.faces[0]))
        obj.FaceCount = len(result.faces[-1])
        obj.Status = f"OK: {obj.FaceCount} faces at level {obj.Levels}"
        if result.fit_max is not None:
            obj.Status += f", {obj.Target.Label} captured within {result.fit_max:.3g} mm (RMS {result.fit_rms:.3g})"
        if result.curve_pins:
            kinds = [k for k, there in (("curves", list(getattr(obj, "Curves", None) or [])),
                                        ("loops", list(obj.CurveLoops) + list(obj.HeldLoops))) if there]
            obj.Status += f", {result.curve_pins} pins along the {' and '.join(kinds)}"
            if list(getattr(obj, "Curves", None) or []):
                obj.Status += (f" (the moved curves on it within {result.curve_distance:.2g} mm, the curves on it "
                               f"within {result.curve_start:.2g} mm before; re-parameterized along them within "
                               f"{result.curve_change:.2g} mm of its shape)")
        if result.region_sizes and (obj.PinTargets or result.curve_pins):
            obj.Status += f", pins met within {result.residual:.2g} mm"
        if result.region_sizes and obj.NormalDirections:
            obj.Status += f", normals within {obj.NormalAngle:.2g}°"


def pins_of(obj):
    """The pins of a SubdSurface's Pins lists, all of one length."""
    lists = [list(obj.PinVertices), list(obj.PinLevels), list(obj.PinInfluence), list(value(obj, "PinTargets"))]
    if len({len(v) for v in lists}) != 1:
        raise errors.SheetError(f"PinVertices, PinLevels, PinInfluence and PinTargets have {', '.join(str(len(v)) for v in lists)} "
                                "entries: give each pin one of each")
    return [multiresolution.Pin(int(lv), int(v), (t.x, t.y, t.z), int(inf))
            for v, lv, inf, t in zip(*lists)]


def normals_of(obj):
    """The prescribed normals of a SubdSurface's Normals lists, all of one length."""
    lists = [list(obj.NormalVertices), list(obj.NormalLevels), list(obj.NormalInfluence),
             list(value(obj, "NormalDirections"))]
    if len({len(v) for v in lists}) != 1:
        raise errors.SheetError(f"NormalVertices, NormalLevels, NormalInfluence and NormalDirections have "
                                f"{', '.join(str(len(v)) for v in lists)} entries: give each normal one of each")
    return [multiresolution.Normal(int(lv), int(v), (d.x, d.y, d.z), int(inf))
            for v, lv, inf, d in zip(*lists)]


def curve_edges(obj, strict: bool = True):
    """The edges a SubdSurface's Curves link, in order. strict: a face or vertex reference is an
    error (the recompute's); otherwise such references and stale links are skipped (a view's)."""
    edges = []
    for link, subs in list(getattr(obj, "Curves", None) or []):
        try:
            shape = shape_of(link)
        except ValueError:
            if strict:
                raise
            continue
        for name in as_names(subs) or tuple(f"Edge{i + 1}" for i in range(len(shape.Edges))):
            if not name.startswith("Edge"):
                if strict:
                    raise errors.SheetError(f"{link.Label}:{name} is not an edge: link edges as Curves")
                continue
            try:
                edges.append(shape.getElement(name))
            except Exception:  # FreeCAD raises a bare exception for a missing element
                if strict:
                    raise errors.SheetError(f"{link.Label} has no {name}: link an existing edge as a Curve")
    return edges


def curves_of(obj):
    """The SubdSurface's Curves as a multiresolution.CurveMotion (None without curves): each edge
    sampled finely enough for the chain (the core densifies further)."""
    loops, held = [int(n) for n in getattr(obj, "CurveLoops", ())], [int(n) for n in getattr(obj, "HeldLoops", ())]
    if not list(getattr(obj, "Curves", None) or []) and not loops and not held:
        return None
    polylines = []
    for edge in curve_edges(obj):
        points = edge.discretize(Deflection=max(1e-4 * edge.Length, 1e-9))
        if len(points) < 32:
            points = edge.discretize(Number=32)
        polylines.append([(p.x, p.y, p.z) for p in points])
    return multiresolution.CurveMotion(polylines, int(obj.CurveLevel), int(obj.CurveInfluence),
                                       placement_matrix(obj.CurveMotion), loops, held)


def placement_matrix(placement):
    """A FreeCAD.Placement as 4 x 4 rows (the core's rigid motion)."""
    m = placement.toMatrix()
    return [[m.A11, m.A12, m.A13, m.A14], [m.A21, m.A22, m.A23, m.A24], [m.A31, m.A32, m.A33, m.A34],
            [0.0, 0.0, 0.0, 1.0]]


def compute(obj):
    """The SubdSurface's MultiresResult (see varsurf.solve.multiresolution.build)."""
    if obj.Source is None:
        raise errors.SheetError("no Source: link the cage (a Mesh, a shape with faces, or a VarSurf sheet)")
    points, faces = subdivision.control_mesh(obj.Source)
    target = None
    if obj.Target is not None:
        target = subdivision.target_triangles(obj.Target, float(value(obj, "TargetTolerance")))
    try:
        return multiresolution.build(points, faces, int(obj.Levels), target=target, pins=pins_of(obj),
                                     solve=str(obj.Solve), rings=int(obj.Rings), normals=normals_of(obj),
                                     curves=curves_of(obj))
    except errors.SheetError as error:
        raise errors.SheetError(f"{error} ({obj.Source.Label} as the cage"
                                + (f", {obj.Target.Label} as the target)" if obj.Target is not None else ")")) from error


def make_subd_surface(source, levels: int = 3, target=None, pins=(), solve: str = "Direct", rings: int = 1,
                      doc=None, name: str = "SubdSurface", normals=()):
    """Add a SubdSurface (computed at the next recompute): ``source`` the cage (a Mesh, a shape's
    faces, or a VarSurf sheet), ``target`` an optional Mesh or shape whose detail is captured,
    ``pins`` (level, vertex, (x, y, z), influence) tuples, ``normals`` (level, vertex,
    (x, y, z) direction, influence) tuples."""
    doc = doc or source.Document
    obj = doc.addObject("Mesh::FeaturePython", name)
    SubdSurfaceFeature(obj)
    obj.Source = source
    obj.Target = target
    obj.Levels = int(levels)
    set_pins(obj, pins)
    set_normals(obj, normals)
    obj.Solve = solve
    obj.Rings = int(rings)
    attach_view_provider(obj, "ViewProviderSubdSurface")
    return obj


def _set_lists(obj, prefix: str, third: str, entries):
    """Write (level, vertex, (x, y, z), influence) tuples into obj's <prefix>Levels, Vertices,
    <third> (vectors) and Influence lists: pins and normals are stored alike."""
    entries = [tuple(e) for e in entries]
    setattr(obj, prefix + "Levels", [int(e[0]) for e in entries])
    setattr(obj, prefix + "Vertices", [int(e[1]) for e in entries])
    setattr(obj, prefix + third, [FreeCAD.Vector(*map(float, e[2])) for e in entries])
    setattr(obj, prefix + "Influence", [int(e[3]) for e in entries])


def set_pins(obj, pins):
    """Replace a SubdSurface's pins by (level, vertex, (x, y, z), influence) tuples."""
    _set_lists(obj, "Pin", "Targets", pins)


def set_curves(obj, curves, motion=None, level=None, influence=0, loops=(), held=()):
    """Move `curves` lying on a SubdSurface rigidly: (object, "EdgeN") or (object, ("EdgeN", ...))
    references (a bare object: all its edges), `motion` a FreeCAD.Placement, `level` the finest
    level whose vertices follow them (default: the finest), `influence` the coarsest, their region
    of influence; `loops` boundary loops of the cage moved with them, `held` loops kept in place
    (numbered as multiresolution.boundary_loops numbers the cage's)."""
    obj.Curves = [(o, list(names)) for o, names in normalize_curves(curves)]
    obj.CurveMotion = motion if motion is not None else FreeCAD.Placement()
    obj.CurveLevel = int(obj.Levels if level is None else level)
    obj.CurveInfluence = int(influence)
    obj.CurveLoops = [int(n) for n in loops]
    obj.HeldLoops = [int(n) for n in held]


def set_normals(obj, normals):
    """Replace a SubdSurface's prescribed normals by (level, vertex, (x, y, z), influence) tuples."""
    _set_lists(obj, "Normal", "Directions", normals)


def move_pin(obj, index: int, target):
    """Move pin `index` of a SubdSurface to `target` (a drag's release)."""
    targets = list(value(obj, "PinTargets"))
    if not 0 <= int(index) < len(targets):
        raise ValueError(f"{obj.Label} has {len(targets)} pins, no pin {index}: give one of 0..{len(targets) - 1}")
    targets[int(index)] = FreeCAD.Vector(target)
    obj.PinTargets = targets


def is_subd_surface(obj) -> bool:
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE


TYPE_BREP = "VarSurf::SubdBRep"

_BREP_PROPERTIES = [
    ("Base", "App::PropertyLink", "SubdBRep", "The SubdSurface whose limit surface this is", False),
    ("Isolation", "App::PropertyIntegerConstraint", "SubdBRep", "Adaptive refinement levels around extraordinary vertices: the approximate end-cap faces there shrink by half with each", False),
    ("Tolerance", "App::PropertyLength", "SubdBRep", "Sewing tolerance (mm; 0: a ten-millionth of the surface's size)", False),
    ("MaxSpan", "App::PropertyIntegerConstraint", "SubdBRep", "Most faces of the finest mesh along a side of one B-rep face: its regular patches are written as one C2 B-spline (1: a B-rep face per mesh face)", False),
    ("Closed", "App::PropertyBool", "Result", "True if the faces close into a solid", True),
    ("PatchCount", "App::PropertyInteger", "Result", "Bicubic patches of the limit surface (OpenSubdiv's patch table)", True),
    ("FaceCount", "App::PropertyInteger", "Result", "B-rep faces: rectangles of regular patches as one B-spline each, and each face refined near an extraordinary vertex as one", True),
    ("EndCapCount", "App::PropertyInteger", "Result", "Of those, the end caps at extraordinary vertices (approximations of the limit surface)", True),
    ("EndCapDeviation", "App::PropertyFloat", "Result", "The end caps' largest distance from the limit surface (mm), against OpenSubdiv's evaluation 10 levels deep", True),
    ("RegularSeamAngle", "App::PropertyFloat", "Result", "The largest angle between tangent planes across seams of regular patches (degrees; exact faces, so rounding only)", True),
    ("EndCapSeamAngle", "App::PropertyFloat", "Result", "The largest angle between tangent planes across seams that touch an end cap (degrees)", True),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]


class SubdBRepFeature(FeatureProxy):
    """Proxy of a VarSurf SubdBRep (Part::FeaturePython): a SubdSurface's limit surface as B-rep
    faces, bicubic B-spline patches sewn into a shell or solid."""

    Type = TYPE_BREP
    TYPE = TYPE_BREP
    VIEW_PROVIDER = "ViewProviderSubdBRep"
    PROPERTIES = _BREP_PROPERTIES
    DEFAULTS = {"Isolation": (4, 1, 8, 1), "MaxSpan": (64, 1, 1000, 1)}

    def consumed(self, obj):
        base = getattr(obj, "Base", None)
        return [base] if base is not None else []

    def execute(self, obj):
        try:
            result = brep_of(obj)
        except Exception as error:
            raise mark_failed(obj, error) from error
        obj.Shape = result.shape
        obj.Closed = result.closed
        obj.PatchCount, obj.EndCapCount, obj.FaceCount = result.patches, result.end_caps, result.faces
        obj.EndCapDeviation = result.end_cap_deviation
        obj.RegularSeamAngle, obj.EndCapSeamAngle = result.regular_angle, result.end_cap_angle
        kind = "solid" if result.closed else "open shell"
        caps = (f"{result.end_caps} end caps within {result.end_cap_deviation:.2g} mm of the limit surface"
                if result.end_caps else "no end caps: the limit surface exactly")
        seams = f"regular within {result.regular_angle:.2g}°"
        if result.end_caps:
            seams += f", at end caps within {result.end_cap_angle:.2g}°"
        obj.Status = (f"OK: {kind} of {result.faces} B-spline faces from {result.patches} bicubic patches ({caps}); "
                      f"seams: {seams}")


def brep_of(obj):
    """The SubdBRep's multiresolution.BRepResult, its shape a Part shape."""
    base = obj.Base
    if base is None or not is_subd_surface(base):
        raise errors.SheetError("no SubdSurface as Base: link the SubdSurface whose limit surface to make")
    outcome = getattr(base.Proxy, "outcome", None)
    if outcome is None:
        outcome = compute(base)
    tolerance = float(value(obj, "Tolerance"))
    result = multiresolution.brep(outcome, int(obj.Isolation), tolerance, int(value(obj, "MaxSpan")))
    result.shape = shape_from_brep(result.brep)
    return result


def make_subd_brep(subd, isolation: int = 4, name: str = "SubdBRep"):
    """Add a SubdBRep of ``subd`` (a SubdSurface): its limit surface as sewn bicubic faces, a solid
    when it closes (computed at the next recompute)."""
    obj = subd.Document.addObject("Part::FeaturePython", name)
    SubdBRepFeature(obj)
    obj.Base = subd
    obj.Isolation = int(isolation)
    attach_view_provider(obj, "ViewProviderSubdBRep")
    return obj
