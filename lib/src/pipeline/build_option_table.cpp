#include "terratin/pipeline/build_option_table.hpp"

#include "terratin/error.hpp"
#include "terratin/io/tin_format.hpp"
#include "../text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <system_error>
#include <utility>

namespace terratin {

using terratin::detail::lowercase;

namespace {

[[noreturn]] void refuse(const std::string& message) {
    throw InvalidInputError(message);
}

// The message Boost.Program_options gave for a number it could not read, kept for both spellings.
[[noreturn]] void refuseNumberText(const std::string& text, const std::string& name) {
    refuse("the argument ('" + text + "') for option '" + name + "' is invalid");
}

// std::from_chars over the whole text; a leading '+' is accepted, as the command line always did.
template <class Number> bool readWhole(std::string_view text, Number& number) {
    if (text.size() > 1 && text.front() == '+' && text[1] != '-')
        text.remove_prefix(1);
    const char* end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, number);
    return !text.empty() && error == std::errc() && ptr == end;
}

double parseNumber(const std::string& text, const std::string& name) {
    double number = 0.0;
    if (!readWhole(text, number))
        refuseNumberText(text, name);
    return number;
}

// Digits only: "-1" is refused, never wrapped to 2^64 - 1. Ranges are checkBuildOptions'.
template <class Count> Count parseCount(const std::string& text, const std::string& name) {
    Count count{};
    const char* end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, count);
    if (error == std::errc::result_out_of_range)
        refuse(name + " is too large (got '" + text + "')");
    if (text.empty() || error != std::errc() || ptr != end)
        refuse(name + " takes a whole number without sign (got '" + text + "')");
    return count;
}

// "2G", "512M", "1.5GiB", "1000000": a number of bytes with K, M, G or T, powers of 1024.
std::uint64_t parseByteSize(const std::string& text, const std::string& name) {
    const auto refuseSize = [&] {
        refuse(name + " takes a size such as 2G or 512M (got '" + text + "')");
    };
    const std::size_t unitAt = std::min(text.find_first_not_of("0123456789.+eE"), text.size());
    std::string unit = lowercase(text.substr(unitAt));
    if (unit.size() > 1 && unit.back() == 'b')
        unit.pop_back(); // "GB", "GiB"
    if (unit.size() == 2 && unit.back() == 'i')
        unit.pop_back();
    double power = 0.0;
    if (!unit.empty()) {
        const std::size_t at = std::string_view("kmgt").find(unit);
        if (unit.size() != 1 || at == std::string_view::npos)
            refuseSize();
        power = static_cast<double>(at + 1);
    }
    double number = 0.0;
    if (!readWhole(std::string_view(text).substr(0, unitAt), number))
        refuseSize();
    const double bytes = number * std::pow(1024.0, power);
    if (!(bytes >= 1.0) || bytes > 0x1p62)
        refuseSize();
    return static_cast<std::uint64_t>(bytes);
}

bool parseFlag(const std::string& text, const std::string& name) {
    const std::string key = lowercase(text);
    if (key == "true")
        return true;
    if (key == "false")
        return false;
    refuse(name + " takes true or false (got '" + text + "')");
}

// "a, b or c".
std::string alternatives(const std::vector<std::string_view>& names) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
        list += std::string(i == 0                  ? ""
                            : i + 1 == names.size() ? " or "
                                                    : ", ") +
                std::string(names[i]);
    return list;
}

// One of `choices` by name, case-insensitively.
template <class Value>
Value parseChoice(const std::string& text, const std::string& name,
                  std::initializer_list<std::pair<std::string_view, Value>> choices) {
    const std::string key = lowercase(text);
    std::vector<std::string_view> names;
    for (const auto& [choiceName, value] : choices) {
        if (key == choiceName)
            return value;
        names.push_back(choiceName);
    }
    refuse(name + " must be " + alternatives(names) + " (got '" + text + "')");
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    std::string item;
    std::istringstream stream(text);
    while (std::getline(stream, item, ','))
        items.push_back(item);
    if (!text.empty() && text.back() == ',')
        items.emplace_back();
    return items;
}

// A CRS given as an empty (or blank) string would mean "no CRS" to the library, which is not
// what a caller naming the option asks for.
std::string parseCrs(const std::string& text, const std::string& name) {
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        refuse(name + " needs a CRS (EPSG:n, WKT, PROJ string, .prj file), not an empty string");
    return text;
}

RefineOptions& refineOf(BuildOptions& options) {
    if (!options.refine)
        options.refine.emplace();
    return *options.refine;
}

