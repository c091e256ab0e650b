#pragma once
/// @file
/// A large valid LAZ file made from a real one, for benchmarking the LAZ reader: the chunks
/// of a chunked LAZ file (compressors 2 and 3) decode independently of each other, so the
/// input's chunks repeated `copies` times, behind the input's header and VLRs with the point
/// counts multiplied, make a LAZ file of copies x its points (the same points over and over,
/// so the bounds stay). The chunk table is written anew with variable chunk sizes, which
/// holds whatever the input's last chunk is; the EVLRs follow it with their offset moved.
///
/// Optionally the uncompressed LAS twin of the result: the same header and VLRs without the
/// LASzip VLR, the input's points decoded by the project's LAZ decoder, `copies` times, then
/// the EVLRs.
///
/// Memory: the input's compressed chunks, and for the twin its decoded records, are held
/// once; the outputs are written as they go.

#include <cstdint>
#include <filesystem>
#include <optional>

namespace terratin::lazrepeat {

struct RepeatRequest {
    std::filesystem::path input;
    std::filesystem::path output;
    /// At least 1.
    std::uint32_t copies = 1;
    /// Where to write the uncompressed twin, if anywhere.
    std::optional<std::filesystem::path> lasTwin;
    /// Replace outputs that exist; without it they are refused before anything is read.
    bool overwrite = false;
};

struct RepeatSummary {
    std::uint64_t inputPoints = 0;
    std::uint64_t inputChunks = 0;
    std::uint64_t points = 0;
    std::uint64_t chunks = 0;
    std::uint64_t lazBytes = 0;
    /// 0 without a twin.
    std::uint64_t lasBytes = 0;
};

/// Writes the repeated file (and its twin), each under a temporary name in its directory,
/// renamed into place only when complete, so a failure leaves no partial output.
/// Throws InvalidInputError (one line naming the file) for an input that is no LAZ file or
/// one that cannot be repeated: an unchunked compressor (0, 1), no points, a COPC file, more
/// points or chunks than the header or the chunk table can count, and for the twin a point
/// layout the decoder does not decode; InvalidInputError for an output that exists without
/// `overwrite` or that is the input; IoError when a file cannot be read or written.
RepeatSummary repeatLaz(const RepeatRequest& request);

} // namespace terratin::lazrepeat
