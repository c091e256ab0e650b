#!/usr/bin/python3
"""terratin's outputs as QGIS (3.22, headless) opens them.

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 tests/qgis/qgis_outputs_test.py \\
        TERRATIN DEM EXPECTED_AUTHID [TERRATIN_OPTION...]

Runs `TERRATIN build DEM -o tin.<ext> --json` once per format (same seed, so the same TIN)
and checks what QGIS reads, against terratin's JSON report and against GDAL/OGR's Python:

  gpkg      vector layer, Polygon Z, one feature per triangle, CRS = the DEM's
  shp, fgb  vector layer, polygons with z, one feature per triangle, CRS = the DEM's
  ply       mesh layer (MDAL), faces = triangles, vertices = vertices, CRS valid and = the DEM's
            (the "comment crs: <WKT>" header line; a broken line leaves the layer without CRS)
  2dm       mesh layer (MDAL), faces = triangles, vertices = vertices, CRS *invalid*: the 2DM
            format has no CRS card and MDAL's 2DM reader reads none. If a later QGIS finds one,
            this check fails on purpose so that README and --help get updated.

EXPECTED_AUTHID ("EPSG:26910") is the DEM's CRS as GDAL identifies it; the test checks that too.
Exit status: 0 all checks pass, 1 a check failed (each failure is printed), 77 DEM absent.
Needs Debian's python3-qgis and python3-gdal (tools/quickstart.sh installs them).
"""
import json
import os
import subprocess
import sys
import tempfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

try:
    from osgeo import gdal, ogr  # noqa: E402
    from qgis.core import (  # noqa: E402  (the environment must be set first)
        Qgis,
        QgsApplication,
        QgsCoordinateReferenceSystem,
        QgsMeshLayer,
        QgsVectorLayer,
        QgsWkbTypes,
    )
except ImportError as error:
    # A failure, not a skip: the suite's machines have them (tools/quickstart.sh).
    sys.exit(f"FAIL {error}: install python3-qgis and python3-gdal (tools/quickstart.sh does)")

gdal.UseExceptions()

VECTOR_FORMATS = ("gpkg", "shp", "fgb")
MESH_FORMATS = ("ply", "2dm")


class Checks:
    """Collects failures instead of stopping at the first, so one run shows them all."""

    def __init__(self):
        self.failures = []

    def expect(self, condition, what):
        print(("ok   " if condition else "FAIL ") + what)
        if not condition:
            self.failures.append(what)


def authid(srs):
    """An OSR CRS as "EPSG:n", identified by GDAL/OSR when it carries no code (empty: none)."""
    if srs is None:
        return ""
    srs = srs.Clone()
    if srs.GetAuthorityCode(None) is None:
        srs.AutoIdentifyEPSG()
    name, code = srs.GetAuthorityName(None), srs.GetAuthorityCode(None)
    return f"{name}:{code}" if name and code else ""


def build(terratin, dem, output, options):
    """Runs terratin and returns its JSON report (counts of the TIN it wrote)."""
    command = [terratin, "build", dem, "-o", output, "--json", "--quiet", *options]
    run = subprocess.run(command, capture_output=True, text=True, check=False)
    if run.returncode != 0:
        raise SystemExit(f"FAIL {' '.join(command)}: exit {run.returncode}: {run.stderr.strip()}")
    return json.loads(run.stdout)


def ogr_layer_facts(path):
    """(first layer name, feature count, EPSG authid) as OGR reads the file."""
    source = ogr.Open(path)
    layer = source.GetLayer(0)
    return layer.GetName(), layer.GetFeatureCount(), authid(layer.GetSpatialRef())


