#!/usr/bin/python3
"""A DEM simplified whole against the same DEM simplified in tiles, side by side.

Runs, --rounds times, `terratin build DEM -o tin.ply --max-error E` and the same with
`--tile-size T` for each T given, with `--memory-limit L` for each L given (the TIN written tile
by tile), and with --ranks N, `mpirun -np N` of the first tile size (rank 0 coordinates, the
others refine with --rank-threads threads each), in turn (the order
rotating from round to round, so that each configuration meets every load), and prints per
configuration the medians of the JSON report's refine and total seconds, the peak resident
memory of the largest process, and the points, triangles and achieved error (the same every
round). --full-resolution leaves --max-error out (every valid cell a vertex); --format gpkg,
fgb, shp, 2dm, obj or xml writes that format instead of PLY. Run from the source tree after the
release build:

    /usr/bin/python3 tools/bench/tiles_bench.py build/release/tools/terratin \\
        ../shared/dems/gdalraster__lf_elev_220_mt_hood_utm.tif --max-error 1 --tiles 256 1024 \\
        --ranks 2 3 --rank-threads 1

docs/benchmarks.md holds the measurement, with its date, commit and machine.
"""

import argparse
import json
import os
import statistics
import subprocess
import tempfile
from pathlib import Path


MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--bind-to", "none"]


def run_once(terratin, dem, output, max_error, configuration, threads):
    """One build: its JSON report and the peak resident memory of the largest process, MiB."""
    tile_size, ranks, memory_limit = configuration
    command = [str(terratin), "build", str(dem), "-o", str(output), "--overwrite", "--json",
               "--quiet", "--threads", str(threads)]
    if max_error is not None:
        command += ["--max-error", str(max_error)]
    if tile_size:
        command += ["--tile-size", str(tile_size)]
    if memory_limit:
        command += ["--memory-limit", memory_limit]
    if ranks:
        command = MPIRUN + ["-np", str(ranks)] + command
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
    parser.add_argument("--full-resolution", action="store_true")
    parser.add_argument("--format", choices=["ply", "gpkg", "fgb", "shp", "2dm", "obj", "xml"],
                        default="ply")
    parser.add_argument("--tiles", type=int, nargs="*", default=[256, 1024])
    parser.add_argument("--memory-limits", nargs="*", default=[])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--ranks", type=int, nargs="*", default=[])
    parser.add_argument("--rank-threads", type=int, default=1)
    args = parser.parse_args()

    max_error = None if args.full_resolution else args.max_error
    configurations = ([(0, 0, "")] + [(t, 0, "") for t in args.tiles]
                      + [(0, 0, limit) for limit in args.memory_limits]
                      + [(args.tiles[0], n, "") for n in args.ranks])
    seconds = {c: {"refine": [], "total": []} for c in configurations}
    memory = {c: [] for c in configurations}
    figures = {}
    with tempfile.TemporaryDirectory() as work:
        output = Path(work) / f"tin.{args.format}"
        for round_index in range(args.rounds):
            shift = round_index % len(configurations)
            for configuration in configurations[shift:] + configurations[:shift]:
                threads = args.rank_threads if configuration[1] else args.threads
                report, peak = run_once(args.terratin, args.dem, output, max_error,
                                        configuration, threads)
                seconds[configuration]["refine"].append(report["timings"]["triangulate"])
                seconds[configuration]["total"].append(report["timings"]["total"])
                memory[configuration].append(peak)
                figures[configuration] = (report["counts"]["vertices"],
                                          report["counts"]["triangles"],
                                          report.get("refine", {}).get("achieved_max_error", 0.0),
                                          ", ".join(report["notices"]))

    whole = statistics.median(seconds[(0, 0, "")]["total"])
    target = "full resolution" if max_error is None else f"--max-error {max_error}"
    print(f"{args.dem.name}, {target}, {args.format}, {args.rounds} rounds, medians")
    print("| tiles | processes | points | triangles | max error | refine s | total s "
          "| total / untiled | peak RSS MiB |")
    print("|---|---|---|---|---|---|---|---|---|")
    for configuration in configurations:
        tile_size, ranks, memory_limit = configuration
        points, triangles, achieved, notices = figures[configuration]
        tiles = f"--memory-limit {memory_limit} ({notices})" if memory_limit else tile_size or "none"
        total = statistics.median(seconds[configuration]["total"])
        processes = f"mpirun -np {ranks}, {args.rank_threads} thread(s) a rank" if ranks else "1"
        print(f"| {tiles} | {processes} | {points:,} | {triangles:,} "
              f"| {achieved:.3f} | {statistics.median(seconds[configuration]['refine']):.3f} "
              f"| {total:.3f} | {total / whole:.2f} "
              f"| {statistics.median(memory[configuration]):.0f} |")


if __name__ == "__main__":
    main()
