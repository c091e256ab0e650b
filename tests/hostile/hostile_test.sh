#!/usr/bin/env bash
# The hostile-input suite: one case of cases.tsv per call.
#   hostile_test.sh CASE TERRATIN_BINARY SAMPLE_DEM CASES_TSV [SHARED_DEMS]
#   hostile_test.sh --list CASES_TSV          (the case names, for CTest)
#
# Every case runs in a fresh directory: the command's working directory is the output
# directory $OUT, inputs it makes go to $IN, and TMPDIR points to an empty $TMPDIR. After the
# command the runner checks, whatever the case:
#   - the exit status is the expected one;
#   - stderr holds exactly one line that is not a finished progress line ("0...10 - failed.",
#     "... - done.") or a notice, it is the last line, it starts with "terratin: " and matches
#     the case's pattern (for a successful case: no such line at all);
#   - every file that was in $OUT before is byte-identical (a FIFO, a link or a device is
#     still that), unless the case names it as changed, and nothing else is new in $OUT;
#   - $TMPDIR is empty: no temporary anywhere.
# Columns of cases.tsv (tab-separated; '-' for empty):
#   name  needs  setup  command  exit  stderr_pattern  changed
#   needs:   shared:FILE (skip without it), tmpfs:SIZE ($OUT is a tmpfs of SIZE: disk full),
#            readonly ($OUT is read-only after setup), root (skip unless root)
#   setup:   shell run in $OUT before the snapshot
#   command: shell run in $OUT; `terratin` runs the binary under a time limit
#   changed: glob patterns of $OUT entries the command may create or change
# Variables for setup and command: $SAMPLE, $D (the shared DEMs), $IN, $OUT.
# Skips (exit 77) when a need cannot be met: no shared DEM, no permission to mount.
set -uo pipefail

if [ "${1:-}" = --list ]; then
  awk -F'\t' '!/^#/ && NF >= 7 && $1 != "name" { print $1 }' "$2"
  exit 0
fi

case_name=$1
binary=$(realpath -- "$2")
SAMPLE=$(realpath -- "$3")
cases=$(realpath -- "$4")
D=${5:-}
[ -z "$D" ] || [ ! -e "$D" ] || D=$(realpath -- "$D")

row=$(awk -F'\t' -v name="$case_name" '!/^#/ && $1 == name' "$cases")
[ -n "$row" ] || { echo "no case '$case_name' in $cases" >&2; exit 1; }
IFS=$'\t' read -r _ needs setup command expected pattern changed <<<"$row"

work=$(mktemp -d)
IN=$work/in
OUT=$work/out
mkdir -p "$IN" "$OUT" "$work/tmp"
mounted=""
cleanup() {
  cd / || true
  [ -z "$mounted" ] || umount "$OUT" 2>/dev/null || umount -l "$OUT" 2>/dev/null
  chmod -R u+w "$work" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

skip() { echo "skip [$case_name]: $*"; exit 77; }
fail() {
  echo "FAIL [$case_name]: $*" >&2
  echo "--- command: $command" >&2
  echo "--- stdout:" >&2; head -c 4000 "$work/stdout" >&2 2>/dev/null
  echo "--- stderr:" >&2; head -c 4000 "$work/stderr" >&2 2>/dev/null
  exit 1
}

# A run never hangs the suite: a generous limit, then SIGKILL.
terratin() { timeout -k 10 600 "$binary" "$@"; }

# The needs.
readonly_out=""
for need in ${needs//,/ }; do
  case "$need" in
    -) ;;
    shared:*) [ -n "$D" ] && [ -e "$D/${need#shared:}" ] || skip "no ${need#shared:}" ;;
    root) [ "$(id -u)" -eq 0 ] || skip "needs root" ;;
    tmpfs:*)
      mount -t tmpfs -o "size=${need#tmpfs:}" terratin-hostile "$OUT" 2>/dev/null ||
        skip "cannot mount a tmpfs (not permitted here)"
      mounted=yes ;;
    readonly)
      if [ "$(id -u)" -eq 0 ]; then
        # Root writes through permission bits: only a read-only mount stops it.
        mount -t tmpfs -o size=16m terratin-hostile "$OUT" 2>/dev/null ||
          skip "cannot mount a tmpfs (not permitted here)"
        mounted=yes
      fi
      readonly_out=yes ;;
    *) echo "unknown need '$need'" >&2; exit 1 ;;
  esac
done

export TMPDIR=$work/tmp IN OUT SAMPLE D
cd "$OUT" || exit 1
if [ "$setup" != - ]; then
  eval "$setup" >"$work/setup.log" 2>&1 || { cat "$work/setup.log" >&2; fail "setup failed"; }
fi
if [ -n "$readonly_out" ]; then
  if [ -n "$mounted" ]; then
    mount -o remount,ro "$OUT" || fail "cannot make $OUT read-only"
  else
    chmod 555 "$OUT"
  fi
fi

# What $OUT holds: type, name, and the bytes' hash of regular files (never opening a FIFO or
# a device), the target of links.
snapshot() {
  (cd "$OUT" && find . -mindepth 1 -printf '%y %p %l\n' | sort | while read -r type path rest; do
    if [ "$type" = f ]; then
      echo "f $path $(sha256sum <"$path" | cut -d' ' -f1)"
    else
      echo "$type $path $rest"
    fi
  done)
}
snapshot >"$work/before"

status=0
(eval "$command") >"$work/stdout" 2>"$work/stderr" || status=$?

# The exit status.
[ "$status" = "$expected" ] || fail "exit status $status, expected $expected"

# stderr: finished progress lines and notices, then at most one error line, last.
others=$(grep -Evc -e '^[0-9][0-9.]* - (done|failed)\.$' -e '^terratin: notice: ' "$work/stderr")
if grep -Eq '^[0-9][0-9.]*$' "$work/stderr"; then
  fail "a bare progress fragment on a line of its own"
fi
if [ "$pattern" = - ]; then
  [ "$others" -eq 0 ] || fail "stderr has lines that are neither progress nor notices"
else
  [ "$others" -eq 1 ] || fail "stderr has $others error lines, not exactly one"
  last=$(tail -n 1 "$work/stderr")
  [[ $last == "terratin: "* ]] || fail "stderr's last line is not the error"
  grep -Eq -- "$pattern" <<<"$last" || fail "the error does not match /$pattern/"
fi

# $OUT: what was there is unchanged; what is new was expected.
allowed() {
  local name=${1#./} glob
  [ "$changed" != - ] || return 1
  for glob in $changed; do
    # shellcheck disable=SC2053 # a glob on purpose
    [[ $name == $glob ]] && return 0
  done
  return 1
}
snapshot >"$work/after"
while read -r type path rest; do
  allowed "$path" && continue
  grep -qxF -- "$type $path $rest" "$work/after" || fail "$path was changed or removed"
done <"$work/before"
while read -r type path rest; do
  allowed "$path" && continue
  awk -v p="$path" '$2 == p { found = 1 } END { exit !found }' "$work/before" ||
    fail "$path was left in the output directory"
done <"$work/after"

# TMPDIR: nothing left.
[ -z "$(ls -A "$work/tmp")" ] || fail "left in TMPDIR: $(ls -A "$work/tmp")"
echo "ok [$case_name]: $(tail -n 1 "$work/stderr")"
