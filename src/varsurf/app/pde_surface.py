# SPDX-License-Identifier: LGPL-2.1-or-later
"""The PdeSurface feature: a surface defined by boundary conditions and the generalized
Bloor-Wilson PDE (Du & Qin).

A ``Part::FeaturePython`` whose ``Shape`` is one B-spline face over [0, 1]^2, v along the boundary
curves ``U0`` (u = 0) and ``U1`` (u = 1). With ``Derivative0``/``Derivative1`` (Hermite-like
conditions) the tangent across each boundary is the difference between the boundary curve and its
derivative curve, times ``Magnitude0``/``Magnitude1``; with ``V0``/``V1`` (Coons-like) the surface
also ends on those curves; ``UCurves``/``VCurves`` at ``UCurveParameters``/``VCurveParameters``
(Gordon-like) are curves it contains inside. The interior minimizes the PDE's energy with the
coefficient ``PdeA`` painted on ``PdeRegions``. App side only.
"""

from __future__ import annotations

import dataclasses

import Part

from varsurf.app.constraint import spec_of
from varsurf.app.feature import FeatureProxy, last_outcome, mark_failed, value
from varsurf.app.view_link import attach as attach_view_provider
from varsurf.solve import errors, settings, shapes
from varsurf.solve import pde_surface as pde
from varsurf.solve.native import native

