#!/usr/bin/env bash
# The README's quick start. On a fresh Debian 12 machine, as root:
#   tools/quickstart.sh demo   install what is missing, build, turn a sample DEM into a GeoPackage TIN
#   tools/quickstart.sh test   install what is missing, build, run the whole test suite
#                              (release, then ASan+UBSan, then ThreadSanitizer on the core)
set -euo pipefail
cd "$(dirname "$0")/.."

readonly packages=(
  g++ cmake ninja-build pkg-config
  libgdal-dev gdal-bin libproj-dev libgeographiclib-dev libboost-program-options-dev libtbb-dev
  googletest libgtest-dev
  libxml2-dev libxml2-utils
)

install_missing_packages() {
  local missing=()
  for package in "${packages[@]}"; do
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
    build_preset release
    ctest --preset release
    # The same suite under AddressSanitizer and UndefinedBehaviorSanitizer.
    build_preset dev
    ctest --preset dev
    # The geometry and triangulation tests, parallel methods included, under ThreadSanitizer.
    build_preset tsan
    ctest --preset tsan
    ;;
  *)
    echo "usage: tools/quickstart.sh demo|test" >&2
    exit 2
    ;;
esac
