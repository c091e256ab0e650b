// terratin-lazrepeat: a large LAZ file for benchmarking the LAZ reader, made from a real one
// by repeating its chunks (see laz_repeat.hpp), and optionally its uncompressed LAS twin.
//
//   terratin-lazrepeat IN.laz OUT.laz COPIES [--las OUT.las] [--overwrite]
//
// Exit status: 0 done, 1 an input that cannot be repeated or a file that cannot be written
// (one line on stderr), 2 a usage error.

#include "laz_repeat.hpp"

#include "terratin/error.hpp"

#include <charconv>
#include <chrono>
#include <cstdio>
#include <exception>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace {

constexpr int kUsageError = 2;
constexpr const char* kUsage =
    "usage: terratin-lazrepeat IN.laz OUT.laz COPIES [--las OUT.las] [--overwrite]\n"
    "  Writes OUT.laz: IN.laz's chunks COPIES times (COPIES x its points), and with --las\n"
    "  its uncompressed LAS twin. Existing outputs are kept unless --overwrite is given.\n";

struct UsageError {
    std::string message;
};

std::uint32_t parseCopies(std::string_view text) {
    std::uint32_t copies = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), copies);
    if (error != std::errc{} || end != text.data() + text.size() || copies == 0)
        throw UsageError{"COPIES must be a whole number from 1 to 4294967295, not '" +
                         std::string(text) + "'"};
    return copies;
}

/// The request the command line makes; nullopt for --help.
std::optional<terratin::lazrepeat::RepeatRequest> parseArguments(int argc, char** argv) {
    terratin::lazrepeat::RepeatRequest request;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "--help" || arg == "-h")
            return std::nullopt;
        if (arg == "--overwrite") {
            request.overwrite = true;
        } else if (arg == "--las") {
            if (i + 1 == argc)
                throw UsageError{"--las needs the path of the LAS output"};
            request.lasTwin = argv[++i];
        } else if (arg.size() > 1 && arg.front() == '-') {
            throw UsageError{"unknown option '" + std::string(arg) + "'"};
        } else {
            positional.emplace_back(arg);
        }
    }
    if (positional.size() != 3)
        throw UsageError{"expected IN.laz OUT.laz COPIES, got " +
                         std::to_string(positional.size()) + " arguments"};
    request.input = positional[0];
    request.output = positional[1];
    request.copies = parseCopies(positional[2]);
    return request;
}

void printSummary(const terratin::lazrepeat::RepeatRequest& request,
                  const terratin::lazrepeat::RepeatSummary& summary, double seconds) {
    std::printf("%s: %u copies of %llu points in %llu chunks: %llu points in %llu chunks, "
                "%llu bytes\n",
                request.output.string().c_str(), request.copies,
                static_cast<unsigned long long>(summary.inputPoints),
                static_cast<unsigned long long>(summary.inputChunks),
                static_cast<unsigned long long>(summary.points),
                static_cast<unsigned long long>(summary.chunks),
                static_cast<unsigned long long>(summary.lazBytes));
    if (request.lasTwin)
        std::printf("%s: its LAS twin, %llu bytes\n", request.lasTwin->string().c_str(),
                    static_cast<unsigned long long>(summary.lasBytes));
    std::printf("done in %.2f s\n", seconds);
}

} // namespace

int main(int argc, char** argv) {
    std::optional<terratin::lazrepeat::RepeatRequest> request;
    try {
        request = parseArguments(argc, argv);
    } catch (const UsageError& error) {
        std::fprintf(stderr, "terratin-lazrepeat: %s\n%s", error.message.c_str(), kUsage);
        return kUsageError;
    }
    if (!request) {
        std::printf("%s", kUsage);
        return 0;
    }
    try {
        const auto start = std::chrono::steady_clock::now();
        const terratin::lazrepeat::RepeatSummary summary = terratin::lazrepeat::repeatLaz(*request);
        printSummary(
            *request, summary,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        return 0;
    } catch (terratin::Error& error) {
        error.nameOptions([](std::string_view keyword) { return "--" + std::string(keyword); });
        std::fprintf(stderr, "%s\n", error.what());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "terratin-lazrepeat: out of memory\n");
    } catch (const std::exception& error) {
        std::fprintf(stderr, "terratin-lazrepeat: %s\n", error.what());
    }
    return 1;
}
