"""The scripts of examples/python, run as a user runs them."""

import os
import pathlib
import subprocess
import sys

import numpy
import pytest
from osgeo import ogr

from conftest import canonical_corners, read_ply

EXAMPLES = pathlib.Path(__file__).parents[2] / "examples" / "python"


def run_example(script, *arguments):
    return subprocess.run(
        [sys.executable, str(EXAMPLES / script), *map(str, arguments)],
        check=True,
        capture_output=True,
        text=True,
        env=os.environ,
    )


def gpkg_corners(path):
    """Each Polygon Z's first three ring points: the triangle's corners."""
    dataset = ogr.Open(str(path))  # held: the layer dies with it
    return canonical_corners(
        [
            feature.GetGeometryRef().GetGeometryRef(0).GetPoints()[:3]
            for feature in dataset.GetLayer(0)
        ]
    )


def test_dem_pipeline_makes_the_command_lines_tin_of_mt_hood(terratin_cli, shared_dems, tmp_path):
    dem = shared_dems / "gdalraster__lf_elev_220_mt_hood_utm.tif"
    if not dem.exists():
        pytest.skip(f"{dem} is absent")
    run_example("dem_pipeline.py", dem, tmp_path / "pipeline.gpkg", "--max-error", "2")
    subprocess.run(
        [terratin_cli, "build", str(dem), "-o", str(tmp_path / "cli.ply"), "--max-error", "2",
         "--quiet"],
        check=True,
    )
    vertices, triangles = read_ply(tmp_path / "cli.ply")
    expected = canonical_corners(vertices[triangles])
    assert numpy.array_equal(gpkg_corners(tmp_path / "pipeline.gpkg"), expected)
    dataset = ogr.Open(str(tmp_path / "pipeline.gpkg"))
    assert dataset.GetLayer(0).GetSpatialRef().GetAuthorityCode(None) == "26910"
