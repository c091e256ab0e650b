#include "cli_options.hpp"

#include "terratin/error.hpp"

#include <boost/program_options.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>
#include <system_error>

namespace terratin::cli {

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage = "Usage: terratin build INPUT... -o OUTPUT [options]\n"
                               "       terratin --help | --version\n";

constexpr const char* kDescription =
    "Builds an exactly Delaunay TIN from a DEM raster (any format GDAL reads: GeoTIFF, VRT,\n"
    "DTED, HGT, ASCII grid...). Every valid cell centre becomes a vertex with the cell's\n"
    "elevation; nodata, masked and NaN cells are skipped. The output holds one Polygon Z\n"
    "triangle per feature with z1 z2 z3 z_min z_max z_mean slope_deg slope_pct aspect_deg\n"
    "area_2d area_3d nx ny nz (GeoPackage, Shapefile, FlatGeobuf), in the input's CRS, or\n"
    "the mesh itself (2DM, PLY, OBJ, LandXML).\n\n"
    "Point clouds too: LAS 1.0-1.4 (.las, uncompressed), delimited text (.xyz .txt .csv...:\n"
    "x y z per line, separated by spaces, ',', ';' or '|', optional header line) and any OGR\n"
    "point layer (GeoPackage, Shapefile, GeoJSON...). Several inputs are merged after being\n"
    "brought into one CRS. Geographic input is projected to the UTM/UPS zone of its centre\n"
    "unless --t_srs or --keep-geographic says otherwise; elevations are never converted\n"
    "except by --z-factor.\n\n"
    "With --max-error, --max-points or --max-triangles the DEM is simplified instead: greedy\n"
    "insertion of the cell farthest from the TIN, kept exactly Delaunay, until the tolerance\n"
    "or a limit is reached; nodata regions larger than --max-hole cells become holes.\n\n"
    "Exit status: 0 success, 1 error (one line on stderr), 2 bad command line.\n";

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

DuplicateZPolicy parseDuplicatePolicy(const std::string& name) {
    const std::string key = lowercase(name);
    if (key == "first")
        return DuplicateZPolicy::First;
    if (key == "last")
        return DuplicateZPolicy::Last;
    if (key == "min")
        return DuplicateZPolicy::Min;
    if (key == "max")
        return DuplicateZPolicy::Max;
    if (key == "mean")
        return DuplicateZPolicy::Mean;
    throw UsageError("--duplicate-z must be first, last, min, max or mean (got '" + name + "')");
}

TriangulationMethod parseMethod(const std::string& name) {
    const std::string key = lowercase(name);
    for (const TriangulationMethod method :
         {TriangulationMethod::Sequential, TriangulationMethod::Batch,
          TriangulationMethod::Circumcircle, TriangulationMethod::Strips,
          TriangulationMethod::Auto})
        if (key == toString(method))
            return method;
    throw UsageError("--method must be sequential, batch, circumcircle, strips or auto (got '" +
                     name + "')");
}

// Boost.Program_options reads "-1" into an unsigned option as 2^64 - 1 (it wraps through
// strtoul): count options are read as text and parsed here, digits only, so that a sign is
// refused instead of wrapped. Their ranges are the library's to check (checkBuildOptions).
template <class Count> Count parseCount(const po::variables_map& values, const std::string& name) {
    const std::string& text = values[name].as<std::string>();
    Count count{};
    const char* end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, count);
    if (error == std::errc::result_out_of_range)
        throw UsageError("--" + name + " is too large (got '" + text + "')");
    if (text.empty() || error != std::errc() || ptr != end)
        throw UsageError("--" + name + " takes a whole number without sign (got '" + text + "')");
    return count;
}

