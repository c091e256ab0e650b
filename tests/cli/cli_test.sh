#!/usr/bin/env bash
# End-to-end checks of the terratin command line: exit status, one-line errors, outputs.
#   cli_test.sh CASE TERRATIN_BINARY SAMPLE_DEM [SHARED_DEMS]
# Each case runs in a fresh temporary directory and exits non-zero with a reason on failure;
# cases that need SHARED_DEMS exit 77 (skipped) without it.
set -uo pipefail

case_name=$1
terratin=$2
sample=$3
shared=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

fail() {
  echo "FAIL [$case_name]: $*" >&2
  echo "--- stdout:" >&2; cat out.txt >&2 2>/dev/null
  echo "--- stderr:" >&2; cat err.txt >&2 2>/dev/null
  exit 1
}

# run EXPECTED_STATUS ARGS...: runs terratin, keeps stdout/stderr in out.txt/err.txt.
run() {
  local expected=$1
  shift
  "$terratin" "$@" >out.txt 2>err.txt
  local status=$?
  [ "$status" -eq "$expected" ] || fail "exit status $status, expected $expected for: $*"
}

# An error is exactly one line on stderr, starting with "terratin: ".
expect_one_error_line() {
  [ "$(wc -l <err.txt)" -eq 1 ] || fail "stderr is not exactly one line"
  grep -q '^terratin: ' err.txt || fail "stderr does not start with 'terratin: '"
  [ -z "${1:-}" ] || grep -qi -- "$1" err.txt || fail "stderr does not mention '$1'"
}

expect_no_leftovers() {
  local stray
  stray=$(find . -name '*.tmp*' -o -name '.*tmp*' | grep -v '^\.$' || true)
  [ -z "$stray" ] || fail "temporary files left behind: $stray"
}

feature_count() {
  ogrinfo -ro -so -al "$1" 2>/dev/null | sed -n 's/^Feature Count: //p' | head -1
}

# need_shared FILE: skip the case (exit 77) when FILE is not in SHARED_DEMS.
need_shared() {
  [ -n "$shared" ] && [ -e "$shared/$1" ] || { echo "skip [$case_name]: no $1"; exit 77; }
}

# small_sample: 40 x 40 cells of the sample (UTM 33N) in small.tif, for fast runs.
small_sample() {
  gdal_translate -q -srcwin 90 90 40 40 "$sample" small.tif || fail "gdal_translate failed"
}

# rotated_sample OUT.tif: the small sample turned 30 degrees about its corner (GT[2], GT[4] set).
rotated_sample() {
  small_sample
  gdal_translate -q -of VRT small.tif north_up.vrt || fail "gdal_translate failed"
  sed 's|<GeoTransform>.*</GeoTransform>|<GeoTransform>455900, 8.660254037844387, 5, 5104100, 5, -8.660254037844387</GeoTransform>|' \
    north_up.vrt >rotated.vrt
  gdal_translate -q rotated.vrt "$1" || fail "gdal_translate of the rotated VRT failed"
  gdalinfo "$1" | grep -q 'GeoTransform' || fail "$1 is not rotated"
}

# feature_count_of FILE LAYER
feature_count_of() {
  ogrinfo -ro -so "$1" "$2" 2>/dev/null | sed -n 's/^Feature Count: //p' | head -1
}

# The triangle and vertex counts of the JSON report in out.txt.
report_count() {
  sed -n "s/.*\"$1\": \([0-9]*\).*/\1/p" out.txt
}