TYPE = "VarSurf::PdeSurface"
_FLOAT_MAX = 1.0e12

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("U0", "App::PropertyLinkSub", "Boundary", "The boundary curve at u = 0 (an edge): v runs along it", False),
    ("U1", "App::PropertyLinkSub", "Boundary", "The boundary curve at u = 1 (an edge), oriented by its ends to match U0", False),
    ("Derivative0", "App::PropertyLinkSub", "Boundary", "Hermite: a curve beside U0; the surface's tangent across U0 is (this curve - U0) x Magnitude0, per unit of u. Empty: none", False),
    ("Derivative1", "App::PropertyLinkSub", "Boundary", "Hermite: a curve beside U1; the tangent across U1 is (this curve - U1) x Magnitude1. Empty: none", False),
    ("Magnitude0", "App::PropertyFloat", "Boundary", "Hermite: scales the tangent Derivative0 gives (1: the distance to the curve itself)", False),
    ("Magnitude1", "App::PropertyFloat", "Boundary", "Hermite: scales the tangent Derivative1 gives", False),
    ("Face0", "App::PropertyLinkSub", "Boundary", "Hermite from a face: the face U0 bounds; the surface leaves U0 tangent to it (G1), the tangent Magnitude0 x the distance to U1 long. Instead of Derivative0", False),
    ("Face1", "App::PropertyLinkSub", "Boundary", "Hermite from a face: the face U1 bounds; the surface meets it tangent (G1), the tangent Magnitude1 x the distance to U0 long. Instead of Derivative1", False),
    ("V0", "App::PropertyLinkSub", "Boundary", "Coons: the side at v = 0, from U0's start to U1's. Empty: a free side", False),
    ("V1", "App::PropertyLinkSub", "Boundary", "Coons: the side at v = 1, from U0's end to U1's. Empty: a free side", False),
    ("UCurves", "App::PropertyLinkSubList", "Network", "Gordon: curves the surface contains at u = UCurveParameters (one each), running like U0", False),
    ("UCurveParameters", "App::PropertyFloatList", "Network", "Gordon: the u (0..1) of each of UCurves", False),
    ("VCurves", "App::PropertyLinkSubList", "Network", "Gordon: curves the surface contains at v = VCurveParameters, running from U0 to U1", False),
    ("VCurveParameters", "App::PropertyFloatList", "Network", "Gordon: the v (0..1) of each of VCurves", False),
    ("Constraints", "App::PropertyLinkList", "Sculpting", "Constraint objects sculpting the surface (Du & Qin's tools: points, normals, tangents, frozen regions, attractors...), placed on the surface the boundary conditions alone give", False),
    ("PdeA", "App::PropertyFloatConstraint", "PDE", "The coefficient a of (d2/du2 + a^2 d2/dv2)^2 P = 0 where nothing is painted: large a shortens the length scale of changes along u (1/a of that along v)", False),
    ("PdeRegions", "App::PropertyFloatList", "PDE", "a painted on rectangles, five numbers each: a, u0, u1, v0, v1 (0..1; later regions over earlier ones)", False),
    ("PdeLoops", "App::PropertyFloatList", "PDE", "a painted inside closed loops of (u, v), over the rectangles: for each loop its a, its point count n, then n pairs u, v (0..1; later loops over earlier ones)", False),
    ("PdeBlend", "App::PropertyFloat", "PDE", "Width of the band over which a blends across a painted region's border, a fraction of the domain (0: sharp; at most 0.5)", False),
    ("DragMode", "App::PropertyEnumeration", "Dynamics", "How a Point's pin drags the surface. Static: the surface follows the pin at once (a solve per move). Dynamic (Du & Qin's dynamic sculpting): the pin pulls it by a spring; it moves with mass and damping and settles when released", False),
    ("Mass", "App::PropertyFloatConstraint", "Dynamics", "Dynamic drag: the surface's mass, relative (1: a full swing takes 0.3 s with the pin held; 4: twice as long)", False),
    ("Damping", "App::PropertyFloatConstraint", "Dynamics", "Dynamic drag: the damping ratio of that swing (0: it keeps swinging; 1: critical, no overshoot)", False),
    ("MaterialRegions", "App::PropertyFloatList", "Dynamics", "Dynamic drag: mass and damping painted on rectangles, six numbers each: mass, damping, u0, u1, v0, v1 (relative like Mass and Damping, u and v 0..1; blended across the border by PdeBlend; later regions over earlier ones)", False),
    ("Spring", "App::PropertyFloatConstraint", "Dynamics", "Dynamic drag: the pin's stiffness, in units of the surface's own stiffness at the pin (10: the pin point reaches 10/11 of the way to the pointer)", False),
    ("Degree", "App::PropertyIntegerConstraint", "Solver", "Degree of the surface in u and v (3 or more for Hermite conditions)", False),
    ("MinSpans", "App::PropertyIntegerConstraint", "Solver", "Spans per direction of the first solve", False),
    ("MaxSpans", "App::PropertyIntegerConstraint", "Solver", "While a curve is farther from the surface than Tolerance, the spans double up to this count", False),
    ("Tolerance", "App::PropertyLength", "Solver", "Distance at which a curve counts as met, and within which curves count as meeting (corners, crossings)", False),
    ("Kind", "App::PropertyString", "Result", "The boundary conditions given: Hermite (derivative curves), Coons (sides), Gordon (a network), joined by +; Boundary: the two boundary curves alone", True),
    ("CurveNames", "App::PropertyStringList", "Result", "The curves the surface contains, in the order of MaxDeviations", True),
    ("MaxDeviations", "App::PropertyFloatList", "Result", "Largest distance (mm) from each curve to the surface, measured on the result", True),
    ("FitError", "App::PropertyFloat", "Result", "Largest distance (mm) between a held boundary row and its curve (and derivative data)", True),
    ("Spans", "App::PropertyInteger", "Result", "Spans per direction of the result", True),
    ("SolveTime", "App::PropertyFloat", "Result", "Time of the last solve (s), every refinement round", True),
    ("SolveModeUsed", "App::PropertyString", "Result", "How the last solve was done and why (multigrid for a surface held by its boundary conditions alone from 500 free poles; a direct factorization otherwise)", True),
    ("Status", "App::PropertyString", "Result", "Outcome of the last recompute", True),
]

_DEFAULTS = {
    "Magnitude0": 1.0,
    "Magnitude1": 1.0,
    "PdeA": (1.0, 1e-3, settings.MAX_PDE_A, 0.1),
    "Degree": (3, 2, settings.MAX_DEGREE, 1),
    "MinSpans": (8, 1, 512, 1),
    "MaxSpans": (64, 1, 512, 1),
    "Tolerance": settings.DEFAULT_TOLERANCE,
    "Status": "Not computed",
    "DragMode": ["Static", "Dynamic"],
}

#: The dynamic drag's numbers: default, bounds and step (a constraint property's bounds are not
#: saved: add_properties sets them again).
DYNAMICS = {"Mass": (1.0, 1e-3, 1e3, 0.1), "Damping": (0.5, 0.0, 10.0, 0.1), "Spring": (10.0, 0.1, 1e4, 1.0)}
_DEFAULTS.update(DYNAMICS)

_LINKS = (("U0", "u0"), ("U1", "u1"), ("Derivative0", "d0"), ("Derivative1", "d1"), ("V0", "v0"), ("V1", "v1"))


