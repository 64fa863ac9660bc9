# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Sheet feature: a variational B-spline sheet over a base face, through curves.

A ``Part::FeaturePython`` whose ``Shape`` is the face that minimizes the thin-plate energy
``Stretch * (first derivatives)^2 + Bend * (second derivatives)^2`` among the B-splines of the
base face's space that contain the ``Curves`` (and, with ``FixBoundary``, keep the base face's
boundary). App side only: no GUI import, so it computes in freecadcmd and headless scripts.
"""

from __future__ import annotations

import math

import FreeCAD
import Part

from varsurf.app import preferences, progress, projection
from varsurf.app.constraint import spec_of
from varsurf.app.feature import FeatureProxy, failure, last_outcome, value
from varsurf.solve import errors, settings
from varsurf.solve.sheet import solve_sheet_from_curves, solve_sheet_on_face

TYPE = "VarSurf::Sheet"
REST_SHAPES = ("Base", "None", "Installed")


_FLOAT_MAX = 1.0e12

# name, type, group, tooltip, output?
# FreeCAD's property view sorts groups by name, and properties within a group too: after its own
# Base (Label, Placement) come what users set most (Constraints: base, curves, tolerance; Energy),
# then Result and Solver, and the anisotropic weights last.
_PROPERTIES = [
    ("Base", "App::PropertyLinkSub", "Constraints", "The base face: its surface is the start shape and its boundary is kept when FixBoundary is on. Empty: the sheet starts from the best-fit plane of the curves, with a free boundary", False),
    ("Curves", "App::PropertyLinkSubList", "Constraints", "Edges the sheet must pass through; each must lie over the base face", False),
    ("Projection", "App::PropertyEnumeration", "Constraints", "How each curve finds its place on the base face. Automatic: curves of a sketch facing the base are seen along the sketch's normal (a plan view: right for sketches drawn above a curved base), other curves are projected orthogonally. Normal: every curve onto its nearest point of the base. Direction: every curve along ProjectionDirection", False),
    ("ProjectionDirection", "App::PropertyVector", "Constraints", "With Projection = Direction: the direction the curves are projected along onto the base face", False),
    ("Constraints", "App::PropertyLinkList", "Constraints", "Constraint objects (points, tangents, normals, planes, lines, attractors, directors, frozen regions)", False),
    ("RestShape", "App::PropertyEnumeration", "Energy", "Base: the energy acts on the displacement from the base face, so edits keep its detail. None: pure fairness (melted). Installed: the displacement from an installed shape", False),
    ("InstalledRest", "Part::PropertyPartShape", "Energy", "The shape installed as rest shape (install_rest_shape)", False),
    ("ExactCurves", "App::PropertyStringList", "Constraints", "Curves (as in CurveNames) met exactly wherever the spline space allows, instead of within Tolerance", False),
    ("StretchTensor", "App::PropertyFloatList", "Weight tensors", "Anisotropic stretch weights (a11, a12, a22) replacing Stretch; empty: isotropic", False),
    ("BendTensor", "App::PropertyFloatList", "Weight tensors", "Anisotropic bend weights (b11, b12, b22) replacing Bend; empty: isotropic", False),
    ("Pressure", "App::PropertyFloat", "Energy", "Inflate (> 0, along the sheet's normal) or deflate (< 0); solved by iteration", False),
    ("Energy", "App::PropertyEnumeration", "Energy", "ThinPlate: Stretch and Bend (fairness). PDE: the Bloor-Wilson PDE (d2/du2 + a^2 d2/dv2)^2 P = 0 of Du & Qin, with a set by PdeA and PdeRegions (u and v normalized to 0..1); with RestShape it acts on the displacement", False),
    ("PdeA", "App::PropertyFloatConstraint", "Energy", "PDE: the coefficient a where nothing is painted. Large a: changes along u happen over a length scale 1/a of that along v. Default 1", False),
    ("PdeRegions", "App::PropertyFloatList", "Energy", "PDE: a painted on rectangles, five numbers each: a, u0, u1, v0, v1 (u and v normalized to 0..1; later regions over earlier ones)", False),
    ("PdeBlend", "App::PropertyFloat", "Energy", "PDE: width of the band over which a blends across a painted region's border, as a fraction of the domain (0: a sharp border; at most 0.5)", False),
    ("Stretch", "App::PropertyFloatConstraint", "Energy", "Stretching weight (alpha, >= 0): penalizes first derivatives, pulls toward a membrane of least area. Default 0", False),
    ("Bend", "App::PropertyFloatConstraint", "Energy", "Bending weight (beta, >= 0): penalizes second derivatives, pulls toward a fair thin plate. Default 1", False),
    ("FixBoundary", "App::PropertyBool", "Constraints", "Keep the base face's boundary (its boundary poles are held)", False),
    ("Trim", "App::PropertyEnumeration", "Constraints", "How the sheet is bounded. Automatic: without a base face, by the closed loop among its curves (as Surface Filling does: it ends on them and sews to the faces around a hole), on a base face by the base's boundary. Loop: by the closed loop among its curves, also on a base face (a hole's loop on a larger face). None: the whole base face, or the whole best-fit rectangle", False),
    ("IncompatibleCorners", "App::PropertyStringList", "Result", "Where two G1 joins meet and their faces' tangent planes differ: the sheet cannot be tangent to both there (which joins, where, by how much)", True),
    ("BoundaryCurves", "App::PropertyStringList", "Result", "The curves of the closed loop that bounds the sheet (Trim)", True),
    ("Tolerance", "App::PropertyLength", "Constraints", "Distance at which a curve counts as met; the sheet fits the curves this closely and leaves the rest to fairness", False),
    ("SolveMode", "App::PropertyEnumeration", "Solver", "Exact: Lagrange multipliers (KKT). Penalty: penalty with refinement (PenaltyQR: by sparse QR). CG: constraints eliminated, conjugate gradients. TSVD / MTSVD: the L-curve decides how much of the curves is fitted (MTSVD smooths the rest by the energy). Automatic: by size", False),
    ("Refinement", "App::PropertyEnumeration", "Solver", "Uniform: the spans are doubled everywhere until the curves are met (up to MaxSpans). Local: only the spans under curves that are off are refined, layer by layer (up to MaxDepth); the exported sheet is one B-spline on the finest level", False),
    ("MaxDepth", "App::PropertyInteger", "Solver", "Local refinement: at most this many levels above MinSpans", False),
    ("InfluenceLevel", "App::PropertyInteger", "Solver", "Local refinement: levels coarser than this keep the start shape, so edits stay local (refined around the constraints); 0: the whole sheet may move", False),
    ("AutoRefine", "App::PropertyBool", "Solver", "Local refinement: refine where the curves are off (off: only RefineRegions)", False),
    ("RefineRegions", "App::PropertyFloatList", "Solver", "Local refinement: regions refined by hand, five numbers each: level, u0, u1, v0, v1 (u and v normalized to 0..1)", False),
    ("RefinementDepth", "App::PropertyInteger", "Result", "Local refinement: the levels reached above the base", True),
    ("RefinedSpans", "App::PropertyFloatList", "Result", "Local refinement: every refined span, five numbers each: level, u0, u1, v0, v1 (the sheet's parameters)", True),
    ("DegreesOfFreedom", "App::PropertyInteger", "Result", "Poles the solve had (Local: the hierarchical sheet's; the exported sheet has PoleCountU x PoleCountV)", True),
    ("SolveModeUsed", "App::PropertyString", "Result", "The solve mode used and why, and how many unknowns it solved (Local: the free poles, or their x, y and z when a constraint couples them)", True),
    ("LCurveResiduals", "App::PropertyFloatList", "Result", "TSVD/MTSVD: constraint residual norm per truncation k (the L-curve's x)", True),
    ("LCurveNorms", "App::PropertyFloatList", "Result", "TSVD/MTSVD: solution change norm per truncation k (the L-curve's y)", True),
    ("LCurveCorner", "App::PropertyInteger", "Result", "TSVD/MTSVD: the truncation k chosen at the L-curve's corner", True),
    ("Degree", "App::PropertyIntegerConstraint", "Solver", "Smallest degree of the sheet in u and v: the base is elevated to it (3: bicubic)", False),
    ("MinSpans", "App::PropertyIntegerConstraint", "Solver", "The base face is refined (knot insertion, shape unchanged) to at least this many spans per direction", False),
    ("MaxSpans", "App::PropertyIntegerConstraint", "Solver", "While the curves cannot be met within Tolerance, spans are doubled up to this count", False),
    ("MaxDeviations", "App::PropertyFloatList", "Result", "Largest distance (mm) from each curve to the sheet, measured on the result", True),
    ("CurveNames", "App::PropertyStringList", "Result", "The curves, in the order of MaxDeviations", True),
    ("PoleCountU", "App::PropertyInteger", "Result", "Poles of the sheet along u", True),
    ("PoleCountV", "App::PropertyInteger", "Result", "Poles of the sheet along v", True),
    ("DegreeU", "App::PropertyInteger", "Result", "Degree of the sheet along u", True),
    ("DegreeV", "App::PropertyInteger", "Result", "Degree of the sheet along v", True),
    ("SolveTime", "App::PropertyFloat", "Result", "Time of the last solve (s); Local: the whole hierarchical solve, every refinement round", True),
    ("ConstraintRank", "App::PropertyInteger", "Result", "Independent constraint rows kept by the solver", True),
    ("Status", "App::PropertyString", "Result", "Outcome of the last recompute", True),
    ("ConstraintNames", "App::PropertyStringList", "Result", "The enabled constraints, in the order of ConstraintResiduals", True),
    ("ConstraintResiduals", "App::PropertyFloatList", "Result", "How far each enabled constraint is from met, measured on the result, in ConstraintUnits", True),
    ("ConstraintUnits", "App::PropertyStringList", "Result", "Unit of each of ConstraintResiduals (mm or deg)", True),
    ("JoinNames", "App::PropertyStringList", "Result", "The G0, G1 and G2 constraints, in the order of JoinGaps, JoinAngles and JoinCurvatureJumps", True),
    ("JoinGaps", "App::PropertyFloatList", "Result", "Largest distance (mm) between the sheet and its neighbour face (G0: its edge) at 200 points along each join, measured by OpenCASCADE on the result", True),
    ("JoinAngles", "App::PropertyFloatList", "Result", "Largest angle (degrees) between the sheet's and the neighbour's tangent planes along each G1 or G2 join (G0: not measured, -1)", True),
    ("JoinCurvatureJumps", "App::PropertyFloatList", "Result", "Largest jump (%) of the normal curvature across each G1 or G2 join, relative to the larger of the two (a G2 join's target: under 1; G0: not measured, -1)", True),
]


def _set_rest_shapes(obj):
    obj.RestShape = list(REST_SHAPES)
    obj.RestShape = "Base"


_DEFAULTS = {
    "Stretch": (settings.DEFAULT_STRETCH, 0.0, _FLOAT_MAX, 0.1),
    "Bend": (settings.DEFAULT_BEND, 0.0, _FLOAT_MAX, 0.1),
    "FixBoundary": True,
    "Trim": list(settings.TRIMS),
    "RestShape": _set_rest_shapes,
    "Energy": list(settings.ENERGIES),
    "PdeA": (1.0, 1e-3, settings.MAX_PDE_A, 0.1),
    "Projection": list(projection.MODES),
    "ProjectionDirection": FreeCAD.Vector(0, 0, 1),
    "Tolerance": settings.DEFAULT_TOLERANCE,
    "SolveMode": list(settings.SOLVE_MODES),
    "Refinement": list(settings.REFINEMENTS),
    "MaxDepth": settings.DEFAULT_MAX_DEPTH,
    "AutoRefine": True,
    "Degree": (settings.SHEET_MIN_DEGREE, 2, settings.MAX_DEGREE, 1),
    "MinSpans": (settings.DEFAULT_MIN_SPANS, 1, 512, 1),
    "MaxSpans": (settings.DEFAULT_MAX_SPANS, 1, 512, 1),
    "Status": "Not computed",
}


def _restore_constraints(obj):
    # The bounds of a dynamic FloatConstraint are not written to the file; set them again.
    for name in ("Stretch", "Bend"):
        if name in obj.PropertiesList:
            number = float(getattr(obj, name))
            setattr(obj, name, (max(number, 0.0), 0.0, _FLOAT_MAX, 0.1))
    if "PdeA" in obj.PropertiesList:
        obj.PdeA = (min(max(float(obj.PdeA), 1e-3), settings.MAX_PDE_A), 1e-3, settings.MAX_PDE_A, 0.1)
    for name in ("MinSpans", "MaxSpans"):
        if name in obj.PropertiesList:
            setattr(obj, name, (min(max(int(getattr(obj, name)), 1), 512), 1, 512, 1))
    if "Degree" in obj.PropertiesList:
        obj.Degree = (min(max(int(obj.Degree), 2), settings.MAX_DEGREE), 2, settings.MAX_DEGREE, 1)
    for name, _kind, _group, _tip, output in _PROPERTIES:
        if output and name in obj.PropertiesList:
            obj.setEditorMode(name, 1)


def resolve_inputs(obj):
    """(face, edges, names) of a Sheet's links, with placements applied; SheetError if broken."""
    face = None  # no base: the sheet starts from the curves' best-fit plane
    if obj.Base is not None:
        base_obj, base_subs = obj.Base
        base_subs = [s for s in base_subs if s]
        if len(base_subs) != 1 or not base_subs[0].startswith("Face"):
            raise errors.SheetError(f"Base must reference exactly one face of {base_obj.Label}: pick one face (FaceN) "
                                    "in the Base property")
        _check_not_cyclic(obj, base_obj)
        face = _element(Part, base_obj, base_subs[0])
    edges, names = [], []
    for link_obj, subs in obj.Curves:
        for sub in subs:
            if not sub:
                continue
            name = f"{link_obj.Label}:{sub}"
            if not sub.startswith("Edge"):
                raise errors.SheetError(f"{name} is not an edge: link edges (EdgeN) as the sheet's Curves")
            _check_not_cyclic(obj, link_obj)
            edges.append(_element(Part, link_obj, sub))
            names.append(name)
    return face, edges, names