void applyClasses(BuildOptions& options, const std::string& text, const std::string& name) {
    for (const std::string& item : splitList(text)) {
        int code = -1;
        const char* end = item.data() + item.size();
        const auto [ptr, error] = std::from_chars(item.data(), end, code);
        if (item.empty() || error != std::errc() || ptr != end || code < 0 || code > 255)
            refuse(name + " takes classification codes 0..255 (got '" + item + "')");
        options.lasClasses.push_back(code);
    }
}

void applyColumns(BuildOptions& options, const std::string& text, const std::string& name) {
    std::vector<std::string> columns = splitList(text);
    if (columns.size() != 3 ||
        std::any_of(columns.begin(), columns.end(),
                    [](const std::string& column) { return column.empty(); }))
        refuse(name + " takes three columns x,y,z (got '" + text + "')");
    if (std::find(columns.begin(), columns.end(), "0") != columns.end())
        refuse(name + ": columns are numbered from 1");
    options.textColumns = std::move(columns);
}

void applyMethod(BuildOptions& options, const std::string& text, const std::string& name) {
    using Method = TriangulationMethod;
    options.triangulation.method =
        parseChoice<Method>(text, name,
                            {{toString(Method::Sequential), Method::Sequential},
                             {toString(Method::Batch), Method::Batch},
                             {toString(Method::Circumcircle), Method::Circumcircle},
                             {toString(Method::Strips), Method::Strips},
                             {toString(Method::Auto), Method::Auto}});
}

void applyDuplicateZ(BuildOptions& options, const std::string& text, const std::string& name) {
    using Policy = DuplicateZPolicy;
    options.triangulation.duplicateZ = parseChoice<Policy>(text, name,
                                                           {{"first", Policy::First},
                                                            {"last", Policy::Last},
                                                            {"min", Policy::Min},
                                                            {"max", Policy::Max},
                                                            {"mean", Policy::Mean}});
}

void applyBand(BuildOptions& options, const std::string& text, const std::string& name) {
    int band = 0;
    if (!readWhole(text, band))
        refuseNumberText(text, name);
    if (band < 1)
        refuse(name + " must be 1 or more");
    options.band = band;
}

void applyMaxError(BuildOptions& options, const std::string& text, const std::string& name) {
    const double maxError = parseNumber(text, name);
    if (!std::isfinite(maxError) || maxError < 0.0)
        refuse(name + " must be a finite number >= 0");
    refineOf(options).maxError = maxError;
}

void applyMaxEdge(BuildOptions& options, const std::string& text, const std::string& name) {
    const double maxEdge = parseNumber(text, name);
    if (!std::isfinite(maxEdge) || maxEdge <= 0.0)
        refuse(name + " must be a positive number");
    options.maxEdge = maxEdge;
}

void applyZFactor(BuildOptions& options, const std::string& text, const std::string& name) {
    const double zFactor = parseNumber(text, name);
    if (!std::isfinite(zFactor) || zFactor == 0.0)
        refuse(name + " must be a finite number other than 0");
    options.zFactor = zFactor;
}

// Fill holes=false alone does not ask for a simplification.
void applyFillHoles(BuildOptions& options, const std::string& text, const std::string& name) {
    const bool fillHoles = parseFlag(text, name);
    if (fillHoles || options.refine)
        refineOf(options).fillHoles = fillHoles;
}

