# SPDX-License-Identifier: LGPL-2.1-or-later
"""Multiresolution Catmull-Clark surfaces without a document (Boier-Martin, Ronfard & Bernardini):
a control mesh refined a number of levels, detail captured from a target mesh, pins moving
vertices of any level with their region of influence, and the limit surface as triangles. The
mathematics is the core's (OpenSubdiv, the detail energy and its solves); this module builds its
inputs, keeps the editor of a topology for the next recompute and words its errors."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Tuple

import numpy as np

from varsurf.solve.errors import SheetError
from varsurf.solve.native import native

Point = Tuple[float, float, float]

#: Solves of a detail edit, as a feature names them.
SOLVES = ("Direct", "SOR", "Approximate")

#: Bytes a multiresolution surface takes per face of its finest level while it is built and
#: edited, measured by bench/multires.py (the process's peak over the finest faces: 3.3 kB at
#: 100k faces, 2.7 kB at 400k, the growth between them 2.5 kB), rounded.
BYTES_PER_FINEST_FACE = 3000
#: The largest surface built: 2 GB at the figure above (about 660,000 finest faces).
MAX_BYTES = 2_000_000_000


@dataclass
class Pin:
    level: int
    vertex: int
    target: Point
    influence: int
    on_limit: bool = False  # the target holds the vertex's limit point, not its control point


@dataclass
class Normal:
    """A normal prescribed at a vertex (Boier-Martin et al. 4.2): its tangents made perpendicular
    to `direction` (either sign)."""
    level: int
    vertex: int
    direction: Point
    influence: int


@dataclass
class CurveMotion:
    """Curves lying on the surface moved rigidly (Boier-Martin et al. 4.2, Figs. 7d and 9): the
    vertices of `level` along each curve (a polyline) become pins propagated to `influence`, each
    moved by `matrix` (a 4 x 4 rigid motion)."""
    curves: Sequence[Sequence[Point]]
    level: int
    influence: int
    matrix: Sequence[Sequence[float]]
    loops: Sequence[int] = ()  # boundary loops of the cage (boundary_loops' numbers) moved with the curves
    held: Sequence[int] = ()  # boundary loops held where they are

    def __bool__(self):
        return bool(self.curves) or bool(self.loops) or bool(self.held)


@dataclass
class MultiresResult:
    points: np.ndarray  # the limit surface at the finest level's vertices
    triangles: List[Tuple[int, int, int]]  # the finest level's quads split
    levels: List[np.ndarray]  # every level's points, the base first
    faces: List[List[List[int]]]  # every level's faces
    fit_max: Optional[float] = None  # the limit's distance from a captured target
    fit_rms: Optional[float] = None
    residual: float = 0.0  # the worst pin's distance from its target
    normal_angle: float = 0.0  # the worst normal's angle from its prescribed line (radians)
    curve_pins: int = 0  # pins placed along curves
    curve_distance: float = 0.0  # the farthest of the moved curves' points from the result (curve_gap)
    curve_start: float = 0.0  # the farthest of the curves' points from the surface before the edit
    curve_change: float = 0.0  # how far re-parameterizing along the curves moved the surface off itself
    rounds: int = 0
    region_sizes: List[int] = field(default_factory=list)
    region_levels: List[int] = field(default_factory=list)
    captured: object = None  # the native Multiresolution before the pins (what a drag edits)
    rest: object = None  # the captured one re-parameterized along the curves (what the pins edited)
    edited: object = None  # the native Multiresolution after them
    editor: object = None  # the native DetailEditor of its topology

    def captured_points(self) -> np.ndarray:
        """The limit surface before the pins, at the finest level's vertices."""
        return np.asarray(self.editor.limit(self.captured))


def finest_faces(faces: Sequence[Sequence[int]], levels: int) -> int:
    """Faces of the finest level: an n-gon makes n quads, each quad four more per level."""
    first = sum(len(f) for f in faces)
    return first * 4 ** (levels - 1) if levels >= 1 else len(faces)


