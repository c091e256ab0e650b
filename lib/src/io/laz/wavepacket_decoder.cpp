/// @file
/// WAVEPACKET13 item decoder, version 1 (see wavepacket_decoder.hpp).

#include "wavepacket_decoder.hpp"

#include "laz_bytes.hpp"

#include <cstring>

namespace terratin::io::laz {

namespace {
/// The four ways an offset is coded.
constexpr std::uint32_t kSameOffset = 0;
constexpr std::uint32_t kAfterLastPacket = 1;
constexpr std::uint32_t kOffsetStep = 2;
} // namespace

WavePacketModels::WavePacketModels()
    : descriptorIndex(256), offsetKind{SymbolModel(4), SymbolModel(4), SymbolModel(4),
                                       SymbolModel(4)},
      offsetStep(32), packetSize(32), returnPoint(32), xyz(32, 3) {}

void WavePacketModels::reset() {
    descriptorIndex.reset();
    for (SymbolModel& model : offsetKind)
        model.reset();
    for (IntegerDecoder* ic : {&offsetStep, &packetSize, &returnPoint, &xyz})
        ic->reset();
    lastOffsetStep = 0;
    lastOffsetKind = kSameOffset;
}

void decodeWavePacket(RangeDecoder& decoder, WavePacketModels& models, const std::byte* last,
                      std::byte* out) {
    // Byte 0, the descriptor index, has an adaptive model and no prediction; the others are
    // predicted from the last packet, read before `out` (which may be `last`) is written.
    auto offset = loadLe<std::uint64_t>(last + 1);
    const auto lastSize = loadLe<std::uint32_t>(last + 9);
    std::array<std::int32_t, 4> shape{};
    for (std::size_t i = 0; i < 4; ++i)
        shape[i] = loadLe<std::int32_t>(last + 13 + 4 * i);
    out[0] = static_cast<std::byte>(decoder.decodeSymbol(models.descriptorIndex));
    models.lastOffsetKind = decoder.decodeSymbol(models.offsetKind[models.lastOffsetKind]);
    if (models.lastOffsetKind == kAfterLastPacket) {
        offset += lastSize;
    } else if (models.lastOffsetKind == kOffsetStep) {
        models.lastOffsetStep = models.offsetStep.decode(decoder, models.lastOffsetStep);
        offset += static_cast<std::uint64_t>(static_cast<std::int64_t>(models.lastOffsetStep));
    } else if (models.lastOffsetKind != kSameOffset) {
        offset = decoder.readInt64();
    }
    const auto size = static_cast<std::uint32_t>(
        models.packetSize.decode(decoder, static_cast<std::int32_t>(lastSize)));
    shape[0] = models.returnPoint.decode(decoder, shape[0]);
    for (std::uint32_t axis = 0; axis < 3; ++axis)
        shape[axis + 1] = models.xyz.decode(decoder, shape[axis + 1], axis);
    storeLe(out + 1, offset);
    storeLe(out + 9, size);
    for (std::size_t i = 0; i < 4; ++i)
        storeLe(out + 13 + 4 * i, shape[i]);
}

void WavePacket13V1Decoder::start(const std::byte* first) {
    std::memcpy(m_last.data(), first, kWavePacketSize);
    m_models.reset();
}

void WavePacket13V1Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    decodeWavePacket(decoder, m_models, m_last.data(), m_last.data());
    std::memcpy(out, m_last.data(), kWavePacketSize);
}

} // namespace terratin::io::laz
