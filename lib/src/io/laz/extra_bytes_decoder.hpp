#pragma once
/// @file
/// Decoders of the BYTE item: the extra bytes after the standard fields of a LAS 1.0-1.4
/// point record (LAS 1.4 R15, 2.6 and the extra bytes VLR, 2.5.2), compressed byte by byte
/// with no knowledge of what they mean. Version 1 predicts each byte from its last value
/// through an integer decoder; version 2 codes each byte's difference (mod 256) with one
/// adaptive model per byte position.

#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::io::laz {

class ExtraBytesV1Decoder {
public:
    explicit ExtraBytesV1Decoder(std::size_t count);
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    std::vector<std::uint8_t> m_last;
    IntegerDecoder m_value;
};

class ExtraBytesV2Decoder {
public:
    explicit ExtraBytesV2Decoder(std::size_t count);
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    std::vector<std::uint8_t> m_last;
    std::vector<SymbolModel> m_difference;
};

} // namespace terratin::io::laz
