#!/usr/bin/env bash
# The installed CMake package, consumed as a user would: cmake --install of this build into a
# staging prefix, examples/cpp configured against it with find_package(terratin), built with
# the same generator, compiler and build type, and both example programs run and checked.
#   install_and_consume.sh BUILD_DIR WORK_DIR EXAMPLES_DIR SAMPLE_DEM GENERATOR CXX BUILD_TYPE [LAUNCHER]
# Everything is written under WORK_DIR (in the build tree), emptied first.
set -uo pipefail

build_dir=$1
work=$2
examples=$3
sample=$4
generator=$5
cxx=$6
build_type=$7
launcher=${8:-}

fail() {
  echo "FAIL [package.install_and_consume]: $*" >&2
  exit 1
}

rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
prefix=$work/prefix

cmake --install "$build_dir" --prefix "$prefix" >"$work/install.log" 2>&1 ||
  { cat "$work/install.log" >&2; fail "cmake --install failed"; }
for file in lib/cmake/terratin/terratinConfig.cmake lib/cmake/terratin/terratinConfigVersion.cmake \
  include/terratin/version.hpp include/terratin/pipeline/build_pipeline.hpp bin/terratin; do
  [ -e "$prefix/$file" ] || fail "not installed: $file"
done
[ ! -e "$prefix/bin/terratin-bench" ] || fail "a bench tool was installed"

# Only the staging prefix: the build tree's targets must not leak into the consumer.
cmake -S "$examples" -B "$work/examples" -G "$generator" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_BUILD_TYPE="$build_type" ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} \
  -DCMAKE_PREFIX_PATH="$prefix" >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log" >&2; fail "configuring examples/cpp failed"; }
cmake --build "$work/examples" >"$work/build.log" 2>&1 ||
  { cat "$work/build.log" >&2; fail "building examples/cpp failed"; }

# Six points, four on the hull: 2n - h - 2 = 6 triangles.
"$work/examples/triangulate_points" >"$work/triangulate.txt" ||
  fail "triangulate_points failed"
cat "$work/triangulate.txt"
grep -q '^terratin [0-9.]*: 6 points, 6 triangles$' "$work/triangulate.txt" ||
  fail "triangulate_points did not report 6 points and 6 triangles"

gpkg=$work/ridges.gpkg
"$work/examples/dem_to_gpkg" "$sample" "$gpkg" >"$work/dem.txt" || fail "dem_to_gpkg failed"
cat "$work/dem.txt"
triangles=$(sed -n 's/^layer tin: \([0-9]*\) triangles$/\1/p' "$work/dem.txt")
[ -n "$triangles" ] && [ "$triangles" -gt 0 ] || fail "dem_to_gpkg reported no triangles"
# The GeoPackage holds the layer the report describes.
features=$(ogrinfo -ro -so "$gpkg" tin 2>/dev/null | sed -n 's/^Feature Count: //p')
[ "$features" = "$triangles" ] ||
  fail "layer tin of $gpkg has '$features' features, the report says $triangles"
