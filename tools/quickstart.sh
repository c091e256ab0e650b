#!/usr/bin/env bash
# The README's quick start. On a fresh Debian 12 machine, as root:
#   tools/quickstart.sh demo   install what is missing, build, turn a sample DEM into a GeoPackage TIN
#   tools/quickstart.sh test   install what is missing, build, run the whole test suite
#                              (release, then ASan+UBSan, then ThreadSanitizer on the core)
#   tools/quickstart.sh tidy   also install clang-tidy, run the repository's .clang-tidy over lib/src
#                              (not part of 'test' or CI: docs/testing.md says why)
#   tools/quickstart.sh fuzz   also install clang and libFuzzer, run each reader fuzzer for a
#                              minute on its seed corpus (not part of 'test' or CI)
set -euo pipefail
cd "$(dirname "$0")/.."

readonly packages=(
  g++ cmake ninja-build pkg-config
  libgdal-dev gdal-bin libproj-dev libgeographiclib-dev libboost-program-options-dev libtbb-dev
  libsqlite3-dev  # the GeoPackage writer's rows and R-tree
  googletest libgtest-dev
  libxml2-dev libxml2-utils
  sqlite3 python3-gdal  # tests: rtreecheck and GDAL's validate_gpkg.py on written GeoPackages
  python3-qgis  # tests/qgis: the outputs opened in QGIS, headless
  clang-format  # the test command checks the C++ files against .clang-format
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest  # the Python module (python/) and its tests
  openmpi-bin libopenmpi-dev  # tiles shared among MPI ranks (mpirun), and their test
)

# Only for 'fuzz': clang and its libFuzzer runtime.
readonly fuzz_packages=(clang libclang-rt-14-dev)

install_missing_packages() {
  local missing=()
  for package in "${packages[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
      missing+=("$package")
  done
  if ((${#missing[@]})); then
    echo "Installing: ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
  fi
}

# Every tracked C++ file as .clang-format (Debian's clang-format) writes it; the list of those
# that differ, and a failure, otherwise.
check_formatting() {
  local unformatted=()
  while IFS= read -r file; do
    clang-format --dry-run --Werror "$file" >/dev/null 2>&1 || unformatted+=("$file")
  done < <(git ls-files '*.cpp' '*.hpp' '*.h')
  if ((${#unformatted[@]})); then
    echo "Not formatted as .clang-format says (run clang-format -i on them):" >&2
    printf '  %s\n' "${unformatted[@]}" >&2
    return 1
  fi
}

build_preset() {
  cmake --preset "$1" >/dev/null
  cmake --build --preset "$1" -j "$(nproc)"
}

case "${1:-}" in
  demo)
    install_missing_packages
    build_preset release
    ./build/release/tools/terratin build sample_dems/ridges_utm.tif -o build/ridges_utm.gpkg --overwrite
    echo "Wrote build/ridges_utm.gpkg"
    ;;
  test)
    install_missing_packages
    check_formatting
    build_preset release
    ctest --preset release
    # The same suite under AddressSanitizer and UndefinedBehaviorSanitizer.
    build_preset dev
    ctest --preset dev
    # The geometry and triangulation tests, parallel methods included, under ThreadSanitizer.
    build_preset tsan
    ctest --preset tsan
    # The simplified constrained build's parallel check, which lives in the I/O library.
    build_preset tsan-pipeline
    ctest --preset tsan-pipeline
    ;;
  tidy)
    install_missing_packages clang-tidy
    cmake --preset release >/dev/null # compile_commands.json
    run-clang-tidy -quiet -p build/release -j "$(nproc)" '/lib/src/'
    ;;
  fuzz)
    install_missing_packages "${fuzz_packages[@]}"
    cmake --preset fuzz >/dev/null
    cmake --build --preset fuzz -j "$(nproc)" --target terratin_las_fuzzer terratin_text_fuzzer
    for reader in las text; do
      found=$(mktemp -d)
      UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
        "build/fuzz/tests/fuzz/terratin_${reader}_fuzzer" -max_total_time=60 -print_final_stats=1 \
        "$found" "tests/fuzz/corpus/$reader"
      rm -rf "$found"
    done
    ;;
  *)
    echo "usage: tools/quickstart.sh demo|test|tidy|fuzz" >&2
    exit 2
    ;;
esac