# report_at_most KEY LIMIT: fails unless the JSON report's number KEY is <= LIMIT.
report_at_most() {
  local value
  value=$(sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p" out.txt | head -1)
  [ -n "$value" ] || fail "no $1 in the report"
  awk -v v="$value" -v limit="$2" 'BEGIN { exit !(v + 0 <= limit + 0) }' ||
    fail "$1 = $value, more than $2"
}

case "$case_name" in
  help)
    run 0 --help
    grep -q 'Usage: terratin build INPUT\.\.\. -o OUTPUT' out.txt || fail "no usage line"
    grep -q -- '--overwrite' out.txt || fail "options not listed"
    ;;
  version_matches_project)
    run 0 --version
    expected="terratin ${TERRATIN_EXPECTED_VERSION:?set by tests/cli/CMakeLists.txt}"
    [ "$(head -1 out.txt)" = "$expected" ] || fail "--version's first line is not '$expected'"
    # The libraries in use, as GDAL's programs name theirs: GDAL's own, as gdalinfo reports it.
    gdal=$(gdalinfo --version | sed -n 's/^GDAL \([0-9.]*\).*/\1/p')
    sed -n 2p out.txt | grep -q "^GDAL $gdal, PROJ [0-9.]*, GeographicLib [0-9.]*, SQLite [0-9.]*$" ||
      fail "--version's second line does not name GDAL $gdal, PROJ, GeographicLib and SQLite"
    ;;
  formats_listed)
    run 0 --formats
    for row in "gpkg .gpkg" "shp .shp" "fgb .fgb" "2dm .2dm" "ply .ply" "obj .obj" "landxml .xml .landxml"; do
      grep -Eq "^  ${row// / +} " out.txt || fail "--formats lacks '$row'"
    done
    [ "$(grep -c '^  ' out.txt)" = 7 ] || fail "--formats does not list 7 formats"
    # Every format listed is one --format takes.
    for name in $(sed -n 's/^  \([a-z0-9]*\) .*/\1/p' out.txt); do
      run 2 build "$sample" -o out.any --format "$name" --max-points 1
      grep -q "unknown output format" err.txt && fail "--format $name is refused"
    done
    ;;
  formats_match_the_readme)
    # The README's format table lists exactly what the format table does: names, extensions.
    readme=$(dirname "$(dirname "$sample")")/README.md
    run 0 --formats
    awk '/^  [a-z0-9]/ { line = $1; for (i = 2; i <= NF && $i ~ /^\./; ++i) line = line " " $i; print line }' \
      out.txt | sort >table.txt
    grep '^| `[a-z0-9]*` | `\.' "$readme" | awk -F'|' '{ gsub(/[`,]/, "", $2); gsub(/[`,]/, "", $3); print $2 $3 }' |
      sed 's/^ *//; s/  */ /g; s/ *$//' | sort >readme.txt
    [ "$(wc -l <table.txt)" = 7 ] || fail "--formats lists $(wc -l <table.txt) formats"
    diff table.txt readme.txt >formats.diff || fail "README's format table differs: $(cat formats.diff)"
    ;;
  gdal_style_single_dash_refused)
    # GDAL users type -of, -t_srs, -overwrite: read as -o f, each would name the output.
    for words in "-of GPKG" "-t_srs EPSG:3857" "-overwrite" "-ooverwrite.fgb"; do
      # shellcheck disable=SC2086 # the words are split on purpose
      run 2 build "$sample" -o tin.gpkg $words
      expect_one_error_line "an option of one dash is one letter"
    done
    run 2 build "$sample" -o tin.gpkg -of GPKG
    expect_one_error_line "did you mean '--format'"
    run 2 build "$sample" -o tin.gpkg -t_srs EPSG:3857
    expect_one_error_line "did you mean '--t_srs'"
    [ -z "$(ls -A)" ] || [ "$(ls -A | grep -v -e out.txt -e err.txt)" = "" ] || fail "files written: $(ls -A)"
    # A negative value after an option is a value, not an option.
    run 2 build "$sample" -o tin.ply --max-edge -5
    expect_one_error_line "--max-edge must be a positive number"
    ;;
  output_dash_refused)
    run 2 build "$sample" -o - --format ply
    expect_one_error_line "not standard output"
    [ ! -e ./- ] || fail "a file named '-' was written"
    ;;
  typo_gets_did_you_mean)
    run 2 build "$sample" -o tin.gpkg --max-eror 3
    expect_one_error_line "did you mean '--max-error'?"
    run 2 build "$sample" -o tin.gpkg --no-such-option
    grep -q "did you mean" err.txt && fail "a suggestion for a name far from every option"
    ;;
  contradicting_options_exit_2)
    run 2 build "$sample" -o tin.gpkg --max-error 3 --tile-size 0
    expect_one_error_line "--tile-size must be 2 to"
    run 2 build "$sample" --tiles-dir tiles --max-error 3 --tile-size 0
    expect_one_error_line "--tile-size must be 2 to"
    run 2 build "$sample" -o tin.gpkg --max-hole 3 --fill-holes
    expect_one_error_line "--max-hole and --fill-holes contradict each other"
    run 2 build "$sample" -o tin.gpkg --memory-limit 64M --edges
    expect_one_error_line "without --edges"
    run 2 build "$sample" -o tin.gpkg --memory-limit 64M --append-layer
    expect_one_error_line "not with --append-layer"
    run 2 build "$sample" -o tin.gpkg --z-factor 2 --max-error 1
    expect_one_error_line "does not combine with --z-factor"
    # Refused from the options alone: the layer file is never looked at.
    run 2 build "$sample" -o tin.gpkg --tile-size 64 --max-error 1 --breaklines absent.gpkg
    expect_one_error_line "does not combine with breaklines"
    [ ! -e tin.gpkg ] && [ ! -e tiles ] || fail "an output was written"
    ;;
  no_arguments)
    run 2
    expect_one_error_line
    ;;
  unknown_option)
    run 2 build "$sample" -o out.gpkg --no-such-option
    expect_one_error_line "no-such-option"
    [ ! -e out.gpkg ] || fail "output written despite usage error"
    ;;
  bad_format)
    run 2 build "$sample" -o out.gpkg --format KML
    expect_one_error_line "KML"
    ;;
  unknown_extension)
    run 2 build "$sample" -o out.kml
    expect_one_error_line "extension.*(or --format)"
    ;;
  build_gpkg_json)
    run 0 build "$sample" -o tin.gpkg --json --quiet --validate
    [ -s tin.gpkg ] || fail "no GeoPackage written"
    for key in '"timings"' '"read"' '"triangulate"' '"write"' '"counts"' '"points"' \
               '"duplicates"' '"triangles"' '"validated": true'; do
      grep -q -- "$key" out.txt || fail "JSON report lacks $key"
    done
    triangles=$(sed -n 's/.*"triangles": \([0-9]*\).*/\1/p' out.txt)
    [ "$(feature_count tin.gpkg)" = "$triangles" ] || fail "feature count differs from report"
    ogrinfo -ro -so -al tin.gpkg | grep -q 'Geometry: 3D Polygon' || fail "not Polygon Z"
    ogrinfo -ro -so -al tin.gpkg | grep -q 'EPSG.*32633\|UTM zone 33N' || fail "CRS missing"
    [ ! -s err.txt ] || fail "--quiet printed on stderr"
    expect_no_leftovers
    ;;
  parallel_methods)
    for method in sequential batch circumcircle strips auto; do
      run 0 build "$sample" -o "tin_$method.gpkg" --method "$method" --threads 2 --json --quiet --validate
      grep -q '"validated": true' out.txt || fail "$method: not validated"
      [ "$method" = auto ] || grep -q "\"method\": \"$method\"" out.txt || fail "$method not reported"
    done
    grep -q '"method": "strips"' out.txt || fail "auto did not choose strips"
    ;;
  random_order)
    run 0 build "$sample" -o tin.gpkg --order random --seed 7 --quiet --validate
    [ "$(feature_count tin.gpkg)" -gt 0 ] || fail "no TIN with --order random"
    run 2 build "$sample" -o other.gpkg --order sideways
    expect_one_error_line "order"
    for method in sequential batch circumcircle; do
      run 0 build "$sample" -o "walk_$method.gpkg" --locate walk --method "$method" -j 2 \
        --quiet --validate
      [ "$(feature_count "walk_$method.gpkg")" = "$(feature_count tin.gpkg)" ] ||
        fail "--locate walk --method $method: another triangle count"
    done
    run 2 build "$sample" -o jump.gpkg --locate jump
    expect_one_error_line "locate"
    ;;
  bad_method)
    run 2 build "$sample" -o out.gpkg --method quantum
    expect_one_error_line "method"
    ;;
  build_progress_and_summary)
    run 0 build "$sample" -o tin.gpkg
    grep -q '0\.\.\.10\.\.\.20\.\.\.30\.\.\.40\.\.\.50\.\.\.60\.\.\.70\.\.\.80\.\.\.90\.\.\.100 - done\.' err.txt ||
      fail "no GDAL-style progress on stderr"
    grep -q 'points.*duplicates.*triangles.*read .* s, triangulate .* s, write .* s' out.txt ||
      fail "no summary line"
    ;;
  build_shapefile)
    run 0 build "$sample" -o tin.shp --quiet
    for ext in shp shx dbf prj; do [ -s "tin.$ext" ] || fail "tin.$ext missing"; done
    [ "$(feature_count tin.shp)" -gt 0 ] || fail "empty shapefile"
    expect_no_leftovers
    ;;
  missing_input)
    run 1 build does_not_exist.tif -o out.gpkg --quiet
    expect_one_error_line "does_not_exist.tif"
    [ ! -e out.gpkg ] || fail "output written for a missing input"
    ;;
  not_a_raster)
    printf 'this is not a raster\n' >notes.txt
    run 1 build notes.txt -o out.gpkg --quiet
    expect_one_error_line "notes.txt"
    [ ! -e out.gpkg ] || fail "output written for a text input"
    expect_no_leftovers
    ;;
  all_nodata)
    gdal_create -q -of GTiff -outsize 20 10 -bands 1 -ot Float32 -burn -9999 -a_nodata -9999 \
      -a_srs EPSG:32633 -a_ullr 0 100 200 0 empty.tif || fail "gdal_create failed"
    run 1 build empty.tif -o out.gpkg --quiet
    expect_one_error_line "valid"
    [ ! -e out.gpkg ] || fail "output written for an all-nodata raster"
    ;;
  band_out_of_range)
    run 1 build "$sample" -o out.gpkg --band 3 --quiet
    expect_one_error_line "band"
    ;;
  missing_output_directory)
    run 1 build "$sample" -o no/such/dir/out.gpkg --quiet
    expect_one_error_line "no/such/dir"
    ;;
  unwritable_output_directory)
    if [ "$(id -u)" -eq 0 ]; then
      target=/proc/terratin-test.gpkg # even root cannot create files in /proc
    else
      mkdir locked && chmod 555 locked && target=locked/out.gpkg
    fi
    run 1 build "$sample" -o "$target" --quiet
    expect_one_error_line
    [ ! -e "$target" ] || fail "output written into an unwritable directory"
    ;;
  existing_output_refused)
    printf 'precious' >tin.gpkg
    run 1 build "$sample" -o tin.gpkg --quiet
    expect_one_error_line "exists; use --overwrite"
    [ "$(cat tin.gpkg)" = "precious" ] || fail "existing output was modified"
    expect_no_leftovers
    ;;
  existing_output_overwritten)
    printf 'old' >tin.gpkg
    run 0 build "$sample" -o tin.gpkg --overwrite --quiet
    [ "$(feature_count tin.gpkg)" -gt 0 ] || fail "output not replaced by a TIN"
    expect_no_leftovers
    ;;
  failed_run_keeps_existing_output)
    printf 'precious' >tin.gpkg
    run 1 build does_not_exist.tif -o tin.gpkg --overwrite --quiet
    [ "$(cat tin.gpkg)" = "precious" ] || fail "a failed run destroyed the existing output"
    ;;
  las_ground)
    need_shared pdal__autzen_trim.las
    run 0 build "$shared/pdal__autzen_trim.las" --class 2 -o autzen.gpkg --json --quiet --validate
    grep -q '"kind": "las"' out.txt || fail "input kind not reported"
    grep -q '"records": 110000' out.txt || fail "records not 110000"
    grep -q '"filtered_out": 83893' out.txt || fail "filtered-out count wrong"
    grep -q '"points": 26107' out.txt || fail "ground count not 26107"
    grep -q '"validated": true' out.txt || fail "not validated"
    ogrinfo -ro -so -al autzen.gpkg | grep -q 'Lambert' || fail "not in Oregon Lambert"
    ogrinfo -ro -so -al autzen.gpkg | grep -qi 'foot' || fail "not in feet"
    run 0 build "$shared/pdal__autzen_trim.las" --class 2 --class 1 --returns last -o last.gpkg
    grep -q 'input 1: .*pdal__autzen_trim.las (las, .*): 110000 records, .* filtered out, .* points, .* duplicates' out.txt ||
      fail "no per-input line in the human report"
    ;;
  text_pipe_with_s_srs)
    need_shared ncsu__lid_mr_pts.txt
    run 0 build "$shared/ncsu__lid_mr_pts.txt" --s_srs EPSG:3358 -o ncsu.gpkg --json --quiet
    grep -q '"kind": "text"' out.txt || fail "not read as text"
    grep -q '"points": 36944' out.txt || fail "not 36944 points"
    grep -q '"source_crs": {"name": "[^"]*", "code": "EPSG:3358"}' out.txt || fail "no source CRS"
    ogrinfo -ro -so -al ncsu.gpkg | grep -q 'EPSG.*3358' || fail "output not in EPSG:3358"
    ;;
  t_srs_web_mercator)
    small_sample
    run 0 build small.tif --t_srs EPSG:3857 -o merc.gpkg --json --quiet --validate
    grep -q '"target_crs": {"name": "WGS 84 / Pseudo-Mercator", "code": "EPSG:3857"}' out.txt ||
      fail "target CRS not reported"
    grep -q '"reprojected": true' out.txt || fail "not reprojected"
    ogrinfo -ro -so -al merc.gpkg | grep -q 'EPSG.*3857' || fail "output not in EPSG:3857"
    # Elevations untouched: the same highest z as the raster.
    zmax=$(gdalinfo -mm small.tif | sed -n 's/.*Computed Min\/Max=[^,]*,\([0-9.-]*\).*/\1/p')
    [ -n "$zmax" ] || fail "no raster maximum"
    ogrinfo -ro -q merc.gpkg -sql 'SELECT MAX(z_max) AS m FROM tin' | grep -q "m (Real) = ${zmax}" ||
      fail "z_max differs from the raster maximum $zmax"
    ;;
  mixed_inputs)
    small_sample
    printf '456003.12 5104000.47 1000\n456100.5 5103800.25 1100\n' >spots.xyz
    gdalsrsinfo -o wkt EPSG:32633 >spots.prj
    printf '%s\n' '{"type": "FeatureCollection", "features": [{"type": "Feature",' \
      '"properties": {"h": 950}, "geometry": {"type": "Point", "coordinates": [13.9, 46.08]}}]}' \
      >spot.geojson
    run 0 build small.tif spots.xyz spot.geojson --z-field h -o mixed.gpkg --json --quiet --validate
    [ "$(grep -o '"kind": "[a-z]*"' out.txt | tr '\n' ' ')" = '"kind": "raster" "kind": "text" "kind": "vector" ' ] ||
      fail "inputs not reported in order"
    grep -q '"points": 1603' out.txt || fail "not 1600 + 2 + 1 points"
    grep -q '"code": "EPSG:32633"}, "zone": ""' out.txt || fail "target is not the raster's CRS"
    ogrinfo -ro -so -al mixed.gpkg | grep -q 'EPSG.*32633' || fail "output not in EPSG:32633"
    ;;
  geographic_to_utm_notice)
    gdal_create -q -of GTiff -outsize 30 20 -bands 1 -ot Int16 -burn 100 -a_srs EPSG:4326 \
      -a_ullr -71.6 44.6 -71.5 44.5 geo.tif || fail "gdal_create failed"
    run 0 build geo.tif -o utm.gpkg
    grep -q 'terratin: notice: .*UTM zone 19N' err.txt || fail "no notice of the zone"
    grep -q 'CRS: WGS 84 \[EPSG:4326\] -> WGS 84 / UTM zone 19N \[EPSG:32619\] (UTM zone 19N' out.txt ||
      fail "zone not in the report"
    ogrinfo -ro -so -al utm.gpkg | grep -q 'EPSG.*32619' || fail "output not in EPSG:32619"
    run 0 build geo.tif -o deg.gpkg --keep-geographic --json --quiet
    [ ! -s err.txt ] || fail "--quiet printed on stderr"
    grep -q '"zone": ""' out.txt || fail "a zone was chosen despite --keep-geographic"
    ogrinfo -ro -so -al deg.gpkg | grep -q 'EPSG.*4326' || fail "output not in EPSG:4326"
    run 0 build geo.tif -o feet.gpkg --z-factor 3.28084 --json --quiet
    grep -q '"z_factor": 3.28084' out.txt || fail "z factor not reported"
    ogrinfo -ro -q feet.gpkg -sql 'SELECT MAX(z_max) AS m FROM tin' | grep -q 'm (Real) = 328.084' ||
      fail "z not scaled"
    ;;
  missing_crs)
    small_sample
    printf '456003 5104000 1000\n456100 5103800 1100\n' >spots.xyz
    run 1 build small.tif spots.xyz -o out.gpkg --quiet
    expect_one_error_line "spots.xyz.*--s_srs"
    [ ! -e out.gpkg ] || fail "output written without a CRS"
    run 1 build spots.xyz -o out.gpkg --t_srs EPSG:3857 --quiet
    expect_one_error_line "--s_srs"
    run 1 build small.tif -o out.gpkg --t_srs EPSG:999999 --quiet
    expect_one_error_line "--t_srs 'EPSG:999999'"
    ;;
  laz_builds_the_tin_of_its_las_twin)
    need_shared laz/lidr__Megaplot.laz
    need_shared laz/lasr__Megaplot.las
    run 0 build "$shared/laz/lidr__Megaplot.laz" -o laz.2dm --class 2 --returns last --quiet
    run 0 build "$shared/laz/lasr__Megaplot.las" -o las.2dm --class 2 --returns last --quiet
    cmp -s laz.2dm las.2dm || fail "the LAZ and its LAS twin gave different TINs"
    run 0 build "$shared/laz/lidr__Megaplot.laz" -o one.2dm --class 2 --returns last -j 1 --quiet
    cmp -s laz.2dm one.2dm || fail "one thread gave another TIN"
    # The layered compressor of LAS 1.4 point formats 6-10.
    need_shared laz/laspy__1_4_w_evlr.laz
    run 0 build "$shared/laz/laspy__1_4_w_evlr.laz" -o laz14.2dm --quiet
    run 0 build "$shared/laz/laspy__1_4_w_evlr.las" -o las14.2dm --quiet
    cmp -s laz14.2dm las14.2dm || fail "the layered LAZ and its LAS twin gave different TINs"
    # Merged with another input, and to a GeoPackage in the file's CRS.
    need_shared laz/lidr__MixedConifer.laz
    run 0 build "$shared/laz/lidr__Megaplot.laz" "$shared/laz/lidr__MixedConifer.laz" \
      -o merged.gpkg --class 2
    grep -q "input 2: .*lidr__MixedConifer.laz (laz, NAD83 / UTM zone 12N.*reprojected" out.txt ||
      fail "second LAZ input not reported with its CRS"
    [ -s merged.gpkg ] || fail "no GeoPackage from LAZ"
    ;;
  laz_broken_gives_one_error_line)
    need_shared laz/laszip__broken_version.laz
    run 1 build "$shared/laz/laszip__broken_version.laz" -o out.gpkg --quiet
    expect_one_error_line "laszip__broken_version.laz.*POINT10 version 6"
    [ ! -e out.gpkg ] || fail "output written for a broken LAZ"
    need_shared pdal__autzen_trim.las
    need_shared laz/pdal__autzen_trim.laz
    head -c 300000 "$shared/laz/pdal__autzen_trim.laz" >cut.laz
    run 1 build cut.laz -o out.gpkg --quiet
    expect_one_error_line "cut.laz"
    [ ! -e out.gpkg ] || fail "output written for a truncated LAZ"
    ;;
  truncated_las)
    need_shared pdal__autzen_trim.las
    head -c 100000 "$shared/pdal__autzen_trim.las" >cut.las
    run 1 build cut.las -o out.gpkg --quiet
    expect_one_error_line "truncated"
    head -c 200 "$shared/pdal__autzen_trim.las" >header.las
    run 1 build header.las -o out.gpkg --quiet
    expect_one_error_line "truncated"
    expect_no_leftovers
    ;;
  bad_point_cloud_options)
    run 2 build "$sample" -o out.gpkg --class ground
    expect_one_error_line "--class"
    run 2 build "$sample" -o out.gpkg --returns second
    expect_one_error_line "--returns"
    run 2 build "$sample" -o out.gpkg --columns 1,2
    expect_one_error_line "--columns"
    run 2 build "$sample" -o out.gpkg --z-factor 0
    expect_one_error_line "--z-factor"
    run 2 build "$sample" -o out.gpkg --keep-geographic --t_srs EPSG:3857
    expect_one_error_line "--keep-geographic"
    [ ! -e out.gpkg ] || fail "output written despite usage errors"
    # The readers' own refusals name the options as the command line does.
    printf '456003 5104000 100\n456100 5104100 101\n456200 5104000 99\n' >spots.xyz
    run 1 build spots.xyz -o out.gpkg --columns x,y,z
    expect_one_error_line "the columns named in --columns"
    printf '%s\n' '{"type": "FeatureCollection", "features": [{"type": "Feature",' \
      '"properties": {"h": 1}, "geometry": {"type": "Point", "coordinates": [1, 2]}}]}' >flat.geojson
    run 1 build flat.geojson -o out.gpkg
    expect_one_error_line "name the elevation attribute with --z-field"
    [ ! -e out.gpkg ] || fail "output written despite refused inputs"
    ;;
  refine_max_error)
    run 0 build "$sample" -o tin.gpkg --max-error 2 --json --quiet --validate --threads 2
    for key in '"refine"' '"achieved_max_error"' '"rmse"' '"stop": "error"' '"validated": true'; do
      grep -q -- "$key" out.txt || fail "JSON report lacks $key"
    done
    achieved=$(sed -n 's/.*"achieved_max_error": \([0-9.]*\).*/\1/p' out.txt)
    awk -v e="$achieved" 'BEGIN { exit !(e <= 2.0) }' || fail "achieved max error $achieved > 2"
    triangles=$(sed -n 's/.*"refine": {.*"triangles": \([0-9]*\).*/\1/p' out.txt)
    [ "$(feature_count tin.gpkg)" = "$triangles" ] || fail "feature count differs from report"
    full=$(sed -n 's/.*"raster_cells": \([0-9]*\).*/\1/p' out.txt)
    points=$(sed -n 's/.*"refine": {.*"points": \([0-9]*\).*/\1/p' out.txt)
    [ "$points" -lt "$full" ] || fail "no simplification: $points points of $full cells"
    ;;
  refine_summary_line)
    run 0 build "$sample" -o tin.gpkg --max-points 500
    grep -q '500 points' out.txt || fail "summary does not give the 500 points"
    grep -q 'max error' out.txt || fail "summary lacks the max error"
    grep -q 'RMSE' out.txt || fail "summary lacks the RMSE"
    grep -q 'CRS: .*EPSG:' out.txt || fail "summary lacks the raster's CRS"
    ;;
  refine_limits)
    run 0 build "$sample" -o tin.gpkg --max-error 0 --max-triangles 300 --json --quiet
    grep -q '"stop": "triangles"' out.txt || fail "the triangle limit did not stop the run"
    [ "$(feature_count tin.gpkg)" -le 300 ] || fail "more than 300 triangles"
    ;;
  refine_bad_values)
    run 2 build "$sample" -o tin.gpkg --max-error -1
    expect_one_error_line "max-error"
    run 2 build "$sample" -o tin.gpkg --max-edge 0
    expect_one_error_line "max-edge"
    [ ! -e tin.gpkg ] || fail "output written despite usage error"
    # Combinations the refiner cannot honour are refused, not silently ignored.
    run 1 build "$sample" "$sample" -o tin.gpkg --max-error 5 --quiet
    expect_one_error_line "one raster input"
    run 2 build "$sample" -o tin.gpkg --max-error 5 --z-factor 2 --quiet
    expect_one_error_line "z-factor"
    [ ! -e tin.gpkg ] || fail "output written despite a refused combination"
    ;;
  refine_tiles)
    # A simplified TIN built tile by tile, each tile exactly Delaunay (--validate),
    # within the bound over every cell, about as many points as untiled.
    run 0 build "$sample" -o whole.ply --max-error 0.5 --json --quiet
    whole=$(report_count vertices)
    run 0 build "$sample" -o tiles.gpkg --max-error 0.5 --tile-size 64 --validate --json --quiet
    report_at_most achieved_max_error 0.5
    tiled=$(report_count vertices)
    [ -n "$tiled" ] && [ "$tiled" -gt 0 ] || fail "no vertices reported"
    awk -v a="$tiled" -v b="$whole" 'BEGIN { exit !(a <= 1.05 * b) }' ||
      fail "$tiled vertices in tiles, against $whole untiled"
    [ "$(feature_count tiles.gpkg)" -gt 0 ] || fail "no triangles written"
    run 2 build "$sample" -o bad.gpkg --max-error 1 --tile-size 1
    expect_one_error_line "--tile-size must be 2 to"
    # Tiles without --max-error are full resolution: every valid cell a vertex.
    run 0 build "$sample" -o full.ply --tile-size 64 --validate --json --quiet
    valid=$(( $(report_count raster_cells) - $(report_count skipped_cells) ))
    [ "$(report_count vertices)" = "$valid" ] || fail "$(report_count vertices) vertices, $valid cells"
    run 2 build "$sample" -o bad.gpkg --tile-size 64 --max-points 1000 --quiet
    expect_one_error_line "point or triangle limit"
    # A point or triangle limit is shared among the tiles and holds for the whole TIN.
    run 0 build "$sample" -o limited.ply --max-error 0.5 --tile-size 64 --max-points 3000 \
      --json --quiet
    [ "$(report_count vertices)" -le 3000 ] || fail "$(report_count vertices) points, limit 3000"
    grep -q '"stop": "points"' out.txt || fail "the point limit did not stop the run"
    run 0 build "$sample" -o limited.ply --max-error 0.5 --tile-size 64 --max-triangles 5000 \
      --memory-limit 1G --json --quiet --overwrite
    [ "$(report_count triangles)" -le 5000 ] || fail "$(report_count triangles) triangles"
    run 1 build "$sample" -o bad.gpkg --max-error 0.01 --tile-size 16 --max-points 100 --quiet
    expect_one_error_line "sides alone take"
    # A rotated DEM's tiles are refined in its pixel frame: the north-up twin's triangles (the
    # same vertex numbers: each vertex a cell), put at the rotated cells' centres.
    rotated_sample rotated.tif
    run 0 build north_up.vrt -o upright.obj --max-error 1 --tile-size 16 --threads 1 --quiet
    run 0 build rotated.tif -o rotated.obj --max-error 1 --tile-size 16 --threads 1 --json --quiet
    report_at_most achieved_max_error 1
    [ "$(grep -c '^f ' rotated.obj)" -gt 100 ] || fail "too few triangles in rotated.obj"
    cmp -s <(grep '^f ' upright.obj) <(grep '^f ' rotated.obj) ||
      fail "the rotated DEM's tiles are not its north-up twin's triangles"
    run 0 build rotated.tif -o rotated.gpkg --max-error 1 --tile-size 16 --memory-limit 1G --quiet
    [ "$(feature_count_of rotated.gpkg tin)" = "$(grep -c '^f ' rotated.obj)" ] ||
      fail "the rotated DEM written tile by tile has another triangle count"
    check=$(sqlite3 rotated.gpkg "SELECT rtreecheck('rtree_tin_geom')")
    [ "$check" = ok ] || fail "rtreecheck of the rotated tiles: $check"
    # A geographic DEM (its corners without data) is refined in its UTM zone, each tile at its
    # cells' projected positions and constrained to a boundary through its sides' vertices
    # (--validate checks each tile constrained Delaunay and the join every shared edge): within
    # the bound, every valid cell covered, about as many points as untiled; streamed, the same
    # triangles; at full resolution every valid cell a vertex.
    gdalwarp -q -t_srs EPSG:4326 -dstnodata -9999 "$sample" geo.tif || fail "gdalwarp failed"
    run 0 build geo.tif -o geo_whole.ply --max-error 1 --json --quiet
    whole=$(report_count vertices)
    run 0 build geo.tif -o geo_tiles.obj --max-error 1 --tile-size 40 --threads 1 --validate \
      --json --quiet
    report_at_most achieved_max_error 1
    grep -q '"uncovered_cells": 0' out.txt || fail "geographic tiles left cells uncovered"
    grep -q '"reprojected": true' out.txt || fail "the geographic tiles were not reprojected"
    tiled=$(report_count vertices)
    awk -v a="$tiled" -v b="$whole" 'BEGIN { exit !(a <= 1.05 * b) }' ||
      fail "$tiled vertices in geographic tiles, against $whole untiled"
    run 0 build geo.tif -o geo_tiles.gpkg --max-error 1 --tile-size 40 --threads 1 \
      --memory-limit 1G --quiet
    [ "$(feature_count_of geo_tiles.gpkg tin)" = "$(grep -c '^f ' geo_tiles.obj)" ] ||
      fail "the geographic tiles streamed have another triangle count"
    check=$(sqlite3 geo_tiles.gpkg "SELECT rtreecheck('rtree_tin_geom')")
    [ "$check" = ok ] || fail "rtreecheck of the geographic tiles: $check"
    ogrinfo -ro -so geo_tiles.gpkg tin | grep -q 'UTM zone 33N' || fail "not in the UTM zone"
    run 0 build geo.tif -o geo_full.ply --tile-size 40 --validate --json --quiet
    valid=$(( $(report_count raster_cells) - $(report_count skipped_cells) ))
    [ "$(report_count vertices)" = "$valid" ] || fail "$(report_count vertices) vertices, $valid cells"
    expect_no_leftovers
    ;;
  tiles_dir)
    # --tiles-dir writes each tile's TIN as its own file and an index of footprints;
    # the tiles hold the joined TIN's triangles, no more, no fewer.
    run 0 build "$sample" -o joined.ply --max-error 0.5 --tile-size 64 --json --quiet
    joined=$(report_count triangles)
    run 0 build "$sample" --tiles-dir tiles -f ply --max-error 0.5 --tile-size 64 --json --quiet
    [ "$(report_count triangles)" = "$joined" ] || fail "the tiles hold other triangles"
    tiles=$(find tiles -name 'tile_*.ply' | wc -l)
    [ "$tiles" -gt 1 ] || fail "$tiles tile files"
    [ "$(feature_count_of tiles/tiles.gpkg tiles)" = "$tiles" ] || fail "the index is not the tiles"
    indexed=$(ogrinfo -ro tiles/tiles.gpkg -sql 'SELECT SUM(triangles) AS t FROM tiles' |
      sed -n 's/.*t (Integer[0-9]*) = //p')
    [ "$indexed" = "$joined" ] || fail "the index counts $indexed triangles, not $joined"
    ogrinfo -ro -so tiles/tiles.gpkg tiles | grep -q 'EPSG.*32633' || fail "index not in EPSG:32633"
    # A geographic DEM's tiles and their footprints lie in its UTM zone, not in degrees.
    gdalwarp -q -t_srs EPSG:4326 "$sample" geo.tif || fail "gdalwarp failed"
    run 0 build geo.tif --tiles-dir geo_tiles -f ply --max-error 1 --tile-size 128 --quiet
    ogrinfo -ro -so geo_tiles/tiles.gpkg tiles | grep -q 'UTM zone 33N' ||
      fail "the geographic tiles' index is not in the UTM zone"
    west=$(ogrinfo -ro -so geo_tiles/tiles.gpkg tiles | sed -n 's/^Extent: (\([0-9.-]*\),.*/\1/p')
    awk -v x="$west" 'BEGIN { exit !(x > 100000) }' || fail "footprints at x = $west, not in metres"
    # An existing tile is not replaced without --overwrite, and the run writes nothing.
    touch before_refusal
    run 1 build "$sample" --tiles-dir tiles -f ply --max-error 0.5 --tile-size 64 --quiet
    expect_one_error_line "overwrite"
    [ -z "$(find tiles -newer before_refusal)" ] || fail "a file was written despite the refusal"
    run 0 build "$sample" --tiles-dir tiles -f ply --max-error 0.5 --tile-size 64 --quiet --overwrite
    # --max-edge drops the same triangles from the tiles as from the joined TIN.
    run 0 build "$sample" -o joined.ply --max-error 0.5 --tile-size 64 --max-edge 100 --json \
      --quiet --overwrite
    joined=$(report_count triangles)
    run 0 build "$sample" --tiles-dir edges --max-error 0.5 --tile-size 64 --max-edge 100 --json \
      --quiet
    [ "$(report_count triangles)" = "$joined" ] || fail "--max-edge: other triangles in the tiles"
    run 2 build "$sample" --tiles-dir tiles -o x.ply --max-error 0.5 --tile-size 64
    expect_one_error_line "tiles-dir"
    run 2 build "$sample" --tiles-dir none --max-error 0.5 --quiet
    expect_one_error_line "tile-size"
    [ ! -e none ] || fail "a directory was made for a refused run"
    # Cancelled once the first tiles are written: every file and the directory it made go.
    need_shared gdalraster__lf_elev_220_mt_hood_utm.tif
    "$terratin" build "$shared/gdalraster__lf_elev_220_mt_hood_utm.tif" --tiles-dir cut \
      --max-error 0.1 --tile-size 32 --quiet >out.txt 2>err.txt &
    pid=$!
    for _ in $(seq 1 600); do
      [ -n "$(find cut -name 'tile_*' 2>/dev/null | head -1)" ] && break
      sleep 0.05
    done
    kill -INT "$pid"
    wait "$pid" && fail "the cancelled run succeeded"
    [ ! -e cut ] || fail "files of a cancelled run were left: $(ls cut | head -3)"
    expect_no_leftovers
    ;;
  memory_limit)
    # --memory-limit writes the TIN tile by tile into one file, the same TIN as joined
    # (one thread: a tile's triangles then come in one order).
    run 0 build "$sample" -o joined.ply --max-error 0.5 --tile-size 64 --threads 1 --quiet
    run 0 build "$sample" -o streamed.ply --max-error 0.5 --tile-size 64 --threads 1 \
      --memory-limit 1G --quiet
    cmp -s joined.ply streamed.ply || fail "the PLY written tile by tile is not the joined one"
    run 0 build "$sample" -o joined.gpkg --max-error 0.5 --tile-size 64 --threads 1 --nodes \
      --qgis-style --quiet
    run 0 build "$sample" -o streamed.gpkg --max-error 0.5 --tile-size 64 --threads 1 --nodes \
      --qgis-style --memory-limit 1G --quiet
    cmp -s joined.qml streamed.qml || fail "the style beside the GeoPackage is not the joined one"
    for layer in tin nodes; do
      rows="SELECT * FROM $layer ORDER BY fid"
      [ "$(sqlite3 joined.gpkg "$rows" | md5sum)" = "$(sqlite3 streamed.gpkg "$rows" | md5sum)" ] ||
        fail "the $layer rows written tile by tile are not the joined ones"
      check=$(sqlite3 streamed.gpkg "SELECT rtreecheck('rtree_${layer}_geom')")
      [ "$check" = ok ] || fail "rtreecheck of $layer: $check"
    done
    validator=/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py
    /usr/bin/python3 "$validator" streamed.gpkg >validate.txt 2>&1 ||
      fail "validate_gpkg.py: $(cat validate.txt)"
    # A Shapefile: the joined one's bytes; a FlatGeobuf: its features (the index orders them).
    mkdir joined streamed
    for kind in joined streamed; do
      limit=()
      [ "$kind" = streamed ] && limit=(--memory-limit 1G)
      run 0 build "$sample" -o "$kind/tin.shp" --max-error 0.5 --tile-size 64 --threads 1 \
        "${limit[@]}" --quiet
      run 0 build "$sample" -o "$kind/tin.fgb" --max-error 0.5 --tile-size 64 --threads 1 \
        "${limit[@]}" --quiet
    done
    for component in shp shx dbf prj cpg; do
      cmp -s "joined/tin.$component" "streamed/tin.$component" ||
        fail "the Shapefile's .$component written tile by tile is not the joined one"
    done
    features_of() { ogr2ogr -f CSV /vsistdout/ "$1" -lco GEOMETRY=AS_WKT | sort; }
    [ "$(features_of joined/tin.fgb | md5sum)" = "$(features_of streamed/tin.fgb | md5sum)" ] ||
      fail "the FlatGeobuf's features written tile by tile are not the joined ones"
    [ "$(features_of streamed/tin.fgb | wc -l)" -gt 100 ] || fail "too few FlatGeobuf features"
    # Without --tile-size the tiles are sized to the limit, and the run says how.
    run 0 build "$sample" -o sized.gpkg --max-error 0.5 --memory-limit 512M --json --quiet
    grep -q '"tiles of [0-9]* cells a side within --memory-limit"' out.txt ||
      fail "no notice of the tile size"
    # Bad values and what cannot be written tile by tile: one line, nothing written.
    for bad in 2X 0 -1G 1.5Q ""; do
      run 2 build "$sample" -o bad.gpkg --max-error 1 --memory-limit "$bad"
      expect_one_error_line "memory-limit"
    done
    run 1 build "$sample" -o bad.gpkg --max-error 1 --memory-limit 100M --quiet
    expect_one_error_line "or more"
    run 1 build "$sample" -o bad.gpkg --max-error 1 --memory-limit 200M --tile-size 4000 --quiet
    expect_one_error_line "tiles of 4000 cells need"
    # Without --max-error, full resolution, written tile by tile too.
    run 0 build "$sample" -o full_joined.ply --tile-size 64 --threads 1 --quiet
    run 0 build "$sample" -o full_streamed.ply --tile-size 64 --threads 1 --memory-limit 1G --quiet
    cmp -s full_joined.ply full_streamed.ply || fail "the full-resolution PLYs differ"
    run 2 build "$sample" -o bad.gpkg --max-error 1 --memory-limit 1G --edges --quiet
    expect_one_error_line "edges"
    # The mesh formats too (LandXML's date and time aside).
    for extension in 2dm obj xml; do
      run 0 build "$sample" -o "joined.$extension" --max-error 0.5 --tile-size 64 --threads 1 \
        --quiet
      run 0 build "$sample" -o "streamed.$extension" --max-error 0.5 --tile-size 64 --threads 1 \
        --memory-limit 1G --quiet
      undated() { sed 's/ date="[^"]*" time="[^"]*"//' "$1"; }
      cmp -s <(undated "joined.$extension") <(undated "streamed.$extension") ||
        fail "the .$extension written tile by tile is not the joined one"
    done
    printf '0 0 1\n1 0 2\n0 1 3\n' >points.xyz
    run 1 build points.xyz -o bad.gpkg --memory-limit 1G --quiet
    expect_one_error_line "takes a DEM raster"
    [ -z "$(ls bad.* 2>/dev/null)" ] || fail "output written despite an error"
    # An existing output stays as it was without --overwrite.
    cp streamed.ply before.ply
    run 1 build "$sample" -o streamed.ply --max-error 2 --memory-limit 1G --quiet
    expect_one_error_line "overwrite"
    cmp -s before.ply streamed.ply || fail "an existing output was changed"
    # Cancelled while tiles are being written: no output, no temporary left.
    need_shared gdalraster__lf_elev_220_mt_hood_utm.tif
    "$terratin" build "$shared/gdalraster__lf_elev_220_mt_hood_utm.tif" -o cut.gpkg \
      --max-error 0.1 --tile-size 32 --memory-limit 1G --quiet >out.txt 2>err.txt &
    pid=$!
    for _ in $(seq 1 600); do
      [ -n "$(find . -name '.cut*tmp*' 2>/dev/null | head -1)" ] && break
      sleep 0.05
    done
    sleep 0.5
    kill -INT "$pid"
    wait "$pid" && fail "the cancelled run succeeded"
    [ ! -e cut.gpkg ] || fail "a cancelled run left its output"
    expect_no_leftovers
    ;;
  mpi_tiles)
    # mpirun shares the tiles among ranks; rank 0 coordinates and writes. The TIN is
    # the one process's for 1 and 2 ranks that refine: the same vertices in the same order, the
    # same triangles (their order within a tile follows the threads a rank runs, as in one
    # process; mpirun may bind a rank to one core).
    command -v mpirun >/dev/null || { echo "skip [$case_name]: no mpirun"; exit 77; }
    mpi=(mpirun --allow-run-as-root --oversubscribe)
    cp "$sample" dem.tif
    # Each face's three vertex numbers in increasing order, the faces sorted (POSIX awk).
    triangles_of() {
      awk '$1 == "f" { a = $2 + 0; b = $3 + 0; c = $4 + 0
             if (a > b) { t = a; a = b; b = t }
             if (b > c) { t = b; b = c; c = t }
             if (a > b) { t = a; a = b; b = t }
             print a, b, c }' "$1" | sort
    }
    run 0 build dem.tif -o one.obj --max-error 0.5 --tile-size 40 --quiet
    # A geographic DEM's tiles too (refined at their cells' projected positions).
    gdalwarp -q -t_srs EPSG:4326 -dstnodata -9999 dem.tif geo.tif || fail "gdalwarp failed"
    run 0 build geo.tif -o geo_one.obj --max-error 0.5 --tile-size 60 --quiet
    "${mpi[@]}" -np 3 "$terratin" build geo.tif -o geo_ranks.obj --max-error 0.5 \
      --tile-size 60 --quiet >out.txt 2>err.txt || fail "mpirun on a geographic DEM failed"
    cmp -s <(grep '^v ' geo_one.obj) <(grep '^v ' geo_ranks.obj) ||
      fail "geographic: not the one process's vertices"
    cmp -s <(triangles_of geo_one.obj) <(triangles_of geo_ranks.obj) ||
      fail "geographic: not the one process's triangles"
    for ranks in 2 3; do
      "${mpi[@]}" -np "$ranks" "$terratin" build dem.tif -o "ranks$ranks.obj" --max-error 0.5 \
        --tile-size 40 --json --quiet >out.txt 2>err.txt || fail "mpirun -np $ranks failed"
      cmp -s <(grep '^v ' one.obj) <(grep '^v ' "ranks$ranks.obj") ||
        fail "-np $ranks: not the one process's vertices"
      cmp -s <(triangles_of one.obj) <(triangles_of "ranks$ranks.obj") ||
        fail "-np $ranks: not the one process's triangles"
      [ "$(grep -c '"input"' out.txt)" -eq 1 ] || fail "-np $ranks: not one report"
    done
    # With --memory-limit rank 0 writes the tiles as they come back: the one process's file,
    # simplified and at full resolution (one thread a rank: the triangles in one order).
    for target in "--max-error 0.5" ""; do
      # shellcheck disable=SC2086 # the target is zero or two words
      run 0 build dem.tif -o one.ply --tile-size 40 --memory-limit 1G --threads 1 $target \
        --overwrite --quiet
      # shellcheck disable=SC2086
      "${mpi[@]}" -np 3 "$terratin" build dem.tif -o ranks.ply --tile-size 40 --memory-limit 1G \
        --threads 1 $target --overwrite --quiet >out.txt 2>err.txt || fail "mpirun failed"
      cmp -s one.ply ranks.ply || fail "--memory-limit '$target': not the one process's file"
    done
    # Failures: one terratin line (mpirun adds its own notice after it), no output left.
    "${mpi[@]}" -np 3 "$terratin" build dem.tif -o bad.ply --max-error 0.5 --quiet \
      >out.txt 2>err.txt && fail "ranks without --tile-size succeeded"
    [ "$(grep -c '^terratin: ' err.txt)" -eq 1 ] || fail "not one error line"
    grep -q 'tile-size' err.txt || fail "the error does not name --tile-size"
    # A rank whose working directory lacks the DEM (no shared filesystem) fails the run.
    mkdir elsewhere
    "${mpi[@]}" -np 2 "$terratin" build dem.tif -o bad.ply --max-error 0.5 --tile-size 40 --quiet \
      : -np 1 -wdir "$work/elsewhere" "$terratin" build dem.tif -o bad.ply --max-error 0.5 \
      --tile-size 40 --quiet >out.txt 2>err.txt && fail "a failing rank did not fail the run"
    [ "$(grep -c '^terratin: ' err.txt)" -eq 1 ] || fail "not one error line for a failing rank"
    grep -q '^terratin: rank 2: .*dem.tif' err.txt || fail "the error does not name the rank"
    [ ! -e bad.ply ] || fail "output written despite a failure"
    expect_no_leftovers
    ;;
  refine_reprojected)
    # A geographic DEM is simplified in its UTM zone, --t_srs in the CRS asked for.
    small_sample
    gdalwarp -q -t_srs EPSG:4326 small.tif geo.tif || fail "gdalwarp failed"
    run 0 build geo.tif -o utm.gpkg --max-error 2 --validate
    grep -q 'terratin: notice: .*UTM zone 33N' err.txt || fail "no notice of the zone"
    run 0 build geo.tif -o utm.gpkg --max-error 2 --validate --json --quiet --overwrite
    report_at_most achieved_max_error 2
    ogrinfo -ro -so -al utm.gpkg | grep -q 'EPSG.*32633' || fail "output not in EPSG:32633"
    run 0 build geo.tif -o deg.gpkg --max-error 2 --keep-geographic --quiet
    ogrinfo -ro -so -al deg.gpkg | grep -q 'EPSG.*4326' || fail "output not in EPSG:4326"
    run 0 build small.tif -o merc.gpkg --max-error 2 --t_srs EPSG:3857 --json --quiet --validate
    grep -q '"reprojected": true' out.txt || fail "not reported as reprojected"
    ogrinfo -ro -so -al merc.gpkg | grep -q 'EPSG.*3857' || fail "output not in EPSG:3857"
    ;;
  refine_everest_done_when)
    # The issue's command (without the R-tree, to keep the suite short): holes over the
    # voids, every covered cell within 5 m, exactly Delaunay, in UTM zone 45N.
    need_shared osgearth__mt_everest_90m.tif
    run 0 build "$shared/osgearth__mt_everest_90m.tif" --max-error 5 -o everest.gpkg \
      --no-spatial-index --validate --json --quiet
    grep -q '"validated": true' out.txt || fail "not validated"
    grep -q '"code": "EPSG:32645"' out.txt || fail "not in UTM zone 45N"
    grep -q '"hole_triangles": [1-9]' out.txt || fail "no triangles dropped over the voids"
    report_at_most achieved_max_error 5
    [ "$(feature_count everest.gpkg)" = "$(report_count triangles)" ] || fail "feature count differs"
    ;;
  max_edge)
    run 0 build "$sample" -o all.gpkg --max-error 5 --json --quiet
    run 0 build "$sample" -o cut.gpkg --max-error 5 --max-edge 200 --json --quiet
    grep -q '"long_edge_triangles"' out.txt || fail "JSON report lacks long_edge_triangles"
    [ "$(feature_count cut.gpkg)" -lt "$(feature_count all.gpkg)" ] || fail "nothing dropped"
    ;;
  build_flatgeobuf)
    run 0 build "$sample" -o tin.fgb --json --quiet
    [ "$(feature_count tin.fgb)" = "$(report_count triangles)" ] || fail "feature count differs"
    ogrinfo -ro -so -al tin.fgb | grep -q 'Geometry: 3D Polygon' || fail "not Polygon Z"
    ogrinfo -ro -so -al tin.fgb | grep -q 'slope_pct: Real' || fail "attributes missing"
    grep -q '"format": "FlatGeobuf"' out.txt || fail "format not reported"
    grep -q '"features_per_second": [1-9]' out.txt || fail "no write rate in the report"
    expect_no_leftovers
    ;;
  build_2dm)
    run 0 build "$sample" -o tin.2dm --json --quiet
    head -1 tin.2dm | grep -qx 'MESH2D' || fail "no MESH2D header"
    [ "$(grep -c '^ND ' tin.2dm)" = "$(report_count vertices)" ] || fail "ND count differs"
    [ "$(grep -c '^E3T ' tin.2dm)" = "$(report_count triangles)" ] || fail "E3T count differs"
    expect_no_leftovers
    ;;
  build_ply)
    run 0 build "$sample" -o tin.ply --json --quiet
    head -c 400 tin.ply | grep -aq 'format binary_little_endian 1.0' || fail "not binary PLY"
    head -c 2000 tin.ply | grep -aq "element vertex $(report_count vertices)" || fail "vertex count"
    head -c 2000 tin.ply | grep -aq "element face $(report_count triangles)" || fail "face count"
    head -c 2000 tin.ply | grep -aq 'comment crs: PROJCS\["WGS 84 / UTM zone 33N"' || fail "no CRS comment"
    expect_no_leftovers
    ;;
  build_obj)
    run 0 build "$sample" -o tin.obj --json --quiet
    [ "$(grep -c '^v ' tin.obj)" = "$(report_count vertices)" ] || fail "v count differs"
    [ "$(grep -c '^f ' tin.obj)" = "$(report_count triangles)" ] || fail "f count differs"
    grep -q '^# terratin-origin ' tin.obj || fail "no local origin recorded"
    grep -q '^# CRS: .*EPSG:32633' tin.obj || fail "no CRS comment"
    ;;
  build_landxml)
    run 0 build "$sample" -o tin.xml --json --quiet
    xmllint --noout tin.xml || fail "not well-formed XML"
    ns='http://www.landxml.org/schema/LandXML-1.2'
    points=$(xmllint --xpath "count(//*[local-name()='P' and namespace-uri()='$ns'])" tin.xml)
    faces=$(xmllint --xpath "count(//*[local-name()='F' and namespace-uri()='$ns'])" tin.xml)
    [ "$points" = "$(report_count vertices)" ] || fail "P count $points"
    [ "$faces" = "$(report_count triangles)" ] || fail "F count $faces"
    xmllint --xpath "string(//*[local-name()='Definition']/@surfType)" tin.xml | grep -qx TIN ||
      fail "not a TIN surface"
    run 0 build "$sample" -o tin.landxml --format landxml --quiet
    xmllint --noout tin.landxml || fail "--format landxml not well-formed"
    ;;
  gpkg_nodes_and_edges)
    run 0 build "$sample" -o tin.gpkg --nodes --edges --no-spatial-index --json --quiet
    [ "$(feature_count_of tin.gpkg nodes)" = "$(report_count vertices)" ] || fail "nodes count"
    ogrinfo -ro -so tin.gpkg nodes | grep -q 'row: Integer64' || fail "nodes lack row"
    ogrinfo -ro -so tin.gpkg edges | grep -q 'Geometry: 3D Line String' || fail "edges not LineString Z"
    ogrinfo -ro -so tin.gpkg edges | grep -q 'tri_right: Integer64' || fail "edges lack triangles"
    # Every cell of the 320 x 240 sample is valid: row / col span the raster.
    ogrinfo -ro tin.gpkg -sql 'SELECT MIN(row), MAX(row), MIN(col), MAX(col) FROM nodes' |
      grep -q '= 239' || fail "row range"
    ;;
  append_layer)
    run 0 build "$sample" -o tin.gpkg --layer first --no-spatial-index --quiet
    before=$(ogrinfo -ro -al -q tin.gpkg first | md5sum)
    run 0 build "$sample" -o tin.gpkg --layer second --append-layer --no-spatial-index --quiet
    [ "$(ogrinfo -ro -q tin.gpkg | grep -c 'Polygon')" = 2 ] || fail "not two layers"
    [ "$(ogrinfo -ro -al -q tin.gpkg first | md5sum)" = "$before" ] || fail "first layer changed"
    run 1 build "$sample" -o tin.gpkg --layer second --append-layer --quiet
    expect_one_error_line "layer 'second'; choose another --layer or use --overwrite"
    run 2 build "$sample" -o tin.fgb --append-layer --quiet
    expect_one_error_line "--append-layer needs a GeoPackage"
    expect_no_leftovers
    ;;
  append_layer_keeps_another_users_file)
    # A GeoPackage this user may not write, in a world-writable directory without the sticky
    # bit: the append is refused and the file keeps its owner and bytes (it was replaced
    # before, because the directory let the rename through).
    [ "$(id -u)" -eq 0 ] && command -v setpriv >/dev/null || { echo "skip: needs root and setpriv"; exit 77; }
    chmod 0755 "$work"
    mkdir open_dir && chmod 0777 open_dir
    run 0 build "$sample" -o open_dir/tin.gpkg --no-spatial-index --quiet
    chmod 0644 open_dir/tin.gpkg
    before=$(md5sum <open_dir/tin.gpkg)
    setpriv --reuid=65534 --regid=65534 --clear-groups "$terratin" build "$sample" \
      -o open_dir/tin.gpkg --layer second --append-layer --quiet >out.txt 2>err.txt
    status=$?
    [ "$status" -eq 1 ] || fail "exit status $status, expected 1"
    expect_one_error_line "read-only for this user"
    [ "$(stat -c %u open_dir/tin.gpkg)" = 0 ] || fail "the file changed owner"
    [ "$(md5sum <open_dir/tin.gpkg)" = "$before" ] || fail "the file changed"
    [ "$(ls -A open_dir)" = tin.gpkg ] || fail "files left beside it: $(ls -A open_dir)"
    ;;
  huge_declared_raster_refused_before_allocating)
    # A VRT that declares 10^6 x 10^6 cells: the simplification refuses it from its size
    # alone, as the other paths do, before it allocates (ulimit: a regression fails, not swaps;
    # a sanitizer's shadow memory needs more address space than any limit leaves, and refuses
    # a 4 TB allocation itself).
    gdal_translate -q -of VRT "$sample" small.vrt || fail "gdal_translate failed"
    sed -e 's/rasterXSize="[0-9]*"/rasterXSize="1000000"/; s/rasterYSize="[0-9]*"/rasterYSize="1000000"/' \
      small.vrt >huge.vrt
    ldd "$terratin" | grep 'lib[at]san' >/dev/null || ulimit -v 8000000
    run 1 build huge.vrt -o tin.ply --max-error 1 --quiet
    expect_one_error_line "1000000 x 1000000 cells, more than one grid holds"
    [ ! -e tin.ply ] || fail "an output was written"
    ;;
  breaklines_layer_stored_without_crs)
    # A GeoPackage layer without CRS (srs_id 0, which GDAL reports as "Undefined geographic
    # SRS") is taken in the TIN's CRS with a notice, as a Shapefile without .prj is.
    roads=$(dirname "$sample")/roads.gpkg
    cp "$roads" roads.gpkg
    sqlite3 roads.gpkg "UPDATE gpkg_geometry_columns SET srs_id = 0; UPDATE gpkg_contents SET srs_id = 0" ||
      fail "sqlite3 failed"
    run 0 build "$sample" --breaklines roads.gpkg -o tin.ply
    grep -q "has no CRS: its coordinates are taken to be in the TIN's CRS" err.txt ||
      fail "no notice of the layer without CRS"
    ;;
  gpkg_validates)
    # GDAL's own GeoPackage validator and SQLite's rtreecheck on the fast writer's files: the
    # triangle, node and edge layers, and a layer appended to an existing file.
    validator=/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py
    [ -f "$validator" ] || fail "no $validator (Debian package python3-gdal)"
    run 0 build "$sample" -o tin.gpkg --nodes --edges --quiet
    run 0 build "$sample" -o tin.gpkg --layer refined --max-error 5 --append-layer --quiet
    /usr/bin/python3 "$validator" tin.gpkg >validate.txt 2>&1 || fail "validate_gpkg.py: $(cat validate.txt)"
    for layer in tin nodes edges refined; do
      check=$(sqlite3 tin.gpkg "SELECT rtreecheck('rtree_${layer}_geom')")
      [ "$check" = ok ] || fail "rtreecheck of $layer: $check"
    done
    ;;
  qgis_style)
    run 0 build "$sample" -o tin.gpkg --qgis-style --no-spatial-index --quiet
    [ -s tin.qml ] || fail "no tin.qml"
    xmllint --noout tin.qml || fail "tin.qml is not well-formed"
    grep -q 'attr="z_mean"' tin.qml || fail "style does not colour by z_mean"
    run 2 build "$sample" -o tin.ply --qgis-style --quiet
    expect_one_error_line "--qgis-style applies to GeoPackage"
    run 2 build "$sample" -o tin2.gpkg --qgis-style --attributes none --quiet
    expect_one_error_line "--qgis-style colours by z_mean: it needs --attributes basic or all"
    ;;
  attributes_basic)
    run 0 build "$sample" -o tin.gpkg --attributes basic --no-spatial-index --quiet
    ogrinfo -ro -so -al tin.gpkg | grep -q 'aspect_deg: Real' || fail "basic attribute missing"
    ! ogrinfo -ro -so -al tin.gpkg | grep -q 'slope_pct' || fail "an 'all' attribute was written"
    run 2 build "$sample" -o tin2.gpkg --attributes many
    expect_one_error_line "attributes"
    ;;
  geopackage_only_options_refused)
    run 2 build "$sample" -o tin.shp --nodes
    expect_one_error_line "--nodes needs a GeoPackage"
    run 2 build "$sample" -o tin.2dm --edges
    expect_one_error_line "--edges needs a GeoPackage"
    run 2 build "$sample" -o tin.ply --no-spatial-index
    expect_one_error_line "--no-spatial-index applies to GeoPackage and FlatGeobuf"
    [ ! -e tin.shp ] && [ ! -e tin.2dm ] && [ ! -e tin.ply ] ||
      fail "output written despite the usage error"
    ;;
  # Every count option bounded, refused with status 2 and one line before reading.
  queue_length_bounded)
    for value in -1 0 1048577 4294967295 18446744073709551617 9223372036854775809; do
      run 2 build "$sample" -o out.gpkg --method batch --queue-length "$value"
      expect_one_error_line "queue"
    done
    run 0 --help
    grep -q 'queue-length L.*' out.txt && grep -q '1 to 1048576' out.txt || fail "no bound in --help"
    [ ! -e out.gpkg ] || fail "output written despite usage errors"
    ;;
  searchers_bounded)
    for value in -1 1024 100000 4294967296; do
      run 2 build "$sample" -o out.gpkg --method batch --searchers "$value"
      expect_one_error_line "search"
    done
    run 0 --help
    grep -q '0 to 1023' out.txt || fail "no bound in --help"
    [ ! -e out.gpkg ] || fail "output written despite usage errors"
    ;;
  threads_bounded)
    for method in circumcircle strips batch; do
      for value in -1 1025 3000 100000; do
        run 2 build "$sample" -o out.gpkg --method "$method" --threads "$value"
        expect_one_error_line "thread"
      done
    done
    run 2 build "$sample" -o out.gpkg --max-error 1 -j 100000
    expect_one_error_line "thread"
    run 0 --help
    grep -q '0 to 1024' out.txt || fail "no bound in --help"
    [ ! -e out.gpkg ] || fail "output written despite usage errors"
    ;;
  invalid_values_refused)
    for option in '--threads -1' '--threads=-1' '--max-points -5' '--max-points 2' \
                  '--max-triangles -1' '--max-triangles 0' '--max-hole -3' '--max-hole 4294967292' \
                  '--searchers -1' '--queue-length 4294967295' '--seed -1' '--threads 1.5' \
                  '--max-points 99999999999999999999999'; do
      # shellcheck disable=SC2086
      run 2 build "$sample" -o out.gpkg $option
      expect_one_error_line "${option%%[ =]*}\|point\|triangle\|hole\|queue\|thread\|search"
    done
    for option in --t_srs --s_srs; do
      run 2 build "$sample" -o out.gpkg "$option" ''
      expect_one_error_line "$option"
      run 2 build "$sample" -o out.gpkg "$option" ' '
      expect_one_error_line "$option"
    done
    [ ! -e out.gpkg ] || fail "output written despite usage errors"
    ;;
  limits_hold_or_refused)
    # The sample's valid cells fill the raster: a hull of 4 corners, 2 triangles.
    run 1 build "$sample" -o out.gpkg --max-points 3 --quiet
    expect_one_error_line "4 corners"
    run 1 build "$sample" -o out.gpkg --max-triangles 1 --quiet
    expect_one_error_line "4 corners"
    [ ! -e out.gpkg ] || fail "output written for a limit below the hull"
    run 0 build "$sample" -o four.gpkg --max-points 4 --json --quiet
    report_at_most vertices 4
    run 0 build "$sample" -o two.gpkg --max-triangles 2 --json --quiet
    report_at_most triangles 2
    for limit in 5 6 7 50; do
      run 0 build "$sample" -o "p$limit.gpkg" --max-points "$limit" --json --quiet
      report_at_most vertices "$limit"
      run 0 build "$sample" -o "t$limit.gpkg" --max-triangles "$limit" --json --quiet
      report_at_most triangles "$limit"
    done
    run 0 --help
    grep -q 'corner count is refused' out.txt || fail "--help does not state the hull guarantee"
    ;;
  rotated_raster_simplified)
    rotated_sample rot.tif
    for limit in '--max-error 1' '--max-points 200' '--max-triangles 300'; do
      # shellcheck disable=SC2086
      run 0 build rot.tif -o out.gpkg $limit --validate --json --quiet --overwrite
      grep -q '"validated": true' out.txt || fail "$limit: not validated"
      grep -q '"uncovered_cells": 0' out.txt || fail "$limit: cells left uncovered"
    done
    report_at_most triangles 300
    run 0 build rot.tif -o points.gpkg --max-points 200 --json --quiet
    report_at_most vertices 200
    run 0 build rot.tif -o error.gpkg --max-error 1 --json --quiet
    report_at_most achieved_max_error 1
    ;;
  infinite_elevations_refused)
    gdal_create -q -of GTiff -outsize 20 10 -bands 1 -ot Float32 -burn inf -a_srs EPSG:32633 \
      -a_ullr 0 100 200 0 all_inf.tif || fail "gdal_create failed"
    small_sample
    gdal_create -q -of GTiff -outsize 1 1 -bands 1 -ot Float32 -burn inf inf_cell.tif ||
      fail "gdal_create failed"
    gdal_translate -q -of VRT small.tif one_inf.vrt || fail "gdal_translate failed"
    sed 's|</VRTRasterBand>|<SimpleSource><SourceFilename relativeToVRT="1">inf_cell.tif</SourceFilename><SourceBand>1</SourceBand><SrcRect xOff="0" yOff="0" xSize="1" ySize="1"/><DstRect xOff="5" yOff="7" xSize="1" ySize="1"/></SimpleSource></VRTRasterBand>|' \
      one_inf.vrt >one_inf_src.vrt
    gdal_translate -q one_inf_src.vrt one_inf.tif || fail "gdal_translate failed"
    for input in all_inf.tif one_inf.tif; do
      for limit in '--max-error 1' '--max-points 50' '--max-triangles 50'; do
        # shellcheck disable=SC2086
        run 1 build "$input" -o out.gpkg $limit --quiet
        expect_one_error_line "infinite elevation"
      done
      run 1 build "$input" -o out.gpkg --quiet # as the full-resolution path does
      expect_one_error_line "non-finite"
    done
    run 1 build one_inf.tif -o out.gpkg --max-error 1 --quiet
    grep -q 'row 7, column 5' err.txt || fail "the infinite cell is not named"
    [ ! -e out.gpkg ] || fail "output written for infinite elevations"
    ;;
  non_horizontal_crs_refused)
    small_sample
    for crs in EPSG:5703 EPSG:4978 '+proj=geocent +datum=WGS84'; do
      for option in --t_srs --s_srs; do
        run 1 build small.tif -o out.gpkg "$option" "$crs" --quiet
        expect_one_error_line "$option.*horizontal CRS"
        run 1 build small.tif -o out.gpkg "$option" "$crs" --max-error 1 --quiet
        expect_one_error_line "$option.*horizontal CRS"
      done
    done
    [ ! -e out.gpkg ] || fail "output written in a non-horizontal CRS"
    # A compound CRS brings its horizontal part (RD New + NAP height), a 3D geographic one too.
    run 0 build small.tif -o compound.2dm --t_srs EPSG:7415 --quiet
    run 0 build small.tif -o geographic3d.2dm --t_srs EPSG:4979 --quiet
    ;;
  layer_control_characters_refused)
    for format in obj 2dm ply xml gpkg shp fgb; do
      for name in "$(printf 'two\nlines')" "$(printf 'tab\there')" "$(printf 'cr\r')" \
                  "$(printf 'esc\033[31m')"; do
        run 2 build "$sample" -o "out.$format" --layer "$name"
        expect_one_error_line "layer name.*control character"
      done
      [ ! -e "out.$format" ] || fail "out.$format written despite the control character"
    done
    # Printable names, spaces and UTF-8 included, still work.
    run 0 build "$sample" -o tin.obj --layer 'Mt Hood – 1 m' --quiet
    [ "$(grep -c '^v ' tin.obj)" -gt 0 ] || fail "no vertices written"
    ;;
  rotated_slivers_have_sane_attributes)
    # The exact hull of the rotated centres keeps border slivers (area ~1e-10 m2); their
    # slope is 0 and aspect -1, not the 1e15 % the rounding made, and areas sum to the hull's
    # (39 x 39 cells of 10 m: 152100 m2).
    rotated_sample rot.tif
    run 0 build rot.tif -o full.gpkg --validate --quiet
    ogrinfo -ro -q full.gpkg -sql 'SELECT MAX(slope_pct) AS m FROM tin' >sql.txt
    max=$(sed -n 's/.*m (Real) = //p' sql.txt)
    awk -v m="$max" 'BEGIN { exit !(m + 0 < 1000) }' || fail "max slope_pct $max"
    ogrinfo -ro -q full.gpkg -sql 'SELECT SUM(area_2d) AS s FROM tin' >sql.txt
    sum=$(sed -n 's/.*s (Real) = //p' sql.txt)
    awk -v s="$sum" 'BEGIN { exit !(s > 152099.999 && s < 152100.001) }' || fail "area sum $sum"
    ogrinfo -ro -q full.gpkg -sql 'SELECT COUNT(*) AS n FROM tin WHERE area_2d < 1e-3' >sql.txt
    slivers=$(sed -n 's/.*n (Integer) = //p' sql.txt)
    ogrinfo -ro -q full.gpkg -sql \
      'SELECT COUNT(*) AS n FROM tin WHERE area_2d < 1e-3 AND slope_deg = 0 AND aspect_deg = -1' >sql.txt
    [ "$(sed -n 's/.*n (Integer) = //p' sql.txt)" = "$slivers" ] || fail "a sliver has a slope"
    ;;
  # Regression cases of an audit of hostile input, named d<N>_ after its defects.
  out_of_memory)
    # A segfault inside GDAL's RasterIO under an address-space limit; now one line. Around
    # 200 MB the limit falls in the raster read; the others land before or after it.
    need_shared gdalraster__lf_elev_220_mt_hood_utm.tif
    ldd "$terratin" | grep 'lib[at]san' >/dev/null && { echo "skip [$case_name]: sanitizer build"; exit 77; }
    for limit in 190000 200000 205000 210000 230000; do
      for extra in "" "--max-error 1"; do
        # shellcheck disable=SC2086
        (ulimit -v "$limit" && exec "$terratin" build "$shared/gdalraster__lf_elev_220_mt_hood_utm.tif" \
          -o "hood$limit.gpkg" --quiet $extra) >out.txt 2>err.txt
        status=$?
        grep -q 'error while loading shared libraries' err.txt && continue
        [ "$status" -le 1 ] || fail "exit status $status under ulimit -v $limit $extra"
        if [ "$status" -eq 1 ]; then
          expect_one_error_line "out of memory"
        fi
      done
    done
    expect_no_leftovers
    ;;
  subdataset_input)
    gdal_translate -q -srcwin 0 0 30 20 "$sample" a.tif || fail "gdal_translate failed"
    gdal_translate -q -srcwin 30 30 20 30 "$sample" b.tif || fail "gdal_translate failed"
    gdal_translate -q -of GPKG a.tif two.gpkg -co RASTER_TABLE=a || fail "no GeoPackage"
    gdal_translate -q -of GPKG b.tif two.gpkg -co RASTER_TABLE=b -co APPEND_SUBDATASET=YES ||
      fail "no second raster"
    run 1 build two.gpkg -o tin.gpkg --quiet
    expect_one_error_line "GPKG:two.gpkg:b"
    # The name the error advises works, at full resolution and simplified.
    advised=$(grep -o "'GPKG:two.gpkg:b'" err.txt | tr -d "'")
    run 0 build "$advised" -o tin.gpkg --quiet --json
    [ "$(report_count vertices)" -eq 600 ] || fail "not the 20 x 30 cells of raster b"
    run 0 build GPKG:two.gpkg:a -o tin2.gpkg --quiet --max-error 1
    run 1 build GPKG:two.gpkg:nothere -o tin3.gpkg --quiet
    expect_one_error_line "nothere"
    ;;
  number_format)
    printf '1e300 2 3\n4 5 6\n1 9 3\n' >huge.xyz
    run 1 build huge.xyz -o tin.ply --quiet
    expect_one_error_line "(1e+300, 2)"
    [ "$(wc -c <err.txt)" -lt 300 ] || fail "a 300-digit number"
    printf '5e-324 -5e-324 3\n4 5 6\n1 9 3\n' >tiny.xyz
    run 1 build tiny.xyz -o tin.ply --quiet
    expect_one_error_line "(5e-324, -5e-324)"
    ;;
  not_a_directory)
    : >plain_file
    run 1 build "$sample" -o plain_file/tin.gpkg --quiet
    expect_one_error_line "'plain_file' is not a directory"
    ;;
  symlink_loop)
    ln -s loop loop
    run 1 build loop -o tin.gpkg --quiet
    expect_one_error_line "too many levels of symbolic links"
    run 1 build "$sample" -o loop/tin.gpkg --quiet
    expect_one_error_line "too many levels of symbolic links"
    ;;
  las_point_format_99)
    need_shared pdal__autzen_trim.las
    cp "$shared/pdal__autzen_trim.las" odd.las && chmod u+w odd.las
    printf '\143' | dd of=odd.las bs=1 seek=104 conv=notrunc status=none
    run 1 build odd.las -o tin.gpkg --quiet
    expect_one_error_line "point data record format 99 is not supported"
    ! grep -q LAZ err.txt || fail "reported as LAZ"
    ;;
  las_garbage_wkt_gives_one_error_line)
    # A LAS 1.4 file whose WKT record holds no WKT: terratin's line alone, without GDAL's own
    # "ERROR 1: ..." line before it.
    need_shared pdal__test1_4.las
    cp "$shared/pdal__test1_4.las" bad_wkt.las && chmod u+w bad_wkt.las
    # The LASF_Projection record 2112 of that file: 911 bytes of WKT from byte 429.
    { printf 'garbage'; head -c 904 /dev/zero; } | dd of=bad_wkt.las bs=1 seek=429 conv=notrunc status=none
    run 1 build bad_wkt.las -o tin.gpkg --quiet
    expect_one_error_line "WKT CRS record cannot be read"
    ;;
  gpkg_disk_full)
    # A GeoPackage on a full disk said "no such table: gpkg_geometry_columns". Needs a small
    # tmpfs, so root; Mt Hood's TIN takes 64 KiB pages, which a 400 KiB disk cannot hold.
    need_shared gdalraster__lf_elev_220_mt_hood_utm.tif
    mkdir full
    mount -t tmpfs -o size=400k tmpfs full 2>/dev/null || { echo "skip [$case_name]: cannot mount a tmpfs"; exit 77; }
    trap 'umount "$work/full"; rm -rf "$work"' EXIT
    run 1 build "$shared/gdalraster__lf_elev_220_mt_hood_utm.tif" -o full/hood.gpkg --quiet
    expect_one_error_line "disk is full"
    [ -z "$(ls -A full)" ] || fail "left in the full directory: $(ls -A full)"
    ;;
  newline_in_message)
    cp "$sample" "$(printf 'two\nlines.tif')"
    run 1 build "$(printf 'two\nlines.tif')" -o tin.gpkg --quiet --band 9
    expect_one_error_line "two lines.tif"
    ;;
  unusable_geotransform)
    small_sample
    cp small.tif nan.tif && gdal_edit.py -a_ullr nan 0 1 1 nan.tif 2>/dev/null
    run 1 build nan.tif -o tin.gpkg --quiet
    expect_one_error_line "geotransform"
    ! grep -q collinear err.txt || fail "reported as collinear"
    cp small.tif huge.tif && gdal_edit.py -a_ullr 0 1e300 1e300 0 huge.tif
    run 1 build huge.tif -o tin.gpkg --quiet --max-error 1
    expect_one_error_line "geotransform"
    ;;
  utf8_bom)
    printf '\357\273\277x,y,z\r\n1,2,3\r\n4,5,6\r\n1,9,3\r\n' >bom.csv
    run 0 build bom.csv -o tin.ply --quiet
    printf '\357\273\2771 2 3\n4 5 6\n1 9 3\n' >bom.xyz
    run 0 build bom.xyz -o tin2.ply --quiet
    ;;
  missing_prj)
    printf '1 2 3\n4 5 6\n1 9 3\n' >points.xyz
    run 1 build points.xyz --s_srs nothere.prj -o tin.ply --quiet
    expect_one_error_line "no such file"
    ! grep -q "not a CRS PROJ knows" err.txt || fail "reported as an unknown CRS"
    ;;
  ascii_pgm)
    printf 'P2\n# plain PGM\n4 3\n255\n0 1 2 3\n10 11 12 13\n20 21 22 255\n' >small.pgm
    run 0 build small.pgm -o tin.gpkg --quiet --json
    [ "$(report_count vertices)" -eq 12 ] || fail "not 12 vertices"
    need_shared pyterra__crater.pgm
    run 0 build "$shared/pyterra__crater.pgm" -o crater.gpkg --quiet --max-error 2
    ;;
  unknown_gdal_error)
    # Causes GDAL knows but did not record: "unknown GDAL error" before.
    mkdir empty_dir
    head -c 3000 /dev/zero >binary.bin
    for input in empty_dir binary.bin; do
      run 1 build "$input" -o tin.gpkg --quiet
      expect_one_error_line "not recognized as a supported file format"
      ! grep -q "unknown GDAL error" err.txt || fail "unknown GDAL error for $input"
    done
    run 1 build "$sample" --s_srs garbage -o tin.gpkg --quiet
    ! grep -q "unknown GDAL error" err.txt || fail "unknown GDAL error for --s_srs garbage"
    ;;
  breaklines)
    # A breakline layer through the command line; its segment is an edge of the TIN.
    printf 'WKT;id\n"LINESTRING (455501.3 5104003.7, 456700.9 5103100.2)";1\n' >lines.csv
    ogr2ogr -q -f GPKG lines.gpkg lines.csv -oo GEOM_POSSIBLE_NAMES=WKT -a_srs EPSG:32633 \
      -nlt LINESTRING -nln roads || fail "ogr2ogr failed"
    run 0 build "$sample" --breaklines "lines.gpkg|layername=roads" --breakline-z surface \
      -o tin.gpkg --validate --json --quiet
    grep -q '"validated": true' out.txt || fail "not validated"
    grep -q '"breaklines": 1' out.txt || fail "no breakline in the report"
    [ "$(report_count added_vertices)" -eq 2 ] || fail "not 2 added vertices"
    run 1 build "$sample" --breaklines lines.gpkg --breakline-z line -o tin2.gpkg --quiet
    expect_one_error_line "--breakline-z line"
    run 2 build "$sample" --breaklines lines.gpkg --breakline-z sky -o tin3.gpkg --quiet
    expect_one_error_line "--breakline-z"
    # Simplified: the cells still over the bound after the breakline went in are inserted.
    run 0 build "$sample" --breaklines lines.gpkg --max-error 1 -o tin4.gpkg --quiet --json \
      --validate
    grep -q '"validated": true' out.txt || fail "simplified: not validated"
    [ "$(report_count check_passes)" -ge 1 ] || fail "simplified: no check pass"
    # Clip and erase areas; a line layer is not one.
    run 1 build "$sample" --clip lines.gpkg -o tin5.gpkg --quiet
    expect_one_error_line "not a Polygon"
    printf 'WKT;id\n"POLYGON ((455600.5 5103000.25,457200.75 5102800.5,456500.5 5104700.25,455600.5 5103000.25))";1\n' >area.csv
    ogr2ogr -q -f GPKG area.gpkg area.csv -oo GEOM_POSSIBLE_NAMES=WKT -a_srs EPSG:32633 \
      -nlt POLYGON || fail "ogr2ogr failed"
    run 1 build "$sample" --clip area.gpkg --erase area.gpkg -o tin6.gpkg --quiet
    expect_one_error_line "no triangle is left"
    [ ! -e tin6.gpkg ] || fail "an output written with no triangle"
    run 0 build "$sample" --erase area.gpkg -o tin7.gpkg --quiet --json
    [ "$(report_count area_triangles)" -gt 0 ] || fail "nothing erased"
    # A replace polygon (a lake) flattened to its field's level.
    printf 'WKT;level\n"POLYGON ((456100.5 5103300.25,457000.75 5103150.5,456600.5 5104400.25,456100.5 5103300.25))";812.5\n' >lake.csv
    ogr2ogr -q -f GPKG lake.gpkg lake.csv -oo GEOM_POSSIBLE_NAMES=WKT -oo AUTODETECT_TYPE=YES \
      -a_srs EPSG:32633 -nlt POLYGON || fail "ogr2ogr failed"
    run 0 build "$sample" --replace lake.gpkg --replace-z-field level -o tin8.gpkg --quiet --json
    [ "$(report_count replaced_points)" -gt 100 ] || fail "no point replaced"
    [ "$(report_count replace_polygons)" -eq 1 ] || fail "not 1 replace polygon"
    run 1 build "$sample" --replace lake.gpkg --replace-z-field depth -o tin9.gpkg --quiet
    expect_one_error_line "no field 'depth'"
    run 2 build "$sample" --replace-z-field level -o tin10.gpkg --quiet
    expect_one_error_line "--replace-z-field names the field of --replace polygons"
    # A layer whose CRS does not fit its coordinates: the error names the layer.
    ogr2ogr -q -f GPKG wrong_crs.gpkg lines.csv -oo GEOM_POSSIBLE_NAMES=WKT -a_srs EPSG:4326 \
      -nlt LINESTRING || fail "ogr2ogr failed"
    run 1 build "$sample" --breaklines wrong_crs.gpkg -o tin11.gpkg --quiet
    expect_one_error_line "--breaklines 'wrong_crs.gpkg' layer 'lines': CRS:"
    [ ! -e tin2.gpkg ] && [ ! -e tin5.gpkg ] && [ ! -e tin9.gpkg ] && [ ! -e tin11.gpkg ] &&
      [ ! -e tin10.gpkg ] || fail "an output written after an error"
    ;;
  mpi_lost_rank_leaves_no_temporary)
    # A rank killed (kill -9), or the run interrupted (SIGINT to mpirun) while a rank is stopped:
    # mpirun ends the others with SIGTERM. Rank 0 must leave off waiting for the lost rank's
    # tile, remove its temporary GeoPackage and say why in one line of its own.
    command -v mpirun >/dev/null || { echo "skip [$case_name]: no mpirun"; exit 77; }
    need_shared gdalraster__lf_elev_220_mt_hood_utm.tif
    mpi=(mpirun --allow-run-as-root --oversubscribe)
    # rank_pid LAUNCHER RANK: the pid of rank RANK among the launcher's children.
    rank_pid() {
      local child
      for child in $(ps -o pid= --ppid "$1"); do
        tr '\0' '\n' <"/proc/$child/environ" 2>/dev/null |
          grep -qx "OMPI_COMM_WORLD_RANK=$2" && { echo "$child"; return 0; }
      done
      return 1
    }
    for how in kill interrupt; do
      mkdir "$how" && cd "$how" || fail "cannot make $how"
      "${mpi[@]}" -np 3 "$terratin" build "$shared/gdalraster__lf_elev_220_mt_hood_utm.tif" \
        --max-error 0.5 --memory-limit 256M --tile-size 64 -o out.gpkg --quiet >out.txt 2>err.txt &
      launcher=$!
      # Rank 0 makes its temporary once every rank has started; the tiles take seconds more.
      # They are small, so that rank 0 writes each in far less than the second mpirun leaves
      # between SIGTERM and SIGKILL.
      for _ in $(seq 600); do
        compgen -G '.out.tmp-*' >/dev/null || ! kill -0 "$launcher" 2>/dev/null && break
        sleep 0.05
      done
      compgen -G '.out.tmp-*' >/dev/null || fail "$how: rank 0 made no temporary"
      worker=$(rank_pid "$launcher" 1) || fail "$how: no rank 1 among the launcher's children"
      if [ "$how" = kill ]; then
        kill -KILL "$worker"
      else
        kill -STOP "$worker"
        kill -INT "$launcher"
      fi
      for _ in $(seq 600); do
        kill -0 "$launcher" 2>/dev/null || break
        sleep 0.05
      done
      if kill -0 "$launcher" 2>/dev/null; then
        for child in $(ps -o pid= --ppid "$launcher"); do kill -KILL "$child"; done
        kill -KILL "$launcher"
        fail "$how: mpirun did not end"
      fi
      wait "$launcher" && fail "$how: the run succeeded"
      [ "$(grep -c '^terratin: ' err.txt)" -eq 1 ] || fail "$how: not one terratin line"
      grep -Eq '^terratin: .*(stopped|lost)' err.txt || fail "$how: the line does not say why"
      [ ! -e out.gpkg ] || fail "$how: output written"
      expect_no_leftovers
      cd ..
    done
    ;;
  layer_not_utf8_refused)
    # A layer name that is not UTF-8 (Latin-1, as a script may pass it) would be a GeoPackage
    # table name no reader can show and LandXML that is not well-formed: refused before anything
    # is written, naming the byte. A UTF-8 name of the same word works.
    small_sample
    for format in xml gpkg obj; do
      run 2 build small.tif -o "out.$format" --layer "$(printf 'caf\351')"
      expect_one_error_line "layer name is not valid UTF-8 (0xE9 at byte 4)"
      [ ! -e "out.$format" ] || fail "out.$format written despite the name"
    done
    expect_no_leftovers
    run 0 build small.tif -o tin.xml --layer "$(printf 'caf\303\251')" --quiet
    xmllint --noout tin.xml || fail "not well-formed XML with a UTF-8 name"
    run 0 build small.tif -o tin.gpkg --layer "$(printf 'caf\303\251')" --quiet
    ogrinfo -ro -q tin.gpkg "$(printf 'caf\303\251')" >/dev/null ||
      fail "no layer of the UTF-8 name"
    ;;
  *)
    fail "unknown case"
    ;;
esac
echo "ok [$case_name]"