def _rest_of(obj, face):
    """The model's rest argument for the Sheet's RestShape."""
    mode = str(getattr(obj, "RestShape", "None"))
    if mode == "Base":
        return "base" if face is not None else None  # a best-fit plane has no detail to keep
    if mode == "Installed":
        shape = obj.InstalledRest
        if shape.isNull() or len(shape.Faces) != 1:
            raise errors.SheetError("RestShape is Installed but no rest shape was installed: install one (Install rest "
                                    "shape), or set RestShape to Base")
        return shape.Faces[0]
    return None


def _check_not_cyclic(obj, link_obj):
    """A link to the sheet itself, or to anything built from it, would make the sheet follow its
    own last result: refuse it (FreeCAD accepts such links in a PropertyLinkSubList)."""
    # FreeCAD's OutListRecursive raises on the cycle itself; walk the OutLists instead.
    seen, stack = set(), [link_obj]
    while stack:
        current = stack.pop()
        if current is obj:
            raise errors.SheetError(f"cyclic dependency: {link_obj.Label} is built from {obj.Label} itself; "
                                    "link curves and faces that do not depend on the sheet")
        if current.Name not in seen:
            seen.add(current.Name)
            stack.extend(current.OutList)


def _element(Part, link_obj, sub):
    try:
        shape = Part.getShape(link_obj, sub, needSubElement=True)
    except Exception as error:
        raise errors.SheetError(f"{link_obj.Label}:{sub} cannot be found ({error}): the object has changed; select "
                                "the element again") from error
    if shape.isNull():
        raise errors.SheetError(f"{link_obj.Label}:{sub} does not exist (anymore): the object has changed; select the "
                                "element again")
    return shape


