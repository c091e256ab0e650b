#!/usr/bin/env bash
# Something happens while a run is under way: a signal (SIGINT, SIGTERM, SIGHUP) or another
# program creating the output, at a chosen phase of a Mt Hood run.
#   during_run_test.sh EVENT PHASE FORMAT TERRATIN_BINARY [SHARED_DEMS]
#   EVENT:  INT | TERM | HUP  (signal the run; an old output is there, --overwrite)
#           appear            (create the output; none was there, no --overwrite)
#   PHASE:  reading        (a 4x upsampled VRT of Mt Hood, signalled at the first dot)
#           triangulating  (progress 20: the triangulation holds 10..50)
#           rows           (progress 60: the writer holds 50..100, rows first)
#           index          (progress 80: a GeoPackage's or FlatGeobuf's spatial index)
#   FORMAT: an output extension (gpkg, shp, fgb, ply...)
# The run must stop with exit 1 and one error line (cancelled / appeared) after its progress
# line, leave the old output (or the other program's file) byte-identical, and leave nothing
# else in the output directory or TMPDIR. No wall-clock duration is asserted: on a loaded
# machine the rest of a Shapefile can take minutes to write after the output appears (the
# 120 s bound this script once had failed there). A run that never stops is caught by the
# test's ctest TIMEOUT. Skips (exit 77) without Mt Hood.
set -uo pipefail

event=$1
phase=$2
format=$3
binary=$(realpath -- "$4")
shared=${5:-}
hood=gdalraster__lf_elev_220_mt_hood_utm.tif
[ -n "$shared" ] && [ -e "$shared/$hood" ] || { echo "skip: no $hood"; exit 77; }
hood=$(realpath -- "$shared/$hood")

work=$(mktemp -d)
out=$work/out
mkdir -p "$out" "$work/tmp"
pid=""
cleanup() {
  [ -z "$pid" ] || kill -KILL "$pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "FAIL [$event $phase $format]: $*" >&2
  echo "--- stderr:" >&2; head -c 4000 "$work/stderr" >&2 2>/dev/null
  echo "--- output directory:" >&2; ls -lA "$out" >&2
  exit 1
}

input=$hood
if [ "$phase" = reading ]; then
  # Mt Hood reads in a blink; sixteen times its cells take long enough to be caught reading.
  gdal_translate -q -of VRT -outsize 400% 400% "$hood" "$work/big.vrt" || fail "gdal_translate"
  input=$work/big.vrt
fi
case "$phase" in
  reading) mark=$'(^|\n)0\\.' ;;
  triangulating) mark='\.\.\.20' ;;
  rows) mark='\.\.\.60' ;;
  # A GeoPackage's index holds 74.5..99; FlatGeobuf reports 75 before it builds its own.
  index) if [ "$format" = fgb ]; then mark='\.\.\.70\.\.'; else mark='\.\.\.80'; fi ;;
  *) echo "unknown phase '$phase'" >&2; exit 1 ;;
esac

output=hood.$format
arguments=(build "$input" -o "$output")
if [ "$event" = appear ]; then
  # The command line's spelling of the option: the CLI's messages name its flags.
  expected='appeared while this run was writing; it was left as it is \(use --overwrite to replace it\)'
else
  # The old output: every file of it must come through intact.
  if [ "$format" = shp ]; then
    for ext in shp shx dbf; do printf 'old %s' "$ext" >"$out/hood.$ext"; done
  else
    printf 'old output' >"$out/$output"
  fi
  arguments+=(--overwrite)
  expected='cancel'
fi
before=$(cd "$out" && find . -type f -exec sha256sum {} + | sort)

cd "$out" || exit 1
: >"$work/stderr"
TMPDIR=$work/tmp "$binary" "${arguments[@]}" >"$work/stdout" 2>"$work/stderr" &
pid=$!

# Catch the run inside its phase. Polling alone once missed a PLY's rows (the whole of 60..100
# took less than one poll), so the run goes in slices of a millisecond and is stopped (SIGSTOP)
# while its progress is read: when the mark is there and 90 is not, the run is still before the
# writer's last cancellation point (98 % of its share), and the event lands there on SIGCONT.
exec {idle}<> <(:)
progress=
while :; do
  kill -STOP "$pid" 2>/dev/null || fail "cannot stop the run"
  read -r _ _ state _ <"/proc/$pid/stat"
  [ "$state" != Z ] || fail "the run ended before reaching the $phase phase"
  IFS= read -r -d '' progress <"$work/stderr"
  [[ $progress =~ $mark ]] && break
  kill -CONT "$pid"
  read -r -t 0.001 -u "$idle"
done
[[ $progress =~ \.\.\.90|done|failed ]] && fail "the run was past the $phase phase when caught"

if [ "$event" = appear ]; then
  printf 'written by another program' >"$out/$output"
  before=$(cd "$out" && sha256sum "./$output")
else
  kill -s "$event" "$pid" || fail "cannot signal the run"
fi
kill -CONT "$pid"

# Wait for the run to stop.
wait "$pid"
status=$?
pid=""

[ "$status" -eq 1 ] || fail "exit status $status, expected 1"
grep -Eq '^[0-9][0-9.]*$' "$work/stderr" && fail "a bare progress fragment on a line of its own"
others=$(grep -Evc -e '^[0-9][0-9.]* - (done|failed)\.$' -e '^terratin: notice: ' "$work/stderr")
[ "$others" -eq 1 ] || fail "stderr has $others error lines, not exactly one"
tail -n 1 "$work/stderr" | grep -Eq "^terratin: .*$expected" ||
  fail "the last line of stderr is not the '$expected' error"

after=$(cd "$out" && find . -type f -exec sha256sum {} + | sort)
[ "$after" = "$before" ] || fail "the output directory changed: $(cd "$out" && ls -A)"
[ -z "$(cd "$out" && find . -mindepth 1 ! -type f)" ] || fail "something other than files left"
[ -z "$(ls -A "$work/tmp")" ] || fail "left in TMPDIR: $(ls -A "$work/tmp")"
echo "ok [$event $phase $format]: $(tail -n 1 "$work/stderr")"
