"""terratin's Processing provider (qgis/terratin_processing) in headless QGIS 3.22.

Run by CTest (qgis.processing) with PYTHONPATH holding the built terratin module and the
plugin's folder, QT_QPA_PLATFORM=offscreen and TERRATIN_CLI, the command line it is compared
with. Each algorithm runs through processing.run as the toolbox runs it.
"""

import json
import os
import pathlib
import subprocess
import sys

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from osgeo import ogr, osr  # noqa: E402
from qgis.core import (  # noqa: E402
    QgsApplication,
    QgsProcessingException,
    QgsProcessingFeedback,
    QgsProject,
    QgsRasterLayer,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QSettings  # noqa: E402

SAMPLE = pathlib.Path(__file__).parents[2] / "sample_dems" / "ridges_utm.tif"


@pytest.fixture(scope="session")
def processing(tmp_path_factory):
    """QGIS with Processing and terratin's provider, once for the whole session; its profile
    and settings in a temporary folder, so that the tests change no user's QGIS."""
    QSettings.setPath(
        QSettings.NativeFormat, QSettings.UserScope, str(tmp_path_factory.mktemp("settings"))
    )
    QgsApplication.setPrefixPath("/usr", True)
    application = QgsApplication([], False, str(tmp_path_factory.mktemp("profile")))
    application.initQgis()
    sys.path.append("/usr/share/qgis/python/plugins")
    import processing as qgis_processing
    from processing.core.Processing import Processing

    from terratin_processing.plugin import TerratinProcessingPlugin

    Processing.initialize()
    plugin = TerratinProcessingPlugin(None)
    plugin.initProcessing()
    yield qgis_processing
    plugin.unload()


def cli_counts(*arguments):
    """The command line's counts for the same build."""
    run = subprocess.run(
        [os.environ["TERRATIN_CLI"], "build", *map(str, arguments), "--json", "--quiet"],
        check=True, capture_output=True, text=True,
    )
    return json.loads(run.stdout)["counts"]


def opened(path):
    layer = QgsVectorLayer(str(path), "tin", "ogr")
    assert layer.isValid(), f"QGIS cannot open {path}"
    return layer


def test_provider_offers_both_algorithms(processing):
    registry = QgsApplication.processingRegistry()
    assert registry.providerById("terratin") is not None
    for name in ("terratin:demtotin", "terratin:pointstotin"):
        algorithm = registry.algorithmById(name)
        assert algorithm is not None, name
        assert algorithm.parameterDefinition("OUTPUT") is not None


def test_the_plugin_installs_into_a_profile_by_link(tmp_path):
    # docs/qgis.md's step: a link in the profile's python/plugins folder; QGIS then loads it.
    plugins = tmp_path / "profile" / "python" / "plugins"
    plugins.mkdir(parents=True)
    source = pathlib.Path(__file__).parents[2] / "qgis" / "terratin_processing"
    (plugins / "terratin_processing").symlink_to(source)
    environment = dict(os.environ)
    # Only the terratin module on the path: the plugin must come from the profile.
    environment["PYTHONPATH"] = os.pathsep.join(
        p for p in environment.get("PYTHONPATH", "").split(os.pathsep)
        if p and not (pathlib.Path(p) / "terratin_processing").exists()
    )
    run = subprocess.run(
        [sys.executable, str(pathlib.Path(__file__).with_name("plugin_install_check.py")),
         str(tmp_path / "profile")],
        env=environment, capture_output=True, text=True,
    )
    assert run.returncode == 0, run.stderr
    lines = dict(line.split(": ", 1) for line in run.stdout.splitlines() if ": " in line)
    assert lines["available"] == "terratin_processing"
    assert lines["processing provider"] == "yes"
    assert lines["from"] == str(plugins / "terratin_processing")
    assert lines["algorithms"] == "terratin:demtotin terratin:pointstotin"
    assert lines["after unload"] == "None"


@pytest.mark.parametrize("extension", ["gpkg", "shp", "fgb"])
def test_dem_to_tin_makes_the_command_lines_tin_with_the_terrain_style(
    processing, extension, tmp_path
):
    output = tmp_path / f"tin.{extension}"
    result = processing.run(
        "terratin:demtotin",
        {"INPUT": str(SAMPLE), "MAX_ERROR": 1.0, "ATTRIBUTES": 1, "OUTPUT": str(output)},
    )
    assert result["OUTPUT"] == str(output)
    counts = cli_counts(SAMPLE, "-o", tmp_path / "cli.ply", "--max-error", "1")
    assert result["TRIANGLES"] == counts["triangles"]
    assert result["VERTICES"] == counts["vertices"]
    layer = opened(output)
    assert layer.featureCount() == counts["triangles"]
    assert layer.crs().authid() == "EPSG:32633"
    # The terrain style (<output>.qml) is what QGIS applies when it adds the layer.
    assert layer.renderer().type() == "graduatedSymbol"
    assert layer.renderer().classAttribute() == "z_mean"


def test_the_loaded_tin_keeps_the_terrain_style_over_processings_polygon_style(
    processing, tmp_path
):
    from processing.core.ProcessingConfig import ProcessingConfig

    # A user's "Style for polygon layers" that Processing applies to every polygon output.
    plain = tmp_path / "plain.qml"
    QgsVectorLayer("Polygon?crs=EPSG:32633", "plain", "memory").saveNamedStyle(str(plain))
    ProcessingConfig.setSettingValue(ProcessingConfig.VECTOR_POLYGON_STYLE, str(plain))
    try:
        processing.runAndLoadResults(
            "terratin:demtotin",
            {"INPUT": str(SAMPLE), "MAX_ERROR": 2.0, "OUTPUT": str(tmp_path / "tin.gpkg")},
        )
    finally:
        ProcessingConfig.setSettingValue(ProcessingConfig.VECTOR_POLYGON_STYLE, "")
    renderers = [
        (layer.renderer().type(), layer.renderer().classAttribute())
        for layer in QgsProject.instance().mapLayers().values()
        if layer.source() == str(tmp_path / "tin.gpkg")
    ]
    QgsProject.instance().removeAllMapLayers()
    assert renderers == [("graduatedSymbol", "z_mean")]


class ProgressRecorder(QgsProcessingFeedback):
    def __init__(self):
        super().__init__()
        self.percentages = []
        self.texts = []
        self.infos = []

    def setProgress(self, progress):  # noqa: N802 (QGIS's name)
        super().setProgress(progress)
        self.percentages.append(progress)

    def setProgressText(self, text):  # noqa: N802 (QGIS's name)
        super().setProgressText(text)
        self.texts.append(text)

    def pushInfo(self, info):  # noqa: N802 (QGIS's name)
        super().pushInfo(info)
        self.infos.append(info)


def test_the_progress_bar_follows_terratins_phases(processing, tmp_path):
    feedback = ProgressRecorder()
    processing.run(
        "terratin:demtotin",
        {"INPUT": str(SAMPLE), "MAX_ERROR": 1.0, "OUTPUT": str(tmp_path / "tin.gpkg")},
        feedback=feedback,
    )
    assert feedback.percentages == sorted(feedback.percentages)
    assert feedback.percentages[-1] == 100
    assert "terratin: reading raster" in feedback.texts
    assert len(feedback.texts) == len(set(feedback.texts)), "each phase named once"


def test_dem_to_tin_also_writes_a_ply_mesh_layer_with_its_crs(processing, tmp_path):
    from qgis.core import QgsMeshLayer

    mesh = tmp_path / "tin.ply"
    result = processing.run(
        "terratin:demtotin",
        {"INPUT": str(SAMPLE), "MAX_ERROR": 1.0, "OUTPUT": str(tmp_path / "tin.gpkg"),
         "MESH": str(mesh)},
    )
    assert result["MESH"] == str(mesh)
    layer = QgsMeshLayer(str(mesh), "mesh", "mdal")
    assert layer.isValid(), "QGIS cannot open the PLY as a mesh layer"
    assert layer.crs().authid() == "EPSG:32633"
    assert layer.dataProvider().faceCount() == result["TRIANGLES"]
    assert layer.dataProvider().vertexCount() == result["VERTICES"]
    with pytest.raises(QgsProcessingException, match="the mesh output is a PLY file"):
        processing.run(
            "terratin:demtotin",
            {"INPUT": str(SAMPLE), "MAX_ERROR": 1.0, "OUTPUT": str(tmp_path / "b.gpkg"),
             "MESH": str(tmp_path / "tin.2dm")},
        )


def test_dem_to_tin_within_a_memory_limit_writes_the_clis_tiled_tin(processing, tmp_path):
    # --memory-limit in the toolbox: the TIN written tile by tile, styled, as the command line's.
    output = tmp_path / "tin.gpkg"
    feedback = ProgressRecorder()
    result = processing.run(
        "terratin:demtotin",
        {"INPUT": str(SAMPLE), "MAX_ERROR": 0.5, "MEMORY_LIMIT": 200, "OUTPUT": str(output)},
        feedback=feedback,
    )
    counts = cli_counts(
        SAMPLE, "-o", tmp_path / "cli.ply", "--max-error", "0.5", "--memory-limit", "200M"
    )
    whole = cli_counts(SAMPLE, "-o", tmp_path / "whole.ply", "--max-error", "0.5")
    assert (result["VERTICES"], result["TRIANGLES"]) == (counts["vertices"], counts["triangles"])
    assert counts != whole, "tiles put their own vertices on their sides"
    assert any("cells a side within memory_limit" in info for info in feedback.infos)
    layer = opened(output)
    assert layer.featureCount() == counts["triangles"]
    assert layer.renderer().type() == "graduatedSymbol"
    with pytest.raises(QgsProcessingException, match="memory_limit 1M is too little"):
        processing.run(
            "terratin:demtotin",
            {"INPUT": str(SAMPLE), "MAX_ERROR": 0.5, "MEMORY_LIMIT": 1,
             "OUTPUT": str(tmp_path / "small.gpkg")},
        )
    assert not (tmp_path / "small.gpkg").exists()


def test_dem_to_tin_limits_points_and_reprojects(processing, tmp_path):
    output = tmp_path / "tin.gpkg"
    result = processing.run(
        "terratin:demtotin",
        {"INPUT": str(SAMPLE), "MAX_POINTS": 1500, "TARGET_CRS": "EPSG:3857",
         "TERRAIN_STYLE": False, "OUTPUT": str(output)},
    )
    assert result["VERTICES"] == 1500
    layer = opened(output)
    assert layer.crs().authid() == "EPSG:3857"
    assert layer.renderer().type() != "graduatedSymbol"


def test_dem_to_tin_takes_breaklines_from_a_file_layer_and_a_scratch_layer(processing, tmp_path):
    from qgis.core import QgsFeature, QgsGeometry

    roads = tmp_path / "roads.gpkg"
    crs = osr.SpatialReference()
    crs.ImportFromEPSG(32633)
    dataset = ogr.GetDriverByName("GPKG").CreateDataSource(str(roads))
    layer = dataset.CreateLayer("roads", crs, ogr.wkbLineString)
    feature = ogr.Feature(layer.GetLayerDefn())
    feature.SetGeometry(ogr.CreateGeometryFromWkt(
        "LINESTRING (455501.3 5104003.7, 456700.9 5103100.2)"))
    layer.CreateFeature(feature)
    dataset = None
    scratch = QgsVectorLayer("LineString?crs=EPSG:32633", "scratch", "memory")
    line = QgsFeature()
    line.setGeometry(QgsGeometry.fromWkt("LineString (455300.7 5102700.1, 456000.3 5102900.9)"))
    scratch.dataProvider().addFeatures([line])
    file_layer = QgsVectorLayer(f"{roads}|layername=roads", "roads", "ogr")
    result = processing.run(
        "terratin:demtotin",
        {"INPUT": str(SAMPLE), "BREAKLINES": [file_layer, scratch],
         "OUTPUT": str(tmp_path / "tin.gpkg")},
    )
    scratch_file = tmp_path / "scratch.gpkg"
    dataset = ogr.GetDriverByName("GPKG").CreateDataSource(str(scratch_file))
    layer = dataset.CreateLayer("lines", crs, ogr.wkbLineString)
    feature = ogr.Feature(layer.GetLayerDefn())
    feature.SetGeometry(ogr.CreateGeometryFromWkt(
        "LINESTRING (455300.7 5102700.1, 456000.3 5102900.9)"))
    layer.CreateFeature(feature)
    dataset = None
    counts = cli_counts(SAMPLE, "-o", tmp_path / "cli.ply", "--breaklines", roads,
                        "--breaklines", scratch_file)
    assert result["VERTICES"] == counts["vertices"] == 75644 + 4
    assert result["TRIANGLES"] == counts["triangles"]


def test_dem_to_tin_simplified_with_a_lake_and_an_erase_area(processing, tmp_path):
    crs = osr.SpatialReference()
    crs.ImportFromEPSG(32633)
    areas = tmp_path / "areas.gpkg"
    dataset = ogr.GetDriverByName("GPKG").CreateDataSource(str(areas))
    for name, wkt, level in (
        ("lakes", "POLYGON ((456100.5 5103300.25, 457000.75 5103150.5, 456600.5 5104400.25, "
                  "456100.5 5103300.25))", 812.5),
        ("buildings", "POLYGON ((455400.5 5102800.5, 455600.5 5102800.5, 455600.5 5102950.5, "
                      "455400.5 5102950.5, 455400.5 5102800.5))", 0.0),
    ):
        layer = dataset.CreateLayer(name, crs, ogr.wkbPolygon)
        layer.CreateField(ogr.FieldDefn("level", ogr.OFTReal))
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        feature["level"] = level
        layer.CreateFeature(feature)
    dataset = None
    lakes = QgsVectorLayer(f"{areas}|layername=lakes", "lakes", "ogr")
    buildings = QgsVectorLayer(f"{areas}|layername=buildings", "buildings", "ogr")
    output = tmp_path / "tin.gpkg"
    result = processing.run(
        "terratin:demtotin",
        {"INPUT": str(SAMPLE), "MAX_ERROR": 2.0, "REPLACE": lakes, "REPLACE_Z_FIELD": "level",
         "ERASE": buildings, "OUTPUT": str(output)},
    )
    counts = cli_counts(SAMPLE, "-o", tmp_path / "cli.ply", "--max-error", "2",
                        "--replace", f"{areas}|layername=lakes", "--replace-z-field", "level",
                        "--erase", f"{areas}|layername=buildings")
    assert result["VERTICES"] == counts["vertices"]
    assert result["TRIANGLES"] == counts["triangles"]
    flat = [f for f in opened(output).getFeatures() if f["z_min"] == f["z_max"] == 812.5]
    assert len(flat) >= 1  # the triangular lake is one flat triangle


def write_points(path, count=300):
    """A GeoPackage of PointZ with an elevation field too, in UTM 33N."""
    import random

    random.seed(4)
    crs = osr.SpatialReference()
    crs.ImportFromEPSG(32633)
    dataset = ogr.GetDriverByName("GPKG").CreateDataSource(str(path))
    layer = dataset.CreateLayer("survey", crs, ogr.wkbPoint25D)
    layer.CreateField(ogr.FieldDefn("height", ogr.OFTReal))
    for _ in range(count):
        x, y, z = random.uniform(0, 1000), random.uniform(0, 1000), random.uniform(100, 200)
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(ogr.CreateGeometryFromWkt(f"POINT Z ({x} {y} {z})"))
        feature.SetField("height", 2 * z)
        layer.CreateFeature(feature)
    dataset = None


def test_points_to_tin_from_a_layer_and_from_a_file(processing, tmp_path):
    points = tmp_path / "points.gpkg"
    write_points(points)
    layer = QgsVectorLayer(f"{points}|layername=survey", "survey", "ogr")
    assert layer.isValid()
    from_layer = processing.run(
        "terratin:pointstotin",
        {"POINTS": layer, "Z_FIELD": "height", "OUTPUT": str(tmp_path / "layer.gpkg")},
    )
    expected = cli_counts(points, "-o", tmp_path / "cli.ply", "--z-field", "height")
    assert from_layer["TRIANGLES"] == expected["triangles"] == opened(tmp_path / "layer.gpkg").featureCount()

    text = tmp_path / "points.xyz"
    text.write_text("".join(f"{x} {y} {z}\n" for x, y, z in [(0, 0, 1), (10, 0, 2), (0, 10, 3), (10, 10, 4), (5, 4, 9)]))
    from_file = processing.run(
        "terratin:pointstotin",
        {"POINTS_FILE": str(text), "SOURCE_CRS": "EPSG:32633", "OUTPUT": str(tmp_path / "file.fgb")},
    )
    assert from_file["TRIANGLES"] == 4
    assert opened(tmp_path / "file.fgb").crs().authid() == "EPSG:32633"


def test_points_to_tin_keeps_the_las_classes_asked_for(processing, tmp_path):
    las = pathlib.Path(os.environ.get("TERRATIN_SHARED_DEMS", "absent")) / "pdal__1.2-with-color.las"
    if not las.exists():
        pytest.skip(f"{las} is absent")
    result = processing.run(
        "terratin:pointstotin",
        {"POINTS_FILE": str(las), "CLASSES": "2", "SOURCE_CRS": "EPSG:2992",
         "OUTPUT": str(tmp_path / "ground.gpkg")},
    )
    ground = cli_counts(las, "-o", tmp_path / "cli.ply", "--class", "2")
    every = cli_counts(las, "-o", tmp_path / "cli.ply", "--overwrite")
    assert ground["points"] < every["points"], "the sample has other classes than ground"
    assert result["VERTICES"] == ground["vertices"]
    layer = opened(tmp_path / "ground.gpkg")
    assert layer.featureCount() == ground["triangles"]
    assert layer.crs().authid() == "EPSG:2992"


def test_points_to_tin_reads_laz_as_its_las_twin(processing, tmp_path):
    shared = pathlib.Path(os.environ.get("TERRATIN_SHARED_DEMS", "absent")) / "laz"
    laz, las = shared / "lidr__Megaplot.laz", shared / "lasr__Megaplot.las"
    if not (laz.exists() and las.exists()):
        pytest.skip(f"{laz} or its twin is absent")
    result = processing.run(
        "terratin:pointstotin",
        {"POINTS_FILE": str(laz), "CLASSES": "2", "OUTPUT": str(tmp_path / "ground.gpkg")},
    )
    ground = cli_counts(las, "-o", tmp_path / "cli.ply", "--class", "2")
    assert result["VERTICES"] == ground["vertices"]
    layer = opened(tmp_path / "ground.gpkg")
    assert layer.featureCount() == ground["triangles"]
    assert layer.crs().authid() == "EPSG:26917"


def test_a_scratch_layer_is_saved_for_terratin_first(processing, tmp_path):
    layer = QgsVectorLayer("PointZ?crs=EPSG:32633", "scratch", "memory")
    from qgis.core import QgsFeature, QgsGeometry

    features = []
    for x, y, z in [(0, 0, 1), (10, 0, 2), (0, 10, 3), (10, 10, 4), (5, 4, 9), (2, 7, 5)]:
        feature = QgsFeature()
        feature.setGeometry(QgsGeometry.fromWkt(f"PointZ ({x} {y} {z})"))
        features.append(feature)
    layer.dataProvider().addFeatures(features)
    result = processing.run(
        "terratin:pointstotin", {"POINTS": layer, "OUTPUT": str(tmp_path / "tin.gpkg")}
    )
    assert result["VERTICES"] == 6


class CancelAtFirstReport(QgsProcessingFeedback):
    def setProgress(self, progress):  # noqa: N802 (QGIS's name)
        super().setProgress(progress)
        self.cancel()


def test_a_cancelled_run_leaves_no_output(processing, tmp_path):
    output = tmp_path / "tin.gpkg"
    with pytest.raises(QgsProcessingException, match="cancelled"):
        processing.run(
            "terratin:demtotin", {"INPUT": str(SAMPLE), "OUTPUT": str(output)},
            feedback=CancelAtFirstReport(),
        )
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "output, message",
    [
        ("tin.ply", r"to a file ending in \.gpkg, \.shp, \.fgb, not to '.*tin\.ply'"),
        ("tin", "to a file ending in"),
        ("memory:", "not to 'memory:'"),
    ],
)
def test_an_output_processing_cannot_load_as_a_tin_layer_is_refused(
    processing, output, message, tmp_path
):
    destination = output if output.endswith(":") else str(tmp_path / output)
    with pytest.raises(QgsProcessingException, match=message):
        processing.run(
            "terratin:demtotin",
            {"INPUT": str(SAMPLE), "MAX_ERROR": 1.0, "TERRAIN_STYLE": False,
             "OUTPUT": destination},
        )
    assert list(tmp_path.iterdir()) == []


