#include "tile_files.hpp"

#include "terratin/error.hpp"
#include "terratin/io/tin_format.hpp"

#include <algorithm>
#include <string>
#include <system_error>

namespace terratin::detail {

namespace fs = std::filesystem;

namespace {

int digitsOf(std::size_t largest) {
    int digits = 1;
    for (; largest >= 10; largest /= 10)
        ++digits;
    return digits;
}

std::string padded(std::size_t number, int digits) {
    std::string text = std::to_string(number);
    return std::string(
               static_cast<std::size_t>(std::max(0, digits - static_cast<int>(text.size()))), '0') +
           text;
}

/// The quadrilateral through the corner cells of the tile (their centres, or their positions
/// with `cellPositions`), counter-clockwise.
std::array<std::array<double, 2>, 4>
footprint(const HeightGrid& extent, CellRange rows, CellRange columns,
          const std::function<std::vector<Point2>(const HeightGrid&)>& cellPositions) {
    const auto centre = [&](std::size_t row, std::size_t column) {
        Point2 p =
            extent.cellCentre(static_cast<std::int64_t>(row), static_cast<std::int64_t>(column));
        if (cellPositions) {
            HeightGrid cell;
            cell.width = 1;
            cell.height = 1;
            cell.geoTransform = extent.geoTransform;
            cell.firstRow = static_cast<int>(row);
            cell.firstColumn = static_cast<int>(column);
            p = cellPositions(cell).at(0);
        }
        return std::array<double, 2>{p.x, p.y};
    };
    std::array<std::array<double, 2>, 4> corners{
        centre(rows.first, columns.first), centre(rows.first, columns.last),
        centre(rows.last, columns.last), centre(rows.last, columns.first)};
    double twiceArea = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
        const auto& a = corners[i];
        const auto& b = corners[(i + 1) % 4];
        twiceArea += a[0] * b[1] - b[0] * a[1];
    }
    if (twiceArea < 0.0)
        std::reverse(corners.begin(), corners.end());
    return corners;
}

} // namespace

TileFiles::TileFiles(fs::path directory, const HeightGrid& extent, std::size_t tileSize,
                     io::TinWriteOptions writeOptions,
                     std::function<std::vector<Point2>(const HeightGrid&)> cellPositions)
    : m_directory(std::move(directory)), m_extent(extent),
      m_tiles(static_cast<std::size_t>(extent.width), static_cast<std::size_t>(extent.height),
              tileSize),
      m_digits(digitsOf(std::max(m_tiles.tileRows(), m_tiles.tileColumns()) - 1)),
      m_writeOptions(std::move(writeOptions)), m_cellPositions(std::move(cellPositions)) {
    std::error_code error;
    if (!fs::exists(m_directory, error)) {
        if (!fs::create_directories(m_directory, error))
            throw IoError("Tiles: cannot make the directory '" + m_directory.string() +
                          "': " + error.message());
        m_madeDirectory = true;
    } else if (!fs::is_directory(m_directory, error)) {
        throw IoError("Tiles: '" + m_directory.string() + "' is not a directory");
    }
    try {
        checkEveryFile();
    } catch (...) {
        removeWritten(); // the directory, if made here
        throw;
    }
}

void TileFiles::checkEveryFile() const {
    // Refused now rather than after hours of refinement.
    for (std::size_t row = 0; row < m_tiles.tileRows(); ++row)
        for (std::size_t column = 0; column < m_tiles.tileColumns(); ++column)
            io::checkTinOutput(m_directory / fileName(row, column), m_writeOptions);
    io::TinWriteOptions indexOptions;
    indexOptions.format = io::TinFormat::GeoPackage;
    indexOptions.overwrite = m_writeOptions.overwrite;
    io::checkTinOutput(indexPath(), indexOptions);
}

TileFiles::~TileFiles() {
    if (!m_committed)
        removeWritten();
}

std::string TileFiles::fileName(std::size_t tileRow, std::size_t tileColumn) const {
    return "tile_" + padded(tileRow, m_digits) + "_" + padded(tileColumn, m_digits) +
           std::string(io::tinFormatExtension(m_writeOptions.format));
}

void TileFiles::write(std::size_t tile, TinMesh tin, std::vector<io::RasterCell> vertexCells) {
    if (tin.triangleCount() == 0)
        return;
    const std::size_t tileRow = tile / m_tiles.tileColumns();
    const std::size_t tileColumn = tile % m_tiles.tileColumns();
    const std::string name = fileName(tileRow, tileColumn);
    io::TinWriteOptions options = m_writeOptions;
    options.vertexCells = std::move(vertexCells);
    // Recorded first: a write that fails half-way is taken back with the others.
    m_entries.push_back({name, static_cast<std::int64_t>(tileRow),
                         static_cast<std::int64_t>(tileColumn),
                         static_cast<std::int64_t>(tin.vertexCount()),
                         static_cast<std::int64_t>(tin.triangleCount()),
                         footprint(m_extent, m_tiles.rowsOf(tileRow), m_tiles.columnsOf(tileColumn),
                                   m_cellPositions)});
    m_features += io::writeTin(tin, m_directory / name, options).features;
    m_points += tin.vertexCount();
    m_triangles += tin.triangleCount();
}

io::TinWriteResult TileFiles::finish(const ProgressCallback&) {
    io::writeTileIndex(indexPath(), m_writeOptions.crsWkt, m_entries, m_writeOptions.overwrite);
    m_committed = true;
    io::TinWriteResult written;
    written.features = m_features;
    return written;
}

void TileFiles::removeWritten() noexcept {
    std::error_code error;
    for (const io::TileIndexEntry& entry : m_entries) {
        // The tile's file and its companions (a Shapefile's .shx .dbf .prj, a style's .qml).
        const std::string stem = fs::path(entry.file).stem().string() + ".";
        for (const fs::directory_entry& file : fs::directory_iterator(m_directory, error))
            if (file.path().filename().string().rfind(stem, 0) == 0)
                fs::remove(file.path(), error);
    }
    if (m_madeDirectory)
        fs::remove(m_directory, error); // only when empty
}

} // namespace terratin::detail
