#!/usr/bin/python3
"""A terrain pipeline on the terratin Python module: GDAL reads a DEM into NumPy,
terratin.simplify makes its error-bounded TIN, OGR writes the triangles to a GeoPackage in
the DEM's CRS, each with its mean elevation.

    /usr/bin/python3 examples/python/dem_pipeline.py DEM OUTPUT.gpkg --max-error 2

The TIN is the one `terratin build DEM -o OUTPUT --max-error 2` makes (python/tests checks
that on Mt Hood). Between the reading and the TIN is where a pipeline does its own work on
the array: masking, smoothing, unit conversion.
"""
import argparse
import sys

import numpy
from osgeo import gdal, ogr, osr

import terratin

gdal.UseExceptions()
ogr.UseExceptions()


def read_dem(path):
    """(z, geotransform, nodata, crs) of the first band of `path`."""
    dataset = gdal.Open(path)
    band = dataset.GetRasterBand(1)
    crs = osr.SpatialReference(wkt=dataset.GetProjection()) if dataset.GetProjection() else None
    return band.ReadAsArray(), dataset.GetGeoTransform(), band.GetNoDataValue(), crs


class ProgressLine:
    """terratin's progress as one line on stderr, redrawn at each whole per cent."""

    def __init__(self):
        self.shown = -1

    def __call__(self, fraction, message):
        percent = int(fraction * 100)
        if percent != self.shown:
            self.shown = percent
            print(f"\r{percent:3d} % {message:<40}", end="", file=sys.stderr, flush=True)
        return True  # False would cancel: terratin.Cancelled


def write_triangles(path, vertices, triangles, crs):
    """One Polygon Z per triangle, with its corners' mean elevation as z_mean."""
    driver = ogr.GetDriverByName("GPKG")
    dataset = driver.CreateDataSource(path)
    layer = dataset.CreateLayer("tin", crs, ogr.wkbPolygon25D)
    layer.CreateField(ogr.FieldDefn("z_mean", ogr.OFTReal))
    corners = vertices[triangles]  # (T, 3 corners, x y z)
    z_mean = corners[:, :, 2].mean(axis=1)
    definition = layer.GetLayerDefn()
    layer.StartTransaction()
    for corner, mean in zip(corners.tolist(), z_mean.tolist()):
        ring = ogr.Geometry(ogr.wkbLinearRing)
        for x, y, z in corner + corner[:1]:
            ring.AddPoint(x, y, z)
        polygon = ogr.Geometry(ogr.wkbPolygon25D)
        polygon.AddGeometryDirectly(ring)
        feature = ogr.Feature(definition)
        feature.SetGeometryDirectly(polygon)
        feature.SetField(0, mean)
        layer.CreateFeature(feature)
    layer.CommitTransaction()
    dataset = None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dem")
    parser.add_argument("output", help="a GeoPackage (.gpkg) that does not exist yet")
    parser.add_argument("--max-error", type=float, required=True, help="metres")
    arguments = parser.parse_args()

    z, geotransform, nodata, crs = read_dem(arguments.dem)
    try:
        vertices, triangles = terratin.simplify(
            z, geotransform, nodata, max_error=arguments.max_error, progress=ProgressLine()
        )
    except terratin.Error as error:
        sys.exit(f"dem_pipeline: {error}")
    print(file=sys.stderr)
    write_triangles(arguments.output, vertices, triangles, crs)
    print(f"{len(vertices)} vertices, {len(triangles)} triangles -> {arguments.output}")


if __name__ == "__main__":
    main()
