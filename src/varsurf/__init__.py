# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf: variational B-spline surface modeling for FreeCAD.

The package has one folder per tier: ``varsurf.solve`` (the computation, without FreeCAD),
``varsurf.app`` (document features and the scripting API, headless) and ``varsurf.gui``. The
public API (importable headless, without any GUI module):

    make_sheet(base, curves, stretch=0.0, bend=1.0, fix_boundary=True)  -> Sheet object
    make_constraint(sheet, kind, location=None, uv=None, vector=None, ...) -> Constraint object
    make_solid(sheets, tolerance=None)                                  -> Solid object
    make_fill_hole(part, "FaceN" or ["EdgeN", ...], curves, "G1")       -> FillHole object
    make_tube([section, ...], curves)                                   -> Sheet object (closed)
    make_space_curve((obj, "EdgeN"), handle_parameters, handles)        -> SpaceCurve object
    move_handle(space_curve, index, position)
    make_hinge(solid, sheet_a, sheet_b, (obj, "EdgeN"), angle=180)      -> Hinge object
    make_pde_surface(u0, u1, derivative0=None, ..., a=1.0)              -> PdeSurface object
    make_subd_surface(cage, levels=3, target=None, pins=(), normals=())  -> SubdSurface object
    set_pins(subd, pins), set_normals(subd, normals), move_pin(subd, i, point)
    set_curves(subd, [(obj, "EdgeN")], placement, level=None, influence=0)
    make_subd_brep(subd_surface, isolation=4)                           -> SubdBRep object (B-rep)
    make_triangular_surface(mesh, degree=3, constraints=())             -> TriangularSurface object
    set_triangular_constraints(surface, [(kind, triangle, at, target, direction)])
    install_rest_shape(sheet), melt(sheet)                              -> sheet
    export_step(objects, path)                                           -> path
    selection_to_sheet_args(selection_ex)                                -> (base, curves)
    solve_sheet_on_face(face, edges, settings, ...)                      -> SheetOutcome
    solve_sheet_from_curves(edges, settings, ...)                        -> SheetOutcome
    SheetSettings(stretch=..., tolerance=..., ...)                       a sheet's settings
"""

import importlib
import importlib.abc
import importlib.util
import sys

__version__ = "0.1.0"

from varsurf.solve.environment import require_numpy  # noqa: E402

require_numpy()  # one clear line, not a traceback from deep inside, when this Python lacks it

from varsurf.solve.errors import SheetError  # noqa: E402
from varsurf.solve.outcome import SheetOutcome  # noqa: E402
from varsurf.solve.plane_fit import plane_face_for_curves  # noqa: E402
from varsurf.solve.settings import (  # noqa: E402
    DEFAULT_BEND,
    DEFAULT_MAX_SPANS,
    DEFAULT_MIN_SPANS,
    DEFAULT_RANK_TOLERANCE,
    DEFAULT_STRETCH,
    DEFAULT_TOLERANCE,
    SheetSettings,
)
from varsurf.solve.sheet import solve_sheet_from_curves, solve_sheet_on_face  # noqa: E402

#: Modules of earlier releases, now elsewhere: scripts and recorded macros that import them (for
#: instance ``import varsurf.analysis`` before ``varsurf.analysis.plot_lcurve(...)``) keep working.
#: An old name with several new homes gets a module that looks its names up in each, in order.
MOVED = {
    "varsurf.model": ("varsurf.solve.sheet", "varsurf.solve.settings", "varsurf.solve.errors",
                      "varsurf.solve.native", "varsurf.solve.outcome", "varsurf.solve.plane_fit"),
    "varsurf.constraints": ("varsurf.solve.constraints",),
    "varsurf.assembly": ("varsurf.solve.assembly",),
    "varsurf.joint": ("varsurf.solve.joint",),
    "varsurf.space_curve": ("varsurf.solve.space_curve", "varsurf.solve.shapes"),
    "varsurf.analysis": ("varsurf.app.analysis", "varsurf.solve.analysis"),
    "varsurf.persistence": ("varsurf.app.persistence",),
    "varsurf.api": ("varsurf.app.api", "varsurf.app.macro", "varsurf.app.actions"),
    "varsurf.joints_api": ("varsurf.app.api", "varsurf.app.actions"),
    "varsurf.drag": ("varsurf.app.drag",),
    "varsurf.progress": ("varsurf.app.progress",),
    "varsurf.preferences": ("varsurf.app.preferences",),
}


class _Moved(importlib.abc.Loader):
    """Loads an old module name as its new module, or as a module looking names up in several."""

    def create_module(self, spec):
        homes = [importlib.import_module(name) for name in MOVED[spec.name]]
        if len(homes) == 1:
            return homes[0]
        module = type(sys)(spec.name, homes[0].__doc__)

        def find(name):
            for home in homes:
                if hasattr(home, name):
                    return getattr(home, name)
            raise AttributeError(f"module {spec.name!r} has no attribute {name!r}")

        module.__getattr__ = find
        return module

    def exec_module(self, module):
        pass


class _MovedFinder(importlib.abc.MetaPathFinder):
    def find_spec(self, fullname, path=None, target=None):
        if fullname in MOVED:
            return importlib.util.spec_from_loader(fullname, _Moved())
        return None


if not any(isinstance(f, _MovedFinder) for f in sys.meta_path):
    sys.meta_path.insert(0, _MovedFinder())


#: The document-level API (varsurf.app.api), which needs FreeCAD.
APP_API = (
    "make_sheet", "make_constraint", "make_solid", "make_fill_hole", "make_tube", "install_rest_shape", "melt",
    "export_step",
    "make_space_curve", "make_hinge", "move_handle", "selection_to_sheet_args", "selection_problem",
    "create_sheet_from_selection", "sheet_command_lines", "is_sheet", "run_sheet_command",
    "run_space_curve_command", "run_hinge_command", "make_pde_surface", "run_pde_surface_command",
    "is_pde_surface", "make_subd_surface", "make_subd_brep", "is_subd_surface", "set_pins", "set_normals",
    "set_curves", "move_pin",
    "run_subd_surface_command", "run_subd_brep_command",
    "make_triangular_surface", "is_triangular_surface", "run_triangular_command", "set_triangular_constraints",
)


def __getattr__(name):
    if name in APP_API:
        # Loaded on first use, so that `import varsurf` also works where only the native
        # extension and the math are wanted (no FreeCAD).
        from varsurf.app import api

        return getattr(api, name)
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
    "SheetSettings",
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
    "make_fill_hole",
    "make_tube",
    "make_space_curve",
    "move_handle",
    "make_hinge",
    "make_pde_surface",
    "make_subd_surface",
]
