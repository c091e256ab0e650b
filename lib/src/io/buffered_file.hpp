#pragma once
/// @file
/// BufferedFile: fast sequential output for the mesh writers. Numbers are formatted with
/// std::to_chars into a 1 MiB buffer that goes to the file with write(2) when full; doubles
/// in their shortest round-trip form, so a reader that parses them with strtod (or
/// std::from_chars) gets back the same bits.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

class BufferedFile {
public:
    /// Creates (or truncates) `path`; IoError "<stage>: cannot create '<display>': <reason>".
    /// `display` is the name used in messages (the final output, not the temporary).
    BufferedFile(std::string_view stage, const std::filesystem::path& path,
                 const std::filesystem::path& display);
    BufferedFile(const BufferedFile&) = delete;
    BufferedFile& operator=(const BufferedFile&) = delete;
    /// Closes without reporting (the caller's failure path); call close() on success.
    ~BufferedFile();

    void text(std::string_view text) { bytes(text.data(), text.size()); }
    void put(char ch) {
        reserve(1);
        m_buffer[m_used++] = ch;
    }
    /// Shortest decimal form that reads back as the same double ("1234.5", "1e+20").
    void number(double value);
    void number(std::uint64_t value);
    /// Raw bytes (binary formats; the caller chooses the byte order).
    void bytes(const void* data, std::size_t size);

    /// Writes what is buffered, flushes it to the file and closes it; IoError on failure
    /// (disk full...), naming the output.
    void close();

private:
    void reserve(std::size_t size) {
        if (m_used + size > m_buffer.size())
            drain();
    }
    /// Writes the buffer out and empties it.
    void drain();
    void writeAll(const char* data, std::size_t size);

    std::string m_stage;
    std::filesystem::path m_display;
    int m_fd = -1;
    std::string m_buffer;
    std::size_t m_used = 0;
};

} // namespace terratin::io::detail