def _edge(link, sub, prop):
    subs = [s for s in ([sub] if isinstance(sub, str) else list(sub)) if s]
    if len(subs) != 1 or not subs[0].startswith("Edge"):
        raise errors.SheetError(f"{prop} must reference exactly one edge of {link.Label}: pick one edge (EdgeN)")
    try:
        edge = Part.getShape(link, subs[0], needSubElement=True)
    except Exception as error:
        raise errors.SheetError(f"{link.Label}:{subs[0]} cannot be found ({error}): select the edge again") from error
    if edge.isNull() or edge.ShapeType != "Edge":
        raise errors.SheetError(f"{link.Label}:{subs[0]} does not exist (anymore): select the edge again")
    return f"{link.Label}:{subs[0]}", edge


def _native_curve(nat, name, edge):
    try:
        return nat.curve_from_edge_brep(edge.exportBrepToString())
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise errors.SheetError(f"{name} cannot be used as a curve: {error}; pick another edge") from error


#: Points along a boundary curve at which a neighbour face gives the tangent across it.
FACE_SAMPLES = 65


def _face(link, sub, prop):
    subs = [s for s in ([sub] if isinstance(sub, str) else list(sub)) if s]
    if len(subs) != 1 or not subs[0].startswith("Face"):
        raise errors.SheetError(f"{prop} must reference exactly one face of {link.Label}: pick one face (FaceN)")
    face = Part.getShape(link, subs[0], needSubElement=True)
    if face.isNull() or face.ShapeType != "Face":
        raise errors.SheetError(f"{link.Label}:{subs[0]} does not exist (anymore): select the face again")
    return f"{link.Label}:{subs[0]}", face


def derivative_from_face(edge, other, face, name, magnitude, into):
    """A derivative curve for the boundary `edge` that continues `face` across it (Du & Qin's
    Hermite data taken from an adjacent face): at each of FACE_SAMPLES points of the edge, the
    direction in the face's tangent plane across the edge, as long as magnitude times the distance
    to the `other` boundary at the same parameter. P_u points along increasing u: away from the
    face at u = 0, into it at u = 1 (`into`)."""
    size = max(edge.BoundBox.DiagonalLength, other.BoundBox.DiagonalLength, 1e-9)
    ends = [other.valueAt(other.FirstParameter), other.valueAt(other.LastParameter)]
    start, end = edge.valueAt(edge.FirstParameter), edge.valueAt(edge.LastParameter)
    turned = (start - ends[1]).Length + (end - ends[0]).Length < (start - ends[0]).Length + (end - ends[1]).Length
    points, params = [], []
    for k in range(FACE_SAMPLES):
        s = k / (FACE_SAMPLES - 1)
        t = edge.FirstParameter + s * (edge.LastParameter - edge.FirstParameter)
        p = edge.valueAt(t)
        so = 1.0 - s if turned else s  # the other boundary drawn the other way: paired by its ends
        q = other.valueAt(other.FirstParameter + so * (other.LastParameter - other.FirstParameter))
        foot = face.Surface.parameter(p)
        gap = (face.Surface.value(*foot) - p).Length
        if gap > 1e-3 * size:
            raise errors.SheetError(f"{name} does not bound the face: it passes {gap:.3g} mm from it; pick the face "
                                    "the boundary curve lies on")
        normal = face.normalAt(*foot)
        across = normal.cross(edge.tangentAt(t))
        if across.Length < 1e-12:
            raise errors.SheetError(f"{name} runs along the face's normal at {s:.2f} of its length: pick the face "
                                    "it bounds")
        across.normalize()
        step = 1e-4 * size
        # Away from the face: a short step that way leaves it, the other way stays on it.
        if face.isInside(p + across * step, 1e-7 * size, True) != into:
            across = across * -1.0
        points.append(p + across * (magnitude * (q - p).Length))
        params.append(s)
    curve = Part.BSplineCurve()
    curve.interpolate(points, Parameters=params)
    return curve.toShape()


def _network(nat, obj, links_prop, params_prop):
    links = [(link, sub) for link, subs in getattr(obj, links_prop) for sub in subs if sub]
    params = list(getattr(obj, params_prop))
    if len(params) != len(links):
        raise errors.SheetError(f"{params_prop} has {len(params)} values for {len(links)} {links_prop}: give one "
                                "parameter (0..1) per curve")
    names, out = [], []
    for (link, sub), at in zip(links, params):
        name, edge = _edge(link, sub, links_prop)
        names.append(name)
        out.append((float(at), _native_curve(nat, name, edge)))
    return names, out


