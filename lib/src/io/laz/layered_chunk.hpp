#pragma once
/// @file
/// The chunk loop of the layered LAZ compressor (3), which stores the LAS 1.4 point formats
/// 6-10. A chunk is laid out as (all integers little-endian):
///
///   the first point's record, raw
///   u32 the chunk's point count
///   u32 the byte count of every layer: POINT14's nine, then those of each following item
///       in item order (RGB14 one, RGBNIR14 two, BYTE14 one per byte, WAVEPACKET14 one)
///   the layers' bytes, back to back in the same order
///
/// Each layer is an arithmetic-coded stream of its own holding one field group of the points
/// after the first (layer_stream.hpp), so a reader can leave out the layers it does not need.
/// ChunkDecoder (chunk_decoder.hpp) is the public face of this.

#include "byte14_decoder.hpp"
#include "chunk_decoder.hpp"
#include "laszip_vlr.hpp"
#include "point14_decoder.hpp"
#include "rgb14_decoder.hpp"
#include "wavepacket14_decoder.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace terratin::io::laz {

/// The decoder of one item after POINT14 in a layered record.
using LayeredItemDecoder = std::variant<Rgb14V3Decoder, Byte14V3Decoder, WavePacket14V3Decoder>;

class LayeredChunkDecoder {
public:
    /// A decoder for the items of `record` (compressor 3): POINT14 first, then any of RGB14,
    /// RGBNIR14, BYTE14, WAVEPACKET14, each of version 3 (or 2, the prototype's number for the
    /// same coding). With FieldSelection::TinFields only the POINT14 layers of x, y, z, the
    /// returns, classification and flags are decoded; the other bytes of each record repeat
    /// the chunk's first record. Throws InvalidInputError naming `fileName` for other items or
    /// versions (version 4 comes with LAS 1.5 and is not decoded).
    LayeredChunkDecoder(const LaszipRecord& record, std::string_view fileName,
                        FieldSelection fields);

    /// Starts on `chunk`, which must stay alive until it is done, holding `pointCount` (at
    /// least 1) points as the chunk table says: checks its layout against its size and that
    /// count, starts the wanted layers and writes the first record (raw) into `first`.
    /// `label` names the chunk in errors. Throws InvalidInputError when the layout does not fit.
    void start(std::span<const std::byte> chunk, std::uint64_t pointCount, std::string label,
               std::byte* first);
    /// The next records.size() / record length points after the first (precondition: no more
    /// than the chunk has left). Throws InvalidInputError when a layer turns out truncated or
    /// corrupt.
    void decode(std::span<std::byte> records);
    /// The layers of a chunk: POINT14's and those of the items after it.
    [[nodiscard]] std::size_t layerCount() const { return m_layerCount; }
    /// Bytes of the chunk that its layout accounts for: the first record, the point count, the
    /// layer sizes and every layer.
    [[nodiscard]] std::size_t chunkBytes() const { return m_chunkBytes; }

private:
    /// An item decoder, where its bytes sit in the record, and where its layers sit among the
    /// chunk's.
    struct PlacedItem {
        LayeredItemDecoder decoder;
        std::size_t offset = 0;
        std::size_t firstLayer = 0;
        std::size_t layerCount = 0;
    };

    void splitLayers(std::span<const std::byte> chunk, std::uint64_t pointCount);
    void startItems(const std::byte* first);
    void checkLayers() const;
    [[noreturn]] void fail(const std::string& what) const;

    std::string m_fileName;
    std::size_t m_recordLength = 0;
    bool m_decodeItems = true;
    Point14V3Decoder m_point;
    std::vector<PlacedItem> m_items;
    std::size_t m_layerCount = 0;
    std::vector<std::span<const std::byte>> m_layerBytes;
    /// The first record of the current chunk: the bytes of the items not decoded.
    std::vector<std::byte> m_firstRecord;
    std::size_t m_chunkBytes = 0;
    std::uint64_t m_pointCount = 0;
    std::string m_label;
};

} // namespace terratin::io::laz
