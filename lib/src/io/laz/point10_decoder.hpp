#pragma once
/// @file
/// Decoders of the POINT10 item: the 20 bytes that begin every LAS 1.0-1.3 point record
/// (formats 0-5; LAS 1.4 R15, table 7): x, y, z (int32), intensity (uint16), the return byte
/// (return number bits 0-2, number of returns bits 3-5, scan direction bit 6, edge of flight
/// line bit 7), the classification byte, scan angle rank (int8), user data (uint8), point
/// source id (uint16).
///
/// Version 1 (LASzip 1.x) predicts x and y from the median of the last three differences and
/// z from the last z; version 2 (LASzip 2.0 on) keeps separate predictors per return, chosen
/// by the return number and the number of returns, and codes first which of the other fields
/// changed (Isenburg 2013).

#include "integer_decoder.hpp"
#include "item_context.hpp"
#include "range_decoder.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace terratin::io::laz {

/// The POINT10 fields as the decoders update them.
struct Point10Fields {
    std::int32_t x = 0;
    std::int32_t y = 0;
    std::int32_t z = 0;
    std::uint16_t intensity = 0;
    std::uint8_t returnByte = 0;
    std::uint8_t classByte = 0;
    std::uint8_t scanAngle = 0;
    std::uint8_t userData = 0;
    std::uint16_t sourceId = 0;

    static Point10Fields load(const std::byte* record);
    void store(std::byte* record) const;
};

class Point10V1Decoder {
public:
    Point10V1Decoder();
    /// A new chunk, whose first point (raw) is `first`.
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    void decodeChangedFields(RangeDecoder& decoder, std::uint32_t coordinateClass);

    Point10Fields m_last;
    std::array<std::int32_t, 3> m_recentDx{};
    std::array<std::int32_t, 3> m_recentDy{};
    std::size_t m_nextRecent = 0;
    IntegerDecoder m_dx;
    IntegerDecoder m_dy;
    IntegerDecoder m_z;
    IntegerDecoder m_intensity;
    IntegerDecoder m_scanAngle;
    IntegerDecoder m_sourceId;
    SymbolModel m_changed;
    ByteContextModels m_returnByteModels;
    ByteContextModels m_classModels;
    ByteContextModels m_userDataModels;
};

class Point10V2Decoder {
public:
    Point10V2Decoder();
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    void decodeChangedFields(RangeDecoder& decoder, std::uint32_t changed);
    void decodeCoordinates(RangeDecoder& decoder);

    Point10Fields m_last;
    /// Per return context (number_return_map): last intensity and the x, y difference medians.
    std::array<std::uint16_t, 16> m_lastIntensity{};
    std::array<RunningMedian5, 16> m_dxMedian{};
    std::array<RunningMedian5, 16> m_dyMedian{};
    /// Per return level |number of returns - return number|: the last z.
    std::array<std::int32_t, 8> m_lastZ{};
    SymbolModel m_changed;
    IntegerDecoder m_intensity;
    std::array<SymbolModel, 2> m_scanAngle;
    IntegerDecoder m_sourceId;
    ByteContextModels m_returnByteModels;
    ByteContextModels m_classModels;
    ByteContextModels m_userDataModels;
    IntegerDecoder m_dx;
    IntegerDecoder m_dy;
    IntegerDecoder m_z;
};

} // namespace terratin::io::laz
