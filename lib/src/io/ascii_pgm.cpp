#include "ascii_pgm.hpp"

#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <vector>

namespace terratin::io::detail {

namespace {

/// Netpbm's largest maxval: samples are at most 16 bits.
constexpr std::uint64_t kMaxSampleValue = 65535;

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};

/// A byte for a message: "'x'" when printable, "byte 0x01" otherwise.
std::string describeByte(int c) {
    if (c >= 0x20 && c < 0x7F)
        return std::string("'") + static_cast<char>(c) + "'";
    constexpr const char* kHex = "0123456789abcdef";
    const auto byte = static_cast<unsigned>(c) & 0xFFu;
    return std::string("byte 0x") + kHex[byte >> 4] + kHex[byte & 0xFu];
}

bool isSpace(int c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/// Decimal unsigned numbers from a plain PGM, skipping whitespace and comments.
class TokenReader {
public:
    explicit TokenReader(std::FILE* file) : m_file(file) {}

    /// The next number; nullopt at the end of the file. Throws the caller's message, through
    /// `fail`, for anything else than digits (or a number above 2^32).
    template <class Fail> std::optional<std::uint64_t> next(const Fail& fail) {
        int c = skipSpaceAndComments();
        if (c == EOF)
            return std::nullopt;
        if (c < '0' || c > '9')
            fail(describeByte(c) + " where a number was expected");
        std::uint64_t value = 0;
        while (c >= '0' && c <= '9') {
            value = value * 10 + static_cast<std::uint64_t>(c - '0');
            if (value > std::numeric_limits<std::uint32_t>::max())
                fail("a number above 4294967295");
            c = getc_unlocked(m_file);
        }
        if (c != EOF && !isSpace(c) && c != '#')
            fail(describeByte(c) + " inside a number");
        if (c == '#')
            ungetc(c, m_file);
        return value;
    }

private:
    int skipSpaceAndComments() {
        for (;;) {
            int c = getc_unlocked(m_file);
            if (c == '#') {
                while (c != '\n' && c != EOF)
                    c = getc_unlocked(m_file);
            }
            if (c == EOF || !isSpace(c))
                return c;
        }
    }

    std::FILE* m_file;
};

} // namespace

bool isAsciiPgm(std::string_view start) {
    return start.size() >= 3 && start[0] == 'P' && start[1] == '2' && isSpace(start[2]);
}

namespace {

/// A plain PGM's header.
struct PgmHeader {
    std::uint64_t width = 0;
    std::uint64_t height = 0;
    std::uint64_t maxValue = 0;
};

/// Width, height and maxval after the signature, checked against each other and against the
/// file's `fileSize` bytes; `fail(what)` throws.
template <class Fail>
PgmHeader readHeader(TokenReader& tokens, std::uint64_t fileSize, const Fail& fail) {
    std::uint64_t header[3] = {0, 0, 0};
    const char* const names[3] = {"width", "height", "maxval"};
    for (int i = 0; i < 3; ++i) {
        const std::optional<std::uint64_t> value =
            tokens.next([&](const std::string& what) { fail("header: " + what); });
        if (!value || *value == 0)
            fail(std::string("header: no ") + names[i] + " above 0");
        header[i] = *value;
    }
    const PgmHeader h{header[0], header[1], header[2]};
    if (h.maxValue > kMaxSampleValue)
        fail("maxval " + std::to_string(h.maxValue) + " is above 65535");
    if (h.width > static_cast<std::uint64_t>(std::numeric_limits<int>::max()) ||
        h.height > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        fail(std::to_string(h.width) + " x " + std::to_string(h.height) +
             " cells: a side above 2^31 - 1");
    // Each sample takes at least two bytes (a digit and a separator, the last one a digit): a
    // header that declares more cannot be honest, and is refused before any allocation.
    if (h.width * h.height > fileSize / 2 + 1)
        fail("truncated: the header declares " + std::to_string(h.width) + " x " +
             std::to_string(h.height) + " samples but the file has " + std::to_string(fileSize) +
             " bytes");
    return h;
}

/// The samples the header declares, each at most its maxval; `fail(what)` throws.
template <class Fail>
std::vector<std::uint16_t> readSamples(TokenReader& tokens, const PgmHeader& h, const Fail& fail) {
    const std::uint64_t cells = h.width * h.height;
    std::vector<std::uint16_t> samples;
    try {
        samples.resize(static_cast<std::size_t>(cells));
    } catch (const std::bad_alloc&) {
        fail(std::to_string(h.width) + " x " + std::to_string(h.height) +
             " cells, too many to hold in memory");
    }
    for (std::uint64_t i = 0; i < cells; ++i) {
        const std::optional<std::uint64_t> value = tokens.next([&](const std::string& what) {
            fail("sample " + std::to_string(i + 1) + ": " + what);
        });
        if (!value)
            fail("truncated: " + std::to_string(i) + " of the " + std::to_string(cells) +
                 " samples the header declares");
        if (*value > h.maxValue)
            fail("sample " + std::to_string(i + 1) + " is " + std::to_string(*value) +
                 ", above the maxval " + std::to_string(h.maxValue));
        samples[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(*value);
    }
    return samples;
}

/// A one-band UInt16 MEM dataset of the samples (which GDAL copies).
GDALDatasetH memoryDataset(std::vector<std::uint16_t>& samples, const PgmHeader& h,
                           std::string_view stage, const std::string& path) {
    initialiseGdal();
    CPLErrorReset();
    GDALDriverH memory = GDALGetDriverByName("MEM");
    const auto xSize = static_cast<int>(h.width);
    const auto ySize = static_cast<int>(h.height);
    GDALDatasetH dataset =
        memory != nullptr ? GDALCreate(memory, "", xSize, ySize, 1, GDT_UInt16, nullptr) : nullptr;
    if (dataset == nullptr)
        throwGdalError(stage, "cannot hold in memory the plain PGM", path,
                       "the MEM driver is missing or out of memory");
    if (GDALRasterIO(GDALGetRasterBand(dataset, 1), GF_Write, 0, 0, xSize, ySize, samples.data(),
                     xSize, ySize, GDT_UInt16, 0, 0) != CE_None) {
        GDALClose(dataset);
        throwGdalError(stage, "cannot hold in memory the plain PGM", path);
    }
    return dataset;
}

} // namespace

GDALDatasetH openAsciiPgm(const std::string& path, std::string_view stage) {
    const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw IoError(std::string(stage) + ": cannot open '" + path + "': " + std::strerror(errno));
    std::uint64_t fileSize = 0;
    if (fseeko(file.get(), 0, SEEK_END) == 0) {
        fileSize = static_cast<std::uint64_t>(std::max<off_t>(ftello(file.get()), 0));
        fseeko(file.get(), 0, SEEK_SET);
    }
    const std::string prefix = std::string(stage) + ": '" + path + "' (a plain PGM image): ";
    const auto fail = [&](const std::string& what) { throw InvalidInputError(prefix + what); };
    // The signature, checked by the caller, then width, height and maxval.
    std::fgetc(file.get());
    std::fgetc(file.get());
    TokenReader tokens(file.get());
    const PgmHeader header = readHeader(tokens, fileSize, fail);
    std::vector<std::uint16_t> samples = readSamples(tokens, header, fail);
    if (std::ferror(file.get()))
        throw IoError(std::string(stage) + ": cannot read '" + path + "'");
    return memoryDataset(samples, header, stage, path);
}

} // namespace terratin::io::detail
