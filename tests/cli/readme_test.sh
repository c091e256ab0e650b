#!/usr/bin/env bash
# The README's examples as a user runs them: every command line of the ```sh blocks of its
# "## Examples" section, in order, in one shell. They run in a fresh temporary folder laid out as
# the repository root looks from inside (sample_dems, and ../shared when the checkout has it
# beside it, are links), so that the outputs land there and never in the checkout.
#
# usage: bash readme_test.sh TERRATIN_BINARY REPOSITORY_ROOT
# Exit 0 when every line succeeded; 1 with the failed line; 77 when every line succeeded but those
# naming ../shared/dems were skipped because the folder is absent.
set -euo pipefail

if [ $# -ne 2 ]; then
  echo "usage: bash readme_test.sh TERRATIN_BINARY REPOSITORY_ROOT" >&2
  exit 2
fi
terratin=$(realpath "$1")
root=$(realpath "$2")
readme=$root/README.md

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/root"
ln -s "$root/sample_dems" "$work/root/sample_dems"
have_shared=false
if [ -d "$root/../shared/dems" ]; then
  ln -s "$(realpath "$root/../shared")" "$work/shared"
  have_shared=true
fi

# "LINE_NUMBER<TAB>COMMAND" for each command of the section's sh blocks; a line ending in a
# backslash continues on the next, comments and blank lines are left out.
commands=$(awk '
  /^## / { in_section = ($0 == "## Examples") ; next }
  !in_section { next }
  /^```sh$/ { in_block = 1; next }
  /^```/ { in_block = 0; next }
  !in_block { next }
  {
    if (pending == "") start = NR
    line = $0
    if (line ~ /\\$/) { pending = pending substr(line, 1, length(line) - 1); next }
    line = pending line
    pending = ""
    if (line ~ /^[ \t]*(#|$)/) next
    print start "\t" line
  }
' "$readme")
if [ -z "$commands" ]; then
  echo "readme_test: no command in the sh blocks of README.md's \"## Examples\" section" >&2
  exit 1
fi

cd "$work/root"
# The binary under test comes first, whatever the README's own PATH line adds.
PATH="$(dirname "$terratin"):$PATH"
export PATH

ran=0
skipped=0
while IFS=$'\t' read -r number command; do
  if [[ $command == *../shared/dems* ]] && ! $have_shared; then
    echo "README.md:$number: skipped (no ../shared/dems beside the checkout): $command"
    skipped=$((skipped + 1))
    continue
  fi
  echo "README.md:$number: $command"
  # eval in this shell, as a user's terminal runs the lines one after another: an export stays.
  if eval "$command" </dev/null; then
    ran=$((ran + 1))
  else
    status=$?
    echo "readme_test: README.md line $number failed (exit status $status): $command" >&2
    exit 1
  fi
done <<<"$commands"

echo "readme_test: $ran README example lines ran, $skipped skipped"
if ((skipped)); then
  exit 77
fi
