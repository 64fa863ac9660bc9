# SPDX-License-Identifier: LGPL-2.1-or-later
"""The TriangularSurface feature: the fairest G1 surface of triangular Bezier patches over a
triangle mesh (Veltkamp & Wesselink), one patch per triangle, through the mesh's vertices; its
Shape is the patches written exactly as tensor-product Bezier faces (three per patch) sewn into a
shell, or a solid when the mesh is closed. Parametric: editing the mesh or a setting recomputes
it. The computation is varsurf.solve.triangular."""

from __future__ import annotations

import FreeCAD

from varsurf.app.feature import FeatureProxy, mark_failed, value
from varsurf.app.subdivision import target_triangles
from varsurf.app.view_link import attach as attach_view_provider
from varsurf.solve import curve_insertion, errors, triangular
from varsurf.solve.shapes import shape_from_brep

TYPE = "VarSurf::TriangularSurface"

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Source", "App::PropertyLink", "TriangularSurface", "The triangulation: a Mesh (each triangle becomes a patch through its corners), or a shape whose faces are tessellated", False),
    ("Degree", "App::PropertyIntegerConstraint", "TriangularSurface", "Degree of every patch (3: the paper's cubics; higher degrees meet G1 with more freedom)", False),
    ("Curves", "App::PropertyLinkSubList", "TriangularSurface", "Edges the surface contains (sketch lines, arcs, splines): the triangles each crosses are split so that mesh edges carry it", False),
    ("InterpolateVertices", "App::PropertyBool", "TriangularSurface", "The surface passes through every vertex of the mesh (off: the vertices are free like the other control points, and point constraints or operators hold the surface)", False),
    ("RestShape", "App::PropertyBool", "Energy", "The energy is of the displacement from the mesh's own flat triangles (sculpting: operators and constraints move the mesh, which stays where nothing pulls) instead of the surface's own", False),
    ("Stretch", "App::PropertyFloat", "Energy", "Weight of the stretch energy (area-like)", False),
    ("Bend", "App::PropertyFloat", "Energy", "Weight of the bend energy (thin plate)", False),
    ("G1", "App::PropertyBool", "Continuity", "Tangent-plane continuity across every inner edge (the default constraints)", False),
    ("ApproximateG1", "App::PropertyBool", "Continuity", "The weaker variant: G1 at the vertices, one condition between them", False),
    ("BorderAngle", "App::PropertyAngle", "Continuity", "The angle the surface turns through at each border vertex (0: the angle the mesh's own triangles span there)", False),
    ("Solver", "App::PropertyEnumeration", "Solve", "Direct (sparse Cholesky), CG (conjugate gradients) or Automatic", False),
    ("Tolerance", "App::PropertyLength", "Solve", "Sewing tolerance (mm; 0: a ten-millionth of the mesh's size)", False),
    ("ConstraintKinds", "App::PropertyStringList", "Constraints", "Per constraint: Point (the surface passes through Target), Normal (its normal is Direction), Plane (the point lies in the plane through Target normal to Direction) or Line (on the line through Target along Direction)", False),
    ("ConstraintTriangles", "App::PropertyIntegerList", "Constraints", "Per constraint: the mesh triangle it sits on (numbered as the mesh's facets)", False),
    ("ConstraintAt", "App::PropertyVectorList", "Constraints", "Per constraint: where on its triangle, in barycentric coordinates of its corners (each >= 0, summing to 1)", False),
    ("ConstraintTargets", "App::PropertyVectorList", "Constraints", "Per constraint: the point it holds (Point), or a point of its plane or line", False),
    ("ConstraintDirections", "App::PropertyVectorList", "Constraints", "Per constraint: the normal (Normal, Plane) or the line's direction (Line); unused by Point", False),
    ("OperatorKinds", "App::PropertyStringList", "Operators", "Per operator: PointAttractor, PlaneAttractor, LineAttractor (pull toward Origin: a point, the plane normal to Direction, the line along it), Director (normals toward Direction), Repeller (away from Origin) or ShapeAttractor (onto the next of OperatorTargets)", False),
    ("OperatorTriangles", "App::PropertyStringList", "Operators", "Per operator: the triangles it acts on, numbers separated by spaces (empty: all)", False),
    ("OperatorOrigins", "App::PropertyVectorList", "Operators", "Per operator: its point (attractors, Repeller)", False),
    ("OperatorDirections", "App::PropertyVectorList", "Operators", "Per operator: the plane's normal, the line's direction or the Director's", False),
    ("OperatorStrengths", "App::PropertyFloatList", "Operators", "Per operator: its strength (1 pulls about as hard as the surface resists)", False),
    ("OperatorTargets", "App::PropertyLinkList", "Operators", "The shapes the ShapeAttractors pull onto, in their order", False),
    ("ConstraintResidual", "App::PropertyFloat", "Result", "The worst constraint's residual (mm; Normal: sine of the angle)", True),
    ("Closed", "App::PropertyBool", "Result", "True if the faces close into a solid", True),
    ("PatchCount", "App::PropertyInteger", "Result", "Triangular patches (one per triangle, after the splits along Curves)", True),
    ("SplitTriangles", "App::PropertyInteger", "Result", "Triangles of the mesh split so that mesh edges carry the Curves", True),
    ("CurveFit", "App::PropertyFloat", "Result", "How far the patch edges carrying the Curves stray from them at most (mm)", True),
    ("FoldedPatches", "App::PropertyIntegerList", "Result", "Patches whose surface turns over inside (a fold: the faces self-intersect)", True),
    ("SelfIntersections", "App::PropertyInteger", "Result", "Self-intersection faults OCCT's full check finds in the shape (checked when Curves split the mesh)", True),
    ("FaceCount", "App::PropertyInteger", "Result", "B-rep faces: three tensor-product Bezier faces per patch", True),
    ("Unknowns", "App::PropertyInteger", "Result", "Free control-point coordinates solved for", True),
    ("WorstAngle", "App::PropertyFloat", "Result", "The largest angle between the normals of two patches along their shared edge (degrees, 50 points an edge)", True),
    ("SeamAngle", "App::PropertyFloat", "Result", "The largest angle between tangent planes across any seam of the B-rep, the patches' internal seams included (degrees)", True),
    ("OverruledEdges", "App::PropertyInteger", "Result", "Inner edges whose patches meet at more than 0.01 degree", True),
    ("SingularVertices", "App::PropertyIntegerList", "Result", "Vertices where the surface's tangents nearly collapse", True),
    ("SolveTime", "App::PropertyFloat", "Result", "Seconds to assemble and solve", True),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]


