#pragma once
/// @file
/// Decoder of the POINT14 item, version 3: the 30 bytes that begin every LAS 1.4 point record
/// of formats 6-10 (LAS 1.4 R15, table 15): x, y, z (int32), intensity (uint16), the return
/// byte (return number bits 0-3, number of returns bits 4-7), the flag byte (classification
/// flags bits 0-3 with withheld = bit 2, scanner channel bits 4-5, scan direction bit 6, edge
/// of flight line bit 7), classification (uint8), user data (uint8), scan angle (int16, 0.006°
/// steps), point source id (uint16), GPS time (double).
///
/// The layered compressor stores the fields in nine layers, each its own arithmetic stream, in
/// this order: channel, returns and x, y; z; classification; flags; intensity; scan angle; user
/// data; point source id; GPS time. The first layer codes per point which fields changed, so a
/// reader can skip any other layer. Context choices only ever look at the first layer's fields
/// and at the layer's own field (z at the x, y corrections and the returns; classification at
/// the last classification and the returns; flags at the last flags), so skipping intensity,
/// scan angle, user data, point source id and GPS time leaves the others exact.
///
/// Every model and predictor exists once per scanner channel (0-3): a channel met for the
/// first time in a chunk starts from the point decoded last (Isenburg, LASzip 3.x; LAS 1.4
/// R15 for the channel).

#include "layer_stream.hpp"

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

namespace terratin::io::laz {

/// The POINT14 fields as the decoder updates them.
struct Point14Fields {
    std::int32_t x = 0;
    std::int32_t y = 0;
    std::int32_t z = 0;
    std::uint16_t intensity = 0;
    std::uint8_t returnByte = 0;
    std::uint8_t flagByte = 0;
    std::uint8_t classification = 0;
    std::uint8_t userData = 0;
    /// The int16 scan angle's bit pattern.
    std::uint16_t scanAngle = 0;
    std::uint16_t sourceId = 0;
    /// The double's bit pattern.
    std::uint64_t gpsTime = 0;

    [[nodiscard]] unsigned returnNumber() const { return returnByte & 0x0Fu; }
    [[nodiscard]] unsigned returnCount() const { return returnByte >> 4; }
    [[nodiscard]] unsigned channel() const { return (flagByte >> 4) & 3u; }

    static Point14Fields load(const std::byte* record);
    void store(std::byte* record) const;
};

class Point14V3Decoder {
public:
    /// The layers, in the order of their byte counts and bytes in the chunk.
    enum Layer : std::size_t {
        kChannelReturnsXy,
        kZ,
        kClassification,
        kFlags,
        kIntensity,
        kScanAngle,
        kUserData,
        kPointSource,
        kGpsTime,
        kLayerCount,
    };
    using LayerSet = std::bitset<kLayerCount>;

    /// A decoder that decodes the layers in `wanted` and repeats the first point's value of the
    /// others. The returns-and-xy layer is always decoded: every other layer depends on it.
    explicit Point14V3Decoder(LayerSet wanted);
    ~Point14V3Decoder();
    Point14V3Decoder(Point14V3Decoder&&) noexcept;
    Point14V3Decoder& operator=(Point14V3Decoder&&) noexcept;
    Point14V3Decoder(const Point14V3Decoder&) = delete;
    Point14V3Decoder& operator=(const Point14V3Decoder&) = delete;

    /// A new chunk, whose first point (raw) is `first`, with the bytes of its kLayerCount
    /// layers (which must stay alive until the chunk is done).
    void start(const std::byte* first, std::span<const std::span<const std::byte>> layers);
    /// The next point, as 30 raw bytes.
    void decode(std::byte* out);
    /// The context the items after POINT14 decode the point last started or decoded with (see
    /// channel_contexts.hpp): its channel at the chunk start, the new channel on a point where
    /// the channel changed, 0 otherwise.
    [[nodiscard]] std::size_t itemContext() const { return m_itemContext; }

    [[nodiscard]] std::span<const LayerStream> layers() const { return m_layers; }

private:
    struct Channel;
    Channel& startChannel(std::size_t index, const Point14Fields& from);
    Channel& switchChannel(std::uint32_t step);
    std::uint32_t decodeReturnsAndXy();
    void decodeReturns(Channel& channel, std::uint32_t changes);
    void decodeXy(Channel& channel, bool timeChanged);
    void decodeOtherLayers(Channel& channel, std::uint32_t changes);

    LayerSet m_wanted;
    std::array<LayerStream, kLayerCount> m_layers;
    std::array<std::unique_ptr<Channel>, 4> m_channels;
    std::array<bool, 4> m_used{};
    std::size_t m_current = 0;
    std::size_t m_itemContext = 0;
};

} // namespace terratin::io::laz
