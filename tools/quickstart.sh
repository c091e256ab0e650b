#!/usr/bin/env bash
# The README's quick start. On a fresh Debian 12 machine, as root:
#   tools/quickstart.sh demo   install what the command line needs, build the terratin target
#                              alone, turn a sample DEM into a GeoPackage TIN
#   tools/quickstart.sh test   install what the tests need too, build, run the whole test suite
#                              (release, then ASan+UBSan, then ThreadSanitizer on the core)
#   tools/quickstart.sh tidy   also install clang-tidy, run the repository's .clang-tidy over lib/src
#                              (not part of 'test' or CI: docs/testing.md says why)
#   tools/quickstart.sh fuzz   also install clang and libFuzzer, run each reader fuzzer for a
#                              minute on its seed corpus (not part of 'test' or CI)
set -euo pipefail
cd "$(dirname "$0")/.."

# What the terratin command line links (the top-level CMakeLists.txt and lib/CMakeLists.txt),
# and what builds it.
readonly cli_packages=(
  g++ cmake ninja-build pkg-config
  ccache  # repeated builds on one machine (CI's) compile only what changed
  libgdal-dev libproj-dev libgeographiclib-dev libboost-program-options-dev libtbb-dev
  libsqlite3-dev  # the GeoPackage writer's rows and R-tree
)

# What the test suite needs on top: GoogleTest (find_package(GTest REQUIRED) in the top-level
# CMakeLists.txt) and libxml2 (find_package(LibXml2 REQUIRED) in tests/CMakeLists.txt) are
# required when TERRATIN_BUILD_TESTS is ON; the rest is found quietly and its tests skipped
# without it.
readonly test_packages=(
  googletest libgtest-dev
  libxml2-dev libxml2-utils
  gdal-bin  # tests: ogrinfo, ogr2ogr, gdal_translate... make inputs and read outputs
  sqlite3 python3-gdal  # tests: rtreecheck and GDAL's validate_gpkg.py on written GeoPackages
  python3-qgis  # tests/qgis: the outputs opened in QGIS, headless
  clang-format  # the test command checks the C++ files against .clang-format
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest  # the Python module (python/) and its tests
  python3-venv python3-setuptools python3-wheel  # tests: pip install . in a venv, as docs/python.md says
  openmpi-bin libopenmpi-dev  # tiles shared among MPI ranks (mpirun), and their test
)

# Only for 'fuzz': clang and its libFuzzer runtime.
readonly fuzz_packages=(clang libclang-rt-14-dev)

installed() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}

install_missing_packages() {
  local missing=()
  for package in "$@"; do
    installed "$package" || missing+=("$package")
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

# CMake takes these environment variables as the launchers' defaults when it first configures a
# build folder (a folder configured before keeps its own choice).
use_ccache_when_installed() {
  if command -v ccache >/dev/null; then
    export CMAKE_CXX_COMPILER_LAUNCHER=ccache CMAKE_C_COMPILER_LAUNCHER=ccache
  fi
}

# build_preset PRESET [CMAKE_CONFIGURE_ARGUMENTS...]
build_preset() {
  local preset=$1
  shift
  cmake --preset "$preset" "$@" >/dev/null
  cmake --build --preset "$preset" -j "$(nproc)"
}

# A release folder that 'demo' configured has TERRATIN_BUILD_TESTS off, and TERRATIN_BUILD_PYTHON
# off where pybind11 was missing; both are cached options, so the test commands turn them on.
readonly release_with_tests=(-DTERRATIN_BUILD_TESTS=ON -DTERRATIN_BUILD_PYTHON=ON)

all_installed() {
  local package
  for package in "$@"; do
    installed "$package" || return 1
  done
}

case "${1:-}" in
  demo)
    install_missing_packages "${cli_packages[@]}"
    use_ccache_when_installed
    # Without the test packages, the tests' required GoogleTest and libxml2 would fail the
    # configure step; with all of them the folder keeps what it was configured with.
    configure=()
    all_installed "${test_packages[@]}" || configure=(-DTERRATIN_BUILD_TESTS=OFF)
    cmake --preset release "${configure[@]}" >/dev/null
    cmake --build --preset release -j "$(nproc)" --target terratin
    ./build/release/tools/terratin build sample_dems/ridges_utm.tif -o build/ridges_utm.gpkg --overwrite
    echo "Wrote build/ridges_utm.gpkg"
    ;;
  test)
    install_missing_packages "${cli_packages[@]}" "${test_packages[@]}"
    use_ccache_when_installed
    check_formatting
    build_preset release "${release_with_tests[@]}"
    ctest --preset release
    # The same suite under AddressSanitizer and UndefinedBehaviorSanitizer.
    build_preset dev
    ctest --preset dev
    # The geometry and triangulation tests, parallel methods included, under ThreadSanitizer.
    build_preset tsan
    ctest --preset tsan
    # The parallel code that lives in the I/O library: the simplified constrained build's check
    # and the LAZ reader's chunks.
    build_preset tsan-pipeline
    ctest --preset tsan-pipeline
    ;;
  tidy)
    install_missing_packages "${cli_packages[@]}" "${test_packages[@]}" clang-tidy
    cmake --preset release "${release_with_tests[@]}" >/dev/null # compile_commands.json
    run-clang-tidy -quiet -p build/release -j "$(nproc)" '/lib/src/'
    ;;
  fuzz)
    install_missing_packages "${cli_packages[@]}" "${test_packages[@]}" "${fuzz_packages[@]}"
    use_ccache_when_installed
    cmake --preset fuzz >/dev/null
    cmake --build --preset fuzz -j "$(nproc)" \
      --target terratin_las_fuzzer terratin_laz_fuzzer terratin_text_fuzzer
    for reader in las laz text; do
      found=$(mktemp -d)
      seeds=("tests/fuzz/corpus/$reader")
      # The real LAZ files seed the LAZ fuzzer where they are, never copied into the corpus.
      [ "$reader" = laz ] && [ -d ../shared/dems/laz ] && seeds+=(../shared/dems/laz)
      UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
        "build/fuzz/tests/fuzz/terratin_${reader}_fuzzer" -max_total_time="${FUZZ_SECONDS:-60}" \
        -print_final_stats=1 "$found" "${seeds[@]}"
      rm -rf "$found"
    done
    ;;
  *)
    echo "usage: tools/quickstart.sh demo|test|tidy|fuzz" >&2
    exit 2
    ;;
esac
