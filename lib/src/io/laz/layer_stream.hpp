#pragma once
/// @file
/// One layer of a layered LAZ chunk (compressor 3, LAS 1.4 point formats 6-10): the bytes of
/// one field group of every point of the chunk, coded as an arithmetic stream of its own. A
/// layer of zero bytes holds a field that never changes in the chunk; a reader that does not
/// need a field leaves its layer unread. Either way the decoder repeats the field's last value.

#include "range_decoder.hpp"

#include <cstddef>
#include <span>
#include <string>
#include <utility>

namespace terratin::io::laz {

/// What went wrong in a layer's stream, as far as the decoder can tell.
enum class StreamFault {
    None,
    Truncated, ///< the decoder wanted bytes past the end of the layer
    Corrupt,   ///< a value came out that no writer produces
};

class LayerStream {
public:
    /// `name` names the layer in errors ("z", "gps time", "extra byte 2").
    explicit LayerStream(std::string name) : m_name(std::move(name)) {}

    /// Starts decoding `bytes` when `wanted` and not empty; otherwise the layer stays idle and
    /// its field keeps its last value. `bytes` must stay alive while the layer is decoded.
    void start(std::span<const std::byte> bytes, bool wanted) {
        m_active = wanted && !bytes.empty();
        m_size = bytes.size();
        if (m_active)
            m_decoder.start(bytes.data(), bytes.data() + bytes.size());
    }

    /// Starts decoding `bytes` whatever their size: for a layer every point needs. An empty
    /// one then reports StreamFault::Truncated as soon as it is read.
    void startRequired(std::span<const std::byte> bytes) {
        m_active = true;
        m_size = bytes.size();
        m_decoder.start(bytes.data(), bytes.data() + bytes.size());
    }

    /// Whether the field is decoded from this layer in the current chunk.
    [[nodiscard]] bool active() const { return m_active; }
    /// Precondition: active().
    [[nodiscard]] RangeDecoder& decoder() { return m_decoder; }
    [[nodiscard]] const std::string& name() const { return m_name; }
    /// Bytes of the layer in the current chunk.
    [[nodiscard]] std::size_t size() const { return m_size; }

    [[nodiscard]] StreamFault fault() const {
        if (!m_active)
            return StreamFault::None;
        if (m_decoder.overran())
            return StreamFault::Truncated;
        return m_decoder.corrupt() ? StreamFault::Corrupt : StreamFault::None;
    }

private:
    std::string m_name;
    RangeDecoder m_decoder;
    std::size_t m_size = 0;
    bool m_active = false;
};

} // namespace terratin::io::laz
