// terratin-lazbench: reading LAZ against its uncompressed LAS twin, as a table. For each pair
// the LAS file and the LAZ file at each thread count are read in turn, round after round
// (interleaved, so a machine whose speed drifts slows all of them alike), and the medians
// give the ratios the LAZ reader is judged by: LAZ time / LAS time, and the speed-up of the
// LAZ read from one thread to more. By default the files sit in the page cache (an untimed
// warm-up read of each puts them there), so that decoding is measured against parsing; with
// --cold the page cache is dropped before every read (root only), so that each read starts
// from the disk, as a user's first read of a file does.
//
//   terratin-lazbench [--runs N] [--threads 1,2] [--cold] LAS LAZ [LAS LAZ...]

#include "terratin/error.hpp"
#include "terratin/io/las_reader.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

struct Arguments {
    int runs = 7;
    std::vector<unsigned> threads{1, 2};
    bool cold = false;
    std::vector<std::string> files;
};

constexpr const char* kUsage =
    "usage: terratin-lazbench [--runs N] [--threads 1,2] [--cold] LAS LAZ [LAS LAZ...]\n";

std::vector<unsigned> parseThreads(const std::string& text) {
    std::vector<unsigned> threads;
    std::stringstream stream(text);
    for (std::string item; std::getline(stream, item, ',');)
        threads.push_back(static_cast<unsigned>(std::max(1, std::atoi(item.c_str()))));
    return threads;
}

bool parseArguments(int argc, char** argv, Arguments& arguments) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--runs" && i + 1 < argc)
            arguments.runs = std::max(1, std::atoi(argv[++i]));
        else if (arg == "--threads" && i + 1 < argc)
            arguments.threads = parseThreads(argv[++i]);
        else if (arg == "--cold")
            arguments.cold = true;
        else
            arguments.files.push_back(arg);
    }
    return !arguments.files.empty() && arguments.files.size() % 2 == 0 &&
           !arguments.threads.empty();
}

/// Empties the page cache, so that the next read comes from the disk.
void dropPageCache() {
    ::sync();
    std::FILE* control = std::fopen("/proc/sys/vm/drop_caches", "w");
    if (control == nullptr || std::fputs("1", control) < 0 || std::fclose(control) != 0)
        throw terratin::Error("--cold: cannot write /proc/sys/vm/drop_caches (root only)");
}

/// Seconds to read `path` on `threads` threads (from the disk when `cold`); the point count
/// goes to `points`.
double timedRead(const std::string& path, unsigned threads, bool cold, std::size_t& points) {
    if (cold)
        dropPageCache();
    terratin::io::LasReadOptions options;
    options.threads = threads;
    const auto start = std::chrono::steady_clock::now();
    const terratin::io::PointCloud cloud = terratin::io::readLasPoints(path, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    points = cloud.points.size();
    return seconds;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

/// One pair's row: the LAS median, then the LAZ median, ratio and points/s per thread count.
void benchPair(const std::string& las, const std::string& laz, const Arguments& arguments) {
    std::size_t lasPoints = 0;
    std::size_t lazPoints = 0;
    (void)timedRead(las, 1, false, lasPoints); // warm-up: into the page cache
    (void)timedRead(laz, 1, false, lazPoints);
    if (lasPoints != lazPoints)
        throw terratin::Error(las + " and " + laz + " give different point counts");
    std::vector<double> lasTimes;
    std::vector<std::vector<double>> lazTimes(arguments.threads.size());
    for (int run = 0; run < arguments.runs; ++run) {
        std::size_t points = 0;
        lasTimes.push_back(timedRead(las, 1, arguments.cold, points));
        for (std::size_t t = 0; t < arguments.threads.size(); ++t)
            lazTimes[t].push_back(timedRead(laz, arguments.threads[t], arguments.cold, points));
    }
    const double lasMedian = median(lasTimes);
    std::printf("| %s | %zu | %.4f |", std::filesystem::path(laz).filename().c_str(), lasPoints,
                lasMedian);
    const double firstLaz = median(lazTimes.front());
    for (std::size_t t = 0; t < arguments.threads.size(); ++t) {
        const double lazMedian = median(lazTimes[t]);
        std::printf(" %.4f | %.2f | %.1f M/s | %.2f |", lazMedian, lazMedian / lasMedian,
                    static_cast<double>(lazPoints) / lazMedian / 1e6, firstLaz / lazMedian);
    }
    std::printf("\n");
    std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv) {
    Arguments arguments;
    if (!parseArguments(argc, argv, arguments)) {
        std::fputs(kUsage, stderr);
        return 2;
    }
    std::printf("| LAZ | points | LAS s |");
    for (const unsigned threads : arguments.threads)
        std::printf(" LAZ s (%u thr) | LAZ/LAS | LAZ points/s | speed-up |", threads);
    std::printf("\n|---|---|---|");
    for (std::size_t t = 0; t < arguments.threads.size(); ++t)
        std::printf("---|---|---|---|");
    std::printf("\n");
    for (std::size_t i = 0; i < arguments.files.size(); i += 2) {
        try {
            benchPair(arguments.files[i], arguments.files[i + 1], arguments);
        } catch (const std::exception& error) {
            std::fprintf(stderr, "terratin-lazbench: %s\n", error.what());
            return 1;
        }
    }
    return 0;
}
