/// @file
/// POINT14 item decoder, version 3 (see point14_decoder.hpp).

#include "point14_decoder.hpp"

#include "gpstime_sequences.hpp"
#include "integer_decoder.hpp"
#include "item_context.hpp"
#include "laz_bytes.hpp"

#include <cstdlib>
#include <vector>

namespace terratin::io::laz {

namespace {

/// Bits of the first symbol of each point: which fields changed since the last point of the
/// same scanner channel. Bits 0-1 say how the return number changed: 0 not, 1 by +1, 2 by -1
/// (mod 16), 3 otherwise (coded in full).
constexpr std::uint32_t kReturnNumberChange = 3;
constexpr std::uint32_t kReturnCountChanged = 1u << 2;
constexpr std::uint32_t kScanAngleChanged = 1u << 3;
constexpr std::uint32_t kTimeChanged = 1u << 4;
constexpr std::uint32_t kSourceIdChanged = 1u << 5;
constexpr std::uint32_t kChannelChanged = 1u << 6;

/// Which of 6 predictor sets the x and y corrections use, by [number of returns][return
/// number]: the valid pairs of up to 3 returns get their own, the rest share by whether they
/// are first, last or between (part of the format).
constexpr std::array<std::array<std::uint8_t, 16>, 16> kReturnMap{{
    {0, 1, 2, 3, 4, 5, 3, 4, 4, 5, 5, 5, 5, 5, 5, 5},
    {1, 0, 1, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3},
    {2, 1, 2, 4, 4, 4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3},
    {3, 3, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {3, 3, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5},
}};

/// The z predictor of a return: how many returns lie between it and the last of its pulse,
/// |number of returns - return number|, at most 7.
std::size_t returnLevel(unsigned count, unsigned number) {
    const int level = std::abs(static_cast<int>(count) - static_cast<int>(number));
    return static_cast<std::size_t>(level < 7 ? level : 7);
}

/// Whether a return is the first (2) and the last (1) of its pulse: 3 a single return.
unsigned returnKind(unsigned count, unsigned number) {
    return (number == 1 ? 2u : 0u) + (number >= count ? 1u : 0u);
}

/// A class of the x or y correction as a context: even classes only, capped.
std::uint32_t evenClass(std::uint32_t k, std::uint32_t cap) {
    return k < cap ? (k & ~1u) : cap;
}

std::vector<SymbolModel> symbolModels(std::size_t count, std::uint32_t symbols) {
    std::vector<SymbolModel> models;
    models.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
        models.emplace_back(symbols);
    return models;
}

} // namespace

Point14Fields Point14Fields::load(const std::byte* record) {
    Point14Fields f;
    f.x = loadLe<std::int32_t>(record);
    f.y = loadLe<std::int32_t>(record + 4);
    f.z = loadLe<std::int32_t>(record + 8);
    f.intensity = loadLe<std::uint16_t>(record + 12);
    f.returnByte = loadLe<std::uint8_t>(record + 14);
    f.flagByte = loadLe<std::uint8_t>(record + 15);
    f.classification = loadLe<std::uint8_t>(record + 16);
    f.userData = loadLe<std::uint8_t>(record + 17);
    f.scanAngle = loadLe<std::uint16_t>(record + 18);
    f.sourceId = loadLe<std::uint16_t>(record + 20);
    f.gpsTime = loadLe<std::uint64_t>(record + 22);
    return f;
}

void Point14Fields::store(std::byte* record) const {
    storeLe(record, x);
    storeLe(record + 4, y);
    storeLe(record + 8, z);
    storeLe(record + 12, intensity);
    record[14] = static_cast<std::byte>(returnByte);
    record[15] = static_cast<std::byte>(flagByte);
    record[16] = static_cast<std::byte>(classification);
    record[17] = static_cast<std::byte>(userData);
    storeLe(record + 18, scanAngle);
    storeLe(record + 20, sourceId);
    storeLe(record + 22, gpsTime);
}

/// Everything POINT14 keeps per scanner channel.
struct Point14V3Decoder::Channel {
    Point14Fields last;
    bool lastTimeChanged = false;
    /// Per return kind and whether the time changed.
    std::array<std::uint16_t, 8> lastIntensity{};
    /// Per return map entry and whether the time changed.
    std::array<RunningMedian5, 12> dxMedian{};
    std::array<RunningMedian5, 12> dyMedian{};
    /// Per return level.
    std::array<std::int32_t, 8> lastZ{};

    /// Which fields changed, per the last point's return kind and whether its time changed.
    std::vector<SymbolModel> changes = symbolModels(8, 128);
    SymbolModel channelStep{3};
    ContextModels<16> returnCounts{16};
    ContextModels<16> returnNumbers{16};
    SymbolModel returnNumberJump{13};
    IntegerDecoder dx{32, 2};
    IntegerDecoder dy{32, 22};
    IntegerDecoder z{32, 20};
    ContextModels<64> classes{256};
    ContextModels<64> flags{64};
    ContextModels<64> userData{256};
    IntegerDecoder intensity{16, 4};
    IntegerDecoder scanAngle{16, 2};
    IntegerDecoder sourceId{16};
    GpsTimeSequences gpsTime{GpsTimeCodes::ChangedOnly};

