#include "bench_options.hpp"

#include <boost/program_options.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <limits>
#include <sstream>
#include <thread>

namespace terratin::bench {

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage = "Usage: terratin-bench [options]\n";

constexpr const char* kDescription =
    "Times terratin's triangulation methods on the distributions of Kohout & Kolingerova\n"
    "(uniform, gauss, cluster, grid, arc in the unit square) against CGAL and GDAL on the\n"
    "same points, and prints the median of --runs runs per configuration: seconds, speed-up\n"
    "over terratin's sequential method, memory per point, and terratin's time / peer's time.\n";

constexpr std::size_t kLargeSize = 10'000'000;
// A triangle needs three points: fewer make the library throw InvalidInputError.
constexpr std::size_t kMinimumPoints = 3;

// Option values compare case-insensitively (ASCII, the "C" locale).
std::string lowercase(std::string_view text) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return lower;
}

std::vector<NamedMethod> methodTable() {
    using Method = TriangulationMethod;
    return {{"sequential", Method::Sequential},
            {"batch", Method::Batch},
            {"circumcircle", Method::Circumcircle},
            {"strips", Method::Strips}};
}

std::vector<std::string> splitList(const std::string& list, const char* option) {
    std::vector<std::string> items;
    std::stringstream stream(list);
    std::string item;
    while (std::getline(stream, item, ','))
        if (!item.empty())
            items.push_back(item);
    if (items.empty())
        throw UsageError(std::string(option) + " needs at least one value");
    return items;
}

// A count of at least `minimum`, optionally with a k (thousand) or M (million) suffix: "1000",
// "10k", "1M".
std::size_t parseCount(const std::string& text, const char* option, std::size_t minimum) {
    std::size_t value = 0;
    const char* end = text.data() + text.size();
    const auto [rest, error] = std::from_chars(text.data(), end, value);
    std::size_t multiplier = 1;
    if (rest + 1 == end && (*rest == 'k' || *rest == 'K'))
        multiplier = 1'000;
    else if (rest + 1 == end && (*rest == 'm' || *rest == 'M'))
        multiplier = 1'000'000;
    else if (rest != end)
        value = 0;
    if (error != std::errc() || value * multiplier < minimum ||
        value > std::numeric_limits<std::uint32_t>::max() / multiplier)
        throw UsageError(std::string(option) + " takes integers from " + std::to_string(minimum) +
                         " to below 2^32 (got '" + text + "')");
    return value * multiplier;
}

// 1, 2, 4, ... up to the hardware threads, and the hardware threads themselves: 1,2 on two
// cores, 1,2,4,8,16 on sixteen.
std::vector<unsigned> defaultThreads() {
    const unsigned hardware = std::max(2U, std::thread::hardware_concurrency());
    std::vector<unsigned> threads;
    for (unsigned count = 1; count < hardware; count *= 2)
        threads.push_back(count);
    threads.push_back(hardware);
    return threads;
}

