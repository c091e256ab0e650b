#!/usr/bin/env bash
# terratin as a subproject: a parent project (tests/package/subproject) does add_subdirectory of
# this checkout with terratin::io off, GoogleTest and Boost unfindable. The configure must pass
# with no terratin test, tool or install rule, and a consumer of terratin::core must compile.
#   subproject_test.sh SOURCE_DIR WORK_DIR WRAPPER_DIR GENERATOR CXX [LAUNCHER]
set -uo pipefail

source_dir=$1
work=$2
wrapper=$3
generator=$4
cxx=$5
launcher=${6:-}

fail() {
  echo "FAIL [package.subproject_without_gtest]: $*" >&2
  exit 1
}

rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"

cmake -S "$wrapper" -B "$work/build" -G "$generator" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_BUILD_TYPE=Release ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} \
  -DTERRATIN_SOURCE_DIR="$source_dir" -DTERRATIN_BUILD_IO=OFF \
  -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_Boost=ON \
  >"$work/configure.log" 2>&1 || { cat "$work/configure.log" >&2; fail "configure failed"; }

cache=$work/build/CMakeCache.txt
for option in TERRATIN_BUILD_TESTS TERRATIN_BUILD_TOOLS TERRATIN_INSTALL; do
  grep -q "^$option:BOOL=OFF$" "$cache" || fail "$option is not OFF in a subproject"
done
[ ! -e "$work/build/terratin/tests" ] || fail "the terratin tests were configured"
[ ! -e "$work/build/terratin/tools" ] || fail "the terratin tools were configured"

cmake --build "$work/build" --target triangulate_points_objects >"$work/build.log" 2>&1 ||
  { cat "$work/build.log" >&2; fail "the terratin::core consumer did not compile"; }
