"""terratin for Python: exact Delaunay TINs from NumPy arrays and from files.

The C++ library (terratin::core, terratin::io) does the work, with the GIL released; arrays
come in and go out without copies where the memory layout allows. docs/python.md in the source
tree has the whole story: installing, the array rules, errors, progress and cancellation.

Functions:
    build(inputs, output, **options) -> dict           the command line's `terratin build`
    triangulate(points, method="auto", threads=0) -> (vertices, triangles)
    simplify(z, geotransform, nodata=None, max_error=None, max_points=None, ...)
        -> (vertices, triangles)

Errors: every failure raises terratin.Error or one of its subclasses InvalidInputError,
IoError, CrsError and Cancelled (a RuntimeError; the message names the stage that failed).
"""

import json
import logging

import numpy

from terratin import _terratin
from terratin._terratin import Cancelled, CrsError, Error, InvalidInputError, IoError

__version__ = _terratin.__version__

# The classes are made in _terratin; they belong to the public package.
for _error_class in (Error, InvalidInputError, IoError, CrsError, Cancelled):
    _error_class.__module__ = "terratin"
del _error_class

__all__ = [
    "Cancelled",
    "CrsError",
    "Error",
    "InvalidInputError",
    "IoError",
    "build",
    "simplify",
    "triangulate",
]


_logger = logging.getLogger("terratin")


def build(inputs, output, *, progress=None, **options):
    """The command line's `terratin build INPUT... -o OUTPUT [options]`, as a function.

    inputs: a path (str, bytes or os.PathLike) or a list of them: DEM rasters, LAS/LAZ, text
        or OGR point files, as the command line takes them.
    output: the TIN file; its extension chooses the format unless format= is given. None
        with tiles_dir= (the command line's --tiles-dir instead of -o).
    options: the command line's build options by keyword, the long name with "_" for "-":
        max_error=2.0, max_points=100000, method="strips", threads=0, t_srs="EPSG:32633",
        attributes="basic", qgis_style=True, overwrite=True, classes=[2, 9], columns=[1, 2, 3]
        ... (docs/cli.md lists them all). A flag takes True or False; a repeatable option
        (classes) a list; None means "not given". The checks and messages are the command
        line's, naming options by keyword ("max_error must be ...").
    progress: callable(fraction, message) -> bool, as for triangulate(); False cancels and
        leaves no output (an existing one stays as it was).

    Returns the command line's --json report as a dict (docs/cli.md); its "notices" are what
    the command line prints as notices, each also logged as INFO by the logger "terratin".

    Raises InvalidInputError (a bad option or input), IoError, CrsError, Cancelled,
    KeyboardInterrupt (Ctrl-C while the library works).
    """
    report = json.loads(_terratin.build(inputs, output, progress=progress, **options))
    for notice in report["notices"]:
        _logger.info("%s", notice)
    return report


def _as_array(value, function, name):
    """`value` as a NumPy array (itself when it is one); InvalidInputError when NumPy cannot
    make one (a ragged list)."""
    try:
        return numpy.asarray(value)
    except (TypeError, ValueError) as error:
        raise InvalidInputError(f"{function}: {name} is not an array: {error}") from error


def triangulate(points, method="auto", threads=0, *, seed=1, progress=None):
    """Exact Delaunay triangulation of points, as the CLI triangulates a point cloud.

    points: array (N, 2) or (N, 3) of x, y[, z] (x, y in any planar units; z carried along,
        0 for (N, 2)). A C-contiguous float64 (N, 3) array is read in place; any other
        layout or integer/floating dtype is copied once (after NumPy's conversion to
        float64 for other dtypes).
    method: "auto" (the strip method), "strips", "sequential", "batch" or "circumcircle".
    threads: hardware threads, 0 = all.
    seed: seed of the insertion order. Every seed, method and thread count gives the same
        triangles (cocircular points, as on grids, are decided by the points alone); the
        same seed also lists them in the same order.
    progress: callable(fraction, message) -> bool, called from this thread a few times a
        second with the GIL held; False cancels (terratin.Cancelled), None continues, an
        exception it raises stops the work and propagates.

    Returns (vertices, triangles): vertices (V, 3) float64, the distinct points (points with
    exactly the same x, y are merged, the first one's z kept, as by the CLI's default
    --duplicate-z first), in their input order; triangles (T, 3) int32 (int64 from 2^31
    vertices) vertex indices, counter-clockwise. The triangles cover exactly the convex hull,
    and no vertex lies strictly inside a triangle's circumcircle (exact predicates).

    Raises InvalidInputError for a bad array (shape, dtype, NaN or infinite values, fewer
    than three distinct points not all collinear) or option; Cancelled; KeyboardInterrupt on
    Ctrl-C while the library works.
    """
    function = "terratin.triangulate"
    return _terratin.triangulate(
        _as_array(points, function, "points"), method, threads, seed=seed, progress=progress
    )


def simplify(
    z,
    geotransform,
    nodata=None,
    max_error=None,
    max_points=None,
    *,
    max_triangles=None,
    max_hole=1,
    fill_holes=False,
    max_edge=None,
    threads=0,
    validate=False,
    tile_size=0,
    progress=None,
):
    """Error-bounded TIN of a DEM: the CLI's `terratin build DEM --max-error E ...` TIN.

    z: 2-D array (rows, columns) of elevations, row 0 first as stored in a raster; any
        integer or floating dtype, read in place whatever its layout. A cell is nodata when
        it is NaN or equals `nodata` (compared in the array's dtype, as GDAL does for a
        band). Elevations are rounded to float32 as the CLI's raster reader does.
    geotransform: GDAL's 6 coefficients (x0, x per column, x per row, y0, y per column,
        y per row); cell centres are at pixel (col + 0.5, row + 0.5).
    max_error: vertical tolerance E (z units, >= 0): every valid cell covered by the TIN is
        within E of it. max_points, max_triangles: limits. Without any limit every valid
        cell becomes a vertex.
    max_hole: nodata regions (8-connected) of more than this many cells stay open;
        fill_holes: cover every one. max_edge: drop triangles with an edge longer than this
        (CRS units). threads: 0 = all (the TIN does not depend on it). validate: check the
        result is exactly Delaunay (Error otherwise; with tiles, each tile). tile_size: refine
        in seam-free tiles of this many cells a side (the CLI's --tile-size; needs max_error).
    progress: as for triangulate().

    Returns (vertices, triangles) as triangulate() does; vertices are exact cell centres
    with the cells' elevations. The TIN is in the geotransform's CRS; a geographic DEM is
    not projected (the CLI projects it to UTM).

    Raises InvalidInputError (bad array, geotransform or option; no valid cell; valid cells
    all collinear), Cancelled, KeyboardInterrupt.
    """
    function = "terratin.simplify"
    return _terratin.simplify(
        _as_array(z, function, "z"),
        geotransform,
        nodata,
        max_error,
        max_points,
        max_triangles=max_triangles,
        max_hole=max_hole,
        fill_holes=fill_holes,
        max_edge=max_edge,
        threads=threads,
        validate=validate,
        tile_size=tile_size,
        progress=progress,
    )
