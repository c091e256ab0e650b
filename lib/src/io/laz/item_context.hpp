#pragma once
/// @file
/// Small pieces of state shared by the LAZ point item decoders: models chosen by the value of
/// a previous byte and created on first use, the running median LASzip predicts coordinate
/// differences with, and wrap-around arithmetic (a LAZ field overflows as its integer type
/// does in the writer, so the decoder must wrap the same way, without signed overflow).

#include "range_decoder.hpp"

#include <array>
#include <cstddef>
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

/// `Count` adaptive models of the same alphabet, one per value of a context (the value of a
/// byte in the previous point, a return count). Most files use a few of them, so each is
/// allocated the first time it is needed and, after every reset(), reset the first time it is
/// needed again: the same as resetting all of them at each chunk start, without the cost.
template <std::size_t Count> class ContextModels {
public:
    /// Models of `symbols` symbols (2-2048).
    explicit ContextModels(std::uint32_t symbols) : m_symbols(symbols) {}

    /// Forget what the models learnt: the start of a chunk (or of a scanner channel in it).
    void reset() { ++m_generation; }

    /// The model of context `context`. Precondition: context < Count.
    [[nodiscard]] SymbolModel& at(std::size_t context) {
        std::unique_ptr<SymbolModel>& model = m_models[context];
        if (!model) {
            model = std::make_unique<SymbolModel>(m_symbols);
            m_resetIn[context] = m_generation;
        } else if (m_resetIn[context] != m_generation) {
            model->reset();
            m_resetIn[context] = m_generation;
        }
        return *model;
    }

private:
    std::uint32_t m_symbols;
    std::array<std::unique_ptr<SymbolModel>, Count> m_models{};
    std::array<std::uint32_t, Count> m_resetIn{};
    std::uint32_t m_generation = 1;
};

/// 256 models of 256 symbols, one per value of the byte being predicted (its value in the
/// previous point).
class ByteContextModels : public ContextModels<256> {
public:
    ByteContextModels() : ContextModels<256>(256) {}
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