def _fives(flat):
    if len(flat) % 5:
        raise errors.SheetError(f"PdeRegions needs five numbers a region (a, u0, u1, v0, v1); got {len(flat)}: give "
                                "each region all five")
    return tuple(tuple(flat[k:k + 5]) for k in range(0, len(flat), 5))


def loops_of(flat):
    """PdeLoops' numbers as (a, ((u, v), ...)) loops."""
    out, k = [], 0
    while k < len(flat):
        if k + 2 > len(flat) or flat[k + 1] != int(flat[k + 1]) or flat[k + 1] < 0 \
                or k + 2 + 2 * int(flat[k + 1]) > len(flat):
            raise errors.SheetError(f"PdeLoops does not read as loops at loop {len(out) + 1}: each is its a, its "
                                    "point count n, then n pairs u, v; paint the loops again")
        n = int(flat[k + 1])
        out.append((flat[k], tuple((flat[k + 2 + 2 * i], flat[k + 3 + 2 * i]) for i in range(n))))
        k += 2 + 2 * n
    return tuple(out)


def flat_loops(loops):
    """(a, ((u, v), ...)) loops as PdeLoops' numbers."""
    return [float(x) for a, points in loops for x in [a, len(points)] + [c for point in points for c in point]]


def _sixes(flat):
    if len(flat) % 6:
        raise errors.SheetError(f"MaterialRegions needs six numbers a region (mass, damping, u0, u1, v0, v1); got "
                                f"{len(flat)}: give each region all six")
    return tuple(tuple(flat[k:k + 6]) for k in range(0, len(flat), 6))


def settings_of(obj) -> pde.PdeSurfaceSettings:
    values = pde.PdeSurfaceSettings(
        a=float(obj.PdeA), regions=_fives([float(x) for x in obj.PdeRegions]), blend=float(obj.PdeBlend),
        loops=loops_of([float(x) for x in getattr(obj, "PdeLoops", [])]),
        magnitude0=float(obj.Magnitude0), magnitude1=float(obj.Magnitude1), degree=int(obj.Degree),
        min_spans=int(obj.MinSpans), max_spans=int(obj.MaxSpans), tolerance=float(value(obj, "Tolerance")),
        materials=_sixes([float(x) for x in getattr(obj, "MaterialRegions", [])]))
    pde.check(values)
    return values


def compute(obj) -> pde.PdeSurfaceOutcome:
    nat = native()
    values = settings_of(obj)
    curves, labels = {}, {}
    for prop, role in _LINKS:
        link = getattr(obj, prop)
        if link is None:
            continue
        name, edge = _edge(link[0], link[1], prop)
        labels[role] = name
        curves[role] = _native_curve(nat, name, edge)
    for prop, role in (("U0", "u0"), ("U1", "u1")):
        if role not in curves:
            raise errors.SheetError(f"{prop} is empty: link the boundary curve at {role.replace('u', 'u = ')} (an edge)")
    edges = {role: _edge(*getattr(obj, prop), prop)[1] for prop, role in (("U0", "u0"), ("U1", "u1"))}
    for k, (mine, other) in enumerate((("u0", "u1"), ("u1", "u0"))):
        link = getattr(obj, f"Face{k}", None)
        if link is None:
            continue
        if f"d{k}" in curves:
            raise errors.SheetError(f"Derivative{k} and Face{k} both give the tangent across U{k}: clear one of them")
        name, face = _face(link[0], link[1], f"Face{k}")
        magnitude = float(getattr(obj, f"Magnitude{k}"))
        edge = derivative_from_face(edges[mine], edges[other], face, labels[mine], magnitude, into=k == 1)
        curves[f"d{k}"] = _native_curve(nat, name, edge)
        labels[f"d{k}"] = f"the tangents of {name}"
        values = dataclasses.replace(values, **{f"magnitude{k}": 1.0})  # the curve carries it
    u_names, u_curves = _network(nat, obj, "UCurves", "UCurveParameters")
    v_names, v_curves = _network(nat, obj, "VCurves", "VCurveParameters")
    specs = [spec_of(c) for c in (getattr(obj, "Constraints", None) or []) if c.Enabled]
    return pde.solve(values, curves, pde.labels_for(labels, u_names, v_names), u_curves, v_curves, constraints=specs)