def check_size(faces: Sequence[Sequence[int]], levels: int) -> None:
    """SheetError, before anything is allocated, when the surface would not fit in memory."""
    count = finest_faces(faces, levels)
    need = count * BYTES_PER_FINEST_FACE
    if need > MAX_BYTES:
        fits = levels
        while fits > 1 and finest_faces(faces, fits) * BYTES_PER_FINEST_FACE > MAX_BYTES:
            fits -= 1
        raise SheetError(f"{levels} levels on {len(faces)} faces make {count:,} faces (about "
                         f"{need / 1e9:.1f} GB, more than {MAX_BYTES / 1e9:.1f} GB): lower Levels to {fits} or "
                         "less, or use a coarser mesh")


class _Editors:
    """The editor of the last topologies asked for: building it (OpenSubdiv's stencils of every
    level) costs more than an edit, and a recompute usually keeps the topology."""

    def __init__(self, size: int = 4):
        self.size = size
        self.items: list = []

    def get(self, points, faces, levels):
        nat = native()
        key = (tuple(tuple(f) for f in faces), len(points), levels)
        for k, editor in self.items:
            if k == key:
                return editor
        editor = nat.DetailEditor(nat.SubdivisionMesh(np.asarray(points, float), [list(f) for f in faces]), levels)
        self.items = [(key, editor)] + self.items[: self.size - 1]
        return editor


_editors = _Editors()


def _solve(name: str):
    nat = native()
    try:
        return {"Direct": nat.DetailSolve.direct, "SOR": nat.DetailSolve.sor,
                "Approximate": nat.DetailSolve.approximate}[name]
    except KeyError:
        raise SheetError(f"the solve {name!r} is not one of {', '.join(SOLVES)}") from None


def build(points: Sequence[Point], faces: Sequence[Sequence[int]], levels: int,
          target: Optional[Tuple[Sequence[Point], Sequence[Tuple[int, int, int]]]] = None,
          pins: Sequence[Pin] = (), solve: str = "Direct", rings: int = 1,
          normals: Sequence[Normal] = (), curves: Optional[CurveMotion] = None) -> MultiresResult:
    """The surface of the cage (points, faces) refined `levels` times, with the detail of
    `target` (points, triangles) captured when given, edited by `pins`, `normals` and the pins
    along `curves`. SheetError says what is wrong with bad input (the mesh, the target, a pin, a
    normal, a curve)."""
    nat = native()
    levels = int(levels)
    if not 1 <= levels <= 8:
        raise SheetError(f"Levels must be 1 to 8, not {levels}")
    check_size(faces, levels)
    cage = np.asarray(points, dtype=float).reshape(-1, 3)
    try:
        base = nat.SubdivisionMesh(cage, [[int(i) for i in f] for f in faces])
        editor = _editors.get(cage, base.faces, levels)
        fit = None
        if target is not None:
            surface = nat.TriangleSurface(np.asarray(target[0], float).reshape(-1, 3),
                                          [[int(i) for i in t] for t in target[1]])
            multires = nat.capture(base, levels, surface)
            fit = nat.capture_fit(multires, surface)
        else:
            details = [np.zeros((editor.vertices(k), 3)) for k in range(1, levels + 1)]
            multires = nat.Multiresolution(base, details)
        report, captured, chained = None, multires, None
        if curves:  # the surface re-parameterized along the curves is the one edited
            chained = curve_vertices(editor, multires, curves, pins)
            multires = chained.surface
            pins = list(pins) + curve_pins(chained, curves.matrix)
        if pins or normals:
            options = nat.DetailEditOptions()
            options.solve = _solve(solve)
            options.rings = int(rings)
            edited = editor.edit(multires, _native_pins(pins), _native_normals(normals), options)
            multires, report = edited.surface, edited.report
        level_points = [np.asarray(p) for p in editor.points(multires)]
        finest = editor.topology(levels)
        limit = editor.limit(multires)
    except nat.InvalidInput as error:
        raise SheetError(str(error)) from error
    triangles = [tuple(t) for t in _triangles(finest)]
    result = MultiresResult(np.asarray(limit), triangles, level_points,
                            [editor.topology(k).faces for k in range(levels + 1)], captured=captured, editor=editor,
                            edited=multires, rest=chained.surface if chained is not None else captured)
    if fit is not None:
        result.fit_max, result.fit_rms = fit.max_distance, fit.rms_distance
    if report is not None:
        result.residual, result.rounds = report.max_residual, report.rounds
        result.normal_angle = report.max_normal_angle
        result.region_sizes, result.region_levels = list(report.region_sizes), list(report.region_levels)
    if chained is not None:
        result.curve_pins, result.curve_change = len(chained.vertices), chained.shape_change
        if curves.curves:
            result.curve_distance = curve_gap(level_points[-1], result.points, finest.faces, curves, curves.matrix)
            result.curve_start = curve_gap(editor.points(chained.surface)[-1], editor.limit(chained.surface),
                                           finest.faces, curves, np.eye(4))
    return result


