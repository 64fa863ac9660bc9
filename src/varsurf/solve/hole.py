# SPDX-License-Identifier: LGPL-2.1-or-later
"""Filling a hole in a shell or solid, or replacing one of its faces: a sheet trimmed to the
hole's loop, joined to every face around it (G0, or G1 by default), sewn with the part's other
faces into one new shape (a solid when it closes).

The hole is given by the face it replaces (its outer wire is the loop, the faces across its
edges are the neighbours) or by the free edges around it (their faces are the neighbours). The
sheet is made from the loop and any interior curves as a Sheet from curves is, with one G1
constraint per loop edge against its neighbour, and ends on the loop, so its edges are the
part's own edges and the sewing closes them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import List, Optional, Sequence

from varsurf.solve import continuity
from varsurf.solve.constraints import ConstraintSpec
from varsurf.solve.errors import SheetError
from varsurf.solve.native import native
from varsurf.solve.outcome import SheetOutcome
from varsurf.solve.settings import SheetSettings
from varsurf.solve.shapes import shape_from_brep
from varsurf.solve.sheet import solve_sheet_from_curves

CONTINUITIES = ("G0", "G1", "G2")
#: The sewing joins the sheet's edges (the loop curves themselves) to the part's within this
#: multiple of the sheet's tolerance.
SEW_FACTOR = 4.0


@dataclass
class HoleOutcome:
    shape: object  # the part with the hole filled: a Part.Solid when it closes, else a shell
    sheet: SheetOutcome  # the filling sheet's solve
    closed: bool = False
    valid: bool = False
    max_tolerance: float = 0.0  # worst edge/vertex tolerance after sewing (mm)
    free_edges: int = 0
    joins: List[continuity.Join] = field(default_factory=list)  # per loop edge, against its neighbour


def _edge_faces(shape):
    """Each edge's faces, by hashCode (the same edge in every face that uses it): a face index
    per use, so a closed face's seam is listed twice and a free edge once."""
    owners = {}
    for i, f in enumerate(shape.Faces):
        for e in f.Edges:
            owners.setdefault(e.hashCode(), []).append(i)
    return owners


def _free_edges(owners) -> int:
    return sum(1 for faces in owners.values() if len(faces) == 1)


def loop_and_neighbours(shape, replace: Sequence[int] = (), edges: Sequence = ()):
    """(loop edges, their neighbour faces, the indices of the faces kept) of the hole: the outer
    wire of the one face ``replace`` names (index into shape.Faces), or the free ``edges``."""
    faces = list(getattr(shape, "Faces", []) or [])
    if not faces:
        raise SheetError("the part has no faces: select a solid or shell to fill a hole in")
    if bool(replace) == bool(edges):
        raise SheetError("give either the face to replace or the free edges around the hole, not both")
    if replace:
        if len(replace) != 1:
            raise SheetError(f"one face at a time is replaced (got {len(replace)}): replace them one by one")
        index = replace[0]
        if not 0 <= index < len(faces):
            raise SheetError(f"the part has no face {index + 1}: it has {len(faces)}")
        face = faces[index]
        if len(face.Wires) > 1:
            holes = len(face.Wires) - 1
            raise SheetError(f"Face{index + 1} has {'a hole' if holes == 1 else f'{holes} holes'} of its own: a sheet "
                             "replaces a face bounded by one loop; fill its holes first")
        # A collapsed edge (a sphere's pole, where a fillet corner patch narrows to a point)
        # bounds nothing: the loop is the rest.
        loop = [e for e in face.OuterWire.Edges if not e.Degenerated]
        kept = [i for i in range(len(faces)) if i != index]
    else:
        loop = list(edges)
        kept = list(range(len(faces)))
    neighbours = []
    owners = _edge_faces(shape)
    for k, edge in enumerate(loop):
        around = sorted(set(i for i in owners.get(edge.hashCode(), []) if i in kept))
        if len(around) != 1:
            where = "no face of the part" if not around else f"{len(around)} faces of the part"
            raise SheetError(f"edge {k + 1} of the hole lies on {where}; a hole's edge bounds exactly one face "
                             "around it (select the free edges of an open shell, or a face of a solid)")
        neighbours.append(faces[around[0]])
    return loop, neighbours, kept


def fill_hole(shape, replace: Sequence[int] = (), edges: Sequence = (), curves: Sequence = (),
              continuity_kind: str = "G1", settings: Optional[SheetSettings] = None) -> HoleOutcome:
    """The part ``shape`` with a sheet where its face ``replace`` (an index into shape.Faces) was,
    or filling the hole bounded by its free ``edges``; ``curves`` are interior curves the sheet
    contains. ``continuity_kind``: G0 (the sheet ends on the edges), G1 (and is tangent to the
    face across each) or G2 (and has its normal curvature across each: iterated). SheetError
    naming the edge or face at fault."""
    if continuity_kind not in CONTINUITIES:
        raise SheetError(f"Continuity must be one of {', '.join(CONTINUITIES)} (got {continuity_kind!r}): "
                         "pick one of them")
    settings = (settings or SheetSettings()).changed(trim="Loop")
    loop, neighbours, kept = loop_and_neighbours(shape, replace, edges)
    specs = []
    if continuity_kind != "G0":
        specs = [ConstraintSpec(kind=continuity_kind, name=f"{continuity_kind} to the face around edge {k + 1}",
                                edge=e, reference=n)
                 for k, (e, n) in enumerate(zip(loop, neighbours))]
    names = [f"hole edge {k + 1}" for k in range(len(loop))] + [f"curve {k + 1}" for k in range(len(curves))]
    sheet = solve_sheet_from_curves(loop + list(curves), settings, names=names, constraints=specs)
    faces = [shape.Faces[i] for i in kept] + [sheet.shape]
    nat = native()
    tolerance = SEW_FACTOR * float(settings.tolerance)
    try:
        sewn = nat.sew_faces_brep([f.exportBrepToString() for f in faces], tolerance)
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(f"the filled hole cannot be sewn to the part: {error}; try a larger Tolerance, or "
                         "G0 continuity") from error
    # A part that the filled hole closes must come out closed (an open shell with other holes
    # keeps those: it is reported as an open shell).
    closes = _free_edges(_edge_faces(shape)) == (len(loop) if edges else 0)
    if closes and sewn.free_edges:
        raise SheetError(f"the sheet does not close the hole: {sewn.free_edges} edges stay open after sewing "
                         f"at {tolerance:.3g} mm: try a larger Tolerance")
    joins = [continuity.measure(f"hole edge {k + 1}", sheet.shape, e, n if continuity_kind != "G0" else None)
             for k, (e, n) in enumerate(zip(loop, neighbours))]
    return HoleOutcome(shape=shape_from_brep(sewn.brep), sheet=sheet, closed=bool(sewn.closed),
                       valid=bool(sewn.valid), max_tolerance=float(sewn.max_tolerance),
                       free_edges=int(sewn.free_edges), joins=joins)