def _set_solver(obj):
    obj.Solver = list(triangular.SOLVERS)
    obj.Solver = "Automatic"


class TriangularSurfaceFeature(FeatureProxy):
    """Proxy of a VarSurf TriangularSurface (Part::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderTriangularSurface"
    PROPERTIES = _PROPERTIES
    DEFAULTS = {"Degree": (3, 3, 12, 1), "Bend": 1.0, "G1": True, "Solver": _set_solver, "InterpolateVertices": True}

    def consumed(self, obj):
        source = getattr(obj, "Source", None)
        return [source] if source is not None else []

    def execute(self, obj):
        try:
            outcome = compute(obj)
        except Exception as error:
            raise mark_failed(obj, error) from error
        self.outcome = outcome
        obj.Shape = shape_from_brep(outcome.brep)
        report = outcome.report
        obj.Closed = outcome.closed
        obj.PatchCount, obj.FaceCount, obj.Unknowns = report.patches, outcome.faces, report.unknowns
        obj.SplitTriangles, obj.CurveFit = outcome.split_triangles, outcome.curve_fit
        obj.FoldedPatches = list(outcome.folded)
        obj.WorstAngle, obj.SeamAngle = report.worst_angle, outcome.seam_angle
        obj.OverruledEdges = len(report.overruled_edges)
        obj.SingularVertices = list(report.singular_vertices)
        obj.SolveTime = report.assembly_seconds + report.solve_seconds
        obj.ConstraintResidual = report.constraint_residual
        kind = "solid" if outcome.closed else "open shell"
        obj.Status = (f"OK: {kind} of {outcome.faces} Bezier faces from {report.patches} patches of degree "
                      f"{int(obj.Degree)}; patches meet within {report.worst_angle:.2g}°")
        if outcome.split_triangles:
            # Split along curves, the surface can fold or overlap itself where the remeshing left
            # crowded vertices (README); OCCT's full check says so before the user builds on it.
            faults = self_intersections(obj.Shape)
            obj.SelfIntersections = faults
            if faults:
                outcome.warnings.insert(0, f"OCCT's check finds {faults} self-intersections: raise Degree, move the "
                                           "curves or remesh there")
        else:
            obj.SelfIntersections = 0
        if outcome.warnings:
            obj.Status = f"{obj.Status}; " + "; ".join(outcome.warnings)
            FreeCAD.Console.PrintWarning(f"{obj.Label}: {outcome.warnings[0]}\n")


def self_intersections(shape) -> int:
    """How many self-intersection faults OCCT's full check (BRepCheck and the Boolean operations'
    checks) finds in `shape`."""
    try:
        shape.check(True)
    except ValueError as fault:  # FreeCAD raises with the list of faults
        return max(1, str(fault).count("SelfIntersect"))
    return 0


def settings_of(obj) -> triangular.Settings:
    return triangular.Settings(
        degree=int(obj.Degree), stretch=float(obj.Stretch), bend=float(obj.Bend), g1=bool(obj.G1),
        approximate_g1=bool(obj.ApproximateG1), border_angle=float(value(obj, "BorderAngle")) or -1.0,
        solver=str(obj.Solver), interpolate_vertices=bool(obj.InterpolateVertices),
        rest_shape=bool(obj.RestShape))


KINDS = ("Point", "Normal", "Plane", "Line")


def constraints_of(obj):
    """The feature's constraints (its Constraint* lists) as triangular.Constraint values."""
    kinds = list(obj.ConstraintKinds)
    lists = {"ConstraintTriangles": list(obj.ConstraintTriangles), "ConstraintAt": list(obj.ConstraintAt),
             "ConstraintTargets": list(value(obj, "ConstraintTargets")),
             "ConstraintDirections": list(value(obj, "ConstraintDirections"))}
    for name in ("ConstraintTriangles", "ConstraintAt"):
        if len(lists[name]) != len(kinds):
            raise errors.SheetError(f"{name} has {len(lists[name])} entries for {len(kinds)} ConstraintKinds: give one "
                                    "per constraint")
    for name in ("ConstraintTargets", "ConstraintDirections"):
        if lists[name] and len(lists[name]) != len(kinds):
            raise errors.SheetError(f"{name} has {len(lists[name])} entries for {len(kinds)} ConstraintKinds: give one "
                                    "per constraint (or none)")
    out = []
    for k, kind in enumerate(kinds):
        if kind not in KINDS:
            raise errors.SheetError(f"constraint {k} is of kind {kind!r}: set one of {', '.join(KINDS)}")
        at = lists["ConstraintAt"][k]
        target = lists["ConstraintTargets"][k] if lists["ConstraintTargets"] else FreeCAD.Vector()
        direction = lists["ConstraintDirections"][k] if lists["ConstraintDirections"] else FreeCAD.Vector(0, 0, 1)
        out.append(triangular.Constraint(kind.lower(), int(lists["ConstraintTriangles"][k]), (at.x, at.y, at.z),
                                         (target.x, target.y, target.z), (direction.x, direction.y, direction.z)))
    return out