@dataclass
class BRepResult:
    brep: str  # the sewn shell or solid
    closed: bool
    patches: int
    end_caps: int
    end_cap_deviation: float
    regular_angle: float
    end_cap_angle: float
    faces: int = 0  # B-rep faces: the patches merged into blocks
    merge_deviation: float = 0.0  # how far the merge moved any patch's Bezier pole
    shape: object = None  # the Part shape, set by the App side


def brep(result: MultiresResult, isolation: int = 4, tolerance: float = 0.0, max_span: int = 64) -> BRepResult:
    """The limit surface of a built surface as B-rep faces, sewn at `tolerance` (0: a ten-millionth
    of the surface's size): OpenSubdiv's bicubic patches (exact where regular; B-spline end caps at
    extraordinary vertices, their deviation measured), the regular ones of each rectangle of up to
    `max_span` x `max_span` faces written as one C2 B-spline face (exactly: a knot at each face's
    border) and the pieces of each face refined near an extraordinary vertex as one."""
    nat = native()
    if not 1 <= int(isolation) <= 8:
        raise SheetError(f"Isolation must be 1 to 8, not {isolation}")
    if not 1 <= int(max_span) <= 1000:
        raise SheetError(f"MaxSpan must be 1 to 1000, not {max_span}")
    finest = nat.SubdivisionMesh(np.asarray(result.levels[-1], float), [list(f) for f in result.faces[-1]])
    size = float(np.linalg.norm(result.points.max(axis=0) - result.points.min(axis=0)))
    tolerance = float(tolerance) or max(1e-7 * size, 1e-9)
    try:
        patches = nat.limit_patches(finest, int(isolation))
        deviation = nat.end_cap_deviation(finest, patches)
        # A pole moved by at most a hundredth of the sewing tolerance: the merged faces are the
        # patches to well within what sewing accepts.
        blocks = nat.patch_blocks(finest, patches, int(max_span), 0.01 * tolerance)
        shell = nat.patch_shell([b.surface for b in blocks.blocks], [not b.regular for b in blocks.blocks],
                                tolerance)
    except nat.InvalidInput as error:
        raise SheetError(str(error)) from error
    if not shell.shell.valid:
        raise SheetError(f"the sewn faces are not a valid shape ({shell.shell.message}): raise Tolerance")
    return BRepResult(shell.shell.brep, shell.shell.closed, len(patches.patches), patches.end_caps, deviation,
                      shell.regular_angle, shell.end_cap_angle, len(blocks.blocks), blocks.deviation)


#: A drag's preview meets its pins to this fraction of the model's size (the release, to 1e-9):
#: one frame-turning round fewer, 5.3 -> 3.4 ms an edit on 10,240 faces (benchmark 10's vase).
DRAG_TOLERANCE = 1e-6