def test_a_dem_that_gdal_cannot_read_as_a_file_is_refused(processing, tmp_path):
    # A virtual raster (raster calculator on the fly) exists only inside QGIS.
    virtual = QgsRasterLayer(
        f"?crs=EPSG:32633&extent=0,0,100,100&width=10&height=10&formula=%22r@1%22*2"
        f"&r:uri={SAMPLE}&r:provider=gdal",
        "doubled", "virtualraster",
    )
    assert virtual.isValid()
    QgsProject.instance().addMapLayer(virtual)
    try:
        with pytest.raises(QgsProcessingException, match="virtualraster layer.*GeoTIFF"):
            processing.run(
                "terratin:demtotin", {"INPUT": virtual, "OUTPUT": str(tmp_path / "tin.gpkg")}
            )
    finally:
        QgsProject.instance().removeAllMapLayers()
    assert list(tmp_path.iterdir()) == []


def test_a_band_the_dem_lacks_gives_terratins_message(processing, tmp_path):
    with pytest.raises(QgsProcessingException, match="terratin: .*band 3 does not exist"):
        processing.run(
            "terratin:demtotin",
            {"INPUT": str(SAMPLE), "BAND": 3, "OUTPUT": str(tmp_path / "tin.gpkg")},
        )
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "parameters, message",
    [
        ({}, "give a point layer or a point file"),
        ({"POINTS_FILE": "absent.xyz"}, "terratin: "),
        ({"POINTS_FILE": str(SAMPLE), "COLUMNS": "1,2"}, "columns"),
    ],
)
def test_bad_parameters_give_one_clear_error(processing, parameters, message, tmp_path):
    with pytest.raises(QgsProcessingException, match=message):
        processing.run(
            "terratin:pointstotin", {**parameters, "OUTPUT": str(tmp_path / "tin.gpkg")}
        )
    assert not (tmp_path / "tin.gpkg").exists()