def operators_of(obj):
    """The feature's operators (its Operator* lists) as triangular.Operator values."""
    kinds = list(getattr(obj, "OperatorKinds", []) or [])
    if not kinds:
        return []
    lists = {"OperatorTriangles": list(obj.OperatorTriangles), "OperatorOrigins": list(value(obj, "OperatorOrigins")),
             "OperatorDirections": list(value(obj, "OperatorDirections")),
             "OperatorStrengths": list(obj.OperatorStrengths)}
    for name, entries in lists.items():
        if entries and len(entries) != len(kinds):
            raise errors.SheetError(f"{name} has {len(entries)} entries for {len(kinds)} OperatorKinds: give one per "
                                    "operator (or none)")
    targets = list(obj.OperatorTargets or [])
    if len(targets) != kinds.count("ShapeAttractor"):
        raise errors.SheetError(f"OperatorTargets has {len(targets)} shapes for {kinds.count('ShapeAttractor')} "
                                "ShapeAttractors: link one shape per ShapeAttractor")
    out = []
    for k, kind in enumerate(kinds):
        text = lists["OperatorTriangles"][k] if lists["OperatorTriangles"] else ""
        try:
            triangles = [int(t) for t in str(text).replace(",", " ").split()]
        except ValueError as error:
            raise errors.SheetError(f"operator {k}'s triangles {text!r} are not numbers: give triangle numbers "
                                    "separated by spaces") from error
        origin = lists["OperatorOrigins"][k] if lists["OperatorOrigins"] else FreeCAD.Vector()
        direction = lists["OperatorDirections"][k] if lists["OperatorDirections"] else FreeCAD.Vector(0, 0, 1)
        strength = lists["OperatorStrengths"][k] if lists["OperatorStrengths"] else 1.0
        brep = ""
        if kind == "ShapeAttractor":
            brep = targets.pop(0).Shape.exportBrepToString()
        out.append(triangular.Operator(kind, triangles, (origin.x, origin.y, origin.z),
                                       (direction.x, direction.y, direction.z), float(strength), brep))
    return out


