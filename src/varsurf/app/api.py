# SPDX-License-Identifier: LGPL-2.1-or-later
"""The App tier's public API in one place: the make-functions, the selection helpers and what
each command does (``varsurf.make_sheet`` and the other top-level names come from here)."""

from varsurf.app.actions import (
    create_sheet_from_selection,
    run_constraint_command,
    run_fill_hole_command,
    run_hinge_command,
    run_pde_surface_command,
    run_subd_brep_command,
    run_subd_surface_command,
    run_sheet_command,
    run_solid_command,
    run_space_curve_command,
    run_triangular_command,
)
from varsurf.app.macro import constraint_command_lines, sheet_command_lines
from varsurf.app.make import (
    export_step,
    install_rest_shape,
    make_constraint,
    make_fill_hole,
    make_sheet,
    make_solid,
    melt,
)
from varsurf.app.make_joints import make_hinge, make_space_curve, move_handle
from varsurf.app.pde_surface import is_pde_surface, make_pde_surface
from varsurf.app.references import is_sheet, single_element
from varsurf.app.subd_surface import (is_subd_surface, make_subd_brep, make_subd_surface, move_pin, set_curves,
                                      set_normals, set_pins)
from varsurf.app.selection import (
    constraint_selection_to_args,
    fill_hole_selection_to_args,
    hinge_selection_to_args,
    pde_surface_selection_to_args,
    selection_hint,
    selection_problem,
    selection_to_sheet_args,
    solid_selection_to_sheets,
    space_curve_selection_to_base,
)
from varsurf.app.transaction import run_in_transaction
from varsurf.app.triangular_surface import is_triangular_surface, make_triangular_surface
from varsurf.app.triangular_surface import set_constraints as set_triangular_constraints
from varsurf.app.tube import make_tube

__all__ = [
    "create_sheet_from_selection",
    "run_constraint_command",
    "run_fill_hole_command",
    "run_hinge_command",
    "run_pde_surface_command",
    "run_subd_surface_command",
    "run_subd_brep_command",
    "run_sheet_command",
    "run_solid_command",
    "run_space_curve_command",
    "constraint_command_lines",
    "sheet_command_lines",
    "export_step",
    "install_rest_shape",
    "make_constraint",
    "make_fill_hole",
    "make_tube",
    "make_sheet",
    "make_solid",
    "melt",
    "make_hinge",
    "make_pde_surface",
    "is_pde_surface",
    "make_subd_surface",
    "make_subd_brep",
    "make_triangular_surface",
    "is_triangular_surface",
    "set_triangular_constraints",
    "run_triangular_command",
    "is_subd_surface",
    "set_pins",
    "set_normals",
    "set_curves",
    "move_pin",
    "make_space_curve",
    "move_handle",
    "is_sheet",
    "single_element",
    "constraint_selection_to_args",
    "fill_hole_selection_to_args",
    "hinge_selection_to_args",
    "pde_surface_selection_to_args",
    "selection_hint",
    "selection_problem",
    "selection_to_sheet_args",
    "solid_selection_to_sheets",
    "space_curve_selection_to_base",
    "run_in_transaction",
]
