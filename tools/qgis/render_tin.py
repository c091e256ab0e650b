#!/usr/bin/python3
"""Renders a terratin GeoPackage TIN as QGIS shows it (its stored terrain style), headless.

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 tools/qgis/render_tin.py TIN.gpkg OUT.png \\
        [--outline AREAS.gpkg] [--zoom FACTOR]

With --outline, the polygons are drawn on top (blue, no fill), the view is their extent scaled
by --zoom, and the triangles whose centroid lies inside them are counted, with how many are
flat (z_min == z_max): a replace area's triangles all are, so the count shows whether an area
was replaced.
"""

import argparse
import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from qgis.core import (  # noqa: E402
    QgsApplication,
    QgsFeatureRequest,
    QgsFillSymbol,
    QgsMapRendererParallelJob,
    QgsMapSettings,
    QgsSingleSymbolRenderer,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QSize  # noqa: E402
from qgis.PyQt.QtGui import QColor  # noqa: E402


def count_inside(tin, outline):
    """Triangles with their centroid inside `outline`'s polygons, and the flat ones of them."""
    inside = flat = 0
    for polygon in outline.getFeatures():
        area = polygon.geometry()
        request = QgsFeatureRequest().setFilterRect(area.boundingBox())
        for triangle in tin.getFeatures(request):
            if area.contains(triangle.geometry().centroid()):
                inside += 1
                flat += triangle["z_min"] == triangle["z_max"]
    return inside, flat


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tin")
    parser.add_argument("png")
    parser.add_argument("--outline")
    parser.add_argument("--zoom", type=float, default=2.0)
    parser.add_argument("--layer", default="tin")
    arguments = parser.parse_args()

    application = QgsApplication([], False)
    application.initQgis()
    tin = QgsVectorLayer(f"{arguments.tin}|layername={arguments.layer}", "tin", "ogr")
    if not tin.isValid():
        raise SystemExit(f"render_tin: cannot open {arguments.tin}")
    layers = [tin]
    extent = tin.extent()
    if arguments.outline:
        outline = QgsVectorLayer(arguments.outline, "outline", "ogr")
        outline.setRenderer(QgsSingleSymbolRenderer(QgsFillSymbol.createSimple(
            {"color": "0,0,0,0", "outline_color": "0,90,255", "outline_width": "0.6"})))
        layers.insert(0, outline)
        extent = outline.extent()
        extent.scale(arguments.zoom)
        inside, flat = count_inside(tin, outline)
        print(f"triangles inside the outline: {inside}, flat: {flat}")
    settings = QgsMapSettings()
    settings.setLayers(layers)
    settings.setDestinationCrs(tin.crs())
    settings.setExtent(extent)
    settings.setOutputSize(QSize(1000, 700))
    settings.setBackgroundColor(QColor("white"))
    job = QgsMapRendererParallelJob(settings)
    job.start()
    job.waitForFinished()
    job.renderedImage().save(arguments.png)
    print(f"{arguments.png}: {tin.featureCount()} triangles, {tin.crs().authid()}, "
          f"renderer {tin.renderer().type()}")
    application.exitQgis()


if __name__ == "__main__":
    main()