def curve_paths(obj):
    """The feature's Curves as curve_insertion.CurvePath values, in the order linked (a link
    without sub-elements: all its edges)."""
    out = []
    for link, subs in list(getattr(obj, "Curves", []) or []):
        names = [s for s in subs if s] or [f"Edge{k + 1}" for k in range(len(link.Shape.Edges))]
        for sub in names:
            try:
                edge = link.Shape.getElement(sub)
            except Exception as error:  # FreeCAD raises a plain Exception for a missing element
                raise errors.SheetError(f"curve {link.Label}.{sub} does not exist: link an edge of "
                                        f"{link.Label}") from error
            if edge.ShapeType != "Edge" or edge.Length <= 0.0:
                raise errors.SheetError(f"curve {link.Label}.{sub} is not an edge of length: link edges as Curves")
            out.append(curve_insertion.CurvePath(
                f"{link.Label}.{sub}", lambda t, e=edge: tuple(e.valueAt(t)), edge.FirstParameter,
                edge.LastParameter, lambda t, e=edge: tuple(e.derivative1At(t))))
    return out


def _constraints_on(insertion, constraints, count):
    """The constraints moved from the source's triangles onto the split ones."""
    out = []
    for k, c in enumerate(constraints):
        if not 0 <= c.triangle < count:
            raise errors.SheetError(f"constraint {k} names triangle {c.triangle}, the mesh has {count}: give a "
                                    "triangle of the mesh")
        if min(c.at) < -1e-9 or abs(sum(c.at) - 1.0) > 1e-9:
            raise errors.SheetError(f"constraint {k} lies outside its triangle (barycentric {tuple(c.at)}): give "
                                    "coordinates of at least 0 summing to 1")
        triangle, at = insertion.locate(c.triangle, c.at)
        out.append(triangular.Constraint(c.kind, triangle, at, c.target, c.direction))
    return out


def _operators_on(insertion, operators):
    """The operators' triangles renumbered as the split triangles that lie in them."""
    return [triangular.Operator(op.kind, sorted({t for s in op.triangles for t in insertion.triangles_of(int(s))}),
                                op.origin, op.direction, op.strength, op.target_brep) if op.triangles else op
            for op in operators]


