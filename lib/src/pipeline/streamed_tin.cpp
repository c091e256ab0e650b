#include "streamed_tin.hpp"

#include <vector>

namespace terratin::detail {

StreamedTin::StreamedTin(const std::filesystem::path& output,
                         const io::TinWriteOptions& writeOptions, std::size_t width,
                         std::size_t height, std::size_t tileSize, std::string_view pieceBy)
    : m_writer(io::detail::openTinStream(output, writeOptions, pieceBy)),
      m_tiles(width, height, tileSize), m_numbers(width) {}

void StreamedTin::write(std::size_t tile, TinMesh tin, std::vector<io::RasterCell> vertexCells) {
    const TilePlace place = m_tiles.placeOf(tile);
    std::vector<std::uint32_t> numbers(tin.vertexCount());
    for (std::size_t v = 0; v < numbers.size(); ++v)
        numbers[v] = m_numbers.number(tin.sourceIndex[v], place).number;
    m_writer->append({&tin, numbers, vertexCells});
}

io::TinWriteResult StreamedTin::finish(const ProgressCallback& progress) {
    return m_writer->finish(progress);
}

} // namespace terratin::detail
