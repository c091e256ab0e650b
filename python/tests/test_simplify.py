"""terratin.simplify: a DEM array in, the CLI's TIN for the same raster and options out."""

import subprocess

import numpy
import pytest
from osgeo import gdal, osr

import terratin
from conftest import canonical_mesh, check_exact_delaunay, read_ply

gdal.UseExceptions()

UTM_GEOTRANSFORM = (500000.0, 10.0, 0.0, 5000000.0, 0.0, -10.0)


def terrain(rows, columns, seed=5):
    """Smooth hills with noise, metres."""
    y, x = numpy.mgrid[0:rows, 0:columns]
    noise = numpy.random.default_rng(seed).normal(0.0, 0.3, (rows, columns))
    return 300.0 + 40.0 * numpy.sin(x / 9.0) * numpy.cos(y / 13.0) + 0.05 * x * y / 10 + noise


def write_geotiff(path, z, geotransform, nodata=None):
    gdal_type = gdal.GetDataTypeByName(
        {"float64": "Float64", "float32": "Float32", "int16": "Int16", "uint16": "UInt16"}[
            z.dtype.name
        ]
    )
    dataset = gdal.GetDriverByName("GTiff").Create(str(path), z.shape[1], z.shape[0], 1, gdal_type)
    dataset.SetGeoTransform(geotransform)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32633)
    dataset.SetProjection(srs.ExportToWkt())
    band = dataset.GetRasterBand(1)
    if nodata is not None:
        band.SetNoDataValue(nodata)
    band.WriteArray(z)
    dataset = None


def cli_tin(cli, raster, output, *options):
    subprocess.run(
        [cli, "build", str(raster), "-o", str(output), "--quiet", *options],
        check=True,
        capture_output=True,
    )
    return read_ply(output)


def assert_same_tin(python_tin, cli_tin_arrays):
    """The same vertices and triangles, as sets of triangles up to rotation."""
    vertices, triangles = canonical_mesh(*python_tin)
    cli_vertices, cli_triangles = canonical_mesh(*cli_tin_arrays)
    assert numpy.array_equal(vertices, cli_vertices)
    assert numpy.array_equal(triangles, cli_triangles)


def with_nodata(z, value):
    """z with a 5 x 6 hole and a few single nodata cells set to `value`."""
    z = z.copy()
    z[10:15, 20:26] = value
    z[3, 4] = z[30, 7] = z[-1, -1] = value
    return z


RASTERS = {
    "float64 rounded to float32": lambda: (terrain(40, 50), None),
    "float32 with nan": lambda: (with_nodata(terrain(40, 50).astype(numpy.float32), numpy.nan), None),
    "float32 with nodata": lambda: (
        with_nodata(terrain(40, 50).astype(numpy.float32), -3.4028234663852886e38),
        -3.4028234663852886e38,
    ),
    "int16 with nodata": lambda: (with_nodata(terrain(40, 50).astype(numpy.int16), -32768), -32768),
}

OPTIONS = {
    "max error": ({"max_error": 1.5}, ["--max-error", "1.5"]),
    "max points": ({"max_points": 150}, ["--max-points", "150"]),
    "holes filled, long edges dropped": (
        {"max_error": 0.5, "fill_holes": True, "max_edge": 80.0},
        ["--max-error", "0.5", "--fill-holes", "--max-edge", "80"],
    ),
    "max hole and max triangles": (
        {"max_hole": 40, "max_triangles": 400},
        ["--max-hole", "40", "--max-triangles", "400"],
    ),
    "seam-free tiles": (
        {"max_error": 1.0, "tile_size": 16, "max_hole": 3},
        ["--max-error", "1", "--tile-size", "16", "--max-hole", "3"],
    ),
}


@pytest.mark.parametrize("raster", RASTERS.values(), ids=RASTERS.keys())
@pytest.mark.parametrize("options", OPTIONS.values(), ids=OPTIONS.keys())
def test_tin_is_the_clis_for_the_same_raster(raster, options, terratin_cli, tmp_path):
    z, nodata = raster()
    python_options, cli_options = options
    write_geotiff(tmp_path / "in.tif", z, UTM_GEOTRANSFORM, nodata)
    expected = cli_tin(terratin_cli, tmp_path / "in.tif", tmp_path / "out.ply", *cli_options)
    tin = terratin.simplify(z, UTM_GEOTRANSFORM, nodata, **python_options)
    assert_same_tin(tin, expected)


