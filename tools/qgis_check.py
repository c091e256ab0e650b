#!/usr/bin/python3
"""Opens terratin outputs in QGIS (headless) and prints what QGIS sees.

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 tools/qgis_check.py hood.gpkg hood.2dm hood.ply ...

Vector files (.gpkg .shp .fgb) are opened as QgsVectorLayer with the "ogr" provider and
reported with their geometry type, CRS and feature count; mesh files (.2dm .ply) as
QgsMeshLayer with the "mdal" provider, with their face and vertex counts and dataset groups.
Exit status 1 when a layer is not valid. Needs Debian's python3-qgis; not part of the test suite.
"""
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from qgis.core import (  # noqa: E402  (the environment must be set first)
    Qgis,
    QgsApplication,
    QgsMeshLayer,
    QgsVectorLayer,
    QgsWkbTypes,
)

MESH_EXTENSIONS = {".2dm", ".ply"}


def check_vector(path):
    layer = QgsVectorLayer(path, os.path.basename(path), "ogr")
    if not layer.isValid():
        print(f"{path}: NOT a valid vector layer")
        return False
    style = os.path.splitext(path)[0] + ".qml"
    renderer = layer.renderer().type() if layer.renderer() else "none"
    print(
        f"{path}: vector layer, {QgsWkbTypes.displayString(layer.wkbType())}, "
        f"CRS {layer.crs().authid() or '(none)'}, {layer.featureCount()} features, "
        f"fields {[f.name() for f in layer.fields()]}, renderer {renderer}"
        + (f" (default style {os.path.basename(style)} present)" if os.path.exists(style) else "")
    )
    return True


def check_mesh(path):
    layer = QgsMeshLayer(path, os.path.basename(path), "mdal")
    if not layer.isValid():
        print(f"{path}: NOT a valid mesh layer (provider mdal)")
        return False
    provider = layer.dataProvider()
    groups = [
        provider.datasetGroupMetadata(i).name() for i in range(provider.datasetGroupCount())
    ]
    print(
        f"{path}: mesh layer, {provider.faceCount()} faces, {provider.vertexCount()} vertices, "
        f"dataset groups {groups}, CRS {layer.crs().authid() or '(none)'}"
    )
    return True


def main(paths):
    QgsApplication.setPrefixPath("/usr", True)
    app = QgsApplication([], False)
    app.initQgis()
    print(f"QGIS {Qgis.QGIS_VERSION}")
    ok = True
    for path in paths:
        if os.path.splitext(path)[1].lower() in MESH_EXTENSIONS:
            ok = check_mesh(path) and ok
        else:
            ok = check_vector(path) and ok
    app.exitQgis()
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
