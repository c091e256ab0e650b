#include "cli_options.hpp"

#include "terratin/error.hpp"

#include <boost/program_options.hpp>

#include <algorithm>
#include <cctype>
#include <sstream>

namespace terratin::cli {

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage = "Usage: terratin build INPUT -o OUTPUT [options]\n"
                               "       terratin --help | --version\n";

constexpr const char* kDescription =
    "Builds an exactly Delaunay TIN from a DEM raster (any format GDAL reads: GeoTIFF, VRT,\n"
    "DTED, HGT, ASCII grid...). Every valid cell centre becomes a vertex with the cell's\n"
    "elevation; nodata, masked and NaN cells are skipped. The output holds one Polygon Z\n"
    "triangle per feature with z1 z2 z3 z_min z_max z_mean slope_deg slope_pct aspect_deg\n"
    "area_2d area_3d nx ny nz (GeoPackage, Shapefile, FlatGeobuf), in the input's CRS, or\n"
    "the mesh itself (2DM, PLY, OBJ, LandXML).\n\n"
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
          TriangulationMethod::Circumcircle, TriangulationMethod::Auto})
        if (key == toString(method))
            return method;
    throw UsageError("--method must be sequential, batch, circumcircle or auto (got '" + name +
                     "')");
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
         "extension)")
        ("band,b", po::value<int>()->default_value(1)->value_name("N"), "raster band, from 1")
        ("seed", po::value<std::uint64_t>()->default_value(1)->value_name("S"),
         "seed of the randomized insertion order (same seed, same TIN)")
        ("order", po::value<std::string>()->default_value("brio")->value_name("ORDER"),
         "insertion order: brio (random rounds, each sorted along a Hilbert curve) or random")
        ("duplicate-z", po::value<std::string>()->default_value("first")->value_name("POLICY"),
         "elevation kept for points with the same x, y: first, last, min, max, mean")
        ("method", po::value<std::string>()->default_value("auto")->value_name("METHOD"),
         "triangulator: sequential, batch (searching threads + one inserting thread), "
         "circumcircle (every thread inserts), auto")
        ("locate", po::value<std::string>()->default_value("dag")->value_name("HOW"),
         "point location: dag (the history DAG) or walk (sequential method only)")
        ("threads,j", po::value<unsigned>()->default_value(0)->value_name("N"),
         "threads to use; 0 = all hardware threads")
        ("searchers", po::value<unsigned>()->default_value(0)->value_name("K"),
         "batch method: searching threads (0 = chosen from the input size and --threads)")
        ("queue-length", po::value<std::size_t>()->default_value(1024)->value_name("L"),
         "batch method: length of the queue to the inserting thread")
        ("searchers-help",
         "batch method: searchers complete queued locations when the queue is full")
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
    if (inputs.size() != 1)
        throw UsageError("expected one INPUT, got " + std::to_string(inputs.size()));
    if (!values.count("output"))
        throw UsageError("missing -o OUTPUT");

    BuildOptions& build = command.build;
    build.input = inputs.front();
    build.output = values["output"].as<std::string>();
    build.band = values["band"].as<int>();
    if (build.band < 1)
        throw UsageError("--band must be 1 or more");
    TriangulationOptions& triangulation = build.triangulation;
    triangulation.seed = values["seed"].as<std::uint64_t>();
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
    triangulation.threads = values["threads"].as<unsigned>();
    triangulation.searchers = values["searchers"].as<unsigned>();
    triangulation.queueLength = values["queue-length"].as<std::size_t>();
    if (triangulation.queueLength == 0)
        throw UsageError("--queue-length must be 1 or more");
    triangulation.searchersHelpWhenQueueFull = values.count("searchers-help") > 0;
    build.layerName = values["layer"].as<std::string>();
    build.overwrite = values.count("overwrite") > 0;
    build.validate = values.count("validate") > 0;
    build.nodes = values.count("nodes") > 0;
    build.edges = values.count("edges") > 0;
    build.appendLayer = values.count("append-layer") > 0;
    build.spatialIndex = values.count("no-spatial-index") == 0;
    build.qgisStyle = values.count("qgis-style") > 0;
    // A format that cannot be named or inferred, or output options that contradict it, are
    // command-line mistakes (status 2).
    try {
        build.format = values.count("format")
                           ? io::parseTinFormat(values["format"].as<std::string>())
                           : io::tinFormatFromPath(build.output);
        build.attributes = io::parseAttributeSet(values["attributes"].as<std::string>());
        io::TinWriteOptions writeOptions;
        writeOptions.format = *build.format;
        writeOptions.layerName = build.layerName;
        writeOptions.attributes = build.attributes;
        writeOptions.nodes = build.nodes;
        writeOptions.edges = build.edges;
        writeOptions.appendLayer = build.appendLayer;
        writeOptions.spatialIndex = build.spatialIndex;
        writeOptions.qgisStyle = build.qgisStyle;
        io::checkTinWriteOptions(writeOptions);
    } catch (const Error& error) {
        throw UsageError(error.what());
    }
    command.quiet = values.count("quiet") > 0;
    command.json = values.count("json") > 0;
    return command;
}

} // namespace terratin::cli
