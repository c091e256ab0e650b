#!/usr/bin/python3
"""Writes the sample vector layers beside sample_dems/ridges_utm.tif, for the README's examples:

  sample_dems/roads.gpkg   layer roads: three 2D LineStrings (breaklines, --breaklines)
  sample_dems/lakes.gpkg   layer lakes: two Polygons (hydro-flattening, --replace)

usage: /usr/bin/python3 tools/make_sample_layers.py [OUTPUT_DIR]   (default: sample_dems)

Needs GDAL's Python bindings (Debian's python3-gdal). The coordinates are fixed numbers in the
DEM's CRS, WGS 84 / UTM zone 33N (EPSG:32633), so every run writes the same features.
"""

import math
import os
import pathlib
import sys

from osgeo import gdal, ogr, osr

gdal.UseExceptions()
# GeoPackage stamps each table with the time it was written; a fixed stamp keeps the files the
# same from run to run, so remaking them changes nothing in git unless the features change.
gdal.SetConfigOption("OGR_CURRENT_DATE", "2026-01-01T00:00:00.000Z")
# Each SQLite table and index takes at least one page and a GeoPackage has a couple of dozen of
# them: 1 KiB pages make these files about a third of their size with the default 4 KiB.
gdal.SetConfigOption("OGR_SQLITE_PRAGMA", "page_size=1024")

EPSG_UTM_33N = 32633

# The DEM covers x 455,000 to 458,200 m and y 5,102,600 to 5,105,000 m. Two roads run past its
# edges on purpose: terratin clips breaklines to the data's hull (with a notice). They keep clear
# of the nodata lake of the DEM (about x 455,544-456,056, y 5,104,136-5,104,424) and of the lakes.
ROADS = [
    ("valley road", [(454900, 5103500), (455800, 5103650), (456600, 5103550),
                     (457800, 5103750), (458300, 5103700)]),
    ("ridge road", [(456200, 5102500), (456300, 5103200), (456100, 5103900),
                    (456400, 5104600), (456300, 5105100)]),
    ("bowl track", [(456900, 5102800), (457700, 5102900), (457900, 5103300)]),
]

# (name, centre x, centre y, semi-axis x, semi-axis y), metres: ellipses in two of the DEM's
# basins, the bowl in the east and a valley floor in the south-west.
LAKES = [
    ("bowl lake", 457305.0, 5103325.0, 160.0, 120.0),
    ("valley pond", 455805.0, 5103075.0, 80.0, 60.0),
]
# Corners of each lake's ring: enough for a round shore, few enough to keep the file small.
LAKE_RING_POINTS = 24


def utm_33n():
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(EPSG_UTM_33N)
    return srs


def new_layer(path, name, geometry_type):
    """A GeoPackage with one empty layer of that geometry type and a text field `name`."""
    if path.exists():
        path.unlink()
    # No gpkg_ogr_contents: a feature count cache that OGR does without, one table less.
    dataset = ogr.GetDriverByName("GPKG").CreateDataSource(str(path), ["ADD_GPKG_OGR_CONTENTS=NO"])
    # No R-tree: a few features need none, and it would make up most of the file.
    layer = dataset.CreateLayer(name, utm_33n(), geometry_type, ["SPATIAL_INDEX=NO"])
    layer.CreateField(ogr.FieldDefn("name", ogr.OFTString))
    return dataset, layer


def add_feature(layer, name, geometry):
    feature = ogr.Feature(layer.GetLayerDefn())
    feature.SetField("name", name)
    feature.SetGeometry(geometry)
    layer.CreateFeature(feature)


def write_roads(path):
    dataset, layer = new_layer(path, "roads", ogr.wkbLineString)
    for name, points in ROADS:
        line = ogr.Geometry(ogr.wkbLineString)
        for x, y in points:
            line.AddPoint_2D(x, y)
        add_feature(layer, name, line)
    dataset = None


def write_lakes(path):
    dataset, layer = new_layer(path, "lakes", ogr.wkbPolygon)
    for name, cx, cy, ax, ay in LAKES:
        ring = ogr.Geometry(ogr.wkbLinearRing)
        for i in range(LAKE_RING_POINTS + 1):
            angle = 2.0 * math.pi * (i % LAKE_RING_POINTS) / LAKE_RING_POINTS
            # Whole centimetres, so that the shore's corners print as short decimals.
            ring.AddPoint_2D(round(cx + ax * math.cos(angle), 2), round(cy + ay * math.sin(angle), 2))
        polygon = ogr.Geometry(ogr.wkbPolygon)
        polygon.AddGeometry(ring)
        add_feature(layer, name, polygon)
    dataset = None


def main():
    root = pathlib.Path(__file__).resolve().parents[1]
    folder = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "sample_dems"
    os.makedirs(folder, exist_ok=True)
    write_roads(folder / "roads.gpkg")
    write_lakes(folder / "lakes.gpkg")
    for name in ("roads.gpkg", "lakes.gpkg"):
        print(f"wrote {folder / name} ({(folder / name).stat().st_size} bytes)")


if __name__ == "__main__":
    main()