// A CRS option given as an empty (or blank) string would mean "no CRS" to the library, which
// is not what a user typing it asks for.
std::string parseCrsOption(const po::variables_map& values, const std::string& name) {
    const std::string& text = values[name].as<std::string>();
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        throw UsageError("--" + name +
                         " needs a CRS (EPSG:n, WKT, PROJ string, .prj file), not an empty string");
    return text;
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

/// --class, --returns, --columns, --z-field, --input-layer, --s_srs, --t_srs,
/// --keep-geographic, --z-factor.
void parsePointCloudOptions(const po::variables_map& values, BuildOptions& build) {
    if (values.count("class")) {
        for (const std::string& list : values["class"].as<std::vector<std::string>>()) {
            for (const std::string& item : splitList(list)) {
                int code = -1;
                const char* end = item.data() + item.size();
                const auto [ptr, error] = std::from_chars(item.data(), end, code);
                if (item.empty() || error != std::errc() || ptr != end || code < 0 || code > 255)
                    throw UsageError("--class takes classification codes 0..255 (got '" + item +
                                     "')");
                build.lasClasses.push_back(code);
            }
        }
    }
    try {
        build.lasReturns = io::parseLasReturns(values["returns"].as<std::string>());
    } catch (const Error& error) {
        throw UsageError(error.what());
    }
    if (values.count("columns")) {
        build.textColumns = splitList(values["columns"].as<std::string>());
        if (build.textColumns.size() != 3 ||
            std::any_of(build.textColumns.begin(), build.textColumns.end(),
                        [](const std::string& column) { return column.empty(); }))
            throw UsageError("--columns takes three columns x,y,z (got '" +
                             values["columns"].as<std::string>() + "')");
        for (const std::string& column : build.textColumns)
            if (column == "0")
                throw UsageError("--columns: columns are numbered from 1");
    }
    if (values.count("z-field"))
        build.zField = values["z-field"].as<std::string>();
    if (values.count("input-layer"))
        build.inputLayer = values["input-layer"].as<std::string>();
    if (values.count("s_srs"))
        build.sourceSrs = parseCrsOption(values, "s_srs");
    if (values.count("t_srs"))
        build.targetSrs = parseCrsOption(values, "t_srs");
    build.keepGeographic = values.count("keep-geographic") > 0;
    if (build.keepGeographic && !build.targetSrs.empty())
        throw UsageError("--keep-geographic and --t_srs contradict each other");
    build.zFactor = values["z-factor"].as<double>();
    if (!std::isfinite(build.zFactor) || build.zFactor == 0.0)
        throw UsageError("--z-factor must be a finite number other than 0");
}

po::options_description buildOptionsDescription() {
    po::options_description options("Options of 'terratin build'");
    // clang-format off
    options.add_options()
        ("output,o", po::value<std::string>()->value_name("OUTPUT"),
         "output file (.gpkg .shp .fgb .2dm .ply .obj .xml); written under a temporary name, "
         "renamed when complete")
        ("format,f", po::value<std::string>()->value_name("FORMAT"),
         "output format: gpkg, shp, fgb, 2dm, ply, obj, landxml (default: from the output's "
         "extension); 2dm has no CRS (QGIS opens it without one): use ply for a QGIS mesh "
         "layer with its CRS")
        ("band,b", po::value<int>()->default_value(1)->value_name("N"), "raster band, from 1")
        ("seed", po::value<std::string>()->default_value("1")->value_name("S"),
         "seed of the randomized insertion order (same seed, same TIN)")
        ("order", po::value<std::string>()->default_value("brio")->value_name("ORDER"),
         "insertion order: brio (random rounds, each sorted along a Hilbert curve) or random")
        ("duplicate-z", po::value<std::string>()->default_value("first")->value_name("POLICY"),
         "elevation kept for points with the same x, y: first, last, min, max, mean")
        ("method", po::value<std::string>()->default_value("auto")->value_name("METHOD"),
         "triangulator: sequential, batch (searching threads + one inserting thread), "
         "circumcircle (every thread inserts), strips (one strip of the plane per thread; "
         "the fastest), auto (strips; sequential with --order random)")
        ("locate", po::value<std::string>()->default_value("dag")->value_name("HOW"),
         "point location of sequential, batch and circumcircle: dag (the history DAG) or "
         "walk (from the previous point; sequential then keeps no history)")
        ("threads,j", po::value<std::string>()->default_value("0")->value_name("N"),
         ("threads to use, 0 to " + std::to_string(kMaxThreads) +
          "; 0 = all hardware threads").c_str())
        ("searchers", po::value<std::string>()->default_value("0")->value_name("K"),
         ("batch method: searching threads, 0 to " + std::to_string(kMaxThreads - 1) +
          " (0 = chosen from the input size and --threads)").c_str())
        ("queue-length", po::value<std::string>()->default_value("1024")->value_name("L"),
         ("batch method: length of the queue to the inserting thread, 1 to " +
          std::to_string(kMaxQueueLength)).c_str())
        ("searchers-help",
         "batch method: searchers complete queued locations when the queue is full")
        ("max-error", po::value<double>()->value_name("E"),
         "simplify: greedy insertion until every valid cell is within E (z units) of the TIN")
        ("max-points", po::value<std::string>()->value_name("N"),
         ("simplify: at most N vertices, 3 to " + std::to_string(kMaxRefineCells) +
          " (the first limit reached stops); the hull of the valid cells is always kept, so N "
          "below its corner count is refused").c_str())
        ("max-triangles", po::value<std::string>()->value_name("N"),
         ("simplify: at most N triangles, 1 to " + std::to_string(2 * kMaxRefineCells) +
          " (the first limit reached stops); the hull's corners alone make corners - 2 "
          "triangles, so a smaller N is refused").c_str())
        ("max-hole", po::value<std::string>()->value_name("N"),
         ("simplify: nodata regions (8-connected) of more than N cells stay open, 0 to " +
          std::to_string(kMaxRefineCells) + " (default 1)").c_str())
        ("fill-holes", "simplify: triangulate across every nodata region")
        ("max-edge", po::value<double>()->value_name("L"),
         "drop triangles with an edge longer than L (CRS units), e.g. across point-cloud gaps")
        ("layer", po::value<std::string>()->default_value("tin")->value_name("NAME"),
         "name of the triangle layer (GeoPackage; the mesh / surface name in 2DM, OBJ, LandXML)")
        ("attributes", po::value<std::string>()->default_value("all")->value_name("SET"),
         "triangle attributes: none, basic (z_min z_max z_mean slope_deg aspect_deg area_2d) "
         "or all")
        ("nodes", "GeoPackage: add a Point Z layer of the vertices with their raster row / col")
        ("edges", "GeoPackage: add a LineString Z layer of the edges with their two triangles")
        ("append-layer",
         "GeoPackage: add the layers to an existing GeoPackage, keeping its other layers")
        ("no-spatial-index",
         "GeoPackage / FlatGeobuf: skip the spatial index (much faster GeoPackage writing)")
        ("qgis-style", "write a QGIS style (.qml) beside the output: triangles coloured by "
         "z_mean on a terrain ramp")
        ("class", po::value<std::vector<std::string>>()->composing()->value_name("C[,C...]"),
         "LAS: keep only these classification codes (2 = ground); repeatable")
        ("returns", po::value<std::string>()->default_value("all")->value_name("WHICH"),
         "LAS: keep first, last or all returns")
        ("columns", po::value<std::string>()->value_name("X,Y,Z"),
         "text: the x, y, z columns, by 1-based number or header name (e.g. 1,2,3 or E,N,H)")
        ("z-field", po::value<std::string>()->value_name("NAME"),
         "vector points: the attribute holding the elevation (default: the geometry's z)")
        ("input-layer", po::value<std::string>()->value_name("NAME"),
         "vector points: the layer to read (default: the first point layer)")
        ("s_srs", po::value<std::string>()->value_name("SRS"),
         "CRS of the inputs, overriding theirs (EPSG:n, WKT, PROJ string, .prj file...); "
         "horizontal: projected or geographic 2D, or compound with such a part")
        ("t_srs", po::value<std::string>()->value_name("SRS"),
         "reproject every point (x, y) to this CRS before triangulating; the output carries "
         "it; horizontal, as --s_srs (not vertical-only, not geocentric)")
        ("keep-geographic",
         "triangulate geographic input in degrees instead of its UTM/UPS zone")
        ("z-factor", po::value<double>()->default_value(1.0)->value_name("F"),
         "multiply every elevation by F (0.3048: feet to metres); z is never converted otherwise")
        ("overwrite", "replace an existing output")
        ("validate", "check the TIN exactly (empty circles, hull, topology) before writing")
        ("quiet,q", "no progress and no summary")
        ("json", "print a JSON report on stdout (counts, CRS, seconds per phase)")
        ("help,h", "show this help");
    // clang-format on
    return options;
}

std::string helpText(const po::options_description& options) {
    std::ostringstream text;
    text << kUsage << "\n" << kDescription << "\n" << options;
    return text.str();
}

} // namespace

