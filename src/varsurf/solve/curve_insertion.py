# SPDX-License-Identifier: LGPL-2.1-or-later
"""Curves carried by patch edges (Veltkamp & Wesselink sec. 4.2, Fig. 3): the triangles a curve
crosses are split so that a chain of mesh edges runs along it, and those edges then take the
curve's pieces as their Bezier control points.

The curve is walked over the source mesh laid flat (each point of the curve projected onto the
plane of the triangle it is in): where it ends inside a triangle, that triangle is split into three
at the end (their first case of Fig. 3: two ends in one triangle give the five triangles of
successive splits); where it crosses an edge, both triangles at the edge are split there (their
second and third cases); where it passes within SNAP of an inner vertex, it goes through that
vertex, which moves onto the curve (no sliver triangles; vertices of the border and of other
curves stay). The control structure is topological, the positions come from the energy (their
remark at the end of sec. 4.2), so the new vertices are then spread along the curve towards even
steps of its parameter between the vertices that already lay on it, as far as no triangle turns
over; pieces that do not follow the curve within the fit are halved. The pieces take the curve's
own tangents at their ends, scaled so that the two pieces at a vertex meet with equal tangents,
which G1 needs (chain_speeds; where two curves join tangentially, _junction_lengths).

G1 at a vertex of valence k makes the k tangents there an affine image of a regular k-gon (the
conditions of sec. 4.3), so the curve's two tangents, which point opposite ways, need an even
valence with as many edges on each side of the curve; measured (see _Balance), only two on each
side meets the conditions to rounding, so each vertex inside a curve is given two edges on each
side, and a curve's end valence 6, by flipping edges near the curve and, where a side has too few,
by splitting a triangle there at its centre (a vertex off the curve, at the mean of its
neighbours: `free` lists them). Where that cannot be reached (crowded vertices, curves meeting at a kink) the surface
can fold inside a patch: triangular.folded_patches finds it."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Set, Tuple

import numpy as np

from varsurf.solve.errors import SheetError
from varsurf.solve.triangular import bezier_piece, hermite_parameter

#: A crossing within this fraction of an edge's length from one of its ends goes through that end.
SNAP = 0.2
#: An end of a curve within this barycentric distance of an edge of its triangle goes onto the edge.
EDGE_SNAP = 0.1
#: Inner vertices of a curve take this many edges on each side (valence 6 with the curve's two).
SIDE_EDGES = 2
#: A vertex moved along its curve keeps each triangle around it within this cosine of the source
#: mesh's orientation there.
TURN = 0.0


@dataclass
class CurvePath:
    """A curve to insert: its points `value(t)` for t in [first, last], named `label` in messages,
    and its first derivative (by central differences when not given)."""
    label: str
    value: Callable[[float], Sequence[float]]
    first: float
    last: float
    derivative: Optional[Callable[[float], Sequence[float]]] = None

    def tangent(self, t: float) -> np.ndarray:
        if self.derivative is not None:
            return np.asarray(self.derivative(float(t)), float)
        h = 1e-6 * abs(self.last - self.first)
        lo, hi = max(self.first, t - h), min(self.last, t + h)
        return (np.asarray(self.value(hi), float) - np.asarray(self.value(lo), float)) / (hi - lo)


@dataclass
class Insertion:
    """The mesh with the curves inserted: the source's vertices first (in order; some moved onto a
    curve), then the new ones; `chains` the vertices each curve runs through with the curve's
    parameter there; `free` the new vertices off the curves (the energy places them)."""
    points: np.ndarray
    triangles: List[Tuple[int, int, int]]
    origins: List[frozenset]
    chains: List[Tuple[CurvePath, List[Tuple[int, float]]]]
    free: List[int] = field(default_factory=list)
    moved: List[Tuple[int, float]] = field(default_factory=list)
    split: int = 0
    source_points: Optional[np.ndarray] = None
    source_triangles: Sequence[Sequence[int]] = ()
    ref: Optional[np.ndarray] = None
    fit_error: float = 0.0  # how far the carried pieces stray from their curves at most
    smooth: Set[int] = field(default_factory=set)  # vertices the curves pass through smoothly

    def triangles_of(self, source_triangle: int) -> List[int]:
        """The triangles that lie in a source triangle (an operator's triangles renumbered)."""
        return [k for k, o in enumerate(self.origins) if source_triangle in o]

    def locate(self, source_triangle: int, at: Sequence[float]) -> Tuple[int, Tuple[float, float, float]]:
        """(triangle, barycentric point) of barycentric point `at` of a source triangle."""
        corners = self.source_points[list(self.source_triangles[source_triangle])]
        target = np.asarray(at, float) @ corners
        best = None
        for k in self.triangles_of(source_triangle):
            lam = _barycentric(self.ref[list(self.triangles[k])], target)
            if best is None or lam.min() > best[1].min():
                best = (k, lam)
        k, lam = best
        lam = np.clip(lam, 0.0, None)
        lam /= lam.sum()
        return k, tuple(float(c) for c in lam)


def _barycentric(corners: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Barycentric coordinates of x's projection onto the plane of a triangle (rows: corners);
    x may be one point or rows of points."""
    e1, e2 = corners[1] - corners[0], corners[2] - corners[0]
    gram = np.array([[e1 @ e1, e1 @ e2], [e1 @ e2, e2 @ e2]])
    d = np.atleast_2d(x) - corners[0]
    s, r = np.linalg.solve(gram, np.vstack([d @ e1, d @ e2]))
    out = np.stack([1.0 - s - r, s, r], axis=-1)
    return out[0] if np.ndim(x) == 1 else out


def _angle(u: np.ndarray, v: np.ndarray) -> float:
    nu, nv = np.linalg.norm(u), np.linalg.norm(v)
    if nu == 0.0 or nv == 0.0:
        return 0.0
    return math.acos(max(-1.0, min(1.0, float(u @ v) / (nu * nv))))


class _Mesh:
    """The triangulation being split: reference positions on the source mesh (where the walk and
    the flips' checks happen), the positions the surface interpolates, and each triangle's source
    triangles."""

    def __init__(self, points: np.ndarray, triangles: Sequence[Sequence[int]]):
        self.ref = [p.copy() for p in points]
        self.pos = [p.copy() for p in points]
        self.tris = [list(int(c) for c in t) for t in triangles]
        self.origins = [frozenset([k]) for k in range(len(self.tris))]
        self.vert_tris: Dict[int, Set[int]] = {v: set() for v in range(len(points))}
        for k, t in enumerate(self.tris):
            for c in t:
                self.vert_tris[c].add(k)
        self.touched: Set[int] = set()
        self.free: List[int] = []

    def edge_tris(self, p: int, q: int) -> List[int]:
        return sorted(self.vert_tris[p] & self.vert_tris[q])

    def add_vertex(self, ref: np.ndarray, pos: np.ndarray) -> int:
        self.ref.append(np.asarray(ref, float))
        self.pos.append(np.asarray(pos, float))
        v = len(self.ref) - 1
        self.vert_tris[v] = set()
        return v

    def set_tri(self, k: int, corners: Sequence[int], origins: frozenset):
        if k == len(self.tris):
            self.tris.append([])
            self.origins.append(origins)
        for c in self.tris[k]:
            self.vert_tris[c].discard(k)
        self.tris[k] = list(corners)
        self.origins[k] = origins
        for c in corners:
            self.vert_tris[c].add(k)
            self.touched.add(c)

    def split_edge(self, p: int, q: int, f: float, pos: np.ndarray) -> int:
        """A new vertex at fraction f from p to q (reference), at `pos`; both triangles split."""
        r = self.add_vertex((1.0 - f) * self.ref[p] + f * self.ref[q], pos)
        for k in self.edge_tris(p, q):
            t = self.tris[k]
            i = t.index(p)
            if t[(i + 1) % 3] == q:  # (p, q, o) in order
                o = t[(i + 2) % 3]
                parts = [(p, r, o), (r, q, o)]
            else:  # (q, p, o)
                o = t[(i + 1) % 3]
                parts = [(q, r, o), (r, p, o)]
            self.set_tri(k, parts[0], self.origins[k])
            self.set_tri(len(self.tris), parts[1], self.origins[k])
        return r

    def split_triangle(self, k: int, lam: np.ndarray, pos: np.ndarray, free: bool = False) -> int:
        a, b, c = self.tris[k]
        r = self.add_vertex(lam @ np.array([self.ref[a], self.ref[b], self.ref[c]]), pos)
        if free:
            self.free.append(r)
        self.set_tri(k, (a, b, r), self.origins[k])
        self.set_tri(len(self.tris), (b, c, r), self.origins[k])
        self.set_tri(len(self.tris), (c, a, r), self.origins[k])
        return r

    def opposite(self, k: int, p: int, q: int) -> int:
        return next(c for c in self.tris[k] if c not in (p, q))

    def turned(self, k: int) -> float:
        """The cosine between triangle k's normal at the positions and on the source mesh."""
        a, b, c = (self.pos[v] for v in self.tris[k])
        n = np.cross(b - a, c - a)
        m = self.normal(k)
        return float(n @ m) / max(float(np.linalg.norm(n) * np.linalg.norm(m)), 1e-300)

    def normal(self, k: int) -> np.ndarray:
        a, b, c = (self.ref[v] for v in self.tris[k])
        return np.cross(b - a, c - a)

    def flip_parts(self, p: int, q: int):
        """(triangle p-q-x, triangle q-p-y, x, y), or None unless p-q is between two triangles."""
        tris = self.edge_tris(p, q)
        if len(tris) != 2:
            return None
        k1, k2 = tris
        if self.tris[k1][(self.tris[k1].index(p) + 1) % 3] != q:
            k1, k2 = k2, k1
        return k1, k2, self.opposite(k1, p, q), self.opposite(k2, p, q)

    def flip(self, p: int, q: int):
        """The edge p-q replaced by the other diagonal of its two triangles."""
        k1, k2, x, y = self.flip_parts(p, q)
        both = self.origins[k1] | self.origins[k2]
        self.set_tri(k1, (x, p, y), both)
        self.set_tri(k2, (y, q, x), both)

    def ring(self, v: int) -> Optional[List[int]]:
        """v's neighbours in order around it, or None on the border."""
        after = {}
        for k in self.vert_tris[v]:
            t = self.tris[k]
            i = t.index(v)
            after[t[(i + 1) % 3]] = t[(i + 2) % 3]
        if set(after) != set(after.values()):
            return None
        start = min(after)
        out = [start]
        while after[out[-1]] != start:
            out.append(after[out[-1]])
            if len(out) > len(after):
                return None
        return out if len(out) == len(after) else None

    def corner_barycentric(self, k: int, x: np.ndarray) -> np.ndarray:
        return _barycentric(np.array([self.ref[c] for c in self.tris[k]]), x)


class _Walker:
    """Walks one curve over the mesh, splitting what it crosses."""

    def __init__(self, mesh: _Mesh, curve: CurvePath, locked: Dict[int, str], locked_edges: Dict[frozenset, str],
                 tolerance: float):
        self.mesh, self.curve, self.tolerance = mesh, curve, tolerance
        self.locked, self.locked_edges = locked, locked_edges  # vertices and edges of curves before
        self.visited: Set[int] = set()  # this curve's vertices so far
        self.own_edges: Set[frozenset] = set()
        coarse = np.linspace(curve.first, curve.last, 201)
        values = np.array([self.point(t) for t in coarse])
        length = float(np.linalg.norm(np.diff(values, axis=0), axis=1).sum())
        edges = [np.linalg.norm(mesh.ref[t[i]] - mesh.ref[t[i - 1]]) for t in mesh.tris for i in range(3)]
        shortest = max(min(edges), 1e-300)
        count = int(min(8000, max(200, math.ceil(16.0 * length / shortest))))
        self.ts = np.linspace(curve.first, curve.last, count + 1)
        self.values = np.array([self.point(t) for t in self.ts])

    def point(self, t: float) -> np.ndarray:
        return np.asarray(self.curve.value(float(t)), float)

    def fail(self, what: str):
        raise SheetError(f"curve {self.curve.label} {what}")

    def closest_parameter(self, p: np.ndarray, near: float) -> float:
        """The curve's parameter nearest to point p about `near` (golden section on a bracket)."""
        step = (self.curve.last - self.curve.first) / (len(self.ts) - 1)
        lo, hi = max(self.curve.first, near - 2 * step), min(self.curve.last, near + 2 * step)
        g = (math.sqrt(5.0) - 1.0) / 2.0
        for _ in range(60):
            a, b = hi - g * (hi - lo), lo + g * (hi - lo)
            if np.linalg.norm(self.point(a) - p) < np.linalg.norm(self.point(b) - p):
                hi = b
            else:
                lo = a
        return 0.5 * (lo + hi)

    def through_vertex(self, w: int, t: float) -> Optional[Tuple[int, float]]:
        """(w, the curve's parameter at w) when the curve may run through vertex w, else None."""
        meets = self.closest_parameter(self.mesh.pos[w], t)
        gap = float(np.linalg.norm(self.point(meets) - self.mesh.pos[w]))
        if gap <= self.tolerance:
            return w, meets
        if w in self.locked or w in self.visited or self.mesh.ring(w) is None:
            return None  # a vertex of a curve that this one passes by, or of the border
        self.mesh.pos[w] = self.point(t)  # not on the curve: it moves onto it
        return w, t

    def along_edge(self, v: int, t: float) -> Optional[Tuple[int, float]]:
        """(w, parameter) when the curve runs from v along the edge v-w to a neighbour w that lies
        on it (a mesh drawn along the curve: between such vertices the curve may bulge out of
        both triangles at the edge), else None."""
        mesh = self.mesh
        best = None
        for w in {c for k in mesh.vert_tris[v] for c in mesh.tris[k]} - {v}:
            later = self.ts > t
            if not later.any():
                continue
            gaps = np.linalg.norm(self.values[later] - mesh.pos[w], axis=1)
            i = int(np.argmin(gaps))
            meets = self.closest_parameter(mesh.pos[w], self.ts[later][i])
            if meets <= t or np.linalg.norm(self.point(meets) - mesh.pos[w]) > self.tolerance:
                continue
            # Between v and w the curve stays near the edge (within a quarter of its length).
            a, b = mesh.pos[v], mesh.pos[w]
            inside = (self.ts > t) & (self.ts < meets)
            length = np.linalg.norm(b - a)
            if inside.any():
                d = self.values[inside] - a
                s = np.clip(d @ (b - a) / length**2, 0.0, 1.0)
                if np.linalg.norm(d - s[:, None] * (b - a), axis=1).max() > 0.25 * length:
                    continue
            if best is None or meets < best[1]:
                best = (w, meets)
        return best

    def exit_from(self, v: int, k: int, t0: float):
        """Where the curve, at vertex v of triangle k at parameter t0, leaves triangle k:
        (parameter, barycentric point) or (last, barycentric point) if it ends inside."""
        corners = np.array([self.mesh.ref[c] for c in self.mesh.tris[k]])
        start = _barycentric(corners, self.point(t0))
        slack = np.minimum(start, 0.0) - 1e-9  # the projection's offset where planes meet
        later = self.ts > t0 + 1e-12 * abs(self.curve.last - self.curve.first)
        ts = np.concatenate([[t0], self.ts[later]])
        lam = _barycentric(corners, np.vstack([self.point(t0), self.values[later]]))
        outside = np.nonzero((lam - slack).min(axis=1) < 0.0)[0]
        if not len(outside):
            return ts[-1], lam[-1], False
        i = outside[0]
        lo, hi = ts[max(i - 1, 0)], ts[i]
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            if (_barycentric(corners, self.point(mid)) - slack).min() < 0.0:
                hi = mid
            else:
                lo = mid
        return lo, _barycentric(corners, self.point(lo)), True

    def place(self, k: int, lam: np.ndarray, t: float, current: Optional[int]) -> Tuple[int, float]:
        """The vertex where the curve is at barycentric point lam of triangle k (parameter t):
        a corner within SNAP, a new vertex on an edge or inside; (vertex, parameter)."""
        mesh = self.mesh
        corners = mesh.tris[k]
        here = self.point(t)
        for c in corners:  # a vertex already there (a closed curve's start, another curve's end)
            if c != current and np.linalg.norm(mesh.pos[c] - here) <= self.tolerance:
                return c, t
        lam = np.asarray(lam, float)
        order = np.argsort(-lam)
        if lam[order[0]] >= 1.0 - SNAP and corners[order[0]] != current:
            hit = self.through_vertex(corners[order[0]], t)
            if hit is not None:
                return hit
        low = int(np.argmin(lam))
        if lam[low] < EDGE_SNAP:
            i, j = (low + 1) % 3, (low + 2) % 3
            a, b = max(lam[i], 0.0), max(lam[j], 0.0)
            f = b / (a + b) if a + b > 0 else 0.5
            p, q = corners[i], corners[j]
            for end, frac in ((p, f), (q, 1.0 - f)):
                if frac < SNAP and end != current:
                    hit = self.through_vertex(end, t)
                    if hit is not None:
                        return hit
            # Not through a vertex it may not move (the border, another curve): a split short of it.
            f = min(max(f, 0.05), 0.95)
            if self.carried(p, q):
                self.fail(f"crosses curve {self.carried(p, q)} between vertices {p} and {q} without a common "
                          "vertex: split both curves where they cross")
            return mesh.split_edge(p, q, f, self.point(t)), t
        lam = np.clip(lam, 0.0, None) / np.clip(lam, 0.0, None).sum()
        return mesh.split_triangle(k, lam, self.point(t)), t

    def carried(self, p: int, q: int) -> Optional[str]:
        """The curve that edge p-q carries already (this one's own label where it crosses itself)."""
        edge = frozenset((p, q))
        return self.locked_edges.get(edge) or (self.curve.label if edge in self.own_edges else None)

    def start(self) -> Tuple[int, float]:
        """The vertex at the curve's start (the nearest triangle; error if beyond the border)."""
        mesh = self.mesh
        x = self.point(self.curve.first)
        gaps = np.linalg.norm(np.array(mesh.pos) - x, axis=1)
        if gaps.min() <= self.tolerance:  # a vertex already there: another curve's end
            return int(np.argmin(gaps)), self.curve.first
        best = None
        for k, t in enumerate(mesh.tris):
            corners = np.array([mesh.ref[c] for c in t])
            lam = _barycentric(corners, x)
            foot = np.clip(lam, 0.0, None) / np.clip(lam, 0.0, None).sum() @ corners
            key = (float(np.linalg.norm(x - foot)), -float(lam.min()))
            if best is None or key < best[0]:
                best = (key, k, lam)
        _, k, lam = best
        corners = np.array([mesh.ref[c] for c in mesh.tris[k]])
        foot = np.clip(lam, 0.0, None) / np.clip(lam, 0.0, None).sum()
        # The nearest triangle is the one the start projects into, unless it projects off the
        # mesh: then it lies beyond the border by more than the snap distance.
        beyond = float(np.linalg.norm((lam - foot) @ corners))
        longest = max(np.linalg.norm(corners[i] - corners[i - 1]) for i in range(3))
        if beyond > SNAP * longest:
            self.fail(f"starts outside the mesh, {beyond:.3g} beyond its border: move the curve's ends onto "
                      "the mesh or add triangles there")
        return self.place(k, lam, self.curve.first, None)

    def walk(self) -> List[Tuple[int, float]]:
        mesh = self.mesh
        first, last = self.curve.first, self.curve.last
        v, t = self.start()
        chain = [(v, first)]
        self.visited.add(v)
        span = abs(last - first)
        step = self.ts[1] - self.ts[0]
        for _ in range(100000):
            if t >= last - 1e-12 * span:
                break
            along = self.along_edge(v, t)
            if along is not None:  # the curve runs along a mesh edge to a vertex on it
                self.own_edges.add(frozenset((v, along[0])))
                v, t = along
                chain.append(along)
                self.visited.add(v)
                continue
            best, graze = None, t
            for k in sorted(mesh.vert_tris[v]):
                t_out, lam, leaves = self.exit_from(v, k, t)
                if t_out <= t + 1e-12 * span and leaves:
                    continue
                corners = mesh.tris[k]
                near = corners[int(np.argmax(lam))]
                if near == v and leaves and lam.max() >= 1.0 - SNAP:
                    graze = max(graze, t_out)  # out again next to v: the curve runs past v
                    continue
                if best is None or t_out > best[0]:
                    best = (t_out, k, lam, leaves)
            if best is None and graze > t + 0.5 * step:
                t = graze  # still within SNAP of v: walk on from there
                continue
            if best is None:
                self.fail(f"leaves the mesh at vertex {v} (parameter {t:.6g}): move the curve onto the mesh, "
                          "shorten it or add triangles there")
            t_out, k, lam, leaves = best
            low = int(np.argmin(lam))
            if leaves and len(mesh.edge_tris(*[mesh.tris[k][(low + s) % 3] for s in (1, 2)])) == 1:
                beyond = self.point(last)
                corners = np.array([mesh.ref[c] for c in mesh.tris[k]])
                if _barycentric(corners, beyond)[low] < -SNAP:
                    self.fail(f"leaves the mesh across its border (parameter {t_out:.6g} of {first:.6g} to "
                              f"{last:.6g}): shorten the curve or add triangles there")
                t_out, leaves = last, False
            w, t_w = self.place(k, lam, t_out, v)
            if w == v:
                self.fail(f"cannot be followed past vertex {v} (parameter {t:.6g}): remesh there")
            t = max(t_w, t + 1e-12 * span) if leaves else last
            chain.append((w, t))
            self.visited.add(w)
            self.own_edges.add(frozenset((v, w)))
            v = w
        chain[-1] = (chain[-1][0], last)
        return chain


def _side_counts(mesh: _Mesh, v: int, prev: int, nxt: int) -> Optional[Tuple[int, int]]:
    ring = mesh.ring(v)
    if ring is None or prev not in ring or nxt not in ring:
        return None
    i, j = ring.index(prev), ring.index(nxt)
    left = (j - i - 1) % len(ring)
    return left, len(ring) - 2 - left


class _Balance:
    """The cost of the valences near the curves, lowered by flips and centre splits. Measured
    (fans of every valence around fixed curve edges, quartic and quintic patches): only an inner
    curve vertex with two edges on each side meets G1 to 1e-4 degrees (three on each side leave
    0.02 to 0.1, one on each side 2 degrees), and only a curve's end of valence 6 does (valence 5
    leaves 0.02 to 0.1, valence 3 six degrees); any other inner vertex wants 5 to 7 (a vertex of
    valence 4 meets G1 only by collapsing its tangents)."""

    def __init__(self, mesh: _Mesh, targets: Dict[int, Tuple[int, int]], ends: Set[int], fixed: Set[frozenset]):
        self.mesh, self.targets, self.ends, self.fixed = mesh, targets, ends, fixed

    def cost(self, v: int) -> float:
        mesh = self.mesh
        if v in self.targets:
            counts = _side_counts(mesh, v, *self.targets[v])
            if counts is None:
                return 0.0
            # Unequal sides make an odd valence or tangents out of line: worse than three each.
            return 8.0 * (counts[0] - counts[1]) ** 2 + 4.0 * sum((c - SIDE_EDGES) ** 2 for c in counts)
        ring = mesh.ring(v)
        if ring is None:  # on the border: a curve's end there wants three triangles
            return 2.0 * (len(mesh.vert_tris[v]) - 3) ** 2 if v in self.ends else 0.0
        k = len(ring)
        if v in self.ends:
            return 2.0 * (k - 6) ** 2
        return self.valence_cost(k)

    def flip_gain(self, p: int, q: int) -> Optional[float]:
        """How much a flip of edge p-q lowers the cost, or None where it may not flip: an edge of a
        curve or the border, a vertex left with three triangles, a quad that is not convex or a
        triangle under 5 degrees (on the source mesh)."""
        mesh = self.mesh
        if frozenset((p, q)) in self.fixed or min(len(mesh.vert_tris[p]), len(mesh.vert_tris[q])) < 4:
            return None
        parts = mesh.flip_parts(p, q)
        if parts is None:
            return None
        k1, k2, x, y = parts
        if mesh.vert_tris[x] & mesh.vert_tris[y]:
            return None  # x-y is an edge already
        r, at = mesh.ref, mesh.pos
        old_normal = mesh.normal(k1) + mesh.normal(k2)
        for a, b, c in ((x, p, y), (y, q, x)):
            # Neither on the source mesh nor where the vertices now are may a triangle turn over.
            if np.cross(r[b] - r[a], r[c] - r[a]) @ old_normal <= 0.0:
                return None
            if np.cross(at[b] - at[a], at[c] - at[a]) @ old_normal <= 0.0:
                return None
            if min(_angle(r[b] - r[a], r[c] - r[a]), _angle(r[a] - r[b], r[c] - r[b]),
                   _angle(r[a] - r[c], r[b] - r[c])) < math.radians(5.0):
                return None
        if np.cross(r[y] - r[x], r[p] - r[x]) @ np.cross(r[y] - r[x], r[q] - r[x]) >= 0.0:
            return None  # p and q on the same side of x-y: the quad is not convex
        around = {p, q, x, y}
        before = sum(self.cost(v) for v in around)
        saved = [(k, list(mesh.tris[k]), mesh.origins[k]) for k in (k1, k2)]
        touched = set(mesh.touched)
        mesh.flip(p, q)
        after = sum(self.cost(v) for v in around)
        for k, corners, origins in saved:
            mesh.set_tri(k, corners, origins)
        mesh.touched = touched
        return before - after

    def edges_near(self, vertices) -> List[Tuple[int, int]]:
        mesh = self.mesh
        return sorted({(min(a, b), max(a, b)) for v in vertices for k in mesh.vert_tris[v]
                       for a, b in zip(mesh.tris[k], mesh.tris[k][1:] + mesh.tris[k][:1])})

    def best_flip(self, edges) -> Optional[Tuple[float, int, int]]:
        best = None
        for p, q in edges:
            gain = self.flip_gain(p, q)
            if gain is not None and (best is None or gain > best[0]):
                best = (gain, p, q)
        return best

    def improve(self, rounds: int = 500):
        """Flip the edge that lowers the cost most until none does; then a pair of flips around a
        vertex that still costs (one flip often only moves a curve vertex's surplus to its
        neighbour, which a second flip there takes away)."""
        mesh = self.mesh
        for _ in range(rounds):
            near = set(self.targets) | self.ends | mesh.touched
            best = self.best_flip(self.edges_near(near))
            if best is not None and best[0] > 1e-9:
                mesh.flip(best[1], best[2])
                continue
            paired = None
            for p, q in self.edges_near([v for v in sorted(set(self.targets) | self.ends) if self.cost(v) > 0.0]):
                first = self.flip_gain(p, q)
                if first is None:
                    continue
                saved = [(k, list(mesh.tris[k]), mesh.origins[k]) for k in mesh.edge_tris(p, q)]
                touched = set(mesh.touched)
                _, _, x, y = mesh.flip_parts(p, q)
                mesh.flip(p, q)
                second = self.best_flip(self.edges_near({p, q, x, y}))
                for k, corners, origins in saved:
                    mesh.set_tri(k, corners, origins)
                mesh.touched = touched
                total = None if second is None else first + second[0]
                if total is not None and total > 1e-9 and (paired is None or total > paired[0]):
                    paired = (total, (p, q), second[1:])
            if paired is None:
                return
            mesh.flip(*paired[1])
            mesh.flip(*paired[2])

    def raised(self, v: int) -> float:
        """How much worse v gets with one more edge."""
        if v in self.targets:
            return 4.0
        ring = self.mesh.ring(v)
        if ring is None:
            return 2.0 * ((len(self.mesh.vert_tris[v]) - 2) ** 2 - (len(self.mesh.vert_tris[v]) - 3) ** 2) \
                if v in self.ends else 0.0
        if v in self.ends:
            return 2.0 * ((len(ring) - 5) ** 2 - (len(ring) - 6) ** 2)
        return self.valence_cost(len(ring) + 1) - self.valence_cost(len(ring))

    @staticmethod
    def valence_cost(k: int) -> float:
        """An inner vertex off the curves: 5 to 7 is best, 3 will do, 4 collapses tangents."""
        return {3: 1.0, 4: 6.0}.get(k, max(0.0, k - 7.0))

    def fill(self) -> bool:
        """Split a triangle at its centre around the first vertex short of edges: a curve vertex's
        side with fewer than SIDE_EDGES or than the other side (preferring a triangle between two of its side edges,
        which raises no other curve vertex), a curve's end of valence under 6; whether it did."""
        mesh = self.mesh
        for v in sorted(set(self.targets) | self.ends):
            ring = mesh.ring(v)
            if ring is None:
                if v in self.targets or len(mesh.vert_tris[v]) >= 3:
                    continue
                fans = [tuple(c for c in mesh.tris[k] if c != v) for k in sorted(mesh.vert_tris[v])]
            else:
                fans = [(ring[s], ring[(s + 1) % len(ring)]) for s in range(len(ring))]
            if ring is None:
                pass
            elif v in self.targets:
                prev, nxt = self.targets[v]
                counts = _side_counts(mesh, v, prev, nxt)
                if min(counts) >= SIDE_EDGES and counts[0] == counts[1]:
                    continue
                i = ring.index(prev)
                side = 0 if counts[0] <= counts[1] else 1
                fans = [fans[(i + s) % len(ring)] for s in range(len(ring))]
                fans = fans[:counts[0] + 1] if side == 0 else fans[counts[0] + 1:]
            elif len(ring) >= 6:
                continue
            options = []
            for a, b in fans:
                if any(c not in self.targets and c not in self.ends and len(mesh.vert_tris[c]) == 3 and mesh.ring(c)
                       for c in (a, b)):
                    continue  # never a vertex off the curves up to valence 4
                k = next(iter(mesh.vert_tris[v] & mesh.vert_tris[a] & mesh.vert_tris[b]))
                area = np.linalg.norm(np.cross(mesh.ref[a] - mesh.ref[v], mesh.ref[b] - mesh.ref[v]))
                options.append((self.raised(a) + self.raised(b), -area, k))
            if not options:
                continue
            _, _, k = min(options)
            centre = np.full(3, 1.0 / 3.0)
            mesh.split_triangle(k, centre, centre @ np.array([mesh.ref[c] for c in mesh.tris[k]]), free=True)
            return True
        return False


def piece_error(curve: CurvePath, first: float, last: float, degree: int, speeds=None) -> float:
    """How far the Bezier piece carried for [first, last] strays from the curve (7 inner samples,
    each against the curve's point at the same parameter)."""
    piece = bezier_piece(curve.value, first, last, degree, curve.tangent, speeds)
    span = last - first
    slope0, slope1 = (span, span) if speeds is None else speeds
    worst = 0.0
    for s in np.linspace(0.0, 1.0, 9)[1:-1]:
        point = sum(math.comb(degree, k) * s**k * (1.0 - s) ** (degree - k) * piece[k] for k in range(degree + 1))
        t = float(hermite_parameter(s, first, last, slope0, slope1))
        worst = max(worst, float(np.linalg.norm(point - np.asarray(curve.value(t), float))))
    return worst


def chain_speeds(chain: Sequence[Tuple[int, float]]) -> List[float]:
    """The parameter speed (dt/ds) the two pieces at each of the chain's vertices take there: at an
    inner vertex the same for both (the harmonic mean of their spans, at most twice the shorter),
    so that their tangents there are equal and opposite, which G1 across the curve needs; at an
    end its piece's span."""
    spans = [tb - ta for (_, ta), (_, tb) in zip(chain[:-1], chain[1:])]
    closed = len(chain) > 2 and chain[0][0] == chain[-1][0]
    out = []
    for i in range(len(chain)):
        before = spans[i - 1] if i > 0 else (spans[-1] if closed else None)
        after = spans[i] if i < len(spans) else (spans[0] if closed else None)
        if before is None or after is None:
            out.append(after if before is None else before)
        else:
            out.append(2.0 * before * after / (before + after))
    return out


def _refine(mesh: _Mesh, curve: CurvePath, chain, anchored, degree: int, fit: float, limit: int = 256):
    """The chain with more vertices between two anchors (the longest piece's edge split at its
    middle, the run spread evenly again) until every piece is within `fit` of the curve; and the
    largest error left (when `limit` splits were not enough)."""
    chain, anchored = list(chain), list(anchored)

    def errors_of(chain):
        speeds = chain_speeds(chain)
        return [piece_error(curve, ta, tb, degree, (speeds[i], speeds[i + 1]))
                for i, ((_, ta), (_, tb)) in enumerate(zip(chain[:-1], chain[1:]))]

    for _ in range(limit):
        errors = errors_of(chain)
        worst = int(np.argmax(errors))
        if errors[worst] <= fit:
            return chain, errors[worst]
        (a, ta), (b, tb) = chain[worst], chain[worst + 1]
        r = mesh.split_edge(a, b, 0.5, np.asarray(curve.value(0.5 * (ta + tb)), float))
        chain.insert(worst + 1, (r, 0.5 * (ta + tb)))
        anchored.insert(worst + 1, False)
        chain = _spread(mesh, curve, chain, anchored)
    return chain, max(errors_of(chain))


def _spread(mesh: _Mesh, curve: CurvePath, chain, anchored):
    """The chain's vertices moved towards even steps of the curve's parameter between its anchors,
    as far as no triangle around them turns over (its corners' positions against the source
    mesh's orientation there): the surface interpolates them, and a triangle turned over would
    make its patch overlap its neighbours."""
    anchors = [i for i, f in enumerate(anchored) if f]
    moving = [m for i, j in zip(anchors[:-1], anchors[1:]) for m in range(i + 1, j)]
    even = {}
    for i, j in zip(anchors[:-1], anchors[1:]):
        for m in range(i + 1, j):
            even[m] = chain[i][1] + (chain[j][1] - chain[i][1]) * (m - i) / (j - i)
    around = sorted({k for m in moving for k in mesh.vert_tris[chain[m][0]]})
    for blend in (1.0, 0.75, 0.5, 0.25, 0.0):
        out = list(chain)
        for m in moving:
            t = chain[m][1] + blend * (even[m] - chain[m][1])
            out[m] = (chain[m][0], t)
            mesh.pos[chain[m][0]] = np.asarray(curve.value(t), float)
        if all(mesh.turned(k) > TURN for k in around):
            return out
    return out


def insert_curves(points: Sequence[Sequence[float]], triangles: Sequence[Sequence[int]],
                  curves: Sequence[CurvePath], tolerance: float, degree: int = 5, fit: float = 0.0) -> Insertion:
    """The mesh split so that chains of its edges carry `curves` (see the module's text); a
    vertex is on a curve within `tolerance`, and each curve is carried by pieces of `degree`
    within `fit` of it (0: `tolerance`), its edges split until they are. SheetError names a curve
    that starts or runs off the mesh or crosses another curve without a common vertex."""
    source = np.asarray(points, float).reshape(-1, 3)
    mesh = _Mesh(source, triangles)
    locked: Dict[int, str] = {}
    locked_edges: Dict[frozenset, str] = {}
    chains = []
    fit_error = 0.0
    for curve in curves:
        walker = _Walker(mesh, curve, locked, locked_edges, tolerance)
        chain = walker.walk()
        # Anchors keep their parameters: the ends, vertices of earlier curves, vertices of the
        # source already on the curve.
        anchored = [i == 0 or i == len(chain) - 1 or v in locked
                    or (v < len(source) and np.linalg.norm(np.asarray(curve.value(t), float) - source[v]) <= tolerance)
                    for i, (v, t) in enumerate(chain)]
        chain, error = _refine(mesh, curve, _spread(mesh, curve, chain, anchored), anchored, int(degree),
                               float(fit) or float(tolerance))
        fit_error = max(fit_error, error)
        chains.append((curve, chain))
        for v, _ in chain:
            locked.setdefault(v, curve.label)
        for (a, _), (b, _) in zip(chain[:-1], chain[1:]):
            locked_edges[frozenset((a, b))] = curve.label
    uses: Dict[int, int] = {}
    for _, chain in chains:
        for v in {v for v, _ in chain}:
            uses[v] = uses.get(v, 0) + 1
    count = len(source)
    # Each curve vertex's neighbours along the curves and the curves' directions towards them: a
    # vertex the curves pass through smoothly (one curve, or two joined tangentially) wants two
    # edges on each side; a curve's end, valence 6; where curves meet at an angle or three or more
    # meet, the valence is left as it comes.
    along: Dict[int, List[Tuple[int, np.ndarray]]] = {}
    for curve, chain in chains:
        for i, (v, t) in enumerate(chain):
            for j, sign in ((i - 1, -1.0), (i + 1, 1.0)):
                if 0 <= j < len(chain) and chain[j][0] != v:
                    along.setdefault(v, []).append((chain[j][0], sign * curve.tangent(t)))
    targets: Dict[int, Tuple[int, int]] = {}
    ends: Set[int] = set()
    for v, out in along.items():
        unique = {w: d for w, d in out}
        if len(unique) == 1:
            ends.add(v)
        elif len(unique) == 2:
            (p, dp), (q, dq) = unique.items()
            if dp @ dq < -math.cos(math.radians(0.5)) * np.linalg.norm(dp) * np.linalg.norm(dq):
                targets[v] = (p, q)
    balance = _Balance(mesh, targets, ends, set(locked_edges))
    for _ in range(4 * (len(targets) + len(ends)) + 4):
        balance.improve()
        if not balance.fill():
            break
    # Vertices along the curves at their parameters.
    moved = []
    for curve, chain in chains:
        for v, t in chain:
            where = np.asarray(curve.value(float(t)), float)
            if v < count and np.linalg.norm(where - source[v]) <= tolerance:
                continue  # already on the curve: stays exactly where the mesh has it
            mesh.pos[v] = where
    # The vertices off the curves sit at the mean of their neighbours: interpolated there (the
    # feature does: left free, the bend energy, without stretch, lets them slide until their
    # patches squash; measured over 12 generated scenes, OCCT's check passed on 3 with them free
    # and 6 with them held), and a centre left on the flat mesh under a lifted curve would tilt
    # or turn its triangles over.
    for _ in range(20):
        for v in mesh.free:
            around = {c for k in mesh.vert_tris[v] for c in mesh.tris[k]} - {v}
            mesh.pos[v] = np.mean([mesh.pos[c] for c in around], axis=0)
    for v in range(count):
        gap = float(np.linalg.norm(mesh.pos[v] - source[v]))
        if gap > tolerance:
            moved.append((v, gap))
    # A triangle left without area (three corners along a straight border or curve) cannot carry
    # a patch: said here, where it can be placed, not by the solve's numbering.
    size = float(np.linalg.norm(source.max(axis=0) - source.min(axis=0))) if len(source) else 1.0
    for corners in mesh.tris:
        a, b, c = (mesh.pos[v] for v in corners)
        if np.linalg.norm(np.cross(b - a, c - a)) <= 1e-12 * size * size:
            where = ", ".join(f"{x:.4g}" for x in (a + b + c) / 3.0)
            raise SheetError(f"the split along the curves leaves a triangle without area at ({where}): move the "
                             "curves' ends off the border's vertices there or remesh there")
    split = len({k for j, o in enumerate(mesh.origins) for k in o
                 if j >= len(triangles) or tuple(mesh.tris[j]) != tuple(triangles[j])})
    return Insertion(points=np.array(mesh.pos), triangles=[tuple(t) for t in mesh.tris], origins=list(mesh.origins),
                     chains=chains, free=sorted(mesh.free), moved=moved, split=split, source_points=source,
                     source_triangles=[tuple(int(c) for c in t) for t in triangles], ref=np.array(mesh.ref),
                     fit_error=fit_error, smooth=set(targets))


def _junction_lengths(insertion: Insertion) -> Dict[int, float]:
    """At each vertex where two curves join tangentially, the tangent length both pieces take:
    the harmonic mean of their own (at most twice the shorter)."""
    own: Dict[int, List[float]] = {}
    for curve, chain in insertion.chains:
        for i in (0, len(chain) - 1):
            v, t = chain[i]
            j = 1 if i == 0 else len(chain) - 2
            own.setdefault(v, []).append(abs(chain[j][1] - t) * float(np.linalg.norm(curve.tangent(t))))
    return {v: 2.0 * a * b / (a + b) for v, lengths in own.items() if len(lengths) == 2 and v in insertion.smooth
            for a, b in [lengths]}


def carried_edges(insertion: Insertion, degree: int) -> List[Tuple[int, int, np.ndarray]]:
    """(from, to, control points) of the edges along each curve: the curve's piece between the two
    vertices as Bezier points of `degree` with the curve's tangents at its ends (see
    triangular.bezier_piece), its ends the vertices; where two curves join tangentially both
    pieces there take the same tangent length. Records how far the pieces stray from their curves
    in insertion.fit_error."""
    out = []
    joins = _junction_lengths(insertion)
    worst = 0.0
    for curve, chain in insertion.chains:
        along = chain_speeds(chain)
        for i, ((a, ta), (b, tb)) in enumerate(zip(chain[:-1], chain[1:])):
            speeds = [along[i], along[i + 1]]
            for k, (v, t) in enumerate(((a, ta), (b, tb))):
                if v in joins:
                    speeds[k] = joins[v] / float(np.linalg.norm(curve.tangent(t))) * np.sign(tb - ta)
            piece = bezier_piece(curve.value, ta, tb, degree, curve.tangent, speeds)
            worst = max(worst, piece_error(curve, ta, tb, degree, speeds))
            # The ends at the vertices themselves: two curves meeting at a vertex, each on it
            # within the tolerance, agree there.
            piece[0], piece[-1] = insertion.points[a], insertion.points[b]
            out.append((a, b, piece))
    insertion.fit_error = worst
    return out
