#include "terratin/pipeline/build_option_table.hpp"

#include "option_text.hpp"

#include "terratin/error.hpp"
#include "terratin/io/tin_format.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace terratin {

namespace {

using detail::parseByteSize;
using detail::parseChoice;
using detail::parseCount;
using detail::parseCrs;
using detail::parseFlag;
using detail::parseNumber;
using detail::readWhole;
using detail::refuse;
using detail::refuseNumberText;
using detail::splitList;

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
    options.band = band; // its range checked with the others' (checkBuildOptions)
}

void applyMaxError(BuildOptions& options, const std::string& text, const std::string& name) {
    const double maxError = parseNumber(text, name);
    if (!std::isfinite(maxError) || maxError < 0.0)
        refuse(name + " must be a finite number >= 0");
    refineOf(options).maxError = maxError;
}

void applyMaxEdge(BuildOptions& options, const std::string& text, const std::string& name) {
    options.maxEdge = parseNumber(text, name); // checked by checkBuildOptions
}

void applyZFactor(BuildOptions& options, const std::string& text, const std::string& name) {
    options.zFactor = parseNumber(text, name); // checked by checkBuildOptions
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
             refineOf(o); // tiles are a DEM's build, simplified or at full resolution
             o.tileSize = cells;
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
         "LAS/LAZ: keep only these classification codes (2 = ground); repeatable", applyClasses},
        {"returns", "returns", 0, Kind::Text, false, "WHICH", "all",
         "LAS/LAZ: keep first, last or all returns",
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

} // namespace

std::span<const BuildOptionSpec> buildOptionTable() {
    static const std::vector<BuildOptionSpec> table = makeTable();
    return table;
}

std::string_view buildOptionHeading(const BuildOptionSpec& option) {
    // The randomized insertion and the parallel methods' own settings: every build runs well
    // on their defaults, and a reader of --help wants the build's options first.
    static constexpr std::string_view kMethodTuning[] = {
        "seed", "order", "method", "locate", "searchers", "queue_length", "searchers_help"};
    for (const std::string_view keyword : kMethodTuning)
        if (option.keyword == keyword)
            return kMethodTuningHeading;
    return {};
}

} // namespace terratin
