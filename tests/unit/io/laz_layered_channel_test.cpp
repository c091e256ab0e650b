// Tests of the scanner channels of the layered LAZ compressor (3) on a synthetic chunk. No
// shared file uses a channel other than 0, so a chunk is written here with the project's
// encoder (tools/lazrepeat/laz_encoder.hpp), following LASzip's writer: POINT14 keeps models
// and predictors per channel, a channel met for the first time starts from the last point of
// the channel it leaves; RGB14 follows POINT14's item context (the new channel on a change,
// else 0) and, on a change to a channel seen before, predicts from the context it leaves.
// Points whose channel, x, y and grey colour change while everything else stays must decode
// back exactly.

#include "laz_encoder.hpp"

#include "chunk_decoder.hpp"
#include "item_context.hpp"
#include "laszip_vlr.hpp"
#include "laz_bytes.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace terratin::io::laz {
namespace {

using lazrepeat::IntegerEncoder;
using lazrepeat::RangeEncoder;

struct SyntheticPoint {
    unsigned channel = 0;
    std::int32_t x = 0;
    std::int32_t y = 0;
    std::uint8_t grey = 0;
};

constexpr std::size_t kRecordLength = 36; ///< POINT14 and RGB14

/// A channel's 8 change models of 128 symbols (a SymbolModel moves but is never copied).
std::vector<SymbolModel> changeModels() {
    std::vector<SymbolModel> models;
    models.reserve(8);
    for (int i = 0; i < 8; ++i)
        models.emplace_back(128);
    return models;
}

/// The returns-and-xy layer of single returns whose time and other fields never change.
class ReturnsXyWriter {
public:
    explicit ReturnsXyWriter(const SyntheticPoint& first) : m_current(first.channel) {
        m_channels[m_current].x = first.x;
        m_channels[m_current].y = first.y;
        m_used[m_current] = true;
    }

