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
    QgsVectorLayer,
)

SAMPLE = pathlib.Path(__file__).parents[2] / "sample_dems" / "ridges_utm.tif"


@pytest.fixture(scope="session")
def processing():
    """QGIS with Processing and terratin's provider, once for the whole session."""
    QgsApplication.setPrefixPath("/usr", True)
    application = QgsApplication([], False)
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