def _clear_results(obj, status):
    obj.MaxDeviations = []
    obj.CurveNames = []
    obj.ConstraintRank = 0
    for name in ("ConstraintNames", "ConstraintResiduals", "ConstraintUnits", "LCurveResiduals", "LCurveNorms",
                 "RefinedSpans", "JoinNames", "JoinGaps", "JoinAngles", "JoinCurvatureJumps", "BoundaryCurves",
                 "IncompatibleCorners"):
        if name in obj.PropertiesList:
            setattr(obj, name, [])
    for name in ("RefinementDepth", "DegreesOfFreedom"):
        if name in obj.PropertiesList:
            setattr(obj, name, 0)
    if "SolveModeUsed" in obj.PropertiesList:
        obj.SolveModeUsed = ""
        obj.LCurveCorner = 0
    obj.SolveTime = 0.0
    obj.Status = status


def settings_of(obj) -> settings.SheetSettings:
    """The SheetSettings a Sheet's properties hold (with the preferences' solve limits); older
    files that lack a property get its default."""
    tensor = lambda name: list(getattr(obj, name, []) or []) or None  # noqa: E731
    return settings.SheetSettings(
        stretch=float(obj.Stretch),
        bend=float(obj.Bend),
        stretch_tensor=tensor("StretchTensor"),
        bend_tensor=tensor("BendTensor"),
        pressure=float(getattr(obj, "Pressure", 0.0)),
        energy=str(getattr(obj, "Energy", "ThinPlate")),
        pde_a=float(getattr(obj, "PdeA", 1.0)),
        pde_regions=tuple(_fives(list(getattr(obj, "PdeRegions", []) or []), "PdeRegions", "a, u0, u1, v0, v1")),
        pde_blend=float(getattr(obj, "PdeBlend", 0.0)),
        fix_boundary=bool(obj.FixBoundary),
        trim=str(getattr(obj, "Trim", "None")),
        tolerance=float(value(obj, "Tolerance")),
        exact_curves=tuple(getattr(obj, "ExactCurves", []) or []),
        degree=int(getattr(obj, "Degree", settings.SHEET_MIN_DEGREE)),
        min_spans=int(obj.MinSpans),
        max_spans=int(obj.MaxSpans),
        solve_mode=str(obj.SolveMode),
        refinement=str(getattr(obj, "Refinement", "Uniform")),
        max_depth=int(getattr(obj, "MaxDepth", settings.DEFAULT_MAX_DEPTH)),
        refine_regions=tuple(_fives(list(getattr(obj, "RefineRegions", []) or []), "RefineRegions",
                                    "level, u0, u1, v0, v1")),
        auto_refine=bool(getattr(obj, "AutoRefine", True)),
        influence_level=int(getattr(obj, "InfluenceLevel", 0)),
        **preferences.solve_limits(),
    )


