# SPDX-License-Identifier: LGPL-2.1-or-later
"""What each command does when activated, headless too: check the selection, then run the
command's macro lines (recorded in the GUI) in one transaction; an unusable selection is reported
(report view, and ``on_error``, e.g. a dialog) and creates nothing."""

from __future__ import annotations

import FreeCAD

from varsurf.app import macro, references, selection, tube
from varsurf.app.transaction import run_in_transaction

#: Names of the undo transactions the commands open.
TRANSACTION_CREATE = "Create VarSurf sheet"
TRANSACTION_SOLID = "Add VarSurf solid"
TRANSACTION_CONSTRAINT = "Add VarSurf constraint"
TRANSACTION_SPACE_CURVE = "Add VarSurf space curve"
TRANSACTION_PDE_SURFACE = "Add VarSurf PDE surface"
TRANSACTION_HINGE = "Add VarSurf hinge"
TRANSACTION_FILL_HOLE = "Fill hole with VarSurf sheet"
TRANSACTION_TUBE = "Add VarSurf tube"
TRANSACTION_SUBD = "Add VarSurf subdivision surface"
TRANSACTION_SUBD_BREP = "Add VarSurf subdivision B-rep"
TRANSACTION_TRIANGULAR = "Add VarSurf triangular surface"


def _report(error, on_error):
    FreeCAD.Console.PrintError(f"VarSurf: {error}\n")
    if on_error is not None:
        on_error(str(error))


def create_sheet_from_selection(selection_ex, do_command=None):
    """Validate the selection and create a sheet through macro lines, in one undo transaction.

    do_command runs one line (FreeCADGui.doCommand in the GUI, so the lines are recorded in
    macros); without it the lines are exec()'d. Raises ValueError for an unusable selection,
    creating nothing. Returns the new Sheet object.
    """
    base, curves = selection.selection_to_sheet_args(selection_ex)
    return run_in_transaction(base[0].Document, TRANSACTION_CREATE, macro.sheet_command_lines(base, curves),
                              do_command, keep=references.is_sheet)


def run_sheet_command(selection_ex, do_command=None, on_error=None):
    """What the VarSurf_Sheet command does: a Sheet on the selected face through the selected
    edges. Returns the new Sheet or None."""
    try:
        return create_sheet_from_selection(selection_ex, do_command=do_command)
    except ValueError as error:
        _report(error, on_error)
        return None


def run_solid_command(selection_ex, do_command=None, on_error=None):
    """What the VarSurf_Solid command does: join the selected Sheets. Returns the new Solid or
    None."""
    try:
        sheets = selection.solid_selection_to_sheets(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(sheets[0].Document, TRANSACTION_SOLID, macro.solid_command_lines(sheets), do_command)


def run_constraint_command(kind: str, selection_ex, do_command=None, on_error=None):
    """What a constraint command does: the constraint of ``kind`` on the selected Sheet. Returns
    the new Constraint or None."""
    try:
        sheet, args = selection.constraint_selection_to_args(kind, selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(sheet.Document, TRANSACTION_CONSTRAINT,
                              macro.constraint_command_lines(kind, sheet, args), do_command)


def run_space_curve_command(selection_ex, do_command=None, on_error=None):
    """What VarSurf_SpaceCurve does: a SpaceCurve on the selected edge."""
    try:
        obj, sub = selection.space_curve_selection_to_base(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(obj.Document, TRANSACTION_SPACE_CURVE, macro.space_curve_command_lines(obj, sub),
                              do_command)


def run_pde_surface_command(selection_ex, do_command=None, on_error=None):
    """What VarSurf_PdeSurface does: a PdeSurface between the selected boundary curves (and their
    derivative curves, or the Coons sides). Returns it, or None."""
    try:
        args = selection.pde_surface_selection_to_args(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(args["u0"][0].Document, TRANSACTION_PDE_SURFACE, macro.pde_surface_command_lines(args),
                              do_command)


def run_subd_surface_command(selection_ex, do_command=None, on_error=None):
    """What VarSurf_SubdSurface does: a SubdSurface of the selected cage, capturing the second
    selected object's detail. Returns it, or None."""
    try:
        cage, target = selection.subd_surface_selection_to_args(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(cage.Document, TRANSACTION_SUBD, macro.subd_surface_command_lines(cage, target),
                              do_command)


def run_subd_brep_command(selection_ex, do_command=None, on_error=None):
    """What VarSurf_SubdBRep does: the selected SubdSurface's limit surface as B-rep faces."""
    try:
        subd = selection.subd_brep_selection_to_args(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(subd.Document, TRANSACTION_SUBD_BREP, macro.subd_brep_command_lines(subd), do_command)


def run_triangular_command(selection_ex, do_command=None, on_error=None):
    """What VarSurf_TriangularSurface does: a G1 surface of triangular patches over the selected
    mesh."""
    try:
        source = selection.triangular_selection_to_args(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(source.Document, TRANSACTION_TRIANGULAR, macro.triangular_command_lines(source),
                              do_command)


def run_fill_hole_command(selection_ex, do_command=None, on_error=None):
    """What VarSurf_FillHole does: a FillHole of the selected part's face or free edges, with the
    other selected curves inside. Returns the new FillHole or None."""
    try:
        part, elements, curves = selection.fill_hole_selection_to_args(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(part.Document, TRANSACTION_FILL_HOLE,
                              macro.fill_hole_command_lines(part, elements, curves), do_command)


def run_hinge_command(selection_ex, do_command=None, on_error=None, angle: float = 180.0):
    """What VarSurf_Hinge does: a Hinge between the selected Sheets."""
    try:
        solid, a, b, (obj, sub) = selection.hinge_selection_to_args(selection_ex)
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(solid.Document, TRANSACTION_HINGE,
                              macro.hinge_command_lines(solid, a, b, obj, sub, angle),
                              do_command,
                              keep=lambda o: getattr(getattr(o, "Proxy", None), "Type", None) == "VarSurf::Hinge")


def run_tube_command(selection_ex, do_command=None, on_error=None):
    """What VarSurf_Tube does: a closed Sheet through the selected closed sections and curves.
    Returns the new tube Sheet or None (sections with corners, or that cannot be ordered, are
    reported and create nothing)."""
    try:
        sections, curves = selection.tube_selection_to_args(selection_ex)
        tube.ordered_sections(sections)  # make_tube's own refusals, before the transaction opens
    except ValueError as error:
        _report(error, on_error)
        return None
    return run_in_transaction(sections[0].Document, TRANSACTION_TUBE, macro.tube_command_lines(sections, curves),
                              do_command, keep=references.is_sheet)
