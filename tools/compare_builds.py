#!/usr/bin/python3
"""Whether two terratin binaries build the same TINs: every output format, every kind of build.

    tools/compare_builds.py BEFORE AFTER SAMPLE_DEMS_DIR [--shared SHARED_DEMS_DIR]

Runs the same builds with both binaries (a DEM triangulated whole; simplified; in tiles; in
tiles streamed under a memory limit; as a directory of tiles; with breaklines, clip and replace
areas; a point cloud) into every output format, and compares what the outputs hold, not their
bytes (a writer may name its temporaries or order its metadata differently):
- mesh formats (2DM, PLY, OBJ, LandXML): the set of triangles, each as its three vertices'
  coordinates, rotated to start at the least;
- vector formats (GeoPackage, Shapefile, FlatGeobuf): every layer's features, each as its
  geometry's WKT and its attributes, as a sorted list.
Prints one line per build and format, and exits 1 when any differs.
"""

import argparse
import pathlib
import re
import shutil
import struct
import subprocess
import sys
import tempfile

from osgeo import ogr

ogr.UseExceptions()

MESH_FORMATS = {"2dm", "ply", "obj", "xml"}
FORMATS = ["gpkg", "shp", "fgb", "2dm", "ply", "obj", "xml"]


def builds(samples, shared):
    """(name, arguments before -o, formats) of each build compared."""
    dem = str(samples / "ridges_utm.tif")
    roads = str(samples / "roads.gpkg")
    lakes = str(samples / "lakes.gpkg")
    runs = [
        ("whole", [dem], FORMATS),
        ("whole-edges-nodes", [dem, "--nodes", "--edges", "--attributes", "all"], ["gpkg"]),
        ("max-edge", [dem, "--max-edge", "40"], ["gpkg", "ply"]),
        ("simplified", [dem, "--max-error", "0.5"], FORMATS),
        ("simplified-nodes", [dem, "--max-error", "1", "--nodes"], ["gpkg"]),
        ("tiles", [dem, "--max-error", "0.5", "--tile-size", "64"], FORMATS),
        ("tiles-every-cell", [dem, "--tile-size", "100"], ["ply"]),
        ("streamed", [dem, "--max-error", "0.5", "--memory-limit", "160M"], FORMATS),
        ("breaklines", [dem, "--max-error", "1", "--breaklines", roads], FORMATS),
        ("replace", [dem, "--max-error", "1", "--replace", lakes], ["gpkg", "xml"]),
        ("clip", [dem, "--clip", lakes], ["gpkg", "ply"]),
        ("methods", [dem, "--method", "circumcircle", "-j", "2"], ["ply"]),
    ]
    if shared is not None:
        las = shared / "pdal__autzen_trim.las"
        if las.exists():
            runs.append(("las", [str(las)], ["gpkg", "ply"]))
        everest = shared / "osgearth__mt_everest_90m.tif"
        if everest.exists():
            # Geographic: refined in its UTM zone, tiles at their cells' projected positions.
            runs.append(("geographic-tiles",
                         [str(everest), "--max-error", "5", "--tile-size", "200"], ["gpkg"]))
    return runs


def triangle(corners):
    """A triangle as a tuple of its corners, rotated to start at the least (orientation kept)."""
    start = corners.index(min(corners))
    return tuple(corners[start:] + corners[:start])


def ply_triangles(path):
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    vertices = int(re.search(r"element vertex (\d+)", header).group(1))
    faces = int(re.search(r"element face (\d+)", header).group(1))
    points = list(struct.iter_unpack("<3d", data[end:end + 24 * vertices]))
    at = end + 24 * vertices
    result = set()
    for _ in range(faces):
        a, b, c = struct.unpack_from("<3i", data, at + 1)
        at += 13
        result.add(triangle([points[a], points[b], points[c]]))
    return result


def obj_triangles(path):
    origin = (0.0, 0.0, 0.0)
    points, result = [], set()
    for line in path.read_text().splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "#" and words[1:2] == ["terratin-origin"]:
            origin = tuple(float(w) for w in words[2:5])
        elif words[0] == "v":
            points.append(tuple(float(w) + o for w, o in zip(words[1:4], origin)))
        elif words[0] == "f":
            corners = [points[int(w.split("/")[0]) - 1] for w in words[1:4]]
            result.add(triangle(corners))
    return result


