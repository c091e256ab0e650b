"""Shared helpers of the terratin module's tests: exact checks of a TIN and a PLY reader."""

import os
import pathlib
from fractions import Fraction

import numpy
import pytest


def orient(a, b, c):
    """Twice the signed area of (a, b, c), exactly (Fractions of the doubles)."""
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def in_circle(a, b, c, d):
    """> 0 when d lies strictly inside the circumcircle of the counter-clockwise (a, b, c)."""
    rows = [(p[0] - d[0], p[1] - d[1]) for p in (a, b, c)]
    lifted = [(x, y, x * x + y * y) for x, y in rows]
    (ax, ay, aw), (bx, by, bw), (cx, cy, cw) = lifted
    return (
        ax * (by * cw - bw * cy) - ay * (bx * cw - bw * cx) + aw * (bx * cy - by * cx)
    )


def hull_area(points):
    """Twice the area of the convex hull of `points` (Fraction pairs), monotone chain."""
    ordered = sorted(set(points))

    def chain(sequence):
        hull = []
        for p in sequence:
            while len(hull) >= 2 and orient(hull[-2], hull[-1], p) <= 0:
                hull.pop()
            hull.append(p)
        return hull[:-1]

    hull = chain(ordered) + chain(reversed(ordered))
    return sum(
        hull[i][0] * hull[(i + 1) % len(hull)][1] - hull[(i + 1) % len(hull)][0] * hull[i][1]
        for i in range(len(hull))
    )


def check_exact_delaunay(vertices, triangles):
    """Asserts, with exact arithmetic independent of terratin's predicates: every triangle
    counter-clockwise; each directed edge used once; across every interior edge the opposite
    vertex not strictly inside the circumcircle; the triangles cover exactly the convex hull;
    every vertex used."""
    points = [(Fraction(x), Fraction(y)) for x, y in vertices[:, :2].tolist()]
    opposite = {}
    area = 0
    for a, b, c in triangles.tolist():
        twice_area = orient(points[a], points[b], points[c])
        assert twice_area > 0, f"triangle {(a, b, c)} is not counter-clockwise"
        area += twice_area
        for edge, apex in (((a, b), c), ((b, c), a), ((c, a), b)):
            assert edge not in opposite, f"edge {edge} used twice"
            opposite[edge] = apex
    for (a, b), c in opposite.items():
        d = opposite.get((b, a))
        if d is not None:
            assert in_circle(points[a], points[b], points[c], points[d]) <= 0, (
                f"vertex {d} inside the circumcircle of {(a, b, c)}"
            )
    assert area == hull_area(points), "the triangles do not cover the convex hull exactly"
    assert set(numpy.unique(triangles).tolist()) == set(range(len(points)))


def canonical_mesh(vertices, triangles):
    """(vertices sorted by x, y, z; triangles over those sorted vertices, each rotated to start
    at its smallest corner, sorted): equal for two meshes with the same vertices and
    triangles, whatever their numbering and each triangle's first corner."""
    order = numpy.lexsort((vertices[:, 2], vertices[:, 1], vertices[:, 0]))
    rank = numpy.empty(len(vertices), dtype=numpy.int64)
    rank[order] = numpy.arange(len(vertices))
    ranked = rank[triangles]
    rotation = (ranked.argmin(axis=1)[:, None] + numpy.arange(3)) % 3
    rotated = numpy.take_along_axis(ranked, rotation, axis=1)
    return vertices[order], rotated[numpy.lexsort(rotated.T[::-1])]


def read_ply(path):
    """(vertices, triangles) of a binary little-endian PLY as terratin writes it
    (lib/src/io/ply_writer.cpp): vertex x y z doubles, face uchar count + int32 indices."""
    data = pathlib.Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii", "replace").splitlines()
    counts = {
        line.split()[1]: int(line.split()[2]) for line in header if line.startswith("element")
    }
    vertex_count, face_count = counts["vertex"], counts["face"]
    vertices = numpy.frombuffer(data, dtype="<f8", count=3 * vertex_count, offset=end)
    faces = numpy.frombuffer(
        data,
        dtype=numpy.dtype([("n", "u1"), ("i", "<i4", (3,))]),
        count=face_count,
        offset=end + 24 * vertex_count,
    )
    assert (faces["n"] == 3).all()
    return vertices.reshape(-1, 3), faces["i"].copy()


@pytest.fixture(scope="session")
def terratin_cli():
    """The terratin CLI the build made (ctest passes it as TERRATIN_CLI)."""
    path = os.environ.get("TERRATIN_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("TERRATIN_CLI is not set to the terratin executable")
    return path


@pytest.fixture(scope="session")
def shared_dems():
    """The real DEMs of ../shared/dems (see its README)."""
    path = pathlib.Path(
        os.environ.get("TERRATIN_SHARED_DEMS", pathlib.Path(__file__).parents[3] / "shared/dems")
    )
    if not path.is_dir():
        pytest.skip(f"no shared DEMs at {path}")
    return path


def canonical_corners(corners):
    """Triangles given by their corners' coordinates (T, 3, 3), each rotated to start at its
    lexicographically smallest corner (x, then y, then z), sorted: equal for two meshes with
    the same triangles, whatever their vertex numbering and each triangle's first corner."""
    corners = numpy.asarray(corners, dtype=numpy.float64)

    def before(a, b):
        x, y, z = (a[:, k] - b[:, k] for k in range(3))
        return (x < 0) | ((x == 0) & ((y < 0) | ((y == 0) & (z < 0))))

    c0, c1, c2 = corners[:, 0], corners[:, 1], corners[:, 2]
    first = numpy.where(
        before(c0, c1) & before(c0, c2), 0, numpy.where(before(c1, c2), 1, 2)
    )
    rotation = (first[:, None] + numpy.arange(3)) % 3
    rotated = numpy.take_along_axis(corners, rotation[:, :, None], axis=1).reshape(-1, 9)
    return rotated[numpy.lexsort(rotated.T[::-1])]
