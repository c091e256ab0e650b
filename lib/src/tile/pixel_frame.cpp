#include "pixel_frame.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <string>

namespace terratin::detail {

bool isRotated(const std::array<double, 6>& geoTransform) {
    return geoTransform[2] != 0.0 || geoTransform[4] != 0.0;
}

PixelFrameCells::PixelFrameCells(CellSource& world) : m_world(&world) {
    const std::array<double, 6> c = world.geoTransform();
    const double determinant = c[1] * c[5] - c[2] * c[4];
    m_frame = {0.0, 1.0, 0.0, 0.0, 0.0, determinant < 0.0 ? -1.0 : 1.0};
}

HeightGrid PixelFrameCells::window(int firstRow, int rows, int firstColumn, int columns) {
    HeightGrid cells = m_world->window(firstRow, rows, firstColumn, columns);
    cells.geoTransform = m_frame;
    return cells;
}

void mapTileToWorld(TinMesh& tile, const TilePlace& place, const std::array<double, 6>& world) {
    HeightGrid grid; // the tile's shape and place, for cellCentre
    grid.width = static_cast<int>(place.width);
    grid.height = static_cast<int>(place.height);
    grid.firstRow = static_cast<int>(place.firstRow);
    grid.firstColumn = static_cast<int>(place.firstColumn);
    grid.geoTransform = world;
    for (std::size_t v = 0; v < tile.vertexCount(); ++v) {
        const Point2 centre = grid.cellCentre(std::uint64_t{tile.sourceIndex[v]});
        tile.vertices[v].x = centre.x;
        tile.vertices[v].y = centre.y;
    }
    const auto at = [&](std::size_t corner) {
        const Point3& p = tile.vertices[tile.triangles[corner]];
        return Point2{p.x, p.y};
    };
    for (std::size_t t = 0; t < tile.triangleCount(); ++t)
        if (predicates::orient2d(at(3 * t), at(3 * t + 1), at(3 * t + 2)) <= 0.0)
            throw Error("Refiner: a triangle of the tile at row " + std::to_string(place.firstRow) +
                        ", column " + std::to_string(place.firstColumn) +
                        " turns over when put through the rotated geotransform; warp the DEM "
                        "first (gdalwarp)");
}

} // namespace terratin::detail