po::options_description benchOptionsDescription() {
    po::options_description options("Options of terratin-bench");
    // clang-format off
    options.add_options()
        ("sizes", po::value<std::string>()->value_name("N,N,..."),
         "point counts (k and M suffixes allowed; default 1000,10000,100000,1000000)")
        ("large", "add 10,000,000 points to the sizes")
        ("distributions", po::value<std::string>()->value_name("LIST"),
         "uniform,gauss,cluster,grid,arc (default: all)")
        ("methods", po::value<std::string>()->value_name("LIST"),
         "terratin methods (default: sequential,batch,circumcircle,strips)")
        ("threads", po::value<std::string>()->value_name("T,T,..."),
         "thread counts of the parallel methods (default: 1,2,4,... up to the hardware's)")
        ("runs", po::value<unsigned>()->default_value(5)->value_name("R"),
         "timed runs per configuration; the median is reported")
        ("seed", po::value<std::uint64_t>()->default_value(1)->value_name("S"),
         "seed of the point sets and of the insertion order")
        ("order", po::value<std::string>()->default_value("brio")->value_name("brio|random"),
         "insertion order of terratin's methods")
        ("locate", po::value<std::string>()->default_value("dag,walk")->value_name("LIST"),
         "point location of terratin's methods: dag, walk or both")
        ("searchers", po::value<unsigned>()->default_value(0)->value_name("K"),
         "batch method: searching threads (0: chosen from points and threads)")
        ("queue-length", po::value<std::size_t>()
             ->default_value(TriangulationOptions{}.queueLength)->value_name("L"),
         "batch method: capacity of the queue to the inserting thread")
        ("help-when-full", "batch method: searchers finish queued locations on a full queue")
        ("peer-limit", po::value<double>()->default_value(10.0)->value_name("SECONDS"),
         "a CGAL or GDAL run longer than this (or that would be, extrapolated linearly from the "
         "previous size) is not repeated, nor run at larger sizes of "
         "that distribution")
        ("no-cgal", "do not run CGAL")
        ("no-gdal", "do not run GDAL (slow and memory-hungry above a few million points)")
        ("no-warm-memory", "time each run on whatever memory it gets, without first touching "
                           "as much fresh memory as the previous run used (which takes a "
                           "hypervisor's cost of first touch out of the timer)")
        ("csv", "print comma-separated rows instead of the table")
        ("refine", "terrain refinement table instead: N44W072 at E = 1, 5, 10 m and Mt Hood at "
                   "E = 1, 5 m (points, triangles, achieved max error, seconds per thread count)")
        ("write", "output table instead: Mt Hood in every format and N44W072 at --max-error 1 "
                  "as a GeoPackage, end to end, against a GDAL + CGAL + OGR script, a plain OGR "
                  "loop and the SQLite bound")
        ("formats", po::value<std::string>()->value_name("LIST"),
         "--write: the formats to time, of gpkg,fgb,shp,ply,2dm,obj,xml (default: all); the "
         "GeoPackage peers and N44W072 come with gpkg, the GDAL minimal loops with shp and fgb")
        ("dems", po::value<std::string>()->default_value("../shared/dems")->value_name("DIR"),
         "--refine, --write: folder of the shared DEMs")
        ("help,h", "show this help");
    // clang-format on
    return options;
}

std::string helpText(const po::options_description& options) {
    std::ostringstream text;
    text << kUsage << "\n" << kDescription << "\n" << options;
    return text.str();
}

std::vector<std::size_t> parseSizes(const po::variables_map& values) {
    std::vector<std::size_t> sizes{1'000, 10'000, 100'000, 1'000'000};
    if (values.count("sizes")) {
        sizes.clear();
        for (const std::string& item : splitList(values["sizes"].as<std::string>(), "--sizes"))
            sizes.push_back(parseCount(item, "--sizes", kMinimumPoints));
    }
    if (values.count("large"))
        sizes.push_back(kLargeSize);
    // Ascending, so that a peer too slow at one size is known before the larger ones.
    std::sort(sizes.begin(), sizes.end());
    sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
    return sizes;
}

std::vector<Distribution> parseDistributions(const po::variables_map& values) {
    if (!values.count("distributions"))
        return {std::begin(kAllDistributions), std::end(kAllDistributions)};
    std::vector<Distribution> distributions;
    for (const std::string& item :
         splitList(values["distributions"].as<std::string>(), "--distributions")) {
        const std::optional<Distribution> distribution = parseDistribution(lowercase(item));
        if (!distribution)
            throw UsageError("--distributions: unknown distribution '" + item +
                             "' (uniform, gauss, cluster, grid, arc)");
        distributions.push_back(*distribution);
    }
    return distributions;
}

std::vector<unsigned> parseThreads(const po::variables_map& values) {
    if (!values.count("threads"))
        return defaultThreads();
    std::vector<unsigned> threads;
    for (const std::string& item : splitList(values["threads"].as<std::string>(), "--threads"))
        threads.push_back(static_cast<unsigned>(parseCount(item, "--threads", 1)));
    return threads;
}

InsertionOrder parseOrder(const std::string& name) {
    const std::string key = lowercase(name);
    if (key == "brio")
        return InsertionOrder::Brio;
    if (key == "random")
        return InsertionOrder::Random;
    throw UsageError("--order must be brio or random (got '" + name + "')");
}

std::vector<PointLocation> parseLocations(const std::string& list) {
    std::vector<PointLocation> locations;
    for (const std::string& item : splitList(list, "--locate")) {
        const std::string key = lowercase(item);
        if (key == "dag")
            locations.push_back(PointLocation::Dag);
        else if (key == "walk")
            locations.push_back(PointLocation::Walk);
        else
            throw UsageError("--locate takes dag and walk (got '" + item + "')");
    }
    return locations;
}

} // namespace

