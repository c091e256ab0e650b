#include "buffered_file.hpp"

#include "atomic_output.hpp"
#include "terratin/error.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

namespace terratin::io::detail {

namespace {
/// Large enough that write(2) calls cost nothing next to the formatting, small enough to stay
/// in the last-level cache.
constexpr std::size_t kBufferBytes = std::size_t{1} << 20;
/// The longest number text: a shortest-form double is at most 24 characters.
constexpr std::size_t kNumberBytes = 32;
} // namespace

BufferedFile::BufferedFile(std::string_view stage, const std::filesystem::path& path,
                           const std::filesystem::path& display)
    : m_stage(stage), m_display(display), m_buffer(kBufferBytes, '\0') {
    m_fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (m_fd < 0)
        throw IoError(m_stage + ": cannot create a temporary file for " + quoted(m_display) + ": " +
                      std::strerror(errno));
}

BufferedFile::~BufferedFile() {
    if (m_fd >= 0)
        ::close(m_fd);
}

void BufferedFile::number(double value) {
    reserve(kNumberBytes);
    const auto result =
        std::to_chars(m_buffer.data() + m_used, m_buffer.data() + m_buffer.size(), value);
    m_used = static_cast<std::size_t>(result.ptr - m_buffer.data());
}

void BufferedFile::number(std::uint64_t value) {
    reserve(kNumberBytes);
    const auto result =
        std::to_chars(m_buffer.data() + m_used, m_buffer.data() + m_buffer.size(), value);
    m_used = static_cast<std::size_t>(result.ptr - m_buffer.data());
}

void BufferedFile::bytes(const void* data, std::size_t size) {
    if (size > m_buffer.size()) {
        drain();
        writeAll(static_cast<const char*>(data), size);
        return;
    }
    reserve(size);
    std::memcpy(m_buffer.data() + m_used, data, size);
    m_used += size;
}

void BufferedFile::drain() {
    writeAll(m_buffer.data(), m_used);
    m_used = 0;
}

void BufferedFile::writeAll(const char* data, std::size_t size) {
    std::size_t written = 0;
    while (written < size) {
        const ssize_t count = ::write(m_fd, data + written, size - written);
        if (count < 0) {
            if (errno == EINTR)
                continue;
            throw IoError(m_stage + ": cannot write " + quoted(m_display) + ": " +
                          std::strerror(errno));
        }
        written += static_cast<std::size_t>(count);
    }
}

void BufferedFile::close() {
    drain();
    const int fd = m_fd;
    m_fd = -1;
    // fsync before the rename: the renamed file must hold its data, not just its name, if the
    // machine stops right after.
    const bool synced = ::fsync(fd) == 0;
    const int syncErrno = errno;
    if (::close(fd) != 0 || !synced)
        throw IoError(m_stage + ": cannot finish writing " + quoted(m_display) + ": " +
                      std::strerror(synced ? errno : syncErrno));
}

} // namespace terratin::io::detail