def apply_settings(obj, values: settings.SheetSettings) -> None:
    """Write the settings a Sheet's make-function chooses into its properties."""
    obj.Stretch = float(values.stretch)
    obj.Bend = float(values.bend)
    obj.FixBoundary = bool(values.fix_boundary)
    obj.Tolerance = float(values.tolerance)
    obj.MinSpans = int(values.min_spans)
    obj.MaxSpans = int(values.max_spans)
    obj.Degree = int(values.degree)
    obj.SolveMode = values.solve_mode
    obj.Energy = values.energy
    obj.PdeA = float(values.pde_a)
    obj.PdeRegions = [float(x) for region in values.pde_regions for x in region]
    obj.PdeBlend = float(values.pde_blend)


def compute(obj):
    """The SheetOutcome of a Sheet's inputs (errors.SheetError naming what is wrong)."""
    face, edges, names = resolve_inputs(obj)
    values = settings_of(obj)
    unknown = [n for n in values.exact_curves if n not in names]
    if unknown:
        raise errors.SheetError(f"ExactCurves names curves the sheet does not have: {', '.join(unknown)}; remove them "
                                "from ExactCurves (names as in CurveNames)")
    inputs = dict(
        names=names,
        projections=projection.directions(obj, face, curve_links(obj)),
        constraints=[spec_of(c) for c in (getattr(obj, "Constraints", None) or []) if c.Enabled],
        rest=_rest_of(obj, face),
    )
    watch = progress.for_solve(obj.Label)
    try:
        if face is None:
            return solve_sheet_from_curves(edges, values, keep_going=watch, **inputs)
        return solve_sheet_on_face(face, edges, values, keep_going=watch, **inputs)
    finally:
        watch.stop()