@dataclass
class CurveVertices:
    """The vertices that follow some curves and boundary loops, each a pin to be: its level, where
    it is, whether it stays (a held loop's) and the level it is propagated to."""
    vertices: List[int]
    levels: List[int]
    points: np.ndarray
    held: List[bool]
    influences: List[int]
    surface: object = None  # the native Multiresolution re-parameterized along the curves
    on_curve: List[int] = field(default_factory=list)  # entries whose limit point is held (at its curve point)
    shape_change: float = 0.0  # how far that moved the limit surface off the one before


def _rigid(matrix) -> np.ndarray:
    matrix = np.asarray(matrix, float)
    rotation = matrix[:3, :3] if matrix.shape == (4, 4) else np.full((3, 3), np.nan)
    if not np.isfinite(matrix).all() or not np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-9):
        raise SheetError("the curves' motion is not a rigid motion: give a placement (a rotation and a move)")
    return matrix


def boundary_loops(faces) -> List[List[int]]:
    """The boundary loops of a mesh (faces as vertex lists, consistently oriented): each the
    vertices of its boundary edges in order, the loops numbered by their lowest vertex."""
    count = {}
    for face in faces:
        for a, b in zip(face, list(face[1:]) + [face[0]]):
            count[(min(a, b), max(a, b))] = count.get((min(a, b), max(a, b)), 0) + 1
    following = {}
    for face in faces:
        for a, b in zip(face, list(face[1:]) + [face[0]]):
            if count[(min(a, b), max(a, b))] == 1:
                following[int(a)] = int(b)
    loops, seen = [], set()
    for start in sorted(following):
        if start in seen:
            continue
        loop, v = [], start
        while v not in seen and v in following:
            seen.add(v)
            loop.append(v)
            v = following[v]
        loops.append(loop)
    return loops


def loop_vertices(editor, level: int, loop: int) -> List[int]:
    """The vertices at `level` of the cage's boundary loop number `loop` (boundary_loops of the
    cage): the loop there through the cage vertex it starts from (vertices keep their numbers)."""
    cage_loops = boundary_loops(editor.topology(0).faces)
    if not 0 <= int(loop) < len(cage_loops):
        raise SheetError(f"the cage has {len(cage_loops)} boundary loop{'' if len(cage_loops) == 1 else 's'}, "
                         f"no loop {loop}: "
                         + (f"give one of 0..{len(cage_loops) - 1}" if cage_loops else "it is closed; remove the loop"))
    first = cage_loops[int(loop)][0]
    return next(found for found in boundary_loops(editor.topology(level).faces) if first in found)