def test_real_dem_tin_is_the_clis(terratin_cli, shared_dems, tmp_path):
    path = shared_dems / "gdalraster__lf_elev_220_mt_hood_utm.tif"
    if not path.exists():
        pytest.skip(f"{path} is absent")
    dataset = gdal.Open(str(path))
    band = dataset.GetRasterBand(1)
    z = band.ReadAsArray()
    tin = terratin.simplify(
        z, dataset.GetGeoTransform(), band.GetNoDataValue(), max_error=5
    )
    expected = cli_tin(terratin_cli, path, tmp_path / "hood.ply", "--max-error", "5")
    assert_same_tin(tin, expected)


def test_without_limits_every_valid_cell_is_a_vertex_at_its_centre():
    z = numpy.arange(12, dtype=numpy.int16).reshape(3, 4)
    z[1, 2] = -1
    vertices, triangles = terratin.simplify(z, (100.0, 2.0, 0.0, 50.0, 0.0, -2.0), nodata=-1)
    assert len(vertices) == 11
    expected = {
        (100.0 + 2.0 * (c + 0.5), 50.0 - 2.0 * (r + 0.5), float(z[r, c]))
        for r in range(3)
        for c in range(4)
        if (r, c) != (1, 2)
    }
    assert set(map(tuple, vertices.tolist())) == expected


def test_result_is_exactly_delaunay_and_reads_any_layout():
    z = terrain(30, 30)
    reference = terratin.simplify(z, UTM_GEOTRANSFORM, max_error=0.5, validate=True)
    check_exact_delaunay(*reference)
    for variant in (numpy.asfortranarray(z), z.astype(">f8"), numpy.repeat(z, 2, axis=1)[:, ::2]):
        tin = terratin.simplify(variant, UTM_GEOTRANSFORM, max_error=0.5)
        assert all(numpy.array_equal(a, b) for a, b in zip(tin, reference))


BAD_CALLS = {
    "one dimension": ((numpy.zeros(9), UTM_GEOTRANSFORM), {}, "2-D"),
    "object dtype": ((numpy.zeros((3, 3), dtype=object), UTM_GEOTRANSFORM), {}, "dtype"),
    "bool dtype": ((numpy.zeros((3, 3), dtype=bool), UTM_GEOTRANSFORM), {}, "dtype"),
    "short geotransform": ((terrain(5, 5), (0, 1, 0, 0)), {}, "6 numbers"),
    "text geotransform": ((terrain(5, 5), "0 1 0 0 0 -1"), {}, "6 numbers"),
    "zero area geotransform": ((terrain(5, 5), (0, 1, 0, 0, 0, 0)), {}, "zero area"),
    "nan geotransform": ((terrain(5, 5), (0, numpy.nan, 0, 0, 0, -1)), {}, "finite"),
    "all nodata": ((numpy.full((4, 4), numpy.nan), UTM_GEOTRANSFORM), {}, "valid"),
    "empty": ((numpy.zeros((0, 4)), UTM_GEOTRANSFORM), {}, ""),
    "infinite elevation": ((numpy.array([[0, 1], [numpy.inf, 2.0]]), UTM_GEOTRANSFORM), {}, ""),
    "negative max_error": ((terrain(5, 5), UTM_GEOTRANSFORM), {"max_error": -1}, ""),
    "max_points below 3": ((terrain(5, 5), UTM_GEOTRANSFORM), {"max_points": 2}, ""),
    "negative max_hole": ((terrain(5, 5), UTM_GEOTRANSFORM), {"max_hole": -1}, "max_hole"),
    "zero max_edge": ((terrain(5, 5), UTM_GEOTRANSFORM), {"max_edge": 0.0}, "max_edge"),
    "negative threads": ((terrain(5, 5), UTM_GEOTRANSFORM), {"threads": -2}, "threads"),
}


@pytest.mark.parametrize("arguments,options,message", BAD_CALLS.values(), ids=BAD_CALLS.keys())
def test_bad_input_raises_invalid_input_error(arguments, options, message):
    with pytest.raises(terratin.InvalidInputError, match=message):
        terratin.simplify(*arguments, **options)