    /// Writes `p`; returns the item context POINT14 hands the items after it.
    unsigned write(const SyntheticPoint& p) {
        Channel& last = m_channels[m_current];
        const bool switched = p.channel != m_current;
        // Context 3 of the change models: the last point was a single return, its time kept.
        m_out.encodeSymbol(last.changes[3], switched ? 64 : 0);
        unsigned context = 0;
        if (switched) {
            m_out.encodeSymbol(last.step, (p.channel + 4 - m_current) % 4 - 1);
            if (!m_used[p.channel]) {
                m_channels[p.channel] = Channel();
                m_channels[p.channel].x = last.x;
                m_channels[p.channel].y = last.y;
                m_used[p.channel] = true;
            }
            m_current = p.channel;
            context = p.channel;
        }
        Channel& c = m_channels[m_current];
        // One return, one median predictor: single returns with the time unchanged.
        const std::int32_t dx = p.x - c.x;
        c.dx.encode(m_out, c.dxMedian.middle(), dx, 1);
        c.dxMedian.add(dx);
        const std::uint32_t k = c.dx.lastClass();
        const std::int32_t dy = p.y - c.y;
        c.dy.encode(m_out, c.dyMedian.middle(), dy, 1 + (k < 20 ? (k & ~1u) : 20));
        c.dyMedian.add(dy);
        c.x = p.x;
        c.y = p.y;
        return context;
    }
    std::vector<std::byte> finish() { return m_out.finish(); }

private:
    struct Channel {
        std::int32_t x = 0, y = 0;
        std::vector<SymbolModel> changes = changeModels();
        SymbolModel step{3};
        IntegerEncoder dx{32, 2};
        IntegerEncoder dy{32, 22};
        RunningMedian5 dxMedian, dyMedian;
    };
    RangeEncoder m_out;
    std::array<Channel, 4> m_channels{};
    std::array<bool, 4> m_used{};
    unsigned m_current;
};

/// The RGB14 layer of grey colours below 256: only red's low byte is ever coded.
class GreyWriter {
public:
    GreyWriter(unsigned context, std::uint8_t first) : m_current(context) {
        m_used[context] = true;
        m_last[context] = first;
    }
    void write(std::uint8_t grey, unsigned context) {
        unsigned lastIndex = m_current;
        if (context != m_current) {
            m_current = context;
            if (!m_used[context]) {
                m_models[context] = Models();
                m_used[context] = true;
                m_last[context] = m_last[lastIndex];
                lastIndex = context;
            }
        }
        Models& m = m_models[m_current];
        const std::uint8_t last = m_last[lastIndex];
        m_out.encodeSymbol(m.changed, grey != last ? 1 : 0);
        if (grey != last)
            m_out.encodeSymbol(m.redLow, static_cast<std::uint8_t>(grey - last));
        m_last[lastIndex] = grey;
    }
    std::vector<std::byte> finish() { return m_out.finish(); }

private:
    struct Models {
        SymbolModel changed{128};
        SymbolModel redLow{256};
    };
    RangeEncoder m_out;
    std::array<Models, 4> m_models{};
    std::array<bool, 4> m_used{};
    std::array<std::uint8_t, 4> m_last{};
    unsigned m_current;
};

/// The record of `p`: the fixed fields of every point, p's channel, x, y and grey.
std::array<std::byte, kRecordLength> recordOf(const SyntheticPoint& p) {
    std::array<std::byte, kRecordLength> r{};
    storeLe(r.data(), p.x);
    storeLe(r.data() + 4, p.y);
    storeLe(r.data() + 8, std::int32_t{1234});
    storeLe(r.data() + 12, std::uint16_t{77});
    r[14] = std::byte{0x11};                                          // return 1 of 1
    r[15] = static_cast<std::byte>(0x04u | (p.channel << 4) | 0x40u); // withheld, scan direction
    r[16] = std::byte{2};
    r[17] = std::byte{9};
    storeLe(r.data() + 18, std::int16_t{-250});
    storeLe(r.data() + 20, std::uint16_t{5});
    storeLe(r.data() + 22, std::uint64_t{0x41D0000000000000u});
    for (std::size_t c = 0; c < 3; ++c)
        storeLe(r.data() + 30 + 2 * c, std::uint16_t{p.grey});
    return r;
}

std::vector<SyntheticPoint> syntheticPoints(std::size_t count) {
    std::mt19937 random(3);
    std::vector<SyntheticPoint> points{{2, 1000, -5000, 40}};
    for (std::size_t i = 1; i < count; ++i) {
        SyntheticPoint p = points.back();
        if (random() % 10 < 3)
            p.channel = (p.channel + 1 + random() % 3) % 4;
        p.x += static_cast<std::int32_t>(random() % 2001) - 1000;
        p.y += static_cast<std::int32_t>(random() % 201) - 100;
        if (random() % 4 == 0)
            p.grey = static_cast<std::uint8_t>(random());
        points.push_back(p);
    }
    return points;
}

/// A layered chunk of `points`, laid out as LASzip's writer lays it out.
std::vector<std::byte> syntheticChunk(const std::vector<SyntheticPoint>& points) {
    ReturnsXyWriter xy(points.front());
    GreyWriter grey(points.front().channel, points.front().grey);
    for (std::size_t i = 1; i < points.size(); ++i)
        grey.write(points[i].grey, xy.write(points[i]));
    const std::vector<std::byte> xyLayer = xy.finish();
    const std::vector<std::byte> greyLayer = grey.finish();
    const std::size_t layersAt = kRecordLength + 4 + 4 * 10;
    std::vector<std::byte> chunk(layersAt + xyLayer.size() + greyLayer.size());
    const auto first = recordOf(points.front());
    std::copy(first.begin(), first.end(), chunk.begin());
    storeLe(chunk.data() + kRecordLength, static_cast<std::uint32_t>(points.size()));
    // Layer sizes: the returns-and-xy layer, eight empty POINT14 layers, the colour layer.
    storeLe(chunk.data() + kRecordLength + 4, static_cast<std::uint32_t>(xyLayer.size()));
    storeLe(chunk.data() + kRecordLength + 4 + 4 * 9, static_cast<std::uint32_t>(greyLayer.size()));
    std::memcpy(chunk.data() + layersAt, xyLayer.data(), xyLayer.size());
    std::memcpy(chunk.data() + layersAt + xyLayer.size(), greyLayer.data(), greyLayer.size());
    return chunk;
}

LaszipRecord layeredRecord() {
    LaszipRecord r;
    r.compressor = Compressor::LayeredChunked;
    r.chunkSize = 0xFFFFFFFFu;
    r.items = {{ItemType::Point14, 30, 3}, {ItemType::Rgb14, 6, 3}};
    return r;
}

TEST(LazLayeredChannels, ChannelSwitchesDecodeAsLaszipWritesThem) {
    const std::vector<SyntheticPoint> points = syntheticPoints(400);
    const std::vector<std::byte> chunk = syntheticChunk(points);
    ChunkDecoder decoder(layeredRecord(), "synthetic.laz");
    std::vector<std::byte> records(points.size() * kRecordLength);
    EXPECT_EQ(decoder.decode(chunk, points.size(), records, "chunk 1 of 1"), chunk.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto expected = recordOf(points[i]);
        ASSERT_TRUE(std::equal(expected.begin(), expected.end(),
                               records.begin() + static_cast<long>(i * kRecordLength)))
            << "point " << i << " (channel " << points[i].channel << ")";
    }
}

TEST(LazLayeredChannels, TinFieldsFollowTheChannelsAndKeepTheFirstColour) {
    const std::vector<SyntheticPoint> points = syntheticPoints(400);
    const std::vector<std::byte> chunk = syntheticChunk(points);
    ChunkDecoder decoder(layeredRecord(), "synthetic.laz", FieldSelection::TinFields);
    std::vector<std::byte> records(points.size() * kRecordLength);
    decoder.begin(chunk, points.size(), "chunk 1 of 1");
    for (std::size_t done = 0; done < points.size();) {
        const std::size_t piece = std::min<std::size_t>(1 + done % 37, points.size() - done);
        decoder.decodeNext(std::span(records).subspan(done * kRecordLength, piece * kRecordLength));
        done += piece;
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        SyntheticPoint expectedPoint = points[i];
        expectedPoint.grey = points.front().grey;
        const auto expected = recordOf(expectedPoint);
        ASSERT_TRUE(std::equal(expected.begin(), expected.end(),
                               records.begin() + static_cast<long>(i * kRecordLength)))
            << "point " << i;
    }
}

} // namespace
} // namespace terratin::io::laz