Command parseCommandLine(const std::vector<std::string>& arguments) {
    Command command;
    const po::options_description options = buildOptionsDescription();
    command.helpText = helpText(options);
    if (arguments.empty())
        throw UsageError("missing command; try 'terratin --help'");
    const std::string& verb = arguments.front();
    if (verb == "--help" || verb == "-h" || verb == "help") {
        command.kind = Command::Kind::Help;
        return command;
    }
    if (verb == "--version") {
        command.kind = Command::Kind::Version;
        return command;
    }
    if (verb != "build")
        throw UsageError("unknown command '" + verb + "'; try 'terratin --help'");

    po::options_description all;
    all.add(options);
    all.add_options()("input", po::value<std::vector<std::string>>());
    po::positional_options_description positional;
    positional.add("input", -1);

    po::variables_map values;
    try {
        const std::vector<std::string> rest(arguments.begin() + 1, arguments.end());
        po::store(po::command_line_parser(rest).options(all).positional(positional).run(), values);
        po::notify(values);
    } catch (const po::error& error) {
        throw UsageError(error.what());
    }
    if (values.count("help")) {
        command.kind = Command::Kind::Help;
        return command;
    }

    command.kind = Command::Kind::Build;
    if (!values.count("input"))
        throw UsageError("missing INPUT");
    const auto& inputs = values["input"].as<std::vector<std::string>>();
    if (!values.count("output"))
        throw UsageError("missing -o OUTPUT");

    BuildOptions& build = command.build;
    build.inputs = inputs;
    parsePointCloudOptions(values, build);
    build.output = values["output"].as<std::string>();
    build.band = values["band"].as<int>();
    if (build.band < 1)
        throw UsageError("--band must be 1 or more");
    TriangulationOptions& triangulation = build.triangulation;
    triangulation.seed = parseCount<std::uint64_t>(values, "seed");
    triangulation.duplicateZ = parseDuplicatePolicy(values["duplicate-z"].as<std::string>());
    triangulation.method = parseMethod(values["method"].as<std::string>());
    const std::string order = lowercase(values["order"].as<std::string>());
    if (order != "brio" && order != "random")
        throw UsageError("--order must be brio or random (got '" + order + "')");
    triangulation.order = order == "brio" ? InsertionOrder::Brio : InsertionOrder::Random;
    const std::string locate = lowercase(values["locate"].as<std::string>());
    if (locate != "dag" && locate != "walk")
        throw UsageError("--locate must be dag or walk (got '" + locate + "')");
    triangulation.locate = locate == "walk" ? PointLocation::Walk : PointLocation::Dag;
    triangulation.threads = parseCount<unsigned>(values, "threads");
    triangulation.searchers = parseCount<unsigned>(values, "searchers");
    triangulation.queueLength = parseCount<std::size_t>(values, "queue-length");
    triangulation.searchersHelpWhenQueueFull = values.count("searchers-help") > 0;
    // Simplification: any of its options selects the refinement path.
    if (values.count("max-error") || values.count("max-points") || values.count("max-triangles") ||
        values.count("max-hole") || values.count("fill-holes")) {
        RefineOptions refine;
        if (values.count("max-error")) {
            const double maxError = values["max-error"].as<double>();
            if (!std::isfinite(maxError) || maxError < 0.0)
                throw UsageError("--max-error must be a finite number >= 0");
            refine.maxError = maxError;
        }
        if (values.count("max-points"))
            refine.maxPoints = parseCount<std::size_t>(values, "max-points");
        if (values.count("max-triangles"))
            refine.maxTriangles = parseCount<std::size_t>(values, "max-triangles");
        if (values.count("max-hole"))
            refine.maxHole = parseCount<std::size_t>(values, "max-hole");
        refine.fillHoles = values.count("fill-holes") > 0;
        build.refine = refine;
    }
    if (values.count("max-edge")) {
        const double maxEdge = values["max-edge"].as<double>();
        if (!std::isfinite(maxEdge) || maxEdge <= 0.0)
            throw UsageError("--max-edge must be a positive number");
        build.maxEdge = maxEdge;
    }
    build.layerName = values["layer"].as<std::string>();
    build.overwrite = values.count("overwrite") > 0;
    build.validate = values.count("validate") > 0;
    build.nodes = values.count("nodes") > 0;
    build.edges = values.count("edges") > 0;
    build.appendLayer = values.count("append-layer") > 0;
    build.spatialIndex = values.count("no-spatial-index") == 0;
    build.qgisStyle = values.count("qgis-style") > 0;
    // A format that cannot be named or inferred, output options that contradict it, and
    // values out of the library's ranges are command-line mistakes (status 2).
    try {
        build.format = values.count("format")
                           ? io::parseTinFormat(values["format"].as<std::string>())
                           : io::tinFormatFromPath(build.output);
        build.attributes = io::parseAttributeSet(values["attributes"].as<std::string>());
        checkBuildOptions(build);
    } catch (const Error& error) {
        throw UsageError(error.what());
    }
    command.quiet = values.count("quiet") > 0;
    command.json = values.count("json") > 0;
    return command;
}

} // namespace terratin::cli
