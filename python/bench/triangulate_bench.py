#!/usr/bin/python3
"""terratin.triangulate from Python against the C++ library on the same work.

Each round times the whole Python call on N uniform points in the unit square (argument checks,
the library, the mesh wrapped into arrays) and, inside that same call, terratin::triangulate
alone (_terratin._triangulate_timed, the code path of terratin.triangulate): their ratio is the
Python overhead, immune to the machine's load. Interleaved with it, terratin-bench runs the same
method and threads from C++ (its own uniform points in the unit square) as a cross-check from
another process, on fresh memory as the Python call is (--no-warm-memory). Prints every round and the medians. Run from the source tree after the
release build:

    PYTHONPATH=build/release/python /usr/bin/python3 python/bench/triangulate_bench.py \\
        --bench build/release/tools/terratin-bench

docs/python.md holds the measurement, with its date, commit and machine.
"""

import argparse
import csv
import io
import statistics
import subprocess
import time

import numpy

from terratin import _terratin


def python_and_library_seconds(points, method, threads):
    start = time.perf_counter()
    _, _, library_seconds = _terratin._triangulate_timed(points, method, threads)
    return time.perf_counter() - start, library_seconds


def cpp_seconds(bench, count, method, threads):
    """The median of one run of terratin-bench, read from its CSV."""
    output = subprocess.run(
        [
            bench, "--sizes", str(count), "--distributions", "uniform", "--methods", method,
            "--threads", str(threads), "--locate", "walk", "--runs", "1", "--no-cgal",
            "--no-gdal", "--no-warm-memory", "--csv",
        ],
        check=True, capture_output=True, text=True,
    ).stdout
    rows = [row for row in csv.DictReader(io.StringIO(output)) if row.get("method") == method]
    if not rows:
        raise SystemExit(f"no '{method}' row in terratin-bench's output:\n{output}")
    return float(rows[0]["seconds"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", required=True, help="path of terratin-bench")
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--method", default="strips")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--rounds", type=int, default=5)
    arguments = parser.parse_args()

    rng = numpy.random.default_rng(1)
    python_times, library_times, bench_times = [], [], []
    for round_number in range(1, arguments.rounds + 1):
        points = rng.random((arguments.points, 3))
        python_seconds, library_seconds = python_and_library_seconds(
            points, arguments.method, arguments.threads
        )
        python_times.append(python_seconds)
        library_times.append(library_seconds)
        del points
        bench_times.append(
            cpp_seconds(arguments.bench, arguments.points, arguments.method, arguments.threads)
        )
        print(f"round {round_number}: python call {python_seconds:.3f} s, library inside it "
              f"{library_seconds:.3f} s (x{python_seconds / library_seconds:.4f}), "
              f"terratin-bench {bench_times[-1]:.3f} s", flush=True)
    ratios = [p / l for p, l in zip(python_times, library_times)]
    print(f"{arguments.points} uniform points, {arguments.method}, {arguments.threads} threads, "
          f"medians of {arguments.rounds}: python call {statistics.median(python_times):.3f} s, "
          f"library inside it {statistics.median(library_times):.3f} s, "
          f"ratio {statistics.median(ratios):.4f}; "
          f"terratin-bench {statistics.median(bench_times):.3f} s")

if __name__ == "__main__":
    main()
