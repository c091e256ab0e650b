#!/usr/bin/env bash
# Two builds of terratin-bench side by side: the triangulation and refinement tables of each,
# and the GeoPackage writing of the terratin beside each bench (Mt Hood whole, the write
# phase of its --json report), run in turn ROUNDS times (before, after, before, after...), so
# that both see the same machine. Prints, per configuration, the median seconds of each and
# after / before.
#   tools/bench/before_after.sh BEFORE_BENCH AFTER_BENCH [ROUNDS] [DEMS]
# Example: keep a copy of build/release/tools/terratin-bench before a change, rebuild, then
#   tools/bench/before_after.sh /tmp/terratin-bench.before build/release/tools/terratin-bench
set -euo pipefail

before=$1
after=$2
rounds=${3:-3}
dems=${4:-../shared/dems}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

triangulation=(--sizes 1M --distributions uniform,gauss --methods sequential,batch,circumcircle,strips
  --threads 2 --runs 1 --no-cgal --no-gdal --csv)
refinement=(--refine --runs 1 --dems "$dems" --csv)

for ((round = 1; round <= rounds; ++round)); do
  for side in before after; do
    bench=$before
    [ "$side" = after ] && bench=$after
    "$bench" "${triangulation[@]}" | grep -v '^#' >"$work/triangulation.$side.$round.csv"
    "$bench" "${refinement[@]}" | grep -v '^#' >"$work/refinement.$side.$round.csv"
    "$(dirname "$bench")/terratin" build "$dems/gdalraster__lf_elev_220_mt_hood_utm.tif" \
      -o "$work/hood.gpkg" --overwrite --quiet --json |
      /usr/bin/python3 -c 'import json, sys; print("format,seconds"); print("gpkg,%s" % json.load(sys.stdin)["timings"]["write"])' \
        >"$work/writing.$side.$round.csv"
  done
done

/usr/bin/python3 - "$work" "$rounds" <<'EOF'
import csv, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
tables = {
    "triangulation": ("distribution", "points", "method", "locate", "threads_used"),
    "refinement": ("dem", "max_error_m", "threads"),
    "writing": ("format",),
}
for table, keys in tables.items():
    seconds = {}
    for side in ("before", "after"):
        for round_ in range(1, rounds + 1):
            with open(f"{work}/{table}.{side}.{round_}.csv") as f:
                for row in csv.DictReader(f):
                    key = tuple(row[k] for k in keys)
                    seconds.setdefault(key, {"before": [], "after": []})[side].append(
                        float(row["seconds"]))
    print(f"\n| {table}: {' / '.join(keys)} | before s | after s | after / before |")
    print("|---|---|---|---|")
    for key, sides in seconds.items():
        b, a = statistics.median(sides["before"]), statistics.median(sides["after"])
        print(f"| {' / '.join(key)} | {b:.3f} | {a:.3f} | {a / b:.3f} |")
EOF
