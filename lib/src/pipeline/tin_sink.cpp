#include "tin_sink.hpp"

#include "terratin/error.hpp"

#include <utility>

namespace terratin::detail {

WholeFileSink::WholeFileSink(std::filesystem::path output, io::TinWriteOptions& writeOptions)
    : m_output(std::move(output)), m_writeOptions(&writeOptions) {}

void WholeFileSink::write(std::size_t piece, TinMesh tin, std::vector<io::RasterCell> vertexCells) {
    if (piece != 0 || m_tin)
        throw Error("WholeFileSink: a whole TIN is one piece");
    m_tin = std::move(tin);
    m_vertexCells = std::move(vertexCells);
}

io::TinWriteResult WholeFileSink::finish(const ProgressCallback& progress) {
    if (!m_tin)
        throw Error("WholeFileSink: no TIN to write");
    m_writeOptions->vertexCells = std::move(m_vertexCells);
    return io::writeTin(*m_tin, m_output, *m_writeOptions, progress);
}

std::uint64_t WholeFileSink::points() const {
    return m_tin ? m_tin->vertexCount() : 0;
}

std::uint64_t WholeFileSink::triangles() const {
    return m_tin ? m_tin->triangleCount() : 0;
}

} // namespace terratin::detail
