/// @file
/// File and memory sources of LAZ bytes (see laz_source.hpp). The file source reads with
/// POSIX pread, which needs no shared file position.

#include "laz_source.hpp"

#include "laz_error.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace terratin::io::laz {

namespace {

class FileSource final : public LazSource {
public:
    explicit FileSource(const std::string& path) : m_path(path) {
        m_descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (m_descriptor < 0)
            throw IoError(std::string(kLazStage) + ": cannot open '" + path +
                          "': " + std::strerror(errno));
        struct stat status {};
        if (::fstat(m_descriptor, &status) != 0 || !S_ISREG(status.st_mode)) {
            ::close(m_descriptor);
            throw IoError(std::string(kLazStage) + ": cannot size '" + path + "' (not a file?)");
        }
        m_size = static_cast<std::uint64_t>(status.st_size);
    }
    ~FileSource() override { ::close(m_descriptor); }
    FileSource(const FileSource&) = delete;
    FileSource& operator=(const FileSource&) = delete;

    [[nodiscard]] std::uint64_t size() const override { return m_size; }

    void read(std::uint64_t offset, std::span<std::byte> out) const override {
        std::size_t done = 0;
        while (done < out.size()) {
            const ssize_t got = ::pread(m_descriptor, out.data() + done, out.size() - done,
                                        static_cast<off_t>(offset + done));
            if (got < 0 && errno == EINTR)
                continue;
            if (got <= 0)
                throw IoError(std::string(kLazStage) + ": cannot read " +
                              std::to_string(out.size()) + " bytes at offset " +
                              std::to_string(offset) + " of '" + m_path +
                              "' (the file changed while being read?)");
            done += static_cast<std::size_t>(got);
        }
    }

private:
    std::string m_path;
    int m_descriptor = -1;
    std::uint64_t m_size = 0;
};

class MemorySource final : public LazSource {
public:
    explicit MemorySource(std::span<const std::byte> bytes) : m_bytes(bytes) {}
    [[nodiscard]] std::uint64_t size() const override { return m_bytes.size(); }
    void read(std::uint64_t offset, std::span<std::byte> out) const override {
        if (!out.empty())
            std::memcpy(out.data(), m_bytes.data() + offset, out.size());
    }

private:
    std::span<const std::byte> m_bytes;
};

} // namespace

std::unique_ptr<LazSource> openFileSource(const std::string& path) {
    return std::make_unique<FileSource>(path);
}

std::unique_ptr<LazSource> memorySource(std::span<const std::byte> bytes) {
    return std::make_unique<MemorySource>(bytes);
}

} // namespace terratin::io::laz
