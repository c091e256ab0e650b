#pragma once
/// @file
/// Small pieces of state shared by the LAZ point item decoders: models chosen by the value of
/// a previous byte and created on first use, the running median LASzip predicts coordinate
/// differences with, and wrap-around arithmetic (a LAZ field overflows as its integer type
/// does in the writer, so the decoder must wrap the same way, without signed overflow).

#include "range_decoder.hpp"

#include <array>
#include <cstdint>
#include <memory>

namespace terratin::io::laz {

/// a + b with 32-bit wrap-around.
[[nodiscard]] inline std::int32_t wrappingAdd(std::int32_t a, std::int32_t b) {
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}

/// a * b with 32-bit wrap-around.
[[nodiscard]] inline std::int32_t wrappingMultiply(std::int32_t a, std::int32_t b) {
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) * static_cast<std::uint32_t>(b));
}

/// 256 symbol models of 256 symbols, one per value of the byte being predicted (its value in
/// the previous point). Most files use a few of them, so each is allocated the first time it
/// is needed and, in every later chunk, reset the first time it is needed there: the same
/// as resetting all of them at each chunk start, without the cost.
class ByteContextModels {
public:
    /// Forget what the models learnt: the start of a chunk.
    void reset() { ++m_chunkNumber; }

    [[nodiscard]] SymbolModel& at(std::uint8_t context) {
        std::unique_ptr<SymbolModel>& model = m_models[context];
        if (!model) {
            model = std::make_unique<SymbolModel>(256);
            m_resetIn[context] = m_chunkNumber;
        } else if (m_resetIn[context] != m_chunkNumber) {
            model->reset();
            m_resetIn[context] = m_chunkNumber;
        }
        return *model;
    }

private:
    std::array<std::unique_ptr<SymbolModel>, 256> m_models{};
    std::array<std::uint32_t, 256> m_resetIn{};
    std::uint32_t m_chunkNumber = 1;
};

/// The predictor of POINT10 version 2 for x and y differences: five recent values kept in
/// order, the prediction being the middle one. A new value replaces the largest while values
/// keep arriving below the middle; one at or above it makes the next value replace the
/// smallest instead (and the reverse), so the window follows the data from both sides. The
/// writer keeps the same window, so the rule is part of the format.
class RunningMedian5 {
public:
    void reset() {
        m_sorted.fill(0);
        m_dropLargest = true;
    }
    [[nodiscard]] std::int32_t middle() const { return m_sorted[2]; }

    void add(std::int32_t value) {
        const std::int32_t oldMiddle = m_sorted[2];
        if (m_dropLargest) {
            std::size_t i = 4;
            for (; i > 0 && m_sorted[i - 1] > value; --i)
                m_sorted[i] = m_sorted[i - 1];
            m_sorted[i] = value;
            m_dropLargest = value < oldMiddle;
        } else {
            std::size_t i = 0;
            for (; i < 4 && m_sorted[i + 1] < value; ++i)
                m_sorted[i] = m_sorted[i + 1];
            m_sorted[i] = value;
            m_dropLargest = !(oldMiddle < value);
        }
    }

private:
    std::array<std::int32_t, 5> m_sorted{};
    bool m_dropLargest = true;
};

} // namespace terratin::io::laz