def check_vector(checks, path, fmt, report, expected_authid):
    triangles = report["counts"]["triangles"]
    layer_name, ogr_count, ogr_authid = ogr_layer_facts(path)
    # The first layer by name: the GeoPackage may hold node and edge layers beside it.
    layer = QgsVectorLayer(f"{path}|layername={layer_name}", fmt, "ogr")
    checks.expect(layer.isValid(), f"{fmt}: QGIS opens it as a vector layer")
    if not layer.isValid():
        return
    wkb = layer.wkbType()
    if fmt == "gpkg":
        checks.expect(
            wkb == QgsWkbTypes.PolygonZ,
            f"{fmt}: geometry type {QgsWkbTypes.displayString(wkb)} is PolygonZ",
        )
    else:
        # Shapefile has no single-polygon type (QGIS reads MultiPolygonZ); FlatGeobuf: PolygonZ.
        checks.expect(
            QgsWkbTypes.geometryType(wkb) == QgsWkbTypes.PolygonGeometry and QgsWkbTypes.hasZ(wkb),
            f"{fmt}: geometry type {QgsWkbTypes.displayString(wkb)} is a polygon with z",
        )
    count = layer.featureCount()
    checks.expect(
        count == triangles == ogr_count,
        f"{fmt}: {count} features in QGIS = {triangles} triangles reported = {ogr_count} in OGR",
    )
    crs = layer.crs()
    checks.expect(
        crs.isValid() and crs.authid() == expected_authid == ogr_authid,
        f"{fmt}: CRS {crs.authid() or '(none)'} = {expected_authid} "
        f"(OGR: {ogr_authid or '(none)'})",
    )


def check_mesh(checks, path, fmt, report, expected_authid, input_crs):
    triangles = report["counts"]["triangles"]
    vertices = report["counts"]["vertices"]
    layer = QgsMeshLayer(path, fmt, "mdal")
    checks.expect(layer.isValid(), f"{fmt}: QGIS opens it as a mesh layer (MDAL)")
    if not layer.isValid():
        return
    provider = layer.dataProvider()
    checks.expect(
        provider.faceCount() == triangles and provider.vertexCount() == vertices,
        f"{fmt}: {provider.faceCount()} faces, {provider.vertexCount()} vertices = "
        f"{triangles} triangles, {vertices} vertices reported",
    )
    crs = layer.crs()
    if fmt == "2dm":
        checks.expect(
            not crs.isValid(),
            f"{fmt}: no CRS in QGIS ({crs.authid() or 'invalid'}), as documented: 2DM has none",
        )
        return
    checks.expect(
        crs.isValid() and crs.authid() == expected_authid and crs == input_crs,
        f"{fmt}: CRS {crs.authid() or '(none)'} is valid and = the DEM's {expected_authid}",
    )


def main(argv):
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    terratin, dem, expected_authid, options = argv[1], argv[2], argv[3], argv[4:]
    if not os.path.exists(dem):
        print(f"skip: no {dem}")
        return 77

    with tempfile.TemporaryDirectory(prefix="terratin-qgis-") as work:
        reports = {}
        for fmt in VECTOR_FORMATS + MESH_FORMATS:
            reports[fmt] = build(terratin, dem, os.path.join(work, f"tin.{fmt}"), options)

        # A profile of its own: parallel runs share no settings database, and $HOME stays clean.
        QgsApplication.setPrefixPath("/usr", True)
        app = QgsApplication([], False, os.path.join(work, "qgis-profile"))
        app.initQgis()
        print(f"QGIS {Qgis.QGIS_VERSION}, GDAL {gdal.__version__}, {os.path.basename(dem)}")
        checks = Checks()
        gdal_authid = authid(gdal.Open(dem).GetSpatialRef())
        checks.expect(
            gdal_authid == expected_authid,
            f"DEM: GDAL reads {gdal_authid or '(none)'} = {expected_authid}",
        )
        # Same DEM, same seed: every format holds the same TIN.
        counts = {
            fmt: (report["counts"]["vertices"], report["counts"]["triangles"])
            for fmt, report in reports.items()
        }
        checks.expect(len(set(counts.values())) == 1, f"same TIN in every format: {counts}")
        for fmt in VECTOR_FORMATS:
            path = os.path.join(work, f"tin.{fmt}")
            check_vector(checks, path, fmt, reports[fmt], expected_authid)
        # The DEM's own CRS, from its WKT, for the mesh layers to equal.
        input_crs = QgsCoordinateReferenceSystem.fromWkt(gdal.Open(dem).GetProjection())
        for fmt in MESH_FORMATS:
            path = os.path.join(work, f"tin.{fmt}")
            check_mesh(checks, path, fmt, reports[fmt], expected_authid, input_crs)
        app.exitQgis()

    if checks.failures:
        print(f"{len(checks.failures)} check(s) failed", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