def compute(obj) -> triangular.Outcome:
    """The surface of the feature's Source with its settings, and its B-rep: with Curves, the
    mesh's triangles split so that its edges carry them (curve_insertion)."""
    source = obj.Source
    if source is None:
        raise errors.SheetError("no Source: link a Mesh (a coarse triangle mesh) whose triangles become patches")
    points, triangles = target_triangles(source)
    if not triangles:
        raise errors.SheetError(f"{source.Label} has no triangles: give a Mesh with facets as Source")
    constraints, operators, curves = constraints_of(obj), operators_of(obj), curve_paths(obj)
    settings, tolerance = settings_of(obj), float(value(obj, "Tolerance"))
    if not curves:
        return triangular.solve(points, triangles, settings, constraints, tolerance=tolerance, operators=operators)
    for k, op in enumerate(operators):
        for t in op.triangles:
            if not 0 <= int(t) < len(triangles):
                raise errors.SheetError(f"operator {k} names triangle {t}, the mesh has {len(triangles)}: give "
                                        "triangles of the mesh")
    box = FreeCAD.BoundBox()
    for p in points:
        box.add(FreeCAD.Vector(*p))
    # A vertex is on a curve, and a carried piece follows its curve, within a millionth of the
    # mesh's size.
    near = 1e-6 * max(box.DiagonalLength, 1e-12)
    insertion = curve_insertion.insert_curves(points, triangles, curves, near, int(obj.Degree), near)
    outcome = triangular.solve(insertion.points, insertion.triangles, settings,
                               _constraints_on(insertion, constraints, len(triangles)), tolerance=tolerance,
                               operators=_operators_on(insertion, operators),
                               fixed_edges=curve_insertion.carried_edges(insertion, int(obj.Degree)))
    outcome.split_triangles, outcome.curve_fit = insertion.split, insertion.fit_error
    if insertion.fit_error > near:
        outcome.warnings.append(f"the curves are carried within {insertion.fit_error:.3g} mm only: raise Degree")
    if insertion.moved:
        listed = ", ".join(str(v) for v, _ in insertion.moved[:8])
        farthest = max(gap for _, gap in insertion.moved)
        outcome.warnings.append(f"vertices {listed} of the mesh moved onto the curves (up to {farthest:.3g} mm): "
                                "move them onto the curves in the mesh to keep them")
    return outcome


def is_triangular_surface(obj) -> bool:
    return getattr(getattr(obj, "Proxy", None), "Type", "") == TYPE


def set_constraints(obj, constraints):
    """Replace a TriangularSurface's constraints by ``constraints``: (kind, triangle, barycentric
    point, target, direction) tuples or triangular.Constraint values, kind one of KINDS."""
    rows = [(c.kind.capitalize(), c.triangle, c.at, c.target, c.direction) if isinstance(c, triangular.Constraint)
            else tuple(c) + ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0))[len(c) - 3:] for c in constraints]
    obj.ConstraintKinds = [str(r[0]) for r in rows]
    obj.ConstraintTriangles = [int(r[1]) for r in rows]
    obj.ConstraintAt = [FreeCAD.Vector(*r[2]) for r in rows]
    obj.ConstraintTargets = [FreeCAD.Vector(*r[3]) for r in rows]
    obj.ConstraintDirections = [FreeCAD.Vector(*r[4]) for r in rows]


def set_operators(obj, operators):
    """Replace a TriangularSurface's operators by ``operators``: (kind, triangles, origin, direction,
    strength[, target]) tuples, kind one of triangular.OPERATOR_KINDS, triangles a list (empty: all),
    target the document object a ShapeAttractor pulls onto."""
    rows = [tuple(o) + (None,) * (6 - len(o)) for o in operators]
    obj.OperatorKinds = [str(r[0]) for r in rows]
    obj.OperatorTriangles = [" ".join(str(int(t)) for t in r[1]) for r in rows]
    obj.OperatorOrigins = [FreeCAD.Vector(*r[2]) for r in rows]
    obj.OperatorDirections = [FreeCAD.Vector(*r[3]) for r in rows]
    obj.OperatorStrengths = [float(r[4]) for r in rows]
    obj.OperatorTargets = [r[5] for r in rows if r[5] is not None]


def make_triangular_surface(source, degree: int = 3, constraints=(), operators=(), name: str = "TriangularSurface"):
    """Add a TriangularSurface over ``source`` (a Mesh object, or a shape whose faces are
    tessellated): a patch of degree ``degree`` per triangle, with ``constraints`` (see
    set_constraints) and ``operators`` (see set_operators; computed at the next recompute)."""
    obj = source.Document.addObject("Part::FeaturePython", name)
    TriangularSurfaceFeature(obj)
    obj.Source = source
    obj.Degree = int(degree)
    set_constraints(obj, constraints)
    set_operators(obj, operators)
    attach_view_provider(obj, "ViewProviderTriangularSurface")
    return obj
