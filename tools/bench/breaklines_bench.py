#!/usr/bin/python3
"""A DEM's TIN with breaklines against the same TIN without, side by side.

Makes a road-like network over the DEM (--lines polylines of --segments segments each: random
walks that turn gently, inside the raster's extent), then runs, in turn, --rounds times:
`terratin build DEM -o tin.ply` and the same with `--breaklines network.gpkg`, and prints the
median seconds of each (the JSON report's total and its triangulate phase, which holds the
constraint insertion), their ratio and the median of each round's own ratio (the two builds of
a round run side by side), and the median of the constrained runs' `constrain` timing
(the constraint layers read and inserted), a part of the phase that the triangulation's noise
does not blur. PLY output (the default) keeps the write phase small, so that the ratio
measures the triangulation; --format gpkg writes GeoPackages, the run a user makes. Run from the
source tree after the release build:

    /usr/bin/python3 tools/bench/breaklines_bench.py build/release/tools/terratin \\
        ../shared/dems/gdalraster__lf_elev_220_mt_hood_utm.tif

With --baseline OTHER_TERRATIN (a build of another commit), each round runs both binaries in
turn (every other round in reverse order), so that a change is measured against its baseline
under the same load. --one-thread adds the constrained build on one thread to each round: the
same TIN, so its `constrain` against the others' is what the threads gain.

docs/benchmarks.md holds the measurement, with its date, commit and machine.
"""

import argparse
import json
import math
import random
import statistics
import subprocess
import tempfile
from pathlib import Path

from osgeo import gdal, ogr, osr

gdal.UseExceptions()
ogr.UseExceptions()


def write_network(dem, path, lines, segments, seed):
    """`lines` random-walk polylines of `segments` segments inside the DEM's extent."""
    dataset = gdal.Open(str(dem))
    x0, dx, _, y0, _, dy = dataset.GetGeoTransform()
    x1, y1 = x0 + dx * dataset.RasterXSize, y0 + dy * dataset.RasterYSize
    left, right, bottom, top = min(x0, x1), max(x0, x1), min(y0, y1), max(y0, y1)
    step = 0.004 * min(right - left, top - bottom)
    random.seed(seed)
    layer_crs = osr.SpatialReference(wkt=dataset.GetProjection())
    network = ogr.GetDriverByName("GPKG").CreateDataSource(str(path))
    layer = network.CreateLayer("roads", layer_crs, ogr.wkbLineString)
    layer.StartTransaction()
    for _ in range(lines):
        x, y = random.uniform(left, right), random.uniform(bottom, top)
        heading = random.uniform(0, 2 * math.pi)
        line = ogr.Geometry(ogr.wkbLineString)
        line.AddPoint_2D(x, y)
        for _ in range(segments):
            heading += random.gauss(0, 0.3)
            x = min(max(x + step * math.cos(heading), left), right)
            y = min(max(y + step * math.sin(heading), bottom), top)
            line.AddPoint_2D(x, y)
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(line)
        layer.CreateFeature(feature)
    layer.CommitTransaction()


def run(terratin, dem, output, extra):
    report = subprocess.run(
        [terratin, "build", str(dem), "-o", str(output), "--overwrite", "--json", "--quiet",
         *extra],
        check=True, capture_output=True, text=True,
    ).stdout
    return json.loads(report)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("terratin")
    parser.add_argument("dem")
    parser.add_argument("--lines", type=int, default=1000)
    parser.add_argument("--segments", type=int, default=50)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--options", default="", help="more build options, e.g. '--max-error 1'")
    parser.add_argument("--baseline", help="another terratin binary, run in turn with the first")
    parser.add_argument("--format", default="ply", help="the output's extension: ply or gpkg")
    parser.add_argument("--one-thread", action="store_true",
                        help="also the constrained build with --threads 1, in turn with the rest")
    arguments = parser.parse_args()

    with tempfile.TemporaryDirectory() as work:
        network = Path(work) / "network.gpkg"
        write_network(arguments.dem, network, arguments.lines, arguments.segments, arguments.seed)
        output = Path(work) / f"tin.{arguments.format}"
        extra = arguments.options.split()
        sides = {"plain": extra, "breaklines": [*extra, "--breaklines", str(network)]}
        if arguments.one_thread:
            sides["one thread"] = [*sides["breaklines"], "--threads", "1"]
        binaries = [arguments.terratin] + ([arguments.baseline] if arguments.baseline else [])
        seconds = {(binary, side): {"total": [], "triangulate": [], "constrain": []}
                   for binary in binaries for side in sides}
        runs = [(binary, side) for binary in binaries for side in sides]
        for round_number in range(1, arguments.rounds + 1):
            # Every other round in reverse: the first run of a round is often slower on this VM,
            # and a fixed order would charge that to one binary.
            for binary, side in runs if round_number % 2 == 1 else reversed(runs):
                report = run(binary, arguments.dem, output, sides[side])
                seconds[binary, side]["total"].append(report["timings"]["total"])
                seconds[binary, side]["triangulate"].append(report["timings"]["triangulate"])
                seconds[binary, side]["constrain"].append(
                    report["timings"].get("constrain", math.nan))
                if side == "breaklines" and round_number == 1:
                    constraints = report["constraints"]
                    print(f"{binary}: breaklines: {constraints}, vertices "
                          f"{report['counts']['vertices']}, triangles "
                          f"{report['counts']['triangles']}")
        print(f"{arguments.lines} lines x {arguments.segments} segments, "
              f"options '{arguments.options}', {arguments.format} output, "
              f"medians of {arguments.rounds} interleaved rounds:")
        # The last column pairs the two builds of each round, run side by side: the VM's drift
        # from round to round, larger than the ratio's own spread, then cancels.
        print("| binary | phase | without s | with breaklines s | with / without "
              "| median of the rounds' with / without |")
        print("|---|---|---|---|---|---|")
        for binary in binaries:
            for phase in ("triangulate", "total"):
                plain = seconds[binary, "plain"][phase]
                constrained = seconds[binary, "breaklines"][phase]
                paired = statistics.median(c / p for c, p in zip(constrained, plain))
                print(f"| {binary} | {phase} | {statistics.median(plain):.3f} "
                      f"| {statistics.median(constrained):.3f} "
                      f"| {statistics.median(constrained) / statistics.median(plain):.2f} "
                      f"| {paired:.2f} |")
            constrain = statistics.median(seconds[binary, "breaklines"]["constrain"])
            print(f"| {binary} | constrain (part of triangulate) | | {constrain:.3f} | | |")
            if arguments.one_thread:
                for phase in ("constrain", "total"):
                    one = statistics.median(seconds[binary, "one thread"][phase])
                    print(f"| {binary} | {phase}, constrained, --threads 1 | | {one:.3f} | | |")


if __name__ == "__main__":
    main()
