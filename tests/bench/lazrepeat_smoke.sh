#!/usr/bin/env bash
# terratin-lazrepeat's command line: exit status 2 for usage errors, 1 with one line on stderr
# for inputs it cannot repeat and outputs it must not replace, 0 for a run, whose outputs
# replace existing ones only with --overwrite, and no temporary left behind in any case.
#   lazrepeat_smoke.sh TERRATIN_LAZREPEAT_BINARY SHARED_DEMS
# Exits 77 (skipped) when SHARED_DEMS has no LAZ files.
set -uo pipefail

tool=$1
laz=${2:-}/laz
[ -f "$laz/lidr__Megaplot.laz" ] || { echo "no shared LAZ files in $laz"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

fail() {
  echo "FAIL: $*" >&2
  echo "--- stdout:" >&2; cat out.txt >&2 2>/dev/null
  echo "--- stderr:" >&2; cat err.txt >&2 2>/dev/null
  exit 1
}

# run EXPECTED_STATUS ARGS...
run() {
  local expected=$1
  shift
  "$tool" "$@" >out.txt 2>err.txt
  local status=$?
  [ "$status" -eq "$expected" ] || fail "exit status $status, expected $expected for: $*"
}

one_error_line() {
  [ "$(wc -l <err.txt)" -eq 1 ] || fail "stderr is not one line"
  grep -qi -- "$1" err.txt || fail "stderr does not mention '$1'"
}

no_temporaries() {
  local stray
  stray=$(find . -name '.*tmp-*' | head -1)
  [ -z "$stray" ] || fail "temporary left behind: $stray"
}

run 2
run 2 "$laz/lidr__Megaplot.laz" out.laz
run 2 "$laz/lidr__Megaplot.laz" out.laz 0
run 2 "$laz/lidr__Megaplot.laz" out.laz 3x
run 2 "$laz/lidr__Megaplot.laz" out.laz 3 --las
run 2 "$laz/lidr__Megaplot.laz" out.laz 3 --bogus
run 0 --help
grep -q '^usage: terratin-lazrepeat' out.txt || fail "--help prints no usage"

run 1 missing.laz out.laz 3
one_error_line "missing.laz"
run 1 "$laz/lazrs__point10.las" out.laz 3
one_error_line "not a LAZ file"
run 1 "$laz/pdal__simple-laszip-compressor-version-1.2r0.laz" out.laz 3
one_error_line "compressor 1"
[ ! -e out.laz ] || fail "a refused input left out.laz"

run 0 "$laz/lidr__Megaplot.laz" out.laz 3 --las out.las
grep -q '244770 points in 6 chunks' out.txt || fail "the summary does not count 3 x 81590 points"
[ -s out.laz ] && [ -s out.las ] || fail "no outputs"
before=$(cksum <out.laz)
run 1 "$laz/pdal__autzen_trim.laz" out.laz 2 --las other.las
one_error_line "--overwrite"
[ "$(cksum <out.laz)" = "$before" ] || fail "an existing output was replaced without --overwrite"
[ ! -e other.las ] || fail "a refused run wrote its LAS output"
run 0 "$laz/pdal__autzen_trim.laz" out.laz 2 --overwrite
grep -q '220000 points in 6 chunks' out.txt || fail "the summary does not count 2 x 110000 points"
no_temporaries
echo "lazrepeat command line: all checks passed"
