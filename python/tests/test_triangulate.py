"""terratin.triangulate: exact Delaunay TINs of NumPy points, arrays in and out."""

import numpy
import pytest

import terratin
from conftest import check_exact_delaunay

METHODS = ["auto", "strips", "sequential", "batch", "circumcircle"]


def random_points(count, seed=7):
    return numpy.random.default_rng(seed).random((count, 3)) * [1000.0, 1000.0, 100.0]


@pytest.mark.parametrize("method", METHODS)
def test_random_points_give_an_exact_delaunay_tin(method):
    points = random_points(300)
    vertices, triangles = terratin.triangulate(points, method=method, threads=2)
    assert vertices.shape == (300, 3) and vertices.dtype == numpy.float64
    assert triangles.shape[1] == 3 and triangles.dtype == numpy.int32
    assert sorted(map(tuple, vertices.tolist())) == sorted(map(tuple, points.tolist()))
    check_exact_delaunay(vertices, triangles)


@pytest.mark.parametrize("method", METHODS)
def test_cocircular_grid_with_duplicates_gives_an_exact_delaunay_tin(method):
    rows, columns = numpy.mgrid[0:12, 0:15]
    grid = numpy.column_stack([columns.ravel() * 0.5, rows.ravel() * 0.25, rows.ravel() * 1.0])
    repeated = grid[::7].copy()
    repeated[:, 2] += 99.0  # duplicates of (x, y) with another z
    vertices, triangles = terratin.triangulate(numpy.vstack([grid, repeated]), method=method)
    assert len(vertices) == len(grid)
    check_exact_delaunay(vertices, triangles)


def test_duplicates_merge_keeping_the_first_z_as_the_cli_does():
    points = numpy.array(
        [[0, 0, 1], [1, 0, 2], [0, 1, 3], [1, 0, 20], [1, 1, 4], [0, 0, 10]], dtype=float
    )
    vertices, triangles = terratin.triangulate(points)
    assert sorted(map(tuple, vertices.tolist())) == [(0, 0, 1), (0, 1, 3), (1, 0, 2), (1, 1, 4)]
    assert len(triangles) == 2


def test_two_columns_give_zero_elevations():
    points = random_points(50)
    vertices, _ = terratin.triangulate(points[:, :2])
    assert (vertices[:, 2] == 0).all()
    assert sorted(map(tuple, vertices[:, :2].tolist())) == sorted(map(tuple, points[:, :2].tolist()))


@pytest.mark.parametrize(
    "convert",
    [
        lambda p: p.astype(numpy.float32),
        lambda p: numpy.round(p).astype(numpy.int64),
        lambda p: numpy.asfortranarray(p),
        lambda p: p.astype(">f8"),
        lambda p: numpy.repeat(p, 2, axis=0)[::2],
        lambda p: p.tolist(),
    ],
    ids=["float32", "int64", "fortran", "big-endian", "strided", "list"],
)
def test_other_dtypes_and_layouts_are_copied_to_the_same_tin(convert):
    points = random_points(200)
    converted = convert(points)
    expected = numpy.asarray(converted, dtype=numpy.float64)
    vertices, triangles = terratin.triangulate(converted, method="sequential")
    reference_vertices, reference_triangles = terratin.triangulate(
        numpy.ascontiguousarray(expected), method="sequential"
    )
    assert numpy.array_equal(vertices, reference_vertices)
    assert numpy.array_equal(triangles, reference_triangles)


def test_results_own_the_mesh_buffers_without_copies():
    vertices, triangles = terratin.triangulate(random_points(100))
    # Each array's base is the capsule holding the library's own vector (arrays.cpp).
    assert type(vertices.base).__name__ == "PyCapsule"
    assert type(triangles.base).__name__ == "PyCapsule"
    assert vertices.flags["C_CONTIGUOUS"] and triangles.flags["C_CONTIGUOUS"]
    del vertices
    assert triangles.max() < 100  # the other array outlives its sibling


def test_same_seed_gives_the_same_mesh():
    points = random_points(500)
    first = terratin.triangulate(points, method="sequential", seed=3)
    second = terratin.triangulate(points, method="sequential", seed=3)
    assert all(numpy.array_equal(a, b) for a, b in zip(first, second))


def triangle_set(vertices, triangles):
    """The triangles as sorted corner coordinates, whatever their order and numbering."""
    return sorted(tuple(sorted(map(tuple, vertices[t][:, :2].tolist()))) for t in triangles)


def test_every_seed_method_and_thread_count_give_the_same_triangles_on_a_grid():
    # Every cell of a grid is cocircular: the diagonals are decided by the points alone.
    xs, ys = numpy.meshgrid(numpy.arange(40.0), numpy.arange(30.0))
    points = numpy.column_stack([xs.ravel(), ys.ravel(), numpy.zeros(xs.size)])
    reference = triangle_set(*terratin.triangulate(points, method="sequential", seed=1))
    assert len(reference) == 2 * 39 * 29
    for method in ("strips", "batch", "circumcircle"):
        for threads in (1, 2):
            for seed in (1, 9):
                mesh = terratin.triangulate(points, method=method, threads=threads, seed=seed)
                assert triangle_set(*mesh) == reference, (method, threads, seed)


BAD_POINTS = {
    "one dimension": (numpy.zeros(9), "shape"),
    "three dimensions": (numpy.zeros((3, 3, 3)), "shape"),
    "four columns": (numpy.zeros((5, 4)), "shape"),
    "one column": (numpy.zeros((5, 1)), "shape"),
    "object dtype": (numpy.array([[1, 2, 3], [4, 5, 6], [7, 8, None]], dtype=object), "dtype"),
    "complex dtype": (numpy.ones((5, 3), dtype=complex), "dtype"),
    "bool dtype": (numpy.ones((5, 3), dtype=bool), "dtype"),
    "strings": (numpy.array([["a", "b"], ["c", "d"], ["e", "f"]]), "dtype"),
    "ragged list": ([[0, 0], [1, 0, 2], [0, 1]], "not an array"),
    "empty": (numpy.zeros((0, 3)), "three distinct points"),
    "nan": (numpy.array([[0, 0, 0], [1, 0, 0], [0, 1, numpy.nan]]), "finite"),
    "infinity": (numpy.array([[0, 0, 0], [numpy.inf, 0, 0], [0, 1, 0]]), "finite"),
    "two distinct points": (numpy.array([[0, 0, 0], [1, 1, 0], [1, 1, 5], [0, 0, 2]]), "distinct"),
    "collinear": (numpy.array([[0, 0, 0], [1, 1, 0], [2, 2, 0], [3, 3, 0]]), "one line"),
}


@pytest.mark.parametrize("points,message", BAD_POINTS.values(), ids=BAD_POINTS.keys())
def test_bad_arrays_raise_invalid_input_error(points, message):
    with pytest.raises(terratin.InvalidInputError, match=message):
        terratin.triangulate(points)


@pytest.mark.parametrize(
    "options,message",
    [
        ({"method": "fastest"}, "method must be"),
        ({"threads": -1}, "threads must be 0 or more"),
        ({"threads": 100000}, "thread count"),
    ],
)
def test_bad_options_raise_invalid_input_error(options, message):
    with pytest.raises(terratin.InvalidInputError, match=message):
        terratin.triangulate(random_points(10), **options)