def curve_vertices(editor, surface, curves: CurveMotion, pins: Sequence[Pin] = ()) -> CurveVertices:
    """The vertices of `surface` (a native Multiresolution) along each curve at each level from
    `curves.influence` to `curves.level`, and on its moved and held boundary loops; a vertex
    pinned already by `pins` keeps its own pin. The curves' vertices are snapped onto them (the
    Appendix's re-parameterization: DetailEditor.snap) on the returned surface."""
    nat = native()
    level = int(curves.level)
    if not 0 <= level <= editor.levels():
        raise SheetError(f"the curves' level {level} does not exist (the surface has levels 0..{editor.levels()}): "
                         "set one of those")
    if not 0 <= int(curves.influence) <= level:
        raise SheetError(f"the curves' influence level must lie in 0..{level}; set it so")
    both = set(map(int, curves.loops)) & set(map(int, curves.held))
    if both:
        raise SheetError(f"boundary loop {min(both)} is both moved and held: "
                         "remove it from CurveLoops or from HeldLoops")
    taken = {(p.level, p.vertex) for p in pins}
    vertices, levels, points, held, influences = [], [], [], [], []

    def add(at, v, where, stays, influence):
        if (at, v) not in taken:  # a vertex pinned already keeps its first pin
            taken.add((at, v))
            vertices.append(int(v))
            levels.append(at)
            points.append(where)
            held.append(stays)
            influences.append(influence)

    original, on_curve = surface, []
    before = None  # the surface as triangles
    # A chain at each level from the influence level on, each vertex pinned at its own level: the
    # finest chain propagated down instead would put more pins on a coarse level than it has
    # vertices near the curve (225 pins on a 10 x 10 cage folded a relief's surface over). The
    # coarser chains carry the curve's neighbourhood as found; the finest level's chain, when
    # CurveLevel is the finest, is snapped onto the curve (DetailEditor.snap) and holds the limit
    # surface there. Snapping coarser chains too moved coarse vertices whole faces, leaving the
    # finest limit points up to 0.9 finest edges off the curve, which only a fold could mend
    # (Fig. 7d's relief); holding the limit from a coarser CurveLevel folded a plane's B-rep
    # (levels 3 and 4 of 5), so a coarser CurveLevel pins its chain as found.
    for at in range(int(curves.influence), level + 1 if curves.curves else 0):
        level_points = np.asarray(editor.points(surface)[at])
        mesh = nat.SubdivisionMesh(level_points, editor.topology(at).faces)
        chains, chosen, targets = [], [], []
        for number, curve in enumerate(curves.curves):
            try:
                chains.append(nat.curve_chain(mesh, np.asarray(curve, float).reshape(-1, 3)))
            except nat.InvalidInput as error:
                raise SheetError(f"curve {number + 1} at level {at}: {error}") from error
        if at == level == editor.levels():
            shortest = _shortest_edges(level_points, mesh.faces)
            for chain in chains:
                for v, target in _snappable(chain, level_points, shortest):
                    if (at, v) not in taken and v not in chosen:
                        chosen.append(v)
                        targets.append(target)
        if chosen:
            before = nat.TriangleSurface(np.asarray(editor.limit(original)),
                                         _triangles(editor.topology(editor.levels())))
            try:
                surface = editor.snap(surface, at, chosen, np.asarray(targets, float), before)
            except nat.InvalidInput as error:
                raise SheetError(f"the curves at level {at}: {error}") from error
            level_points = np.asarray(editor.points(surface)[at])
        # Every chain vertex is pinned: the snapped ones where they now are (on the curve), the
        # rest where they were, carrying the curve's neighbourhood with it.
        for chain in chains:
            for v in chain.vertices:
                add(at, v, level_points[v], False, at)
        if at == level and chosen:
            # The curves' level holds the limit surface at the curve points (on the surface before:
            # a curve drawn a little off it is not forced through). The snap put most limit points
            # there already; one it stopped short is pulled at most SNAP_PULL of an edge further.
            rest = np.asarray(editor.limit(surface))[chosen]
            shift = before.closest(np.asarray(targets, float)) - rest
            length = np.linalg.norm(shift, axis=1)
            shift *= np.minimum(1.0, SNAP_PULL * shortest[chosen] / np.maximum(length, 1e-300))[:, None]
            feet = dict(zip(chosen, rest + shift))
            on_curve = [k for k, (lv, v) in enumerate(zip(levels, vertices)) if lv == at and v in feet]
            for k in on_curve:
                points[k] = feet[vertices[k]]
    # Boundary loops: every vertex of the loop at the curves' level (from the topology, exactly),
    # propagated to the influence level: their masks there take boundary vertices only, so a
    # rigid motion meets them all, as pinning each boundary vertex by hand does.
    finest_points = np.asarray(editor.points(surface)[level])
    for loop, stays in [(n, False) for n in curves.loops] + [(n, True) for n in curves.held]:
        for v in loop_vertices(editor, level, loop):
            add(level, v, finest_points[v], stays, int(curves.influence))
    change = 0.0
    if before is not None:  # how far the re-parameterization moved the surface off its shape
        limit = np.asarray(editor.limit(surface))
        moved = np.flatnonzero(np.linalg.norm(limit - np.asarray(editor.limit(original)), axis=1) > 0.0)
        if moved.size:
            change = float(np.linalg.norm(before.closest(limit[moved]) - limit[moved], axis=1).max())
    return CurveVertices(vertices, levels, np.asarray(points, float).reshape(-1, 3), held, influences,
                         surface=surface, shape_change=change, on_curve=on_curve)


