#pragma once
/// @file
/// The encoder side of LAZ's entropy coding, for the decoder tests: the range encoder, its
/// adaptive models and the integer compressor, written from the same published rules as the
/// decoder (FastAC as LASzip adapts it; Isenburg 2013). Tests use it to make streams the real
/// files do not contain: every alphabet size, extreme corrections, synthetic chunks.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::io::laz::test {

/// The interval length below which the encoder shifts out a byte (2^24).
inline constexpr std::uint32_t kMinLength = 0x01000000u;

/// The adaptive symbol model, encoder side: counts, a 15-bit cumulative distribution, the
/// same refresh schedule, searched linearly (the decoder's lookup table is not needed here).
struct TestSymbolModel {
    explicit TestSymbolModel(std::uint32_t n) : counts(n, 1), cumulative(n) {
        cycle = n;
        refresh();
        cycle = until = (n + 6) / 2;
    }
    void refresh() {
        total += cycle;
        if (total > (1u << 15)) {
            total = 0;
            for (auto& c : counts)
                total += c = (c + 1) / 2;
        }
        const std::uint32_t scale = 0x80000000u / total;
        std::uint32_t sum = 0;
        for (std::size_t s = 0; s < counts.size(); ++s) {
            cumulative[s] = (scale * sum) >> 16;
            sum += counts[s];
        }
        cycle = std::min<std::uint32_t>(5 * cycle / 4,
                                        (static_cast<std::uint32_t>(counts.size()) + 6) * 8);
        until = cycle;
    }
    std::vector<std::uint32_t> counts;
    std::vector<std::uint32_t> cumulative;
    std::uint32_t total = 0, cycle = 0, until = 0;
};

struct TestBitModel {
    void refresh() {
        total += cycle;
        if (total > (1u << 13)) {
            total = (total + 1) / 2;
            zeros = (zeros + 1) / 2;
            if (zeros == total)
                ++total;
        }
        probability = (zeros * (0x80000000u / total)) >> 18;
        cycle = std::min<std::uint32_t>(5 * cycle / 4, 64);
        until = cycle;
    }
    std::uint32_t zeros = 1, total = 2, probability = 1u << 12, cycle = 4, until = 4;
};

class TestEncoder {
public:
    void symbol(TestSymbolModel& m, std::uint32_t s) {
        const std::uint32_t before = m_base;
        if (s + 1 == m.counts.size()) {
            const std::uint32_t low = m.cumulative[s] * (m_length >> 15);
            m_base += low;
            m_length -= low;
        } else {
            m_length >>= 15;
            const std::uint32_t low = m.cumulative[s] * m_length;
            m_base += low;
            m_length = m.cumulative[s + 1] * m_length - low;
        }
        settle(before);
        ++m.counts[s];
        if (--m.until == 0)
            m.refresh();
    }
    void bit(TestBitModel& m, std::uint32_t b) {
        const std::uint32_t split = m.probability * (m_length >> 13);
        const std::uint32_t before = m_base;
        if (b == 0) {
            m_length = split;
            ++m.zeros;
        } else {
            m_base += split;
            m_length -= split;
        }
        settle(before);
        if (--m.until == 0)
            m.refresh();
    }
    void raw(std::uint32_t count, std::uint32_t value) {
        if (count > 19) {
            raw(16, value & 0xFFFFu);
            raw(count - 16, value >> 16);
            return;
        }
        const std::uint32_t before = m_base;
        m_length >>= count;
        m_base += value * m_length;
        settle(before);
    }
    std::vector<std::byte> finish() {
        const std::uint32_t before = m_base;
        const bool threeZeros = m_length > 2 * kMinLength;
        m_base += threeZeros ? kMinLength : kMinLength >> 1;
        m_length = threeZeros ? kMinLength >> 1 : kMinLength >> 9;
        if (before > m_base)
            carry();
        shiftOut();
        m_bytes.resize(m_bytes.size() + (threeZeros ? 3 : 2), std::byte{0});
        return m_bytes;
    }

private:
    void settle(std::uint32_t before) {
        if (before > m_base)
            carry();
        if (m_length < kMinLength)
            shiftOut();
    }
    void carry() {
        std::size_t i = m_bytes.size();
        while (m_bytes[--i] == std::byte{0xFF})
            m_bytes[i] = std::byte{0};
        m_bytes[i] = static_cast<std::byte>(std::to_integer<unsigned>(m_bytes[i]) + 1);
    }
    void shiftOut() {
        do {
            m_bytes.push_back(static_cast<std::byte>(m_base >> 24));
            m_base <<= 8;
        } while ((m_length <<= 8) < kMinLength);
    }
    std::uint32_t m_base = 0;
    std::uint32_t m_length = 0xFFFFFFFFu;
    std::vector<std::byte> m_bytes;
};

/// The integer compressor, encoder side, for `bits`-bit values and `contexts` contexts.
class TestIntegerEncoder {
public:
    TestIntegerEncoder(std::uint32_t bits, std::uint32_t contexts, std::uint32_t highBits = 8)
        : m_highBits(highBits) {
        m_bits = bits >= 1 && bits < 32 ? bits : 32;
        m_range = m_bits < 32 ? (std::uint64_t{1} << m_bits) : 0;
        for (std::uint32_t c = 0; c < contexts; ++c)
            m_classes.emplace_back(m_bits + 1);
        for (std::uint32_t k = 1; k <= m_bits; ++k)
            m_positions.emplace_back(1u << std::min(k, highBits));
    }
    void encode(TestEncoder& out, std::int32_t prediction, std::int32_t value,
                std::uint32_t context) {
        std::int64_t correction = std::int64_t{value} - prediction;
        if (m_range != 0) {
            const auto half = static_cast<std::int64_t>(m_range / 2);
            if (correction < -half)
                correction += static_cast<std::int64_t>(m_range);
            else if (correction > half - 1)
                correction -= static_cast<std::int64_t>(m_range);
        } else {
            correction = static_cast<std::int32_t>(static_cast<std::uint32_t>(correction));
        }
        const auto c = static_cast<std::int32_t>(correction);
        std::uint32_t magnitude =
            c <= 0 ? 0u - static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(c) - 1;
        std::uint32_t k = 0;
        for (; magnitude != 0; magnitude >>= 1)
            ++k;
        out.symbol(m_classes[context], k);
        m_lastClass = k;
        if (k == 0) {
            out.bit(m_zeroOrOne, static_cast<std::uint32_t>(c));
            return;
        }
        if (k >= 32)
            return;
        const std::uint32_t position = c < 0 ? static_cast<std::uint32_t>(c) + ((1u << k) - 1)
                                             : static_cast<std::uint32_t>(c) - 1;
        if (k <= m_highBits) {
            out.symbol(m_positions[k - 1], position);
        } else {
            const std::uint32_t low = k - m_highBits;
            out.symbol(m_positions[k - 1], position >> low);
            out.raw(low, position & ((1u << low) - 1));
        }
    }

    /// The magnitude class of the last correction, as IntegerDecoder::lastClass().
    [[nodiscard]] std::uint32_t lastClass() const { return m_lastClass; }

private:
    std::uint32_t m_bits = 32, m_highBits = 8, m_lastClass = 0;
    std::uint64_t m_range = 0;
    std::vector<TestSymbolModel> m_classes, m_positions;
    TestBitModel m_zeroOrOne;
};

} // namespace terratin::io::laz::test
