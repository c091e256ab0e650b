// terratin-readbench: reader throughput, as a table. Each file is read --runs times through
// io::readInput (the pipeline's reader dispatch); the median wall time of a run gives points/s
// and MB/s. Run it on a quiet machine, on files in the page cache (the first, untimed warm-up
// read puts them there), so that the parser is measured, not the disk.
//
//   terratin-readbench [--runs N] FILE...

#include "terratin/error.hpp"
#include "terratin/io/input_reader.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    int runs = 5;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--runs" && i + 1 < argc) {
            runs = std::max(1, std::atoi(argv[++i]));
        } else if (arg == "--help" || arg == "-h") {
            std::printf("usage: terratin-readbench [--runs N] FILE...\n");
            return 0;
        } else {
            files.push_back(arg);
        }
    }
    if (files.empty()) {
        std::fprintf(stderr, "usage: terratin-readbench [--runs N] FILE...\n");
        return 2;
    }

    std::printf("%-40s %-7s %12s %10s %14s %10s\n", "file", "kind", "points", "median s",
                "points/s", "MB/s");
    for (const std::string& file : files) {
        try {
            const double megabytes =
                static_cast<double>(std::filesystem::file_size(file)) / (1024.0 * 1024.0);
            std::size_t points = 0;
            std::string kind;
            {
                const terratin::io::PointCloud warmUp = terratin::io::readInput(file);
                points = warmUp.points.size();
                kind = terratin::io::toString(warmUp.kind);
            }
            std::vector<double> seconds;
            for (int run = 0; run < runs; ++run) {
                const auto start = std::chrono::steady_clock::now();
                const terratin::io::PointCloud cloud = terratin::io::readInput(file);
                seconds.push_back(
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                        .count());
                if (cloud.points.size() != points)
                    throw terratin::Error("the point count changed between runs");
            }
            std::sort(seconds.begin(), seconds.end());
            const double median = seconds[seconds.size() / 2];
            std::printf("%-40s %-7s %12zu %10.4f %14.0f %10.1f\n",
                        std::filesystem::path(file).filename().c_str(), kind.c_str(), points,
                        median, static_cast<double>(points) / median, megabytes / median);
        } catch (const std::exception& error) {
            std::fprintf(stderr, "%s: %s\n", file.c_str(), error.what());
            return 1;
        }
    }
    return 0;
}
