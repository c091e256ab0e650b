#pragma once
/// @file
/// The GPS time coding that GPSTIME11 version 2 and POINT14 version 3's GPS time layer share.
/// LASzip never decodes the double as a number: it predicts the 64-bit pattern as an integer,
/// since consecutive pulses differ by a nearly constant step. A time is coded as a multiple of
/// the last step plus a correction, as a new 32-bit step, or as the start of a new sequence
/// (its high 32 bits predicted from the current time's, its low 32 raw). Four sequences are
/// kept, for files that interleave flight lines or scanners, and switches between them are
/// coded (Isenburg 2013).
///
/// The two items number their codes differently in one place only: GPSTIME11 v2 codes every
/// point, so both its alphabets hold an "unchanged" code just before "new sequence"; POINT14's
/// layer holds only the points whose time changed (its returns-and-xy layer says which), so it
/// has no such code and its codes from "new sequence" on are one lower.

#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <array>
#include <cstdint>

namespace terratin::io::laz {

/// Adds a signed 32-bit difference to a time's bit pattern, wrapping as the writer does.
[[nodiscard]] inline std::uint64_t advancedTime(std::uint64_t time, std::int32_t difference) {
    return time + static_cast<std::uint64_t>(static_cast<std::int64_t>(difference));
}

/// An outlier becomes the new step only after more than this many in a row.
inline constexpr std::int32_t kOutlierRunLimit = 3;

/// Which of the two numberings of the codes (see the file's description).
enum class GpsTimeCodes {
    /// GPSTIME11 version 2: every point coded, an unchanged time included.
    WithUnchanged,
    /// POINT14 version 3: only the times that changed are coded.
    ChangedOnly,
};

/// The four GPS time sequences of one stream (a chunk, or a scanner channel of a POINT14
/// chunk) and the models that decode them.
class GpsTimeSequences {
public:
    explicit GpsTimeSequences(GpsTimeCodes codes);

    /// A new chunk or scanner channel whose last time was `first` (bit pattern); every model
    /// back to its initial state.
    void start(std::uint64_t first);
    /// The next coded time; current() holds it afterwards. A writer switches sequence at most
    /// once per time, only to a sequence whose time is within a 32-bit step, so a second
    /// switch marks the stream corrupt (decoder.corrupt()) instead of decoding on.
    void decode(RangeDecoder& decoder);
    /// The time decoded last (bit pattern of the double).
    [[nodiscard]] std::uint64_t current() const { return m_time[m_current]; }

private:
    /// Whether the time is done; false: the current sequence changed, decode again.
    bool decodeAfterZeroStep(RangeDecoder& decoder);
    bool decodeWithStep(RangeDecoder& decoder);
    [[nodiscard]] std::int32_t decodeMultipleOfStep(RangeDecoder& decoder, std::uint32_t symbol);
    void countOutlier(std::int32_t difference);
    void startSequence(RangeDecoder& decoder);
    void switchSequence(std::uint32_t ahead) { m_current = (m_current + ahead) & 3u; }

    /// 1 with an "unchanged" code (GPSTIME11 v2), else 0: how much higher the codes from
    /// "new sequence" on are.
    std::uint32_t m_unchangedCodes;
    std::array<std::uint64_t, 4> m_time{};
    std::array<std::int32_t, 4> m_step{};
    std::array<std::int32_t, 4> m_outlierRun{};
    std::uint32_t m_current = 0;
    std::uint32_t m_newest = 0;
    /// The codes while the current sequence's step is not zero.
    SymbolModel m_multiple;
    /// The codes while it is zero: no multiple of it can predict anything.
    SymbolModel m_afterZeroStep;
    IntegerDecoder m_difference;
};

// Inline: it runs once per coded time, and a call of its own would cost about as much as it does.
inline void GpsTimeSequences::decode(RangeDecoder& decoder) {
    // Decoding on after a second switch could loop forever on a corrupt stream.
    bool done = m_step[m_current] == 0 ? decodeAfterZeroStep(decoder) : decodeWithStep(decoder);
    if (!done) {
        done = m_step[m_current] == 0 ? decodeAfterZeroStep(decoder) : decodeWithStep(decoder);
        if (!done)
            decoder.markCorrupt();
    }
}

} // namespace terratin::io::laz