def twodm_triangles(path):
    points, faces = {}, []
    for line in path.read_text().splitlines():
        words = line.split()
        if words and words[0] == "ND":
            points[int(words[1])] = tuple(float(w) for w in words[2:5])
        elif words and words[0] == "E3T":
            faces.append([int(w) for w in words[2:5]])
    return {triangle([points[i] for i in face]) for face in faces}


def landxml_triangles(path):
    text = path.read_text()
    points = {int(m.group(1)): tuple(float(v) for v in m.group(2).split())
              for m in re.finditer(r'<P id="(\d+)">([^<]+)</P>', text)}
    faces = [[int(v) for v in m.group(1).split()] for m in re.finditer(r"<F>([^<]+)</F>", text)]
    return {triangle([points[i] for i in face]) for face in faces}


def vector_features(path):
    """Every layer's features of an OGR dataset (a file, or a directory of tiles)."""
    files = sorted(path.glob("*.gpkg")) if path.is_dir() else [path]
    layers = {}
    for file in files:
        dataset = ogr.Open(str(file))
        for layer in dataset:
            rows = []
            for feature in layer:
                geometry = feature.GetGeometryRef()
                fields = tuple(feature.GetField(i) for i in range(feature.GetFieldCount()))
                rows.append(((geometry.ExportToIsoWkt() if geometry else ""), fields))
            layers[(file.name, layer.GetName())] = sorted(rows, key=repr)
    return layers


def mesh_triangles(path):
    if path.is_dir():
        return {f.name: mesh_triangles(f) for f in sorted(path.iterdir())
                if f.suffix in (".ply", ".obj", ".2dm", ".xml")}
    reader = {".ply": ply_triangles, ".obj": obj_triangles, ".2dm": twodm_triangles,
              ".xml": landxml_triangles}[path.suffix]
    return reader(path)


def contents(path, extension):
    return mesh_triangles(path) if extension in MESH_FORMATS else vector_features(path)


def count(items):
    """Triangles or features, summed over the tiles or layers."""
    if isinstance(items, dict):
        return sum(count(value) for value in items.values())
    return len(items)


def run(binary, arguments, output, tiles_dir):
    target = ["--tiles-dir", str(output)] if tiles_dir else ["-o", str(output)]
    command = [binary, "build", *arguments, *target, "--overwrite", "-q"]
    done = subprocess.run(command, capture_output=True, text=True)
    return done.returncode, done.stderr.strip().splitlines()[-1:] if done.stderr else []


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("samples", type=pathlib.Path)
    parser.add_argument("--shared", type=pathlib.Path)
    args = parser.parse_args()
    work = pathlib.Path(tempfile.mkdtemp(prefix="compare_builds."))
    differ = 0
    try:
        runs = builds(args.samples, args.shared)
        runs.append(("tiles-dir", runs[5][1], ["gpkg", "ply"]))
        for name, arguments, formats in runs:
            for extension in formats:
                tiles_dir = name == "tiles-dir"
                found = []
                for label, binary in (("before", args.before), ("after", args.after)):
                    output = work / f"{name}.{label}" / ("tiles" if tiles_dir else f"tin.{extension}")
                    output.parent.mkdir(parents=True, exist_ok=True)
                    extra = ["--format", "landxml" if extension == "xml" else extension] if tiles_dir else []
                    code, message = run(binary, arguments + extra, output, tiles_dir)
                    found.append((code, message, contents(output, extension) if code == 0 else None))
                    shutil.rmtree(output.parent)
                same = found[0] == found[1]
                size = "" if found[0][2] is None else f" ({count(found[0][2])} items)"
                print(f"{'same   ' if same else 'DIFFER '} {name:20} {extension:5}{size}"
                      + ("" if found[0][0] == 0 else f" exit {found[0][0]}: {found[0][1]}"))
                differ += 0 if same else 1
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"{differ} output(s) differ")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
