#!/usr/bin/python3
"""terratin.triangulate from Python against the C++ library on the same work.

Each round runs two processes, one after the other: a Python process making --calls calls of
terratin.triangulate on fresh arrays of N uniform points in the unit square, and terratin-bench
making as many runs of terratin::triangulate from C++ (its own uniform points in the unit square,
--no-warm-memory: each run on whatever memory it gets, as each Python call is). Both are
processes that start cold and call the library repeatedly, as a script does; the median call of
each is compared. The Python process also times terratin::triangulate inside each call
(_terratin._triangulate_timed, the code path of terratin.triangulate): the whole call against
that is the cost of the Python layer itself. Run from the source tree after the release build:

    PYTHONPATH=build/release/python /usr/bin/python3 python/bench/triangulate_bench.py \\
        --bench build/release/tools/terratin-bench

docs/python.md holds the measurement, with its date, commit and machine.
"""

import argparse
import csv
import io
import json
import os
import statistics
import subprocess
import sys
import time


def python_process(arguments):
    """Runs this script as a child that makes the calls; (call seconds, library seconds)."""
    output = subprocess.run(
        [sys.executable, __file__, "--child", "--points", str(arguments.points),
         "--method", arguments.method, "--threads", str(arguments.threads),
         "--calls", str(arguments.calls)],
        check=True, capture_output=True, text=True, env=os.environ,
    ).stdout
    times = json.loads(output)
    return times["calls"], times["library"]


def child(arguments):
    """The child: --calls calls on fresh arrays, their times as JSON on stdout."""
    import numpy

    from terratin import _terratin

    rng = numpy.random.default_rng(1)
    calls, library = [], []
    for _ in range(arguments.calls):
        points = rng.random((arguments.points, 3))
        start = time.perf_counter()
        vertices, triangles, seconds = _terratin._triangulate_timed(
            points, arguments.method, arguments.threads
        )
        calls.append(time.perf_counter() - start)
        library.append(seconds)
        del vertices, triangles, points
    print(json.dumps({"calls": calls, "library": library}))


def cpp_process(arguments):
    """terratin-bench's median of --calls runs in one process."""
    output = subprocess.run(
        [
            arguments.bench, "--sizes", str(arguments.points), "--distributions", "uniform",
            "--methods", arguments.method, "--threads", str(arguments.threads), "--locate",
            "walk", "--runs", str(arguments.calls), "--no-cgal", "--no-gdal",
            "--no-warm-memory", "--csv",
        ],
        check=True, capture_output=True, text=True,
    ).stdout
    rows = [row for row in csv.DictReader(io.StringIO(output)) if row.get("method") == arguments.method]
    if not rows:
        raise SystemExit(f"no '{arguments.method}' row in terratin-bench's output:\n{output}")
    return float(rows[0]["seconds"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", help="path of terratin-bench")
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--method", default="strips")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--calls", type=int, default=5, help="calls (runs) per process")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    arguments = parser.parse_args()
    if arguments.child:
        child(arguments)
        return
    if not arguments.bench:
        parser.error("--bench is required")

    python_medians, overheads, cpp_medians = [], [], []
    for round_number in range(1, arguments.rounds + 1):
        calls, library = python_process(arguments)
        python_medians.append(statistics.median(calls))
        overheads.append(statistics.median(c / l for c, l in zip(calls, library)))
        cpp_medians.append(cpp_process(arguments))
        print(f"round {round_number}: python median call {python_medians[-1]:.3f} s "
              f"(whole call / library inside it x{overheads[-1]:.4f}), "
              f"terratin-bench median run {cpp_medians[-1]:.3f} s", flush=True)
    python_seconds, cpp_seconds = statistics.median(python_medians), statistics.median(cpp_medians)
    print(f"{arguments.points} uniform points, {arguments.method}, {arguments.threads} threads, "
          f"{arguments.calls} calls per process, medians of {arguments.rounds} rounds: "
          f"python {python_seconds:.3f} s, C++ {cpp_seconds:.3f} s, "
          f"python / C++ {python_seconds / cpp_seconds:.3f}; "
          f"whole call / library inside it {statistics.median(overheads):.4f}")


if __name__ == "__main__":
    main()
