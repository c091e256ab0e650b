#pragma once
/// @file
/// Little-endian loads and stores for the LAZ decoder, and a bounds-checked cursor for the
/// container's fixed-layout records (LAS header, VLR headers, the LASzip VLR, the chunk table
/// header). Every multi-byte field of LAS and LAZ is little-endian (LAS 1.4 R15, 2.1).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>

namespace terratin::io::laz {

/// The value of type T stored little-endian at `bytes`. Precondition: sizeof(T) bytes there.
template <typename T> [[nodiscard]] inline T loadLe(const std::byte* bytes) {
    static_assert(std::is_integral_v<T> || std::is_floating_point_v<T>);
    T value;
    if constexpr (std::endian::native == std::endian::little) {
        std::memcpy(&value, bytes, sizeof(T));
    } else {
        std::make_unsigned_t<std::conditional_t<std::is_floating_point_v<T>, std::int64_t, T>>
            bits = 0;
        for (std::size_t i = sizeof(T); i-- > 0;)
            bits = static_cast<decltype(bits)>((bits << 8) | std::to_integer<unsigned>(bytes[i]));
        std::memcpy(&value, &bits, sizeof(T));
    }
    return value;
}

/// Stores `value` little-endian at `bytes`. Precondition: sizeof(T) bytes there.
template <typename T> inline void storeLe(std::byte* bytes, T value) {
    static_assert(std::is_integral_v<T>);
    if constexpr (std::endian::native == std::endian::little) {
        std::memcpy(bytes, &value, sizeof(T));
    } else {
        auto bits = static_cast<std::make_unsigned_t<T>>(value);
        for (std::size_t i = 0; i < sizeof(T); ++i, bits = static_cast<decltype(bits)>(bits >> 8))
            bytes[i] = static_cast<std::byte>(bits & 0xFFu);
    }
}

/// Reads fields in order from a byte range; a read past the end sets overran() and yields
/// zero instead of touching memory outside the range, so a parser checks once at the end of
/// a record (or before trusting a field) rather than before every field.
class ByteCursor {
public:
    explicit ByteCursor(std::span<const std::byte> bytes) : m_bytes(bytes) {}

    template <typename T> [[nodiscard]] T read() {
        if (sizeof(T) > m_bytes.size() - m_position) {
            m_overran = true;
            m_position = m_bytes.size();
            return T{};
        }
        const T value = loadLe<T>(m_bytes.data() + m_position);
        m_position += sizeof(T);
        return value;
    }
    /// A fixed-width text field without its trailing NULs (VLR user ids, LAS 1.4 R15 2.5).
    [[nodiscard]] std::string readText(std::size_t width) {
        if (width > m_bytes.size() - m_position) {
            m_overran = true;
            m_position = m_bytes.size();
            return {};
        }
        const auto* first = reinterpret_cast<const char*>(m_bytes.data() + m_position);
        m_position += width;
        std::size_t length = 0;
        while (length < width && first[length] != '\0')
            ++length;
        return std::string(first, length);
    }
    void skip(std::size_t count) {
        if (count > m_bytes.size() - m_position) {
            m_overran = true;
            m_position = m_bytes.size();
            return;
        }
        m_position += count;
    }
    [[nodiscard]] bool overran() const { return m_overran; }
    [[nodiscard]] std::size_t position() const { return m_position; }

private:
    std::span<const std::byte> m_bytes;
    std::size_t m_position = 0;
    bool m_overran = false;
};

} // namespace terratin::io::laz
