// terratin: DEM -> exactly Delaunay TIN, on the command line. A thin layer over runBuild.

#include "cli_options.hpp"
#include "progress_printer.hpp"

#include "terratin/error.hpp"
#include "terratin/pipeline/build_pipeline.hpp"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;
constexpr int kExitUsage = 2;

std::atomic<bool> g_cancelRequested{false};

// Ctrl-C asks the run to stop at the next progress report, so the writer can remove its
// temporary file instead of leaving it behind.
extern "C" void requestCancel(int) { g_cancelRequested.store(true); }

int runBuildCommand(const terratin::cli::Command& command) {
    terratin::cli::ProgressPrinter printer(stderr, g_cancelRequested);
    try {
        // Even a quiet run needs the callback: it is how Ctrl-C reaches the pipeline.
        terratin::ProgressCallback progress =
            command.quiet ? terratin::ProgressCallback([](double, std::string_view) {
                return !g_cancelRequested.load();
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
        if (command.json) {
            std::printf("%s\n", terratin::toJson(report).c_str());
            if (!command.quiet)
                std::fprintf(stderr, "%s%s\n", terratin::toInputSummary(report).c_str(),
                             terratin::toSummaryLine(report).c_str());
        } else if (!command.quiet) {
            std::printf("%s%s\n", terratin::toInputSummary(report).c_str(),
                        terratin::toSummaryLine(report).c_str());
        }
        return kExitOk;
    } catch (const terratin::Error& error) {
        printer.breakLine();
        std::fprintf(stderr, "terratin: %s\n", error.what());
    } catch (const std::bad_alloc&) {
        printer.breakLine();
        std::fprintf(stderr, "terratin: out of memory\n");
    } catch (const std::exception& error) {
        printer.breakLine();
        std::fprintf(stderr, "terratin: unexpected error: %s\n", error.what());
    }
    return kExitError;
}

} // namespace

int main(int argc, char** argv) {
    std::signal(SIGINT, requestCancel);
    std::signal(SIGTERM, requestCancel);
    terratin::cli::Command command;
    try {
        command = terratin::cli::parseCommandLine(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const terratin::cli::UsageError& error) {
        std::fprintf(stderr, "terratin: %s\n", error.what());
        return kExitUsage;
    }
    switch (command.kind) {
    case terratin::cli::Command::Kind::Help:
        std::printf("%s", command.helpText.c_str());
        return kExitOk;
    case terratin::cli::Command::Kind::Version:
        std::printf("terratin %s\n", TERRATIN_VERSION);
        return kExitOk;
    case terratin::cli::Command::Kind::Build:
        return runBuildCommand(command);
    }
    return kExitUsage;
}
