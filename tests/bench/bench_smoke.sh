#!/usr/bin/env bash
# terratin-bench end to end on small inputs: every method and point location at 1 and 2
# threads on two of the paper's distributions, with every row measured, one triangle count
# per distribution, and the GDAL line and --refine matching how the bench was built.
#   bench_smoke.sh TERRATIN_BENCH_BINARY built|not-built
set -uo pipefail

bench=$1
gdal=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

fail() {
  echo "FAIL: $*" >&2
  cat "$work/out.csv" >&2 2>/dev/null
  exit 1
}

"$bench" --sizes 2000 --runs 1 --distributions uniform,arc --threads 1,2 --no-cgal --csv \
  >"$work/out.csv" 2>"$work/err.txt" || fail "exit status $?: $(cat "$work/err.txt")"

rows=$(grep -E '^(uniform|arc),' "$work/out.csv")
# Per distribution: sequential at each location, batch and circum-circle at each location
# and thread count, strips at each thread count: 2 + 2*2*2 + 2 = 12 rows of terratin's, then
# GDAL's where built. Every row, the peer's too, has the same triangle count.
for distribution in uniform arc; do
  count=$(grep "^$distribution," <<<"$rows" | grep -cv ',gdal,')
  [ "$count" -eq 12 ] || fail "$distribution: $count rows, expected 12"
  triangles=$(grep "^$distribution," <<<"$rows" | cut -d, -f9 | sort -u)
  [ "$(wc -l <<<"$triangles")" -eq 1 ] || fail "$distribution: triangle counts differ: $triangles"
done
# Every row measured: a time in column 11 and no reason in the last column.
unmeasured=$(awk -F, '$11 == "" || $18 != ""' <<<"$rows")
[ -z "$unmeasured" ] || fail "unmeasured rows: $unmeasured"

if [ "$gdal" = built ]; then
  grep -q "^# GDAL [0-9]" "$work/err.txt" || fail "no GDAL line in the preamble"
else
  grep -q "^# GDAL: not built" "$work/err.txt" || fail "the preamble does not say GDAL is not built"
  "$bench" --refine >"$work/refine.txt" 2>"$work/err.txt"
  status=$?
  [ "$status" -eq 1 ] || fail "--refine without terratin::io: exit status $status, expected 1"
  grep -q 'terratin::io' "$work/err.txt" || fail "--refine without terratin::io: $(cat "$work/err.txt")"
fi
exit 0
