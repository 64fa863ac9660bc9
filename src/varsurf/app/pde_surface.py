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

import Part

from varsurf.app.feature import FeatureProxy, mark_failed, value
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
    ("V0", "App::PropertyLinkSub", "Boundary", "Coons: the side at v = 0, from U0's start to U1's. Empty: a free side", False),
    ("V1", "App::PropertyLinkSub", "Boundary", "Coons: the side at v = 1, from U0's end to U1's. Empty: a free side", False),
    ("UCurves", "App::PropertyLinkSubList", "Network", "Gordon: curves the surface contains at u = UCurveParameters (one each), running like U0", False),
    ("UCurveParameters", "App::PropertyFloatList", "Network", "Gordon: the u (0..1) of each of UCurves", False),
    ("VCurves", "App::PropertyLinkSubList", "Network", "Gordon: curves the surface contains at v = VCurveParameters, running from U0 to U1", False),
    ("VCurveParameters", "App::PropertyFloatList", "Network", "Gordon: the v (0..1) of each of VCurves", False),
    ("PdeA", "App::PropertyFloatConstraint", "PDE", "The coefficient a of (d2/du2 + a^2 d2/dv2)^2 P = 0 where nothing is painted: large a shortens the length scale of changes along u (1/a of that along v)", False),
    ("PdeRegions", "App::PropertyFloatList", "PDE", "a painted on rectangles, five numbers each: a, u0, u1, v0, v1 (0..1; later regions over earlier ones)", False),
    ("PdeBlend", "App::PropertyFloat", "PDE", "Width of the band over which a blends across a painted region's border, a fraction of the domain (0: sharp; at most 0.5)", False),
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
}

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


def settings_of(obj) -> pde.PdeSurfaceSettings:
    values = pde.PdeSurfaceSettings(
        a=float(obj.PdeA), regions=_fives([float(x) for x in obj.PdeRegions]), blend=float(obj.PdeBlend),
        magnitude0=float(obj.Magnitude0), magnitude1=float(obj.Magnitude1), degree=int(obj.Degree),
        min_spans=int(obj.MinSpans), max_spans=int(obj.MaxSpans), tolerance=float(value(obj, "Tolerance")))
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
    u_names, u_curves = _network(nat, obj, "UCurves", "UCurveParameters")
    v_names, v_curves = _network(nat, obj, "VCurves", "VCurveParameters")
    return pde.solve(values, curves, pde.labels_for(labels, u_names, v_names), u_curves, v_curves)


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

    def execute(self, obj):
        try:
            outcome = compute(obj)
        except Exception as error:
            obj.MaxDeviations, obj.CurveNames = [], []
            raise mark_failed(obj, error) from error
        nat = native()
        obj.Shape = shapes.shape_from_brep(nat.face_brep(outcome.surface))
        obj.Kind = outcome.kind
        obj.CurveNames = outcome.names
        obj.MaxDeviations = outcome.deviations
        obj.FitError = outcome.fit_error
        obj.Spans = outcome.spans
        obj.SolveTime = outcome.seconds
        worst = max(outcome.deviations + [outcome.fit_error])
        tolerance = float(value(obj, "Tolerance"))
        if worst > tolerance:
            obj.Status = (f"Warning: a curve is {worst:.3g} mm from the surface at {outcome.spans} spans, more than "
                          f"the tolerance {tolerance:.3g} mm: raise MaxSpans or loosen Tolerance")
        else:
            obj.Status = f"OK: {outcome.kind}, {outcome.spans} x {outcome.spans} spans, within {worst:.2g} mm"

    def consumed(self, obj):
        return []


def is_pde_surface(obj) -> bool:
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE


def make_pde_surface(u0, u1, derivative0=None, derivative1=None, v0=None, v1=None, u_curves=(), v_curves=(),
                     a: float = 1.0, regions=(), blend: float = 0.0, magnitude0: float = 1.0,
                     magnitude1: float = 1.0, tolerance=None, doc=None, name: str = "PdeSurface"):
    """Add a PdeSurface (computed at the next recompute). Curves are (object, "EdgeN");
    u_curves and v_curves are ((object, "EdgeN"), parameter) pairs (Gordon networks); regions are
    (a, u0, u1, v0, v1) rectangles (0..1) painting the coefficient."""
    if doc is None:
        doc = u0[0].Document
    obj = doc.addObject("Part::FeaturePython", name)
    PdeSurfaceFeature(obj)
    for prop, link in (("U0", u0), ("U1", u1), ("Derivative0", derivative0), ("Derivative1", derivative1),
                       ("V0", v0), ("V1", v1)):
        if link is not None:
            setattr(obj, prop, (link[0], link[1]))
    obj.UCurves = [(link[0], link[1]) for link, _ in u_curves]
    obj.UCurveParameters = [float(at) for _, at in u_curves]
    obj.VCurves = [(link[0], link[1]) for link, _ in v_curves]
    obj.VCurveParameters = [float(at) for _, at in v_curves]
    obj.PdeA = float(a)
    obj.PdeRegions = [float(x) for region in regions for x in region]
    obj.PdeBlend = float(blend)
    obj.Magnitude0, obj.Magnitude1 = float(magnitude0), float(magnitude1)
    if tolerance is not None:
        obj.Tolerance = float(tolerance)
    attach_view_provider(obj, "ViewProviderPdeSurface")
    return obj
