#pragma once
/// @file
/// Tiles of a rotated grid. A rotated geotransform rounds the centres of a tile
/// side's cells off their common line, so the sides of two tiles would no longer be the same
/// straight chain of hull edges. Such a grid's tiles are therefore refined in its pixel frame,
/// where every cell centre is exact (x = column + 0.5, y = +-(row + 0.5)), and each joined
/// tile's vertices are then put at their cells' centres through the real geotransform: the same
/// positions the untiled refiner uses. The map is affine with a positive determinant (the
/// frame's y sign is the geotransform's), so triangles keep their orientation; each is checked
/// exactly after the mapping. Within a tile the TIN is exactly Delaunay in the pixel frame,
/// which for square pixels is the CRS's Delaunay TIN up to the ties the rounding breaks.

#include "terratin/tile/cell_source.hpp"
#include "terratin/triangulate/tin_mesh.hpp"
#include "tile_grid.hpp"

#include <array>

namespace terratin::detail {

/// True when `geoTransform` has rotation (shear) terms: c[2] or c[4] nonzero.
bool isRotated(const std::array<double, 6>& geoTransform);

/// The cells of `world` (a rotated grid) in its pixel frame: the same windows, with the
/// geotransform {0, 1, 0, 0, 0, s}, s the sign of the geotransform's determinant.
class PixelFrameCells final : public CellSource {
public:
    /// `world` must outlive this.
    explicit PixelFrameCells(CellSource& world);

    [[nodiscard]] int width() const override { return m_world->width(); }
    [[nodiscard]] int height() const override { return m_world->height(); }
    [[nodiscard]] std::array<double, 6> geoTransform() const override { return m_frame; }
    [[nodiscard]] HeightGrid window(int firstRow, int rows, int firstColumn, int columns) override;

private:
    CellSource* m_world;
    std::array<double, 6> m_frame;
};

/// Moves each vertex of `tile` (refined in the pixel frame, sourceIndex its cell within the
/// tile at `place`) to its cell's centre through `world`. Throws Error when a triangle's
/// orientation does not survive the rounding of the mapped positions.
void mapTileToWorld(TinMesh& tile, const TilePlace& place, const std::array<double, 6>& world);

} // namespace terratin::detail
