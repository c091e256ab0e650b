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
import numbers

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

    inputs: a path (str, bytes or os.PathLike) or a list of them: DEM rasters, LAS 1.0-1.4,
        LAZ (COPC too), delimited text or OGR point files, as the command line takes them.
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
    KeyboardInterrupt (Ctrl-C while the library works). SIGTERM or SIGHUP, where their
    handler is the default, cancel the run, which removes its temporary files, and then end
    the process as they would have.
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


def _integer(value, function, name, low=None, high=None):
    """`value` when it is an integer (a Python or NumPy one, not a bool) in [low, high];
    InvalidInputError otherwise, rather than the binding's TypeError."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InvalidInputError(
            f"{function}: {name} must be an integer, not {type(value).__name__} {value!r}"
        )
    if (low is not None and value < low) or (high is not None and value > high):
        bounds = f"{low} to {high}" if high is not None else f"{low} or more"
        raise InvalidInputError(f"{function}: {name} must be {bounds} (got {value})")
    return int(value)


def _optional_integer(value, function, name):
    return None if value is None else _integer(value, function, name)


def _optional_number(value, function, name):
    """None, or `value` as a float when it is a real number (not a bool)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InvalidInputError(
            f"{function}: {name} must be a number or None, not {type(value).__name__} {value!r}"
        )
    return float(value)


def _gdal_geotransform(geotransform, function):
    """GDAL's 6 coefficients from GDAL's order, or from an affine transform as rasterio and
    affine give it (an Affine with .to_gdal(), or its 9 values a, b, c, d, e, f, 0, 0, 1),
    whose first 6 values are in another order."""
    if hasattr(geotransform, "to_gdal"):
        return tuple(geotransform.to_gdal())
    try:
        values = tuple(geotransform)
    except TypeError:
        return geotransform  # the library says what is wrong with it
    if len(values) == 9:
        a, b, c, d, e, f, g, h, i = values
        if (g, h, i) != (0, 0, 1):
            raise InvalidInputError(
                f"{function}: a geotransform of 9 values is an affine matrix a, b, c, d, e, f, "
                f"0, 0, 1; its last row is {(g, h, i)}"
            )
        return (c, a, b, f, d, e)
    return values


def triangulate(points, method="auto", threads=0, *, seed=1, progress=None, return_index=False):
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

    return_index: also return, for every vertex, the row of `points` it came from.

    Returns (vertices, triangles), or (vertices, triangles, index) with return_index:
    vertices (V, 3) float64, the distinct points (points with exactly the same x, y are
    merged, the first one's z kept, as by the CLI's default --duplicate-z first), in the
    triangulation's own order, not the input's: index (V,) int64 gives each vertex's row in
    `points` (points[index] == vertices for (N, 3) input). triangles (T, 3) int32 (int64 from
    2^31 vertices) vertex indices, counter-clockwise. The triangles cover exactly the convex
    hull, and no vertex lies strictly inside a triangle's circumcircle (exact predicates).

    Raises InvalidInputError for a bad array (shape, dtype, NaN or infinite values, fewer
    than three distinct points not all collinear) or option; Cancelled; KeyboardInterrupt on
    Ctrl-C while the library works.
    """
    function = "terratin.triangulate"
    return _terratin.triangulate(
        _as_array(points, function, "points"),
        method,
        _integer(threads, function, "threads"),
        seed=_integer(seed, function, "seed", 0, 2**64 - 1),
        progress=progress,
        return_index=bool(return_index),
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
        y per row), or an affine transform as rasterio gives it (an Affine, or its 9 values
        a, b, c, d, e, f, 0, 0, 1); cell centres are at pixel (col + 0.5, row + 0.5).
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
        _gdal_geotransform(geotransform, function),
        _optional_number(nodata, function, "nodata"),
        _optional_number(max_error, function, "max_error"),
        _optional_integer(max_points, function, "max_points"),
        max_triangles=_optional_integer(max_triangles, function, "max_triangles"),
        max_hole=_integer(max_hole, function, "max_hole"),
        fill_holes=bool(fill_holes),
        max_edge=_optional_number(max_edge, function, "max_edge"),
        threads=_integer(threads, function, "threads"),
        validate=bool(validate),
        tile_size=_integer(tile_size, function, "tile_size"),
        progress=progress,
    )
