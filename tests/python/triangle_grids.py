# SPDX-License-Identifier: LGPL-2.1-or-later
"""Grid triangulations for the triangular surface's tests: n x n squares, each cut along the same
diagonal (every inner vertex of valence 6, so the mesh itself can be made G1)."""


def grid_triangles(n):
    """The triangles of an n x n grid of (n + 1)^2 points numbered row by row."""
    triangles = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            triangles += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
    return triangles


def grid_points(n, cell, offset=lambda i, j: (0.0, 0.0)):
    """The grid's points in z = 0, each inner one moved by offset(i, j) (the border stays)."""
    points = []
    for j in range(n + 1):
        for i in range(n + 1):
            dx, dy = offset(i, j) if 0 < i < n and 0 < j < n else (0.0, 0.0)
            points.append((cell * i + dx, cell * j + dy, 0.0))
    return points