class PdeSurfaceFeature(FeatureProxy):
    """Proxy of a VarSurf PdeSurface (Part::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderPdeSurface"
    PROPERTIES = _PROPERTIES
    DEFAULTS = _DEFAULTS

    def add_properties(self, obj):
        super().add_properties(obj)
        for name, _kind, _group, _tip, output in _PROPERTIES:
            if output:
                obj.setEditorMode(name, 1)
        # The bounds of a dynamic constraint property are not written to the file: set them again.
        obj.PdeA = (min(max(float(obj.PdeA), 1e-3), settings.MAX_PDE_A), 1e-3, settings.MAX_PDE_A, 0.1)
        obj.Degree = (min(max(int(obj.Degree), 2), settings.MAX_DEGREE), 2, settings.MAX_DEGREE, 1)
        for name in ("MinSpans", "MaxSpans"):
            setattr(obj, name, (min(max(int(getattr(obj, name)), 1), 512), 1, 512, 1))
        for name, (_default, low, high, step) in DYNAMICS.items():
            setattr(obj, name, (min(max(float(getattr(obj, name)), low), high), low, high, step))

    def execute(self, obj):
        self.outcome = None
        try:
            outcome = compute(obj)
        except Exception as error:
            obj.MaxDeviations, obj.CurveNames, obj.SolveModeUsed = [], [], ""
            raise mark_failed(obj, error) from error
        self.outcome = outcome  # for a drag's prepared solve (not saved: a reopened file solves again)
        nat = native()
        obj.Shape = shapes.shape_from_brep(nat.face_brep(outcome.surface))
        obj.Kind = outcome.kind
        obj.CurveNames = outcome.names
        obj.MaxDeviations = outcome.deviations
        obj.FitError = outcome.fit_error
        obj.Spans = outcome.spans
        obj.SolveTime = outcome.seconds
        obj.SolveModeUsed = str(outcome.report.mode_reason)
        worst = max(outcome.deviations + [outcome.fit_error])
        tolerance = float(value(obj, "Tolerance"))
        if worst > tolerance:
            obj.Status = (f"Warning: a curve is {worst:.3g} mm from the surface at {outcome.spans} spans, more than "
                          f"the tolerance {tolerance:.3g} mm: raise MaxSpans or loosen Tolerance")
        else:
            obj.Status = f"OK: {outcome.kind}, {outcome.spans} x {outcome.spans} spans, within {worst:.2g} mm"

    def consumed(self, obj):
        return []


def outcome_of(obj):
    """The PdeSurfaceOutcome of a PdeSurface's last recompute (solved again if this session has none)."""
    return last_outcome(obj, compute)


def is_pde_surface(obj) -> bool:
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE


def make_pde_surface(u0, u1, derivative0=None, derivative1=None, v0=None, v1=None, u_curves=(), v_curves=(),
                     face0=None, face1=None, a: float = 1.0, regions=(), blend: float = 0.0, magnitude0: float = 1.0,
                     magnitude1: float = 1.0, tolerance=None, doc=None, name: str = "PdeSurface", loops=()):
    """Add a PdeSurface (computed at the next recompute). Curves are (object, "EdgeN"); face0 and
    face1 (object, "FaceN") give the tangents across U0 and U1 from the faces they bound (G1);
    u_curves and v_curves are ((object, "EdgeN"), parameter) pairs (Gordon networks); regions are
    (a, u0, u1, v0, v1) rectangles (0..1) painting the coefficient, loops (a, ((u, v), ...)) closed
    polygons painting it over them."""
    if doc is None:
        doc = u0[0].Document
    obj = doc.addObject("Part::FeaturePython", name)
    PdeSurfaceFeature(obj)
    for prop, link in (("U0", u0), ("U1", u1), ("Derivative0", derivative0), ("Derivative1", derivative1),
                       ("V0", v0), ("V1", v1), ("Face0", face0), ("Face1", face1)):
        if link is not None:
            setattr(obj, prop, (link[0], link[1]))
    obj.UCurves = [(link[0], link[1]) for link, _ in u_curves]
    obj.UCurveParameters = [float(at) for _, at in u_curves]
    obj.VCurves = [(link[0], link[1]) for link, _ in v_curves]
    obj.VCurveParameters = [float(at) for _, at in v_curves]
    obj.PdeA = float(a)
    obj.PdeRegions = [float(x) for region in regions for x in region]
    obj.PdeLoops = flat_loops(loops)
    obj.PdeBlend = float(blend)
    obj.Magnitude0, obj.Magnitude1 = float(magnitude0), float(magnitude1)
    if tolerance is not None:
        obj.Tolerance = float(tolerance)
    attach_view_provider(obj, "ViewProviderPdeSurface")
    return obj
