#!/usr/bin/python3
"""A DEM simplified whole against the same DEM simplified in tiles, side by side (issue 25).

Runs, --rounds times, `terratin build DEM -o tin.ply --max-error E` and the same with
`--tile-size T` for each T given, in turn (the order rotating from round to round, so that
each configuration meets every load), and prints per configuration the medians of the JSON
report's refine and total seconds, the peak resident memory of the process, and the points,
triangles and achieved error (the same every round). Run from the source tree after the
release build:

    /usr/bin/python3 tools/bench/tiles_bench.py build/release/tools/terratin \\
        ../shared/dems/gdalraster__lf_elev_220_mt_hood_utm.tif --max-error 1 --tiles 256 1024

docs/benchmarks.md holds the measurement, with its date, commit and machine.
"""

import argparse
import json
import os
import statistics
import subprocess
import tempfile
from pathlib import Path


def run_once(terratin, dem, output, max_error, tile_size, threads):
    """One build: its JSON report and the peak resident memory of the process, in MiB."""
    command = [str(terratin), "build", str(dem), "-o", str(output), "--overwrite", "--json",
               "--quiet", "--max-error", str(max_error), "--threads", str(threads)]
    if tile_size:
        command += ["--tile-size", str(tile_size)]
    with tempfile.TemporaryFile() as stdout:
        process = subprocess.Popen(command, stdout=stdout, stderr=subprocess.PIPE)
        _, status, usage = os.wait4(process.pid, 0)
        process.returncode = os.waitstatus_to_exitcode(status)
        if process.returncode != 0:
            raise SystemExit(f"{' '.join(command)} failed: {process.stderr.read().decode()}")
        stdout.seek(0)
        report = json.loads(stdout.read())
    return report, usage.ru_maxrss / 1024.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("terratin", type=Path)
    parser.add_argument("dem", type=Path)
    parser.add_argument("--max-error", type=float, default=1.0)
    parser.add_argument("--tiles", type=int, nargs="+", default=[256, 1024])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--threads", type=int, default=0)
    args = parser.parse_args()

    configurations = [0] + args.tiles
    seconds = {c: {"refine": [], "total": []} for c in configurations}
    memory = {c: [] for c in configurations}
    figures = {}
    with tempfile.TemporaryDirectory() as work:
        output = Path(work) / "tin.ply"
        for round_index in range(args.rounds):
            shift = round_index % len(configurations)
            for tile_size in configurations[shift:] + configurations[:shift]:
                report, peak = run_once(args.terratin, args.dem, output, args.max_error,
                                        tile_size, args.threads)
                seconds[tile_size]["refine"].append(report["timings"]["triangulate"])
                seconds[tile_size]["total"].append(report["timings"]["total"])
                memory[tile_size].append(peak)
                figures[tile_size] = (report["counts"]["vertices"],
                                      report["counts"]["triangles"],
                                      report["refine"]["achieved_max_error"])

    whole = statistics.median(seconds[0]["total"])
    print(f"{args.dem.name}, --max-error {args.max_error}, {args.rounds} rounds, medians")
    print("| tiles | points | triangles | max error | refine s | total s | total / untiled "
          "| peak RSS MiB |")
    print("|---|---|---|---|---|---|---|---|")
    for tile_size in configurations:
        points, triangles, achieved = figures[tile_size]
        total = statistics.median(seconds[tile_size]["total"])
        print(f"| {tile_size or 'none'} | {points:,} | {triangles:,} | {achieved:.3f} "
              f"| {statistics.median(seconds[tile_size]['refine']):.3f} | {total:.3f} "
              f"| {total / whole:.2f} | {statistics.median(memory[tile_size]):.0f} |")


if __name__ == "__main__":
    main()