// The table: one line of help per option, the same order as `terratin build --help`.
std::vector<BuildOptionSpec> makeTable() {
    using Kind = OptionKind;
    std::vector<BuildOptionSpec> table = {
        {"inputs", "input", 0, Kind::Repeatable, true, "INPUT", "",
         "input rasters and point clouds, merged",
         [](BuildOptions& o, const std::string& t, const std::string&) { o.inputs.push_back(t); }},
        {"output", "output", 'o', Kind::Text, false, "OUTPUT", "",
         "output file (" + io::tinFormatExtensionList() +
             "); written under a temporary name, renamed when complete",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             if (t == "-")
                 refuse(n + " '-': terratin writes files, not standard output; give a file name "
                            "(./- for a file named '-')");
             o.output = t;
         }},
        {"format", "format", 'f', Kind::Text, false, "FORMAT", "",
         "output format: " + io::tinFormatNameList() +
             " (default: from the output's extension; terratin --formats lists them); 2dm has "
             "no CRS (QGIS opens it without one): use ply for a QGIS mesh layer with its CRS",
         [](BuildOptions& o, const std::string& t, const std::string&) {
             o.format = io::parseTinFormat(t);
         }},
        {"band", "band", 'b', Kind::Count, false, "N", "1", "raster band, from 1", applyBand},
        {"seed", "seed", 0, Kind::Count, false, "S", "1",
         "seed of the randomized insertion order (same seed, same TIN)",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.triangulation.seed = parseCount<std::uint64_t>(t, n);
         }},
        {"order", "order", 0, Kind::Text, false, "ORDER", "brio",
         "insertion order: brio (random rounds, each sorted along a Hilbert curve) or random",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.triangulation.order = parseChoice<InsertionOrder>(
                 t, n, {{"brio", InsertionOrder::Brio}, {"random", InsertionOrder::Random}});
         }},
        {"duplicate_z", "duplicate-z", 0, Kind::Text, false, "POLICY", "first",
         "elevation kept for points with the same x, y: first, last, min, max, mean",
         applyDuplicateZ},
        {"method", "method", 0, Kind::Text, false, "METHOD", "auto",
         "triangulator: sequential, batch (searching threads + one inserting thread), "
         "circumcircle (every thread inserts), strips (one strip of the plane per thread; "
         "the fastest), auto (strips; sequential with --order random)",
         applyMethod},
        {"locate", "locate", 0, Kind::Text, false, "HOW", "dag",
         "point location of sequential, batch and circumcircle: dag (the history DAG) or "
         "walk (from the previous point; sequential then keeps no history)",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.triangulation.locate = parseChoice<PointLocation>(
                 t, n, {{"dag", PointLocation::Dag}, {"walk", PointLocation::Walk}});
         }},
        {"threads", "threads", 'j', Kind::Count, false, "N", "0",
         "threads to use, 0 to " + std::to_string(kMaxThreads) + "; 0 = all hardware threads",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.triangulation.threads = parseCount<unsigned>(t, n);
         }},
        {"searchers", "searchers", 0, Kind::Count, false, "K", "0",
         "batch method: searching threads, 0 to " + std::to_string(kMaxThreads - 1) +
             " (0 = chosen from the input size and --threads)",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.triangulation.searchers = parseCount<unsigned>(t, n);
         }},
        {"queue_length", "queue-length", 0, Kind::Count, false, "L", "1024",
         "batch method: length of the queue to the inserting thread, 1 to " +
             std::to_string(kMaxQueueLength),
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.triangulation.queueLength = parseCount<std::size_t>(t, n);
         }},
        {"searchers_help", "searchers-help", 0, Kind::Flag, false, "", "",
         "batch method: searchers complete queued locations when the queue is full",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.triangulation.searchersHelpWhenQueueFull = parseFlag(t, n);
         }},
        {"max_error", "max-error", 0, Kind::Number, false, "E", "",
         "simplify: greedy insertion until every valid cell is within E (z units) of the TIN",
         applyMaxError},
        {"max_points", "max-points", 0, Kind::Count, false, "N", "",
         "simplify: at most N vertices, 3 to " + std::to_string(kMaxRefineCells) +
             " (the first limit reached stops); the hull of the valid cells is always kept, so "
             "N below its corner count is refused",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             refineOf(o).maxPoints = parseCount<std::size_t>(t, n);
         }},
        {"max_triangles", "max-triangles", 0, Kind::Count, false, "N", "",
         "simplify: at most N triangles, 1 to " + std::to_string(2 * kMaxRefineCells) +
             " (the first limit reached stops); the hull's corners alone make corners - 2 "
             "triangles, so a smaller N is refused",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             refineOf(o).maxTriangles = parseCount<std::size_t>(t, n);
         }},
        {"max_hole", "max-hole", 0, Kind::Count, false, "N", "",
         "simplify: nodata regions (8-connected) of more than N cells stay open, 0 to " +
             std::to_string(kMaxRefineCells) + " (default 1)",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             refineOf(o).maxHole = parseCount<std::size_t>(t, n);
         }},
        {"tile_size", "tile-size", 0, Kind::Count, false, "CELLS", "",
         "build a DEM's TIN in square tiles of CELLS cells a side, 2 to " +
             std::to_string(kMaxTileSize) +
             ", sharing their border cells: one TIN without cracks, simplified with "
             "--max-error, else at full resolution; no breaklines or areas yet",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             const auto cells = parseCount<std::size_t>(t, n);
             // 0 would read as "no tiles" further down: refused as 1 is.
             if (cells < 2 || cells > kMaxTileSize)
                 refuse(n + " must be 2 to " + std::to_string(kMaxTileSize) + " cells (got " + t +
                        ")");
             refineOf(o).tileSize = cells;
         }},
        {"memory_limit", "memory-limit", 0, Kind::Text, false, "SIZE", "",
         "build a DEM's TIN in tiles within SIZE of memory (2G, 512M: K M G T are powers of "
         "1024): the tile size follows from it unless --tile-size gives one, and the TIN is "
         "written tile by tile to -o in any format, simplified with --max-error, else at full "
         "resolution; not with --edges, --append-layer, breaklines or areas",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.memoryLimit = parseByteSize(t, n);
             refineOf(o); // tiles are a simplification's
         }},
        {"tiles_dir", "tiles-dir", 0, Kind::Text, false, "DIR", "",
         "instead of -o, with --tile-size or --memory-limit: each tile's TIN in its own file "
         "in DIR (tile_ROW_COLUMN.EXT, -f or gpkg) and DIR/tiles.gpkg, their footprints; never "
         "joined",
         [](BuildOptions& o, const std::string& t, const std::string&) { o.tilesDir = t; }},
        {"fill_holes", "fill-holes", 0, Kind::Flag, false, "", "",
         "simplify: triangulate across every nodata region", applyFillHoles},
        {"max_edge", "max-edge", 0, Kind::Number, false, "L", "",
         "drop triangles with an edge longer than L (CRS units), e.g. across point-cloud gaps",
         applyMaxEdge},
        {"layer", "layer", 0, Kind::Text, false, "NAME", "tin",
         "name of the triangle layer (GeoPackage; the mesh / surface name in 2DM, OBJ, LandXML)",
         [](BuildOptions& o, const std::string& t, const std::string&) { o.layerName = t; }},
        {"attributes", "attributes", 0, Kind::Text, false, "SET", "all",
         "triangle attributes: none, basic (z_min z_max z_mean slope_deg aspect_deg area_2d) "
         "or all",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.attributes = parseChoice<io::AttributeSet>(t, n,
                                                          {{"none", io::AttributeSet::None},
                                                           {"basic", io::AttributeSet::Basic},
                                                           {"all", io::AttributeSet::All}});
         }},
        {"nodes", "nodes", 0, Kind::Flag, false, "", "",
         "GeoPackage: add a Point Z layer of the vertices with their raster row / col",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.nodes = parseFlag(t, n);
         }},
        {"edges", "edges", 0, Kind::Flag, false, "", "",
         "GeoPackage: add a LineString Z layer of the edges with their two triangles",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.edges = parseFlag(t, n);
         }},
        {"append_layer", "append-layer", 0, Kind::Flag, false, "", "",
         "GeoPackage: add the layers to an existing GeoPackage, keeping its other layers",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.appendLayer = parseFlag(t, n);
         }},
        {"no_spatial_index", "no-spatial-index", 0, Kind::Flag, false, "", "",
         "GeoPackage / FlatGeobuf: skip the spatial index (much faster GeoPackage writing)",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.spatialIndex = !parseFlag(t, n);
         }},
        {"qgis_style", "qgis-style", 0, Kind::Flag, false, "", "",
         "write a QGIS style (.qml) beside the output: triangles coloured by z_mean on a "
         "terrain ramp",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.qgisStyle = parseFlag(t, n);
         }},
        // `class` is a Python keyword: the keyword is `classes`.
        {"classes", "class", 0, Kind::Repeatable, false, "C[,C...]", "",
         "LAS: keep only these classification codes (2 = ground); repeatable", applyClasses},
        {"returns", "returns", 0, Kind::Text, false, "WHICH", "all",
         "LAS: keep first, last or all returns",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.lasReturns = parseChoice<io::LasReturns>(t, n,
                                                        {{"first", io::LasReturns::First},
                                                         {"last", io::LasReturns::Last},
                                                         {"all", io::LasReturns::All}});
         }},
        {"columns", "columns", 0, Kind::List, false, "X,Y,Z", "",
         "text: the x, y, z columns, by 1-based number or header name (e.g. 1,2,3 or E,N,H)",
         applyColumns},
        {"z_field", "z-field", 0, Kind::Text, false, "NAME", "",
         "vector points: the attribute holding the elevation (default: the geometry's z)",
         [](BuildOptions& o, const std::string& t, const std::string&) { o.zField = t; }},
        {"input_layer", "input-layer", 0, Kind::Text, false, "NAME", "",
         "vector points: the layer to read (default: the first point layer)",
         [](BuildOptions& o, const std::string& t, const std::string&) { o.inputLayer = t; }},
        {"breaklines", "breaklines", 0, Kind::Repeatable, false, "FILE", "",
         "hard breaklines: an OGR line layer (FILE or FILE|layername=NAME); every segment "
         "becomes a chain of TIN edges, in full-resolution and simplified TINs; repeatable",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             if (t.empty())
                 refuse(n + " needs a file name");
             o.breaklines.push_back(t);
         }},
        {"breaklines_layer", "breaklines-layer", 0, Kind::Text, false, "NAME", "",
         "the layer of a breaklines source that names none (default: its only layer)",
         [](BuildOptions& o, const std::string& t, const std::string&) { o.breaklinesLayer = t; }},
        {"breakline_z", "breakline-z", 0, Kind::Text, false, "FROM", "",
         "elevation of breakline vertices: line (the line's z) or surface (a DEM's, "
         "bilinear; else the TIN of the inputs); default: the line's z when it has one, else "
         "the surface",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.breaklineZ = parseChoice<BreaklineZ>(
                 t, n, {{"line", BreaklineZ::Line}, {"surface", BreaklineZ::Surface}});
         }},
        {"clip", "clip", 0, Kind::Text, false, "FILE", "",
         "clip area: an OGR polygon layer (FILE or FILE|layername=NAME); triangles outside "
         "are removed, its boundary becomes TIN edges",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             if (t.empty())
                 refuse(n + " needs a file name");
             o.clip = t;
         }},
        {"erase", "erase", 0, Kind::Text, false, "FILE", "",
         "erase areas: polygons cut out of the TIN as holes, their boundaries TIN edges",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             if (t.empty())
                 refuse(n + " needs a file name");
             o.erase = t;
         }},
        {"replace", "replace", 0, Kind::Text, false, "FILE", "",
         "replace areas (lakes, rivers): polygons flattened to one elevation; no input point "
         "inside is kept, their boundaries become TIN edges at that elevation",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             if (t.empty())
                 refuse(n + " needs a file name");
             o.replace = t;
         }},
        {"replace_z_field", "replace-z-field", 0, Kind::Text, false, "NAME", "",
         "the numeric attribute holding each replace polygon's elevation (default: the lowest "
         "elevation of the surface on its boundary)",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             if (t.empty())
                 refuse(n + " needs a field name");
             o.replaceZField = t;
         }},
        {"s_srs", "s_srs", 0, Kind::Text, false, "SRS", "",
         "CRS of the inputs, overriding theirs (EPSG:n, WKT, PROJ string, .prj file...); "
         "horizontal: projected or geographic 2D, or compound with such a part",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.sourceSrs = parseCrs(t, n);
         }},
        {"t_srs", "t_srs", 0, Kind::Text, false, "SRS", "",
         "reproject every point (x, y) to this CRS before triangulating; the output carries "
         "it; horizontal, as --s_srs (not vertical-only, not geocentric)",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.targetSrs = parseCrs(t, n);
         }},
        {"keep_geographic", "keep-geographic", 0, Kind::Flag, false, "", "",
         "triangulate geographic input in degrees instead of its UTM/UPS zone",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.keepGeographic = parseFlag(t, n);
         }},
        {"z_factor", "z-factor", 0, Kind::Number, false, "F", "1",
         "multiply every elevation by F (0.3048: feet to metres); z is never converted "
         "otherwise",
         applyZFactor},
        {"overwrite", "overwrite", 0, Kind::Flag, false, "", "", "replace an existing output",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.overwrite = parseFlag(t, n);
         }},
        {"validate", "validate", 0, Kind::Flag, false, "", "",
         "check the TIN exactly (empty circles, hull, topology) before writing",
         [](BuildOptions& o, const std::string& t, const std::string& n) {
             o.validate = parseFlag(t, n);
         }},
    };
    return table;
}