#: Each bicubic patch is sampled on this many points a side to measure a curve's distance from
#: it: the triangles' sag is then 1/64 of the finest level's (0.2 mm -> 0.003 mm on a 100 mm plane
#: lifted 15 mm at influence 3, where the finest level's own triangles misstated 0.083 as 0.29).
GAP_SAMPLES = 9


def curve_gap(finest, limit, faces, curves: CurveMotion, matrix) -> float:
    """The farthest of the curves' points moved by `matrix` (each polyline sampled a twentieth of
    a finest edge apart) from the limit surface of the finest level (its points, their limit points
    and its quads),
    measured on its bicubic patches (OpenSubdiv's) near the curves, each sampled
    GAP_SAMPLES x GAP_SAMPLES."""
    nat = native()
    matrix = _rigid(matrix)
    finest = np.asarray(finest, float)
    quads = np.asarray(faces, int).reshape(-1, 4)
    edges = np.linalg.norm(finest[quads] - finest[np.roll(quads, 1, axis=1)], axis=2)
    step = 0.05 * float(np.median(edges))
    samples = []
    for curve in curves.curves:
        polyline = np.asarray(curve, float).reshape(-1, 3)
        for a, b in zip(polyline[:-1], polyline[1:]):
            pieces = max(1, int(np.ceil(np.linalg.norm(b - a) / step)))
            samples.append(a + np.outer(np.arange(pieces) / pieces, b - a))
        samples.append(polyline[-1:])
    points = np.vstack(samples) @ matrix[:3, :3].T + matrix[:3, 3]
    # The patches near the samples: those of the faces two rings around each sample's nearest
    # limit vertex (a vertex is its own triangle to the closest-point tree).
    limit = np.asarray(limit, float)
    corners = nat.TriangleSurface(limit, [[i, i, i] for i in range(len(limit))]).closest(points)
    index = {row.tobytes(): i for i, row in enumerate(limit)}
    nearest = np.unique([index[row.tobytes()] for row in np.ascontiguousarray(corners)])
    near_faces = np.zeros(len(quads), bool)
    near_faces[np.isin(quads, nearest).any(axis=1)] = True
    near_faces |= np.isin(quads, np.unique(quads[near_faces])).any(axis=1)
    patches = [p for p in nat.limit_patches(nat.SubdivisionMesh(finest, quads.tolist()), 2).patches
               if near_faces[p.face]]
    poles = np.stack([np.asarray(p.surface.poles, float) for p in patches]).reshape(-1, 4, 4, 3)
    t = np.linspace(0.0, 1.0, GAP_SAMPLES)
    bernstein = np.stack([(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t ** 2 * (1 - t), t ** 3], axis=1)
    grids = np.einsum("ia,nabk,jb->nijk", bernstein, poles, bernstein).reshape(-1, 3)
    g = GAP_SAMPLES
    cell = np.arange(g - 1)
    base = (cell[:, None] * g + cell[None, :]).ravel()
    cells = np.concatenate([base + k * g * g for k in range(len(patches))])
    triangles = np.concatenate([np.stack([cells, cells + g, cells + g + 1], axis=1),
                                np.stack([cells, cells + g + 1, cells + 1], axis=1)])
    surface = nat.TriangleSurface(grids, triangles.tolist())
    return float(np.linalg.norm(surface.closest(points) - points, axis=1).max())


def _triangles(topology) -> List[List[int]]:
    """A level's faces split into triangles (a fan from each face's first vertex)."""
    return [[f[0], f[k], f[k + 1]] for f in topology.faces for k in range(1, len(f) - 1)]


#: A chain vertex is snapped onto its curve point when that lies within this fraction of its
#: shortest edge (the Appendix's "sufficiently close": a curve through the middle of faces runs
#: half an edge from the vertices beside it; an open curve's end vertex, which has no vertex
#: beyond it, reaches further), and its curve point at least SNAP_SPACING of that edge from the
#: last one snapped (two vertices on one curve point would collapse a face).
SNAP_REACH = 0.6
SNAP_END_REACH = 0.75
SNAP_SPACING = 0.35
#: How far (a fraction of its shortest edge) the edit may pull a vertex's limit point along the
#: surface towards its curve point where the snap stopped short of it: curves generated on a
#: captured relief, lifted and turned, folded the B-rep in 2 of 6 scenes at 0.5, 1 of 22 at 0.25,
#: none of 22 at 0.1 but the one that folds without snapping too.
SNAP_PULL = 0.1
#: Distances within this fraction of a threshold count as on it and are not snapped, so that a
#: scene moved rigidly, whose rounding differs, makes the same choices.
SNAP_TIE = 1e-9


def _shortest_edges(level_points: np.ndarray, faces) -> np.ndarray:
    """Each vertex's shortest edge."""
    shortest = np.full(len(level_points), np.inf)
    pairs = np.asarray([(f[k], f[(k + 1) % len(f)]) for f in faces for k in range(len(f))], int).reshape(-1, 2)
    lengths = np.linalg.norm(level_points[pairs[:, 0]] - level_points[pairs[:, 1]], axis=1)
    np.minimum.at(shortest, pairs[:, 0], lengths)
    np.minimum.at(shortest, pairs[:, 1], lengths)
    return shortest


def _snappable(chain, level_points, shortest):
    """The chain's vertices close enough to snap, with their curve points, in the curve's order."""
    kept, last = [], len(chain.vertices) - 1
    # A chain that does not follow its curve (a level too coarse for it: a circle's chain of one
    # vertex, or of a few the curve strays from by more than their spacing) has nothing to snap:
    # each vertex would be dragged across faces.
    steps = np.linalg.norm(np.diff(level_points[list(chain.vertices)], axis=0), axis=1)
    if (chain.closed and len(chain.vertices) < 3) or not steps.size or \
            chain.max_gap >= (1.0 - SNAP_TIE) * float(np.median(steps)):
        return kept
    for i, (v, foot) in enumerate(zip(chain.vertices, np.asarray(chain.points, float).reshape(-1, 3))):
        edge = shortest[v]
        reach = SNAP_END_REACH if i in (0, last) and not chain.closed else SNAP_REACH
        if np.linalg.norm(level_points[v] - foot) >= (reach - SNAP_TIE) * edge:
            continue
        if kept and np.linalg.norm(foot - kept[-1][1]) <= (SNAP_SPACING + SNAP_TIE) * edge:
            continue
        kept.append((v, foot))
    if chain.closed and len(kept) > 2 and \
            np.linalg.norm(kept[-1][1] - kept[0][1]) <= (SNAP_SPACING + SNAP_TIE) * shortest[kept[-1][0]]:
        kept.pop()
    return kept


def curve_pins(chained: CurveVertices, matrix) -> List[Pin]:
    """Pins moving the chains' vertices by `matrix` (4 x 4, rigid)."""
    matrix = _rigid(matrix)
    moved = chained.points @ matrix[:3, :3].T + matrix[:3, 3]
    moved = np.where(np.asarray(chained.held, bool).reshape(-1, 1), chained.points, moved)
    limit = set(chained.on_curve)
    return [Pin(lv, v, tuple(float(c) for c in m), inf, k in limit)
            for k, (v, lv, inf, m) in enumerate(zip(chained.vertices, chained.levels, chained.influences, moved))]


def _native_pins(pins: Sequence[Pin]):
    nat = native()
    return [nat.DetailPin(p.level, p.vertex, np.asarray(p.target, float), p.influence, p.on_limit) for p in pins]


def _native_normals(normals: Sequence[Normal]):
    nat = native()
    return [nat.DetailNormal(n.level, n.vertex, np.asarray(n.direction, float), n.influence) for n in normals]


def edited_limit(result: MultiresResult, pins: Sequence[Pin], solve: str = "Approximate",
                 normals: Sequence[Normal] = (), curves=None, curve_matrix=None,
                 tolerance: float = DRAG_TOLERANCE) -> np.ndarray:
    """The limit points of a built surface's captured levels edited by `pins`, `normals` and the
    pins along `curves` (a CurveMotion, or a drag's CurveVertices moved by `curve_matrix`): a
    drag's move, the approximate solve by default, to `tolerance` (a drag's DRAG_TOLERANCE by
    default), without building anything again."""
    nat = native()
    options = nat.DetailEditOptions()
    options.solve = _solve(solve)
    options.tolerance = tolerance
    surface = result.captured
    try:
        if curves and not isinstance(curves, CurveVertices):
            curves, curve_matrix = curve_vertices(result.editor, result.captured, curves, pins), curves.matrix
        if isinstance(curves, CurveVertices):  # a drag's chains, found once, and their snapped surface
            surface = curves.surface
            pins = list(pins) + curve_pins(curves, curve_matrix) if curve_matrix is not None else pins
        edited = result.editor.edit(surface, _native_pins(pins), _native_normals(normals), options)
        return np.asarray(result.editor.limit(edited.surface))
    except nat.InvalidInput as error:
        raise SheetError(str(error)) from error


def nearest_vertex(result: MultiresResult, level: int, point: Point) -> int:
    """The vertex of `level` of a built surface nearest to `point` (a pick in the view)."""
    level = int(level)
    if not 0 <= level < len(result.levels):
        raise SheetError(f"level {level} does not exist (the surface has levels 0..{len(result.levels) - 1}): "
                         "pick one of those")
    points = np.asarray(result.levels[level], float)
    return int(np.argmin(((points - np.asarray(point, float)) ** 2).sum(axis=1)))


def vertex_normal(result: MultiresResult, level: int, vertex: int) -> Point:
    """The unit normal at a vertex of a built surface from its divided differences: what a
    Normal there holds (so holding it changes nothing until the surface is moved)."""
    nat = native()
    try:
        # The edited surface is the one shown: the captured levels with the pins and normals.
        surface = result.edited if result.edited is not None else result.captured
        return tuple(float(c) for c in result.editor.normal(surface, int(level), int(vertex)))
    except nat.InvalidInput as error:
        raise SheetError(str(error)) from error


#: A probe moves the pin by this fraction of the model's size to find its region of influence.
PROBE = 1e-3


def influence_region(result: MultiresResult, pins: Sequence[Pin], index: int,
                     normals: Sequence[Normal] = (), curves: CurveMotion = None) -> np.ndarray:
    """The finest level's vertices that pin `index` moves (its region of influence, Boier-Martin
    et al. 4.2): the approximate edit with the pin probed along the surface's normal, against the
    edit without the probe, both with the same normals and curves, to the recompute's tolerance:
    outside the region nothing moves by more than that tolerance (bitwise nothing without curves,
    whose limit-surface pins are met in rounds)."""
    nat = native()
    pins = list(pins)
    p = pins[int(index)]
    size = float(np.linalg.norm(np.ptp(result.points, axis=0))) or 1.0
    chained, matrix = None, None
    if curves:  # the chains found once, as a drag does
        chained, matrix = curve_vertices(result.editor, result.captured, curves, pins), curves.matrix
    # To the recompute's tolerance: pins held on the limit surface take rounds (their details'
    # frames turn), and fewer rounds would leave out what the recompute's last ones move.
    exact = nat.DetailEditOptions().tolerance
    base = edited_limit(result, pins, normals=normals, curves=chained, curve_matrix=matrix, tolerance=exact)
    direction = np.asarray(vertex_normal(result, p.level, p.vertex))
    pins[int(index)] = Pin(p.level, p.vertex, tuple(np.asarray(p.target, float) + PROBE * size * direction),
                           p.influence)
    probed = edited_limit(result, pins, normals=normals, curves=chained, curve_matrix=matrix, tolerance=exact)
    return np.flatnonzero(np.linalg.norm(probed - base, axis=1) > 1e-12 * size)