def _write_joins(obj, joins):
    """Publish the joins' measurements (-1 where a G0 join has no neighbour to measure against)."""
    measured = lambda x: -1.0 if math.isnan(x) else float(x)  # noqa: E731
    obj.JoinNames = [j.name for j in joins]
    obj.JoinGaps = [float(j.gap) for j in joins]
    obj.JoinAngles = [measured(j.angle) for j in joins]
    obj.JoinCurvatureJumps = [measured(j.curvature_jump) for j in joins]


def _fives(flat, name, fields):
    """A list property's numbers in fives (RefineRegions, PdeRegions)."""
    if len(flat) % 5:
        raise errors.SheetError(f"{name} needs five numbers a region ({fields}); got {len(flat)}: give each region "
                                "all five")
    return [tuple(flat[k:k + 5]) for k in range(0, len(flat), 5)]


def curve_links(obj):
    """(link object, "EdgeN") per curve of a Sheet, in the order of its solve's curves."""
    return [(link, sub) for link, subs in obj.Curves for sub in subs if sub]


def curve_keys(obj):
    """"ObjectName:EdgeN" per curve of a Sheet, in the order of its solve's curves."""
    return [f"{link.Name}:{sub}" for link, sub in curve_links(obj)]


def outcome_of(obj):
    """The SheetOutcome of a Sheet's last recompute (solved again if this session has none)."""
    return last_outcome(obj, compute)


