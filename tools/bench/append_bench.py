#!/usr/bin/python3
"""A DEM's TIN appended to an existing GeoPackage against the same TIN written as a new file.

--append-layer changes the user's file in place, in one SQLite transaction under its own
journal: this measures what that costs against the new file's path (its own temporary, no
journal, large pages). Each round runs, in turn (every other round in reverse order):
  new              terratin build DEM -o new.gpkg
  append, journal  the DEM's TIN appended to a small GeoPackage in rollback-journal mode
  append, WAL      the same, the small GeoPackage in WAL mode
  append, 64 KiB   the same, rollback journal, the small GeoPackage on 64 KiB pages (the new
                   file's page size for a large table), which separates the page size's share
and prints the median seconds of each (whole runs, as a user waits for them) and the ratio to
the new file. The small GeoPackage is made afresh before each append, from the sample DEM.

    /usr/bin/python3 tools/bench/append_bench.py build/release/tools/terratin \\
        ../shared/dems/gdalraster__lf_elev_220_mt_hood_utm.tif --rounds 5

docs/benchmarks.md holds the measurement, with its date, commit and machine.
"""

import argparse
import sqlite3
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

SAMPLE = Path(__file__).resolve().parents[2] / "sample_dems" / "ridges_utm.tif"


def small_geopackage(terratin, path, journal_mode, page_size=None):
    path.unlink(missing_ok=True)
    subprocess.run([terratin, "build", str(SAMPLE), "-o", str(path), "--quiet"], check=True)
    db = sqlite3.connect(path)
    if page_size:
        db.execute(f"PRAGMA page_size = {page_size}")
        db.execute("VACUUM")
    db.execute(f"PRAGMA journal_mode = {journal_mode}")
    db.close()


def timed(command):
    start = time.perf_counter()
    subprocess.run(command, check=True)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("terratin")
    parser.add_argument("dem")
    parser.add_argument("--rounds", type=int, default=5)
    arguments = parser.parse_args()
    terratin = arguments.terratin
    runs = {
        "new": None,
        "append, journal": ("delete", None),
        "append, WAL": ("wal", None),
        "append, 64 KiB pages": ("delete", 65536),
    }
    seconds = {name: [] for name in runs}
    with tempfile.TemporaryDirectory() as directory:
        output = Path(directory) / "tin.gpkg"
        for round_number in range(arguments.rounds):
            names = list(runs) if round_number % 2 == 0 else list(reversed(runs))
            for name in names:
                output.unlink(missing_ok=True)
                command = [terratin, "build", arguments.dem, "-o", str(output), "--quiet"]
                if runs[name]:
                    small_geopackage(terratin, output, *runs[name])
                    command += ["--layer", "appended", "--append-layer"]
                seconds[name].append(timed(command))
    new = statistics.median(seconds["new"])
    print(f"| run | rounds | median s | / new file |\n|---|---|---|---|")
    for name, values in seconds.items():
        median = statistics.median(values)
        print(f"| {name} | {len(values)} | {median:.3f} | {median / new:.2f} |")


if __name__ == "__main__":
    main()