// Edits (insertions, deletions, substitutions) that turn `a` into `b`.
std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// A name two edits or fewer from `name`, for "did you mean"; empty when none is that close.
std::string closestName(std::string_view name, OptionSpelling spelling) {
    constexpr std::size_t kMaxTypoEdits = 2; // one slip of the finger, or two
    std::string closest;
    std::size_t best = kMaxTypoEdits + 1;
    for (const BuildOptionSpec& option : buildOptionTable()) {
        const std::string candidate = optionName(option, spelling);
        const std::size_t distance = editDistance(name, candidate);
        if (distance < best) {
            best = distance;
            closest = candidate;
        }
    }
    return closest;
}

[[noreturn]] void refuseUnknown(std::string_view name, OptionSpelling spelling) {
    const std::string closest = closestName(name, spelling);
    refuse("unknown option '" + std::string(name) + "'" +
           (closest.empty() ? std::string() : "; did you mean '" + closest + "'?"));
}

} // namespace

std::string closestBuildOption(std::string_view name, OptionSpelling spelling) {
    return closestName(name, spelling);
}

namespace {

bool given(const std::vector<OptionValue>& values, std::string_view keyword,
           OptionSpelling spelling) {
    return std::any_of(values.begin(), values.end(), [&](const OptionValue& value) {
        const BuildOptionSpec* option = findBuildOption(value.name, spelling);
        return option != nullptr && option->keyword == keyword;
    });
}

} // namespace

