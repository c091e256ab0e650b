#pragma once
/// @file
/// Which LAS point records a read keeps, and their coordinates: the per-point path of the LAS
/// and LAZ readers, kept small enough to be inlined into their loops over records.
///
/// Point records (LAS 1.4 R15, 2.6) begin with X, Y, Z as int32 and x = X * scale + offset.
/// Formats 0-5 pack return number / number of returns in 3 + 3 bits of byte 14 and the class
/// in the low 5 bits of byte 15 (withheld: bit 7); formats 6-10 use 4 + 4 bits in byte 14,
/// flags in byte 15 (withheld: bit 2) and a whole byte 16 for the class.

#include "las_header.hpp"
#include "terratin/error.hpp"
#include "terratin/io/las_reader.hpp"

#include <array>
#include <bitset>
#include <span>
#include <string>

namespace terratin::io::detail {

/// The classes `options` keeps (all when it names none); InvalidInputError for a code outside
/// 0..255.
inline std::bitset<256> classesKept(const LasReadOptions& options) {
    std::bitset<256> keep;
    if (options.classes.empty())
        return keep.set();
    for (const int code : options.classes) {
        if (code < 0 || code > 255)
            throw InvalidInputError(std::string(kLasStage) + ": classification " +
                                    std::to_string(code) + " is outside 0..255");
        keep.set(static_cast<std::size_t>(code));
    }
    return keep;
}

/// Which point records a read keeps, and their coordinates: the per-point path, kept small
/// enough to be inlined into the loop over a buffer of records.
class LasRecordFilter {
public:
    LasRecordFilter(const LasHeader& h, LasReturns returns, const std::bitset<256>& keepClass)
        : m_keepClass(keepClass), m_returns(returns), m_extended(h.pointFormat >= 6),
          m_scale(h.scale), m_offset(h.offset) {}

    /// Whether `record` passes the filters: not withheld (the specification calls such points
    /// deleted), of a return and a class the options keep.
    [[nodiscard]] bool keeps(std::span<const std::byte> record) const {
        const auto returnByte = field<std::uint8_t>(record, 14);
        const auto flagByte = field<std::uint8_t>(record, 15);
        unsigned returnNumber = 0;
        unsigned returnCount = 0;
        unsigned classification = 0;
        bool withheld = false;
        if (m_extended) {
            returnNumber = returnByte & 0x0Fu;
            returnCount = (returnByte >> 4) & 0x0Fu;
            withheld = (flagByte & 0x04u) != 0;
            classification = field<std::uint8_t>(record, 16);
        } else {
            returnNumber = returnByte & 0x07u;
            returnCount = (returnByte >> 3) & 0x07u;
            withheld = (flagByte & 0x80u) != 0;
            classification = flagByte & 0x1Fu;
        }
        const bool returnKept = m_returns == LasReturns::All ||
                                (m_returns == LasReturns::First && returnNumber <= 1) ||
                                (m_returns == LasReturns::Last && returnNumber >= returnCount);
        return !withheld && returnKept && m_keepClass.test(classification);
    }

    /// x = X * scale + offset, the same for y and z.
    [[nodiscard]] Point3 point(std::span<const std::byte> record) const {
        const auto x = field<std::int32_t>(record, 0);
        const auto y = field<std::int32_t>(record, 4);
        const auto z = field<std::int32_t>(record, 8);
        return {x * m_scale[0] + m_offset[0], y * m_scale[1] + m_offset[1],
                z * m_scale[2] + m_offset[2]};
    }

    /// Appends to `cloud` the kept points of `records` records of `recordLength` bytes each
    /// at `chunk`, counting the others as filtered out.
    void decode(const std::byte* chunk, std::size_t records, std::size_t recordLength,
                PointCloud& cloud) const {
        for (std::size_t r = 0; r < records; ++r) {
            const std::span<const std::byte> record(chunk + r * recordLength, recordLength);
            if (keeps(record))
                cloud.points.push_back(point(record));
            else
                ++cloud.filteredOut;
        }
    }

private:
    std::bitset<256> m_keepClass;
    LasReturns m_returns;
    bool m_extended;
    std::array<double, 3> m_scale;
    std::array<double, 3> m_offset;
};

} // namespace terratin::io::detail
