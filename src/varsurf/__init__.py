"""VarSurf: variational B-spline surface modeling for FreeCAD.

App-side public API (importable headless, without any GUI module):

    make_sheet(base, curves, stretch=0.0, bend=1.0, fix_boundary=True)  -> Sheet object
    make_constraint(sheet, kind, location=None, uv=None, vector=None, ...) -> Constraint object
    make_solid(sheets, tolerance=None)                                  -> Solid object
    make_space_curve((obj, "EdgeN"), handle_parameters, handles)        -> SpaceCurve object
    move_handle(space_curve, index, position)
    make_hinge(solid, sheet_a, sheet_b, (obj, "EdgeN"), angle=180)      -> Hinge object
    install_rest_shape(sheet), melt(sheet)                              -> sheet
    export_step(objects, path)                                           -> path
    selection_to_sheet_args(selection_ex)                                -> (base, curves)
    solve_sheet_on_face(face, edges, ...)                                -> SheetOutcome
    solve_sheet_from_curves(edges, ...)                                  -> SheetOutcome
"""

__version__ = "0.1.0"

from varsurf.model import (  # noqa: E402
    DEFAULT_BEND,
    DEFAULT_RANK_TOLERANCE,
    DEFAULT_TOLERANCE,
    DEFAULT_MIN_SPANS,
    DEFAULT_MAX_SPANS,
    DEFAULT_STRETCH,
    SheetError,
    SheetOutcome,
    solve_sheet_on_face,
    solve_sheet_from_curves,
    plane_face_for_curves,
)


def __getattr__(name):
    # The document-level API needs FreeCAD; load it on first use so that `import varsurf` also
    # works where only the native extension and the math are wanted.
    if name in ("make_sheet", "make_constraint", "make_solid", "install_rest_shape", "melt", "export_step", "selection_to_sheet_args", "selection_problem",
                "create_sheet_from_selection", "sheet_command_lines", "is_sheet",
                "run_sheet_command"):
        from varsurf import api

        return getattr(api, name)
    if name in ("make_space_curve", "make_hinge", "move_handle", "run_space_curve_command", "run_hinge_command"):
        from varsurf import joints_api

        return getattr(joints_api, name)
    raise AttributeError(f"module 'varsurf' has no attribute {name!r}")


__all__ = [
    "__version__",
    "DEFAULT_BEND",
    "DEFAULT_RANK_TOLERANCE",
    "DEFAULT_TOLERANCE",
    "DEFAULT_MIN_SPANS",
    "DEFAULT_MAX_SPANS",
    "DEFAULT_STRETCH",
    "SheetError",
    "SheetOutcome",
    "solve_sheet_on_face",
    "solve_sheet_from_curves",
    "plane_face_for_curves",
    "make_sheet",
    "make_constraint",
    "install_rest_shape",
    "melt",
    "export_step",
    "selection_to_sheet_args",
    "selection_problem",
    "create_sheet_from_selection",
    "sheet_command_lines",
    "is_sheet",
    "run_sheet_command",
    "make_solid",
    "make_space_curve",
    "move_handle",
    "make_hinge",
]
