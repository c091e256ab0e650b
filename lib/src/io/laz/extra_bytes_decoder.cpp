/// @file
/// BYTE item decoders, versions 1 and 2 (see extra_bytes_decoder.hpp).

#include "extra_bytes_decoder.hpp"

#include <cstring>

namespace terratin::io::laz {

ExtraBytesV1Decoder::ExtraBytesV1Decoder(std::size_t count)
    : m_last(count), m_value(8, static_cast<std::uint32_t>(count)) {}

void ExtraBytesV1Decoder::start(const std::byte* first) {
    std::memcpy(m_last.data(), first, m_last.size());
    m_value.reset();
}

void ExtraBytesV1Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    // Byte i is predicted by its last value under context i.
    for (std::size_t i = 0; i < m_last.size(); ++i) {
        const std::int32_t value =
            m_value.decode(decoder, m_last[i], static_cast<std::uint32_t>(i));
        m_last[i] = static_cast<std::uint8_t>(value);
    }
    std::memcpy(out, m_last.data(), m_last.size());
}

ExtraBytesV2Decoder::ExtraBytesV2Decoder(std::size_t count) : m_last(count) {
    m_difference.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
        m_difference.emplace_back(256);
}

void ExtraBytesV2Decoder::start(const std::byte* first) {
    std::memcpy(m_last.data(), first, m_last.size());
    for (SymbolModel& model : m_difference)
        model.reset();
}

void ExtraBytesV2Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    for (std::size_t i = 0; i < m_last.size(); ++i)
        m_last[i] = static_cast<std::uint8_t>(m_last[i] + decoder.decodeSymbol(m_difference[i]));
    std::memcpy(out, m_last.data(), m_last.size());
}

} // namespace terratin::io::laz
