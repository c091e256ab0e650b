"""Regression tests of what a user's first hour with the module found: the vertices' source
rows, huge broadcast arrays, options of the wrong type, rasterio transforms, NUL in paths,
and SIGTERM / SIGHUP during build()."""

import os
import pathlib
import signal
import subprocess
import sys
import textwrap

import numpy
import pytest

import terratin

SAMPLE = pathlib.Path(__file__).resolve().parents[2] / "sample_dems" / "ridges_utm.tif"


def test_source_index_gives_each_vertex_its_row_in_the_input():
    # The vertices come back in the triangulation's order, not the input's.
    points = numpy.array([[0.0, 0.0, 1.0], [1.0, 0.0, 2.0], [0.0, 1.0, 3.0], [1.0, 1.0, 4.0]])
    vertices, triangles, index = terratin.triangulate(points, return_index=True)
    assert index.dtype == numpy.int64
    assert sorted(index.tolist()) == [0, 1, 2, 3]
    assert (points[index] == vertices).all()
    assert len(triangles) == 2


def test_source_index_of_merged_duplicates_is_the_first_ones_row():
    random = numpy.random.default_rng(4)
    points = random.random((500, 3))
    points = numpy.concatenate([points, points[:100] + [0.0, 0.0, 5.0]])
    vertices, _, index = terratin.triangulate(points, return_index=True)
    assert len(vertices) == 500
    assert index.max() < 500
    assert (points[index] == vertices).all()


def test_a_huge_broadcast_array_is_refused_before_any_copy():
    point = numpy.array([1.0, 2.0, 3.0])
    with pytest.raises(terratin.InvalidInputError, match="repeated 1000000000 times"):
        terratin.triangulate(numpy.broadcast_to(point, (10**9, 3)))


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: terratin.triangulate(numpy.eye(3), seed=-1), "seed must be 0 to"),
        (lambda: terratin.triangulate(numpy.eye(3), seed=1.5), "seed must be an integer"),
        (lambda: terratin.triangulate(numpy.eye(3), threads="2"), "threads must be an integer"),
        (
            lambda: terratin.simplify(numpy.ones((3, 3)), (0, 1, 0, 3, 0, -1), nodata="x"),
            "nodata must be a number or None",
        ),
        (
            lambda: terratin.simplify(numpy.ones((3, 3)), (0, 1, 0, 3, 0, -1), max_points=2.5),
            "max_points must be an integer",
        ),
    ],
)
def test_options_of_the_wrong_type_raise_the_modules_own_error(call, message):
    with pytest.raises(terratin.InvalidInputError, match=message):
        call()


class Affine(tuple):
    """What rasterio's Affine is: a 9-tuple a, b, c, d, e, f, 0, 0, 1 with to_gdal()."""

    def __new__(cls, a, b, c, d, e, f):
        return super().__new__(cls, (a, b, c, d, e, f, 0.0, 0.0, 1.0))

    def to_gdal(self):
        return (self[2], self[0], self[1], self[5], self[3], self[4])


def test_an_affine_transform_gives_the_same_tin_as_gdals_coefficients():
    z = numpy.arange(20.0).reshape(4, 5)
    gdal_order = (500000.0, 10.0, 0.0, 5000040.0, 0.0, -10.0)
    affine = Affine(10.0, 0.0, 500000.0, 0.0, -10.0, 5000040.0)
    expected, _ = terratin.simplify(z, gdal_order)
    for transform in (affine, tuple(affine)):
        vertices, _ = terratin.simplify(z, transform)
        assert (vertices == expected).all()
    assert vertices[:, 0].min() == 500005.0  # the first cell's centre


def test_nine_values_that_are_no_affine_matrix_are_refused():
    with pytest.raises(terratin.InvalidInputError, match="its last row is"):
        terratin.simplify(numpy.ones((3, 3)), (1, 0, 0, 0, -1, 0, 5, 0, 1))


@pytest.mark.parametrize("where", ["output", "input"])
def test_a_nul_in_a_path_is_refused_not_cut(where, tmp_path):
    output = str(tmp_path / "o.gpkg")
    inputs = str(SAMPLE)
    if where == "output":
        output = str(tmp_path / "o\x00.gpkg")
    else:
        inputs = inputs + "\x00.tif"
    with pytest.raises(terratin.InvalidInputError, match="holds a NUL character"):
        terratin.build(inputs, output)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("signal_number", [signal.SIGTERM, signal.SIGHUP])
@pytest.mark.parametrize("target", ["output", "tiles_dir"])
def test_a_termination_signal_during_build_leaves_no_temporary_files(
    signal_number, target, tmp_path
):
    # The signal comes from the progress callable, in the middle of writing; the process must
    # still end by it, after the run has removed its temporaries.
    arguments = (
        f"'{SAMPLE}', '{tmp_path}/tin.gpkg'"
        if target == "output"
        else f"'{SAMPLE}', None, tiles_dir='{tmp_path}/tiles', max_error=1, tile_size=64"
    )
    script = textwrap.dedent(
        f"""
        import os, terratin
        def progress(fraction, message):
            if fraction > 0.2:
                os.kill(os.getpid(), {int(signal_number)})
            return True
        terratin.build({arguments}, progress=progress)
        print("build returned")
        """
    )
    environment = dict(os.environ)
    completed = subprocess.run(
        [sys.executable, "-c", script], env=environment, capture_output=True, text=True
    )
    assert completed.returncode == -signal_number, completed.stderr
    assert "build returned" not in completed.stdout
    assert list(tmp_path.iterdir()) == []
