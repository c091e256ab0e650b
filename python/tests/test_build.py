"""terratin.build: the command line's build from Python, with its checks and messages."""

import json
import logging
import pathlib
import subprocess

import numpy
import pytest
from osgeo import gdal, ogr

import terratin
from conftest import canonical_corners, read_ply

gdal.UseExceptions()

SAMPLE = pathlib.Path(__file__).parents[2] / "sample_dems" / "ridges_utm.tif"


def cli_report(cli, inputs, output, *options):
    run = subprocess.run(
        [cli, "build", *map(str, inputs), "-o", str(output), "--json", "--quiet", *options],
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(run.stdout)


def ply_corners(path):
    vertices, triangles = read_ply(path)
    return canonical_corners(vertices[triangles])


def feature_count(path):
    dataset = ogr.Open(str(path))  # held: the layer dies with it
    return dataset.GetLayer(0).GetFeatureCount()


def test_writes_the_tin_and_returns_the_json_report(tmp_path):
    output = tmp_path / "tin.gpkg"
    report = terratin.build(SAMPLE, output, max_error=2.0, attributes="basic")
    assert report["output"] == str(output)
    assert report["format"] == "GPKG"
    assert report["crs"]["code"] == "EPSG:32633"
    assert report["counts"]["triangles"] > 0
    assert feature_count(output) == report["counts"]["triangles"]


def test_same_tin_and_counts_as_the_command_line(terratin_cli, tmp_path):
    report = terratin.build([SAMPLE], tmp_path / "python.ply", max_points=3000, seed=7)
    expected = cli_report(
        terratin_cli, [SAMPLE], tmp_path / "cli.ply", "--max-points", "3000", "--seed", "7"
    )
    assert report["counts"] == expected["counts"]
    assert numpy.array_equal(ply_corners(tmp_path / "python.ply"), ply_corners(tmp_path / "cli.ply"))


def test_tiles_give_the_command_lines_tin(terratin_cli, tmp_path):
    # tile_size is the CLI's --tile-size: seam-free tiles within the bound.
    report = terratin.build(SAMPLE, tmp_path / "python.ply", max_error=0.5, tile_size=64)
    expected = cli_report(
        terratin_cli, [SAMPLE], tmp_path / "cli.ply", "--max-error", "0.5", "--tile-size", "64"
    )
    assert report["counts"] == expected["counts"]
    assert report["refine"]["achieved_max_error"] <= 0.5
    assert numpy.array_equal(ply_corners(tmp_path / "python.ply"), ply_corners(tmp_path / "cli.ply"))
    with pytest.raises(terratin.InvalidInputError, match="tile_size must be 2 to"):
        terratin.build(SAMPLE, tmp_path / "bad.ply", max_error=0.5, tile_size=1)


def test_tiles_dir_takes_the_place_of_the_output(tmp_path):
    joined = terratin.build(SAMPLE, tmp_path / "joined.ply", max_error=0.5, tile_size=64)
    report = terratin.build(SAMPLE, None, max_error=0.5, tile_size=64, tiles_dir=tmp_path / "t")
    assert report["counts"]["triangles"] == joined["counts"]["triangles"]
    tiles = list((tmp_path / "t").glob("tile_*.gpkg"))
    assert len(tiles) > 1
    assert feature_count(tmp_path / "t" / "tiles.gpkg") == len(tiles)
    with pytest.raises(terratin.InvalidInputError, match="output must be a path"):
        terratin.build(SAMPLE, None, max_error=0.5, tile_size=64)


def test_memory_limit_writes_the_tiled_tin_tile_by_tile(tmp_path):
    # memory_limit is --memory-limit: the joined TIN's file, written as tiles come
    # (one thread, so that a tile's triangles come in one order).
    joined = terratin.build(SAMPLE, tmp_path / "joined.ply", max_error=0.5, tile_size=64, threads=1)
    streamed = terratin.build(
        SAMPLE, tmp_path / "streamed.ply", max_error=0.5, tile_size=64, threads=1, memory_limit="1G"
    )
    assert streamed["counts"] == joined["counts"]
    assert (tmp_path / "streamed.ply").read_bytes() == (tmp_path / "joined.ply").read_bytes()
    sized = terratin.build(SAMPLE, tmp_path / "sized.gpkg", max_error=0.5, memory_limit=512 << 20)
    assert any(notice.startswith("tiles of ") for notice in sized["notices"])
    assert feature_count(tmp_path / "sized.gpkg") == sized["counts"]["triangles"]
    with pytest.raises(terratin.InvalidInputError, match="memory_limit takes a size"):
        terratin.build(SAMPLE, tmp_path / "bad.ply", max_error=0.5, memory_limit="2X")


def test_options_of_every_kind_reach_the_build(tmp_path):
    # Text with a List option (columns), a Repeatable one given as a list (inputs), a Flag
    # (overwrite), a Count (threads) and a Number (z_factor).
    points = tmp_path / "points.txt"
    rng = numpy.random.default_rng(3)
    table = numpy.column_stack([rng.integers(0, 9, 200), rng.random((200, 3)) * 100])
    numpy.savetxt(points, table, fmt="%.6f")
    output = tmp_path / "points.ply"
    output.write_text("old")
    report = terratin.build(
        [points, str(points)],
        output,
        columns=[2, 3, 4],
        s_srs="EPSG:32633",
        overwrite=True,
        threads=1,
        z_factor=2.0,
        duplicate_z="max",
    )
    # The second input repeats the first: every point is a duplicate once.
    assert report["counts"]["points"] == 400
    assert report["counts"]["duplicates"] == 200
    vertices, _ = read_ply(output)
    assert vertices[:, 2].max() == 2.0 * numpy.loadtxt(points)[:, 3].max()


def test_none_means_not_given(tmp_path):
    report = terratin.build(SAMPLE, tmp_path / "tin.ply", max_error=None, max_points=2000)
    assert report["counts"]["vertices"] == 2000


@pytest.mark.parametrize(
    "options, message",
    [
        ({"max_eror": 2}, "unknown option 'max_eror'; did you mean 'max_error'?"),
        ({"method": "fast"}, "method must be sequential, batch, circumcircle, strips or auto"),
        ({"overwrite": "yes"}, "overwrite takes true or false"),
        ({"keep_geographic": True, "t_srs": "EPSG:4326"}, "keep_geographic"),
        ({"threads": -1}, "threads"),
    ],
)
def test_bad_options_raise_with_the_keyword_in_the_message(options, message, tmp_path):
    with pytest.raises(terratin.InvalidInputError, match=message) as raised:
        terratin.build(SAMPLE, tmp_path / "tin.gpkg", **options)
    assert "--" not in str(raised.value)
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize(
    "inputs, output, message",
    [
        ([SAMPLE, 3], "tin.gpkg", "each of inputs must be a path"),
        (3.5, "tin.gpkg", "inputs must be a path or a list of paths"),
        (SAMPLE, None, "output must be a path"),
        ([], "tin.gpkg", "inputs"),
    ],
)
def test_bad_paths_raise_invalid_input_error(inputs, output, message, tmp_path):
    with pytest.raises(terratin.InvalidInputError, match=message):
        terratin.build(inputs, output if output is None else tmp_path / output)


def test_a_missing_input_raises_io_error(tmp_path):
    with pytest.raises(terratin.IoError):
        terratin.build(tmp_path / "absent.tif", tmp_path / "tin.gpkg")
    assert not list(tmp_path.iterdir())


def test_an_existing_output_stays_without_overwrite(tmp_path):
    output = tmp_path / "tin.gpkg"
    output.write_bytes(b"not a tin")
    with pytest.raises(terratin.Error, match="exists"):
        terratin.build(SAMPLE, output, max_error=2)
    assert output.read_bytes() == b"not a tin"


@pytest.mark.parametrize("stop_at", [0.0, 0.5, 0.9])
def test_cancelling_leaves_the_old_output_and_nothing_else(stop_at, tmp_path):
    output = tmp_path / "tin.gpkg"
    output.write_bytes(b"old tin")
    with pytest.raises(terratin.Cancelled):
        terratin.build(SAMPLE, output, overwrite=True, progress=lambda f, m: f < stop_at)
    assert output.read_bytes() == b"old tin"
    assert [path.name for path in tmp_path.iterdir()] == ["tin.gpkg"]


def test_progress_rises_to_one_and_an_exception_in_it_propagates(tmp_path):
    fractions = []
    terratin.build(SAMPLE, tmp_path / "tin.ply", max_error=1, progress=lambda f, m: fractions.append(f) or True)
    assert fractions == sorted(fractions)
    assert fractions[-1] == 1.0

    def failing(fraction, message):
        raise ValueError("stop here")

    with pytest.raises(ValueError, match="stop here"):
        terratin.build(SAMPLE, tmp_path / "other.ply", progress=failing)
    assert not (tmp_path / "other.ply").exists()


def test_notices_are_in_the_report_and_logged(tmp_path, caplog):
    # A geographic DEM is projected to the UTM zone of its centre, with a notice.
    geographic = tmp_path / "geographic.tif"
    gdal.Warp(str(geographic), str(SAMPLE), dstSRS="EPSG:4326")
    with caplog.at_level(logging.INFO, logger="terratin"):
        report = terratin.build(geographic, tmp_path / "tin.ply", max_error=5)
    assert any("UTM" in notice for notice in report["notices"])
    assert [record.getMessage() for record in caplog.records] == report["notices"]


def test_a_lake_and_a_road_simplified_match_the_command_line(terratin_cli, tmp_path):
    from osgeo import osr

    crs = osr.SpatialReference()
    crs.ImportFromEPSG(32633)
    areas = tmp_path / "areas.gpkg"
    dataset = ogr.GetDriverByName("GPKG").CreateDataSource(str(areas))
    lakes = dataset.CreateLayer("lakes", crs, ogr.wkbPolygon)
    lakes.CreateField(ogr.FieldDefn("level", ogr.OFTReal))
    lake = ogr.Feature(lakes.GetLayerDefn())
    lake.SetGeometry(ogr.CreateGeometryFromWkt(
        "POLYGON ((456100.5 5103300.25, 457000.75 5103150.5, 456600.5 5104400.25, "
        "456100.5 5103300.25))"))
    lake["level"] = 812.5
    lakes.CreateFeature(lake)
    roads = dataset.CreateLayer("roads", crs, ogr.wkbLineString)
    road = ogr.Feature(roads.GetLayerDefn())
    road.SetGeometry(ogr.CreateGeometryFromWkt(
        "LINESTRING (455501.3 5104003.7, 456700.9 5103100.2, 457800.1 5104500.3)"))
    roads.CreateFeature(road)
    dataset = None
    report = terratin.build(
        str(SAMPLE), str(tmp_path / "py.ply"), max_error=2.0,
        breaklines=[f"{areas}|layername=roads"], replace=f"{areas}|layername=lakes",
        replace_z_field="level",
    )
    cli = subprocess.run(
        [terratin_cli, "build", str(SAMPLE), "-o", str(tmp_path / "cli.ply"), "--json", "--quiet",
         "--max-error", "2", "--breaklines", f"{areas}|layername=roads",
         "--replace", f"{areas}|layername=lakes", "--replace-z-field", "level"],
        check=True, capture_output=True, text=True,
    )
    assert report["constraints"] == json.loads(cli.stdout)["constraints"]
    assert report["constraints"]["replace_polygons"] == 1
    assert (tmp_path / "py.ply").read_bytes() == (tmp_path / "cli.ply").read_bytes()


def test_a_laz_gives_the_tin_of_its_las_twin(shared_dems, tmp_path):
    laz, las = shared_dems / "laz" / "lidr__Megaplot.laz", shared_dems / "laz" / "lasr__Megaplot.las"
    if not (laz.exists() and las.exists()):
        pytest.skip("the shared LAZ files are absent")
    from_laz = terratin.build(laz, tmp_path / "laz.ply", classes=[2], returns="last")
    from_las = terratin.build(las, tmp_path / "las.ply", classes=[2], returns="last")
    assert from_laz["counts"] == from_las["counts"]
    assert from_laz["crs"]["code"] == "EPSG:26917"
    assert numpy.array_equal(ply_corners(tmp_path / "laz.ply"), ply_corners(tmp_path / "las.ply"))
