// terratin: DEM -> exactly Delaunay TIN, on the command line. A thin layer over runBuild.

#include "cancel_signals.hpp"
#include "cli_options.hpp"
#include "mpi_launch.hpp"
#if defined(TERRATIN_WITH_MPI)
#include "mpi_tiles.hpp"
#endif
#include "progress_printer.hpp"

#include "terratin/error.hpp"
#include "terratin/io/library_versions.hpp"
#include "terratin/pipeline/build_pipeline.hpp"
#include "terratin/version.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;
constexpr int kExitUsage = 2;

// One line on stderr whatever the message holds (a GDAL message may carry newlines).
void printError(const std::string& text) {
    std::string line = "terratin: " + text;
    for (char& ch : line)
        if (ch == '\n' || ch == '\r')
            ch = ' ';
    std::fprintf(stderr, "%s\n", line.c_str());
}

// Writes `text` and a newline to stdout. The report is the run's result: one that cannot be
// written (a full disk, a closed pipe) is an error, not a silent success.
bool writeReport(const std::string& text) {
    if (text.empty())
        return true;
    errno = 0;
    if (std::fputs(text.c_str(), stdout) >= 0 && std::fputc('\n', stdout) != EOF &&
        std::fflush(stdout) == 0)
        return true;
    const int error = errno;
    printError(std::string("cannot write the report to standard output: ") +
               (error != 0 ? std::strerror(error) : "write error"));
    return false;
}

// `onFailure` runs before the error is printed (rank 0 of an MPI run releases the others).
int runBuildCommand(const terratin::cli::Command& command,
                    const std::function<void()>& onFailure = {}) {
    terratin::cli::ProgressPrinter printer(stderr, terratin::cli::cancelledBySignal());
    const auto fail = [&](const std::string& message) {
        if (onFailure)
            onFailure();
        printer.fail();
        printError(message);
    };
    try {
        // Even a quiet run needs the callback: it is how Ctrl-C reaches the pipeline.
        terratin::ProgressCallback progress =
            command.quiet ? terratin::ProgressCallback([](double, std::string_view) {
                return !terratin::cli::cancelledBySignal().load();
            })
                          : printer.callback();
        terratin::BuildOptions build = command.build;
        if (!command.quiet)
            build.notice = [&printer](std::string_view text) {
                printer.printLine("terratin: notice: " + std::string(text));
            };
        const terratin::BuildReport report = terratin::runBuild(build, progress);
        if (!command.quiet)
            printer.finish();
        // The summary goes to stdout, or to stderr when stdout carries the JSON report.
        const std::string summary =
            terratin::toInputSummary(report) + terratin::toSummaryLine(report);
        if (command.json && !command.quiet)
            std::fprintf(stderr, "%s\n", summary.c_str());
        const std::string result =
            command.json ? terratin::toJson(report) : (command.quiet ? std::string() : summary);
        return writeReport(result) ? kExitOk : kExitError;
    } catch (const terratin::Error& error) {
        fail(error.what());
    } catch (const std::bad_alloc&) {
        fail("out of memory");
    } catch (const std::exception& error) {
        fail(std::string("unexpected error: ") + error.what());
    }
    return kExitError;
}

#if defined(TERRATIN_WITH_MPI)
// A rank other than 0: reads the DEM and refines the tiles rank 0 hands it; prints nothing
// (rank 0 reports for the run, a failure here included).
int serveTiles(const terratin::cli::Command& command, terratin::cli::MpiTiles& tiles) {
    try {
        const terratin::ProgressCallback keepGoing = [](double, std::string_view) {
            return !terratin::cli::cancelledBySignal().load();
        };
        terratin::runBuild(command.build, keepGoing);
        return kExitOk;
    } catch (const std::exception& error) {
        tiles.abandon(error.what());
    }
    return kExitError;
}

int runDistributedBuild(terratin::cli::Command command, int& argc, char**& argv) {
    const terratin::cli::MpiSession session(argc, argv);
    terratin::cli::MpiTiles tiles(session);
    command.build.tileDistribution = &tiles;
    if (!tiles.coordinates())
        return serveTiles(command, tiles);
    return runBuildCommand(command, [&tiles] { tiles.releaseAll(); });
}
#else
int runDistributedBuild(const terratin::cli::Command&, int&, char**&) {
    const terratin::cli::MpiLaunch launch = terratin::cli::mpiLaunch();
    if (launch.rank == 0)
        printError("started by mpirun as " + std::to_string(launch.size) +
                   " processes, but this terratin was built without MPI (install "
                   "libopenmpi-dev and build again)");
    return kExitError;
}
#endif

} // namespace

int main(int argc, char** argv) {
    terratin::cli::installCancelSignals();
    // Under mpirun every rank parses the same command line; rank 0 alone speaks.
    const terratin::cli::MpiLaunch launch = terratin::cli::mpiLaunch();
    const bool speaks = launch.rank == 0;
    terratin::cli::Command command;
    try {
        command = terratin::cli::parseCommandLine(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const terratin::cli::UsageError& error) {
        if (speaks)
            printError(error.what());
        return kExitUsage;
    }
    switch (command.kind) {
    case terratin::cli::Command::Kind::Help:
        if (speaks)
            std::printf("%s", command.helpText.c_str());
        return kExitOk;
    case terratin::cli::Command::Kind::Version:
        if (speaks)
            std::printf("terratin %s\n%s\n", terratin::version(),
                        terratin::io::libraryVersions().c_str());
        return kExitOk;
    case terratin::cli::Command::Kind::Formats:
        if (speaks)
            std::printf("%s", command.helpText.c_str());
        return kExitOk;
    case terratin::cli::Command::Kind::Build:
        return launch.size > 1 ? runDistributedBuild(command, argc, argv)
                               : runBuildCommand(command);
    }
    return kExitUsage;
}