std::span<const BuildOptionSpec> buildOptionTable() {
    static const std::vector<BuildOptionSpec> table = makeTable();
    return table;
}

const BuildOptionSpec* findBuildOption(std::string_view name, OptionSpelling spelling) {
    if (spelling == OptionSpelling::CommandLine && name.substr(0, 2) == "--")
        name.remove_prefix(2);
    for (const BuildOptionSpec& option : buildOptionTable())
        if (name == (spelling == OptionSpelling::Keyword ? option.keyword : option.longFlag))
            return &option;
    return nullptr;
}

std::string optionName(const BuildOptionSpec& option, OptionSpelling spelling) {
    if (spelling == OptionSpelling::Keyword)
        return std::string(option.keyword);
    return option.positional ? std::string(option.valueName) : "--" + std::string(option.longFlag);
}

std::string optionName(std::string_view keyword, OptionSpelling spelling) {
    const BuildOptionSpec* option = findBuildOption(keyword, OptionSpelling::Keyword);
    if (option == nullptr)
        throw Error("optionName: no build option has the keyword '" + std::string(keyword) + "'");
    return optionName(*option, spelling);
}

OptionNaming optionNaming(OptionSpelling spelling) {
    return [spelling](std::string_view keyword) { return optionName(keyword, spelling); };
}

