/// @file
/// The file source of byte_source.hpp.

#include "byte_source.hpp"

#include "terratin/error.hpp"

#include <cerrno>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace terratin::io::detail {

FileSource::FileSource(const std::string& path, std::string_view stage)
    : m_path(path), m_stage(stage) {
    m_descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (m_descriptor < 0)
        throw IoError(m_stage + ": cannot open '" + path + "': " + std::strerror(errno));
    struct stat status {};
    if (::fstat(m_descriptor, &status) != 0 || !S_ISREG(status.st_mode)) {
        ::close(m_descriptor);
        throw IoError(m_stage + ": cannot size '" + path + "' (not a file?)");
    }
    m_size = static_cast<std::uint64_t>(status.st_size);
}

FileSource::~FileSource() {
    ::close(m_descriptor);
}

void FileSource::read(std::uint64_t offset, std::span<std::byte> out) const {
    std::size_t done = 0;
    while (done < out.size()) {
        const ssize_t got = ::pread(m_descriptor, out.data() + done, out.size() - done,
                                    static_cast<off_t>(offset + done));
        if (got < 0 && errno == EINTR)
            continue;
        if (got <= 0)
            throw IoError(m_stage + ": cannot read " + std::to_string(out.size()) +
                          " bytes at offset " + std::to_string(offset) + " of '" + m_path +
                          "' (the file changed while being read?)");
        done += static_cast<std::size_t>(got);
    }
}

} // namespace terratin::io::detail