const std::vector<NamedMethod>& benchMethods() {
    static const std::vector<NamedMethod> methods = methodTable();
    return methods;
}

NamedMethod parseMethod(std::string_view name) {
    const std::string key = lowercase(name);
    std::string known;
    for (const NamedMethod& method : benchMethods()) {
        if (method.name == key)
            return method;
        known += (known.empty() ? "" : ", ") + std::string(method.name);
    }
    throw UsageError("--methods: '" + std::string(name) + "' is not a method of this build (" +
                     known + ")");
}

namespace {

po::variables_map parseArguments(const std::vector<std::string>& arguments,
                                 const po::options_description& options) {
    po::variables_map values;
    try {
        // No positional arguments: without this empty description Boost ignores them.
        const po::positional_options_description noPositionals;
        po::store(
            po::command_line_parser(arguments).options(options).positional(noPositionals).run(),
            values);
        po::notify(values);
    } catch (const po::error& error) {
        throw UsageError(error.what());
    }
    return values;
}

// What the triangulation table runs: the points, the configurations and the peers.
void readTriangulationRuns(const po::variables_map& values, BenchOptions& bench) {
    bench.sizes = parseSizes(values);
    bench.distributions = parseDistributions(values);
    if (values.count("methods")) {
        for (const std::string& item : splitList(values["methods"].as<std::string>(), "--methods"))
            bench.methods.push_back(parseMethod(item));
    } else {
        bench.methods = benchMethods();
    }
    bench.threads = parseThreads(values);
    bench.runs = values["runs"].as<unsigned>();
    if (bench.runs == 0)
        throw UsageError("--runs must be at least 1");
    bench.seed = values["seed"].as<std::uint64_t>();
    bench.order = parseOrder(values["order"].as<std::string>());
    bench.locations = parseLocations(values["locate"].as<std::string>());
    bench.searchers = values["searchers"].as<unsigned>();
    bench.queueLength = values["queue-length"].as<std::size_t>();
    if (bench.queueLength == 0)
        throw UsageError("--queue-length must be at least 1");
    bench.helpWhenFull = values.count("help-when-full") != 0;
    bench.peerLimitSeconds = values["peer-limit"].as<double>();
    if (!(bench.peerLimitSeconds > 0.0))
        throw UsageError("--peer-limit must be a positive number of seconds");
    bench.runCgal = values.count("no-cgal") == 0;
    bench.runGdal = values.count("no-gdal") == 0;
    bench.warmMemory = values.count("no-warm-memory") == 0;
}

// Which table, in which form, and the other tables' own options.
void readTableChoice(const po::variables_map& values, BenchOptions& bench) {
    bench.csv = values.count("csv") != 0;
    bench.refine = values.count("refine") != 0;
    bench.write = values.count("write") != 0;
    if (values.count("formats")) {
        const std::vector<std::string> known = bench.writeFormats;
        bench.writeFormats.clear();
        for (const std::string& item :
             splitList(values["formats"].as<std::string>(), "--formats")) {
            if (std::find(known.begin(), known.end(), item) == known.end())
                throw UsageError("--formats: unknown format '" + item +
                                 "' (gpkg, fgb, shp, ply, 2dm, obj, xml)");
            bench.writeFormats.push_back(item);
        }
    }
    if (bench.refine && bench.write)
        throw UsageError("--refine and --write are two different tables: choose one");
    bench.demDirectory = values["dems"].as<std::string>();
    bench.threadsGiven = values.count("threads") != 0;
}

} // namespace

BenchCommand parseBenchCommandLine(const std::vector<std::string>& arguments) {
    const po::options_description options = benchOptionsDescription();
    const po::variables_map values = parseArguments(arguments, options);
    BenchCommand command;
    if (values.count("help")) {
        command.kind = BenchCommand::Kind::Help;
        command.helpText = helpText(options);
        return command;
    }
    readTriangulationRuns(values, command.options);
    readTableChoice(values, command.options);
    return command;
}

} // namespace terratin::bench