    void start(const Point14Fields& from);
};

void Point14V3Decoder::Channel::start(const Point14Fields& from) {
    last = from;
    lastTimeChanged = false;
    lastIntensity.fill(from.intensity);
    for (RunningMedian5& median : dxMedian)
        median.reset();
    for (RunningMedian5& median : dyMedian)
        median.reset();
    lastZ.fill(from.z);
    for (SymbolModel& model : changes)
        model.reset();
    channelStep.reset();
    returnCounts.reset();
    returnNumbers.reset();
    returnNumberJump.reset();
    for (IntegerDecoder* ic : {&dx, &dy, &z, &intensity, &scanAngle, &sourceId})
        ic->reset();
    classes.reset();
    flags.reset();
    userData.reset();
    gpsTime.start(from.gpsTime);
}

Point14V3Decoder::Point14V3Decoder(LayerSet wanted)
    : m_wanted(wanted), m_layers{LayerStream("channel, returns and xy"),
                                 LayerStream("z"),
                                 LayerStream("classification"),
                                 LayerStream("flags"),
                                 LayerStream("intensity"),
                                 LayerStream("scan angle"),
                                 LayerStream("user data"),
                                 LayerStream("point source id"),
                                 LayerStream("gps time")} {}

Point14V3Decoder::~Point14V3Decoder() = default;
Point14V3Decoder::Point14V3Decoder(Point14V3Decoder&&) noexcept = default;
Point14V3Decoder& Point14V3Decoder::operator=(Point14V3Decoder&&) noexcept = default;

void Point14V3Decoder::start(const std::byte* first,
                             std::span<const std::span<const std::byte>> layers) {
    m_layers[kChannelReturnsXy].startRequired(layers[kChannelReturnsXy]);
    for (std::size_t i = kChannelReturnsXy + 1; i < kLayerCount; ++i)
        m_layers[i].start(layers[i], m_wanted[i]);
    m_used.fill(false);
    const Point14Fields point = Point14Fields::load(first);
    m_current = point.channel();
    startChannel(m_current, point);
    m_itemContext = m_current;
}

void Point14V3Decoder::decode(std::byte* out) {
    const std::uint32_t changes = decodeReturnsAndXy();
    Channel& channel = *m_channels[m_current];
    decodeOtherLayers(channel, changes);
    channel.lastTimeChanged = (changes & kTimeChanged) != 0;
    channel.last.store(out);
}

Point14V3Decoder::Channel& Point14V3Decoder::startChannel(std::size_t index,
                                                          const Point14Fields& from) {
    std::unique_ptr<Channel>& channel = m_channels[index];
    if (!channel)
        channel = std::make_unique<Channel>();
    channel->start(from);
    m_used[index] = true;
    return *channel;
}

Point14V3Decoder::Channel& Point14V3Decoder::switchChannel(std::uint32_t step) {
    // The step is 0-2 for a change by +1, +2, +3 (mod 4): never to the same channel.
    const std::size_t next = (m_current + step + 1) % 4;
    Channel& channel =
        m_used[next] ? *m_channels[next] : startChannel(next, m_channels[m_current]->last);
    m_current = next;
    channel.last.flagByte =
        static_cast<std::uint8_t>((channel.last.flagByte & ~0x30u) | (next << 4));
    return channel;
}

std::uint32_t Point14V3Decoder::decodeReturnsAndXy() {
    RangeDecoder& decoder = m_layers[kChannelReturnsXy].decoder();
    Channel* channel = m_channels[m_current].get();
    // The last point's return: 1 first, 2 last (both: a single return); 4 more when its time
    // changed.
    const unsigned lastNumber = channel->last.returnNumber();
    const std::size_t lastReturn = (lastNumber == 1 ? 1u : 0u) +
                                   (lastNumber >= channel->last.returnCount() ? 2u : 0u) +
                                   (channel->lastTimeChanged ? 4u : 0u);
    const std::uint32_t changes = decoder.decodeSymbol(channel->changes[lastReturn]);
    m_itemContext = 0;
    if (changes & kChannelChanged) {
        channel = &switchChannel(decoder.decodeSymbol(channel->channelStep));
        m_itemContext = m_current;
    }
    decodeReturns(*channel, changes);
    decodeXy(*channel, (changes & kTimeChanged) != 0);
    return changes;
}

void Point14V3Decoder::decodeReturns(Channel& channel, std::uint32_t changes) {
    RangeDecoder& decoder = m_layers[kChannelReturnsXy].decoder();
    unsigned count = channel.last.returnCount();
    unsigned number = channel.last.returnNumber();
    if (changes & kReturnCountChanged)
        count = decoder.decodeSymbol(channel.returnCounts.at(count));
    switch (changes & kReturnNumberChange) {
    case 1:
        number = (number + 1) & 15u;
        break;
    case 2:
        number = (number + 15) & 15u;
        break;
    case 3:
        // A jump: coded in full when the time changed (a new pulse), else as a step of 2-14.
        if (changes & kTimeChanged)
            number = decoder.decodeSymbol(channel.returnNumbers.at(number));
        else
            number = (number + decoder.decodeSymbol(channel.returnNumberJump) + 2) & 15u;
        break;
    default:
        break;
    }
    channel.last.returnByte = static_cast<std::uint8_t>(number | (count << 4));
}

void Point14V3Decoder::decodeXy(Channel& channel, bool timeChanged) {
    RangeDecoder& decoder = m_layers[kChannelReturnsXy].decoder();
    Point14Fields& point = channel.last;
    const unsigned count = point.returnCount();
    const std::size_t median =
        (std::size_t{kReturnMap[count][point.returnNumber()]} << 1) | (timeChanged ? 1u : 0u);
    const std::uint32_t single = count == 1 ? 1 : 0;

    const std::int32_t dx = channel.dx.decode(decoder, channel.dxMedian[median].middle(), single);
    point.x = wrappingAdd(point.x, dx);
    channel.dxMedian[median].add(dx);

    // The magnitude class of the x correction picks the context of the y correction.
    const std::uint32_t yContext = single + evenClass(channel.dx.lastClass(), 20);
    const std::int32_t dy = channel.dy.decode(decoder, channel.dyMedian[median].middle(), yContext);
    point.y = wrappingAdd(point.y, dy);
    channel.dyMedian[median].add(dy);
}

void Point14V3Decoder::decodeOtherLayers(Channel& channel, std::uint32_t changes) {
    Point14Fields& point = channel.last;
    const unsigned count = point.returnCount();
    const unsigned kind = returnKind(count, point.returnNumber());
    const std::uint32_t timeChanged = (changes & kTimeChanged) != 0 ? 1 : 0;
    if (m_layers[kZ].active()) {
        const std::uint32_t xyClass = (channel.dx.lastClass() + channel.dy.lastClass()) / 2;
        const std::uint32_t context = (count == 1 ? 1 : 0) + evenClass(xyClass, 18);
        const std::size_t level = returnLevel(count, point.returnNumber());
        point.z = channel.z.decode(m_layers[kZ].decoder(), channel.lastZ[level], context);
        channel.lastZ[level] = point.z;
    }
    if (m_layers[kClassification].active()) {
        const std::size_t context = ((point.classification & 0x1Fu) << 1) + (kind == 3 ? 1 : 0);
        point.classification = static_cast<std::uint8_t>(
            m_layers[kClassification].decoder().decodeSymbol(channel.classes.at(context)));
    }
    if (m_layers[kFlags].active()) {
        // Coded as 6 bits: the classification flags (0-3), scan direction (4), edge (5); the
        // channel (bits 4-5 of the record's byte) comes from the first layer.
        const unsigned lastFlags = (point.flagByte & 0x0Fu) | ((point.flagByte >> 2) & 0x30u);
        const std::uint32_t flags =
            m_layers[kFlags].decoder().decodeSymbol(channel.flags.at(lastFlags));
        point.flagByte = static_cast<std::uint8_t>((flags & 0x0Fu) | ((flags & 0x30u) << 2) |
                                                   (point.flagByte & 0x30u));
    }
    if (m_layers[kIntensity].active()) {
        std::uint16_t& last = channel.lastIntensity[(kind << 1) | timeChanged];
        last = static_cast<std::uint16_t>(
            channel.intensity.decode(m_layers[kIntensity].decoder(), last, kind));
        point.intensity = last;
    }
    if ((changes & kScanAngleChanged) && m_layers[kScanAngle].active())
        point.scanAngle = static_cast<std::uint16_t>(
            channel.scanAngle.decode(m_layers[kScanAngle].decoder(),
                                     static_cast<std::int16_t>(point.scanAngle), timeChanged));
    if (m_layers[kUserData].active())
        point.userData = static_cast<std::uint8_t>(
            m_layers[kUserData].decoder().decodeSymbol(channel.userData.at(point.userData / 4)));
    if ((changes & kSourceIdChanged) && m_layers[kPointSource].active())
        point.sourceId = static_cast<std::uint16_t>(
            channel.sourceId.decode(m_layers[kPointSource].decoder(), point.sourceId));
    if (timeChanged && m_layers[kGpsTime].active()) {
        channel.gpsTime.decode(m_layers[kGpsTime].decoder());
        point.gpsTime = channel.gpsTime.current();
    }
}

} // namespace terratin::io::laz