namespace {

// applyBuildOption, its messages naming options by keyword (markOption).
void applyNamingByKeyword(BuildOptions& options, const OptionValue& value,
                          OptionSpelling spelling) {
    const BuildOptionSpec* option = findBuildOption(value.name, spelling);
    if (option == nullptr)
        refuseUnknown(value.name, spelling);
    // A C string ends at a NUL: a path holding one would name another file.
    if (value.text.find('\0') != std::string::npos)
        refuse(markOption(option->keyword) + " holds a NUL character");
    option->apply(options, value.text, markOption(option->keyword));
}

BuildOptions parseNamingByKeyword(const std::vector<OptionValue>& values, OptionSpelling spelling) {
    const auto name = [](std::string_view keyword) { return markOption(keyword); };
    // What is missing first: a usage line is more use than a complaint about one value.
    if (!given(values, "inputs", spelling))
        refuse("missing " + name("inputs"));
    const bool tiles = given(values, "tiles_dir", spelling);
    if (!given(values, "output", spelling) && !tiles)
        refuse(spelling == OptionSpelling::CommandLine ? std::string("missing -o OUTPUT")
                                                       : "missing " + name("output"));
    if (given(values, "output", spelling) && tiles)
        refuse(name("tiles_dir") + " takes the place of " + name("output") + ": give one");
    BuildOptions options;
    options.optionSpelling = spelling;
    for (const OptionValue& value : values)
        applyNamingByKeyword(options, value, spelling);
    if (options.refine && options.refine->fillHoles && given(values, "max_hole", spelling))
        refuse(name("max_hole") + " and " + name("fill_holes") +
               " contradict each other: give one");
    if (!options.format)
        options.format = tiles ? io::TinFormat::GeoPackage : io::tinFormatFromPath(options.output);
    checkBuildOptions(options);
    return options;
}

} // namespace

void applyBuildOption(BuildOptions& options, const OptionValue& value, OptionSpelling spelling) {
    try {
        applyNamingByKeyword(options, value, spelling);
    } catch (Error& error) {
        error.nameOptions(optionNaming(spelling));
        throw;
    }
}

BuildOptions parseBuildOptions(const std::vector<OptionValue>& values, OptionSpelling spelling) {
    try {
        return parseNamingByKeyword(values, spelling);
    } catch (Error& error) {
        error.nameOptions(optionNaming(spelling));
        throw;
    }
}

} // namespace terratin
