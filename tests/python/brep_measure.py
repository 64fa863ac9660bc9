# SPDX-License-Identifier: LGPL-2.1-or-later
"""Measurements on a result's B-rep made with OpenCASCADE through Part alone, independently of
what VarSurf reports: the angle between two faces across an edge, and an enclosed volume by the
divergence theorem over sampled surfaces."""

import math
import random

import FreeCAD
import Part

V = FreeCAD.Vector


def _normal_at(face, point):
    """The face's oriented unit normal at its point nearest `point` (orthogonal projection onto
    the face's surface), and how far that point is from `point`."""
    u, v = face.Surface.parameter(point)
    return face.normalAt(u, v), (face.Surface.value(u, v) - point).Length


def seam_angles(face_a, face_b, edge, samples=101, skip_ends=True):
    """Angles (degrees) between two faces across `edge` at `samples` points along it: 180 minus the
    angle between their oriented normals, each found by projecting the edge's point onto that
    face's surface. 180 is tangent-continuous. Returns (angles, largest projection distance)."""
    t0, t1 = edge.FirstParameter, edge.LastParameter
    ks = range(1, samples - 1) if skip_ends else range(samples)
    angles, far = [], 0.0
    for k in ks:
        p = edge.valueAt(t0 + (t1 - t0) * k / (samples - 1))
        na, da = _normal_at(face_a, p)
        nb, db = _normal_at(face_b, p)
        far = max(far, da, db)
        angles.append(180.0 - angle_between(na, nb))
    return angles, far


def angle_between(a, b):
    """Angle (degrees) between two vectors, accurate near 0 and 180 (atan2, not acos)."""
    return math.degrees(math.atan2(a.cross(b).Length, a.dot(b)))


def shared_edges(shape, i, j):
    """The edges faces i and j of `shape` share."""
    a = {e.hashCode() for e in shape.Faces[i].Edges}
    return [e for e in shape.Faces[j].Edges if e.hashCode() in a]


def surface_angles(face, other, edge, samples=101, skip_ends=True):
    """Angle (degrees) between the tangent planes of `face` and `other` (unoriented: 0 when they
    coincide) at points along `edge`, both found by projection; and the largest projection
    distance."""
    t0, t1 = edge.FirstParameter, edge.LastParameter
    ks = range(1, samples - 1) if skip_ends else range(samples)
    angles, far = [], 0.0
    for k in ks:
        p = edge.valueAt(t0 + (t1 - t0) * k / (samples - 1))
        na, da = _normal_at(face, p)
        nb, db = _normal_at(other, p)
        far = max(far, da, db)
        a = angle_between(na, nb)
        angles.append(min(a, 180.0 - a))
    return angles, far


def enclosed_volume(shape, order=24):
    """Volume enclosed by a closed shell, from its faces' surfaces and trimming curves alone (not
    OCCT's volume properties): by the divergence theorem, V = sum over faces of the integral of
    z * n_z dA, and by Green's theorem each face's integral over its trimmed (u, v) domain D is
    the boundary integral of G dv, G(u, v) = integral from u0 to u of z * (S_u x S_v)_z. Both are
    evaluated by Gauss-Legendre quadrature of `order` points (per edge, and along u), so the
    result is exact up to quadrature on smooth faces. The wires' orientation (material on the
    left in (u, v)) is taken from each wire's own (u, v) area, the side of the normal from the
    face's orientation."""
    import numpy

    xs, ws = numpy.polynomial.legendre.leggauss(order)
    total = 0.0
    for face in shape.Faces:
        s = face.Surface
        u_ref = face.ParameterRange[0]

        def g(u, v):
            du, dv = s.getDN(u, v, 1, 0), s.getDN(u, v, 0, 1)
            return s.value(u, v).z * (du.x * dv.y - du.y * dv.x)

        def inner(u, v):  # integral of g from u_ref to u at this v
            half = 0.5 * (u - u_ref)
            return half * sum(w * g(u_ref + half * (1.0 + x), v) for x, w in zip(xs, ws))

        face_total = 0.0
        outer = face.OuterWire
        for wire in face.Wires:
            integral = area = 0.0
            for edge in wire.OrderedEdges:
                c2d, first, last = face.curveOnSurface(edge)[:3]
                if edge.Orientation == "Reversed":
                    first, last = last, first
                half = 0.5 * (last - first)
                h = 1e-6 * abs(last - first)
                for x, w in zip(xs, ws):
                    t = first + half * (1.0 + x)
                    p = c2d.value(t)
                    dv = (c2d.value(t + h).y - c2d.value(t - h).y) / (2.0 * h)  # dv/dt
                    integral += w * half * inner(p.x, p.y) * dv
                    area += w * half * (p.x - u_ref) * dv
            # the outer wire runs counter-clockwise in (u, v), holes clockwise, whatever the
            # orientation flags say: the sign of the wire's own (u, v) area tells
            ccw = area > 0.0
            face_total += integral if ccw == wire.isSame(outer) else -integral
        total += -face_total if face.Orientation == "Reversed" else face_total
    return total


def inside_points(face, count, seed):
    """Points of `face` (inside its trim), sampled at random over its parameter range."""
    rng = random.Random(seed)
    u0, u1, v0, v1 = face.ParameterRange
    points = []
    while len(points) < count:
        u, v = u0 + (u1 - u0) * rng.random(), v0 + (v1 - v0) * rng.random()
        if face.isPartOfDomain(u, v):
            points.append(face.valueAt(u, v))
    return points