class SheetFeature(FeatureProxy):
    """Proxy of a VarSurf Sheet (Part::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderSheet"

    PROPERTIES = _PROPERTIES
    DEFAULTS = _DEFAULTS

    def add_properties(self, obj):
        super().add_properties(obj)
        _restore_constraints(obj)

    def onDocumentRestored(self, obj):
        older = "Projection" not in obj.PropertiesList
        trimmed = "Trim" in obj.PropertiesList
        super().onDocumentRestored(obj)
        if self.state_problem() is not None:
            return
        if older:  # files from before projection choices projected every curve orthogonally
            obj.Projection = "Normal"
        if not trimmed:  # files from before trimming to a loop keep their whole rectangle
            obj.Trim = "None"
        # Files from before a mode was added list fewer modes: offer them all, keep the choice.
        if list(obj.getEnumerationsOfProperty("SolveMode")) != list(settings.SOLVE_MODES):
            mode = str(obj.SolveMode)
            obj.SolveMode = list(settings.SOLVE_MODES)
            obj.SolveMode = mode if mode in settings.SOLVE_MODES else "Automatic"

    def onChanged(self, obj, prop):
        pass

    def consumed(self, obj):
        """A base object that is nothing but the face the sheet replaces (a plane, a loft made
        for it); a part whose face it is stays shown, as Surface Filling leaves its inputs."""
        base = getattr(obj, "Base", None)
        if base and base[0] is not None and len(getattr(base[0].Shape, "Faces", ())) == 1:
            return [base[0]]
        return []

    def execute(self, obj):
        self.outcome = None
        try:
            outcome = compute(obj)
        except Exception as error:  # fail the recompute of this object, saying why
            _clear_results(obj, f"Error: {error}")
            raise failure(obj, error) from error

        self.outcome = outcome  # for joint solves (not saved: a reopened file solves again)
        obj.Shape = outcome.shape
        obj.MaxDeviations = [float(d) for d in outcome.max_deviations]
        obj.SolveModeUsed = outcome.solve_mode
        obj.LCurveResiduals = outcome.lcurve_residuals
        obj.LCurveNorms = outcome.lcurve_norms
        obj.LCurveCorner = outcome.lcurve_corner
        obj.CurveNames = list(outcome.curve_names)
        obj.PoleCountU = outcome.pole_count_u
        obj.PoleCountV = outcome.pole_count_v
        obj.DegreeU = outcome.degree_u
        obj.DegreeV = outcome.degree_v
        obj.SolveTime = outcome.solve_seconds
        obj.ConstraintRank = outcome.constraint_rank
        obj.ConstraintNames = list(outcome.constraint_names)
        obj.ConstraintResiduals = [float(r) for r in outcome.constraint_residuals]
        obj.ConstraintUnits = list(outcome.constraint_units)
        _write_joins(obj, outcome.joins)
        obj.BoundaryCurves = list(outcome.boundary_curves)
        obj.IncompatibleCorners = [c.message() for c in outcome.corners]
        if "RefinementDepth" in obj.PropertiesList:
            obj.RefinementDepth = outcome.refinement_depth
            obj.DegreesOfFreedom = outcome.degrees_of_freedom
            obj.RefinedSpans = [float(x) for span in outcome.refined_spans for x in span]
        if not outcome.refinement_met:
            FreeCAD.Console.PrintWarning(
                f"VarSurf: {obj.Label}: local refinement reached MaxDepth {obj.MaxDepth} before every "
                "curve was within the tolerance: raise MaxDepth, or the Tolerance\n")
        if not outcome.converged:
            FreeCAD.Console.PrintWarning(
                f"VarSurf: {obj.Label}: the nonlinear solve (repellers, pressure) did not converge "
                f"in {outcome.iterations} steps; the result is the last step: give the sheet a Stretch, or weaken them\n"
            )
        n = len(outcome.max_deviations)
        obj.Status = (
            f"OK: {outcome.pole_count_u} x {outcome.pole_count_v} poles, {n} curve"
            f"{'' if n == 1 else 's'}, max deviation {outcome.max_deviation:.3g} mm"
        )
        if outcome.curvature_iterations:  # G2 is not linear: say that it was iterated, and how far it got
            obj.Status += (f", G2 in {outcome.curvature_iterations} Newton steps (largest curvature jump "
                           f"{100.0 * outcome.curvature_jump:.3g} % at the solver's samples)")
        off = [f"{name} ({dev:.3g} mm)" for name, dev in zip(outcome.curve_names, outcome.max_deviations)
               if dev > float(value(obj, "Tolerance"))]
        if off:  # met in the RMS the solve fits to, but farther somewhere: say so, in the result too
            obj.Status = obj.Status.replace("OK:", "Warning:", 1) + f"; beyond the tolerance: {', '.join(off)}"
            FreeCAD.Console.PrintWarning(
                f"VarSurf: {obj.Label}: curves farther than the tolerance {float(value(obj, 'Tolerance')):.3g} mm somewhere: "
                f"{', '.join(off)} (operators pull the sheet off its curves, or it has too few spans): raise MaxSpans, "
                "or weaken the operators\n")
        for corner in outcome.corners:  # reported where it is, not smeared over the sheet
            obj.Status = obj.Status.replace("OK:", "Warning:", 1) + f"; {corner.message()}"
            FreeCAD.Console.PrintWarning(f"VarSurf: {obj.Label}: {corner.message()}\n")
