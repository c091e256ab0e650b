#pragma once
/// @file
/// The scanner-channel contexts of the LAZ items that follow POINT14 in a layered chunk
/// (RGB14, RGBNIR14, BYTE14, WAVEPACKET14, version 3). Each item keeps up to four sets of
/// models, one per scanner channel, each created the first time its channel appears in a chunk
/// and seeded with the value last decoded.
///
/// Which set a point uses is not simply its channel. POINT14 version 3 hands the other items
/// a context that is the new channel on a point where the channel changes and 0 on every
/// other point (LASzip resets it before each point and sets it only on a change; version 4
/// corrects this). And on a change to a channel already seen in the chunk, the point is
/// predicted from, and its value stored as, the last value of the context it leaves; only a
/// channel met for the first time starts from its own copy. Writers follow the same rules, so
/// the decoder must too.

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <utility>

namespace terratin::io::laz {

/// `Models` needs reset(); `Value` is the item's last decoded value (copyable).
template <typename Models, typename Value> class ChannelContexts {
public:
    static constexpr std::size_t kChannels = 4;

    /// `makeModels` creates one set of models, at most kChannels times per decoder.
    explicit ChannelContexts(std::function<std::unique_ptr<Models>()> makeModels)
        : m_makeModels(std::move(makeModels)) {}

    /// A new chunk whose first point has item context `context` (< kChannels) and value
    /// `first`.
    void start(std::size_t context, const Value& first) {
        m_used.fill(false);
        activate(context, first);
        m_current = context;
    }

    /// The models and last value to decode the next point with, given its item context
    /// (< kChannels). The value may be updated in place.
    struct Selection {
        Models& models;
        Value& last;
    };
    [[nodiscard]] Selection select(std::size_t context) {
        std::size_t lastIndex = m_current;
        if (context != m_current) {
            m_current = context;
            if (!m_used[context]) {
                activate(context, Value(m_last[lastIndex]));
                lastIndex = context;
            }
        }
        return {*m_models[m_current], m_last[lastIndex]};
    }

private:
    void activate(std::size_t context, const Value& from) {
        if (!m_models[context])
            m_models[context] = m_makeModels();
        else
            m_models[context]->reset();
        m_last[context] = from;
        m_used[context] = true;
    }

    std::function<std::unique_ptr<Models>()> m_makeModels;
    std::array<std::unique_ptr<Models>, kChannels> m_models{};
    std::array<Value, kChannels> m_last{};
    std::array<bool, kChannels> m_used{};
    std::size_t m_current = 0;
};

} // namespace terratin::io::laz