def farthest(points, shape):
    """Largest distance from `points` to `shape` (OCCT's distToShape)."""
    return max(Part.Vertex(p).distToShape(shape)[0] for p in points)


def bending_energy(face, samples=60):
    """Fairness of a (trimmed) face: the integral of k1^2 + k2^2 over it, by the midpoint rule on a
    samples x samples grid of its parameter rectangle, keeping the cells whose centres the trim
    keeps (OCCT's curvatures and first derivatives). Returns (energy, area)."""
    u0, u1, v0, v1 = face.ParameterRange
    du, dv = (u1 - u0) / samples, (v1 - v0) / samples
    energy = area = 0.0
    for i in range(samples):
        for j in range(samples):
            u, v = u0 + (i + 0.5) * du, v0 + (j + 0.5) * dv
            if not face.isPartOfDomain(u, v):
                continue
            su, sv = face.derivative1At(u, v)
            d_area = su.cross(sv).Length * du * dv
            k1, k2 = face.curvatureAt(u, v)
            energy += (k1 * k1 + k2 * k2) * d_area
            area += d_area
    return energy, area


class Columns:
    """A closed shape's inside as vertical columns: a fine tessellation of its faces (OCCT's mesher,
    not its volume integration) crossed by vertical lines on an ``nx`` x ``ny`` grid over the
    bounding box; each line's entries and exits give its inside intervals. Volumes of the shape
    cut by a half-space or a vertical cylinder follow by the midpoint rule over the columns: an
    answer independent of FreeCAD's booleans and of GProp.

    Mesh a copy (``Columns(shape.copy())``): the mesh stays on the faces it was made for, and
    OCCT's booleans of a meshed shape can differ (measured: one of the rounded box's 20 half-space
    cuts then fails the BOP check with a self-intersection that the unmeshed shape's cut has not).
    """

    def __init__(self, shape, nx=160, ny=100, deflection=0.01):
        import numpy

        self.np = numpy
        points, triangles = shape.tessellate(deflection)
        p = numpy.array([(v.x, v.y, v.z) for v in points])
        t = numpy.array(triangles)
        a, b, c = p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]
        box = shape.BoundBox
        # Column centres off any symmetry of the grid (a line through a mesh vertex or edge would
        # count a crossing twice).
        self.dx, self.dy = box.XLength / nx, box.YLength / ny
        xs = box.XMin + (numpy.arange(nx) + 0.5 + 1e-3 * math.sqrt(2)) * self.dx
        ys = box.YMin + (numpy.arange(ny) + 0.5 + 1e-3 * math.sqrt(3)) * self.dy
        self.x, self.y, self.intervals = [], [], []
        det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
        live = numpy.abs(det) > 1e-300
        a, b, c, det = a[live], b[live], c[live], det[live]
        self.odd = 0
        for x in xs:
            near = (numpy.minimum(numpy.minimum(a[:, 0], b[:, 0]), c[:, 0]) <= x) & \
                   (numpy.maximum(numpy.maximum(a[:, 0], b[:, 0]), c[:, 0]) >= x)
            an, bn, cn, dn = a[near], b[near], c[near], det[near]
            for y in ys:
                s = ((x - an[:, 0]) * (cn[:, 1] - an[:, 1]) - (cn[:, 0] - an[:, 0]) * (y - an[:, 1])) / dn
                r = ((bn[:, 0] - an[:, 0]) * (y - an[:, 1]) - (x - an[:, 0]) * (bn[:, 1] - an[:, 1])) / dn
                hit = (s >= 0) & (r >= 0) & (s + r <= 1)
                if not hit.any():
                    continue
                z = numpy.sort(an[hit, 2] + s[hit] * (bn[hit, 2] - an[hit, 2]) + r[hit] * (cn[hit, 2] - an[hit, 2]))
                if len(z) % 2:
                    self.odd += 1  # grazing the mesh: left out, and counted
                    continue
                self.x.append(x)
                self.y.append(y)
                self.intervals.append(z.reshape(-1, 2))

    def volume(self, keep=None):
        """The volume of the columns' parts where ``keep(x, y, z0, z1)`` (the kept length of the
        segment z0..z1 at (x, y)) says; all of it without ``keep``."""
        total = 0.0
        for x, y, spans in zip(self.x, self.y, self.intervals):
            for z0, z1 in spans:
                total += (z1 - z0) if keep is None else keep(x, y, z0, z1)
        return total * self.dx * self.dy

    def half_space_volume(self, origin, normal):
        """The volume on the side of the plane through ``origin`` that ``normal`` points to."""
        def keep(x, y, z0, z1):
            # normal . (p - origin) >= 0 along the segment: linear in z.
            base = normal.x * (x - origin.x) + normal.y * (y - origin.y) - normal.z * origin.z
            f0, f1 = base + normal.z * z0, base + normal.z * z1
            if f0 >= 0 and f1 >= 0:
                return z1 - z0
            if f0 < 0 and f1 < 0:
                return 0.0
            return (z1 - z0) * (max(f0, f1) / abs(f1 - f0))
        return self.volume(keep)

    def cylinder_volume(self, centre, radius):
        """The volume inside the vertical cylinder of ``radius`` about (centre.x, centre.y)."""
        return self.volume(lambda x, y, z0, z1: (z1 - z0) if (x - centre.x) ** 2 + (y - centre.y) ** 2 <= radius ** 2
                           else 0.0)
