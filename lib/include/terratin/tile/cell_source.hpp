#pragma once
/// @file
/// Where a tiled refinement reads its cells (refineTiles): a window at a time, so
/// that a raster read through GDAL (io::RasterCells) never has to be held whole.

#include "terratin/geometry/height_grid.hpp"

#include <array>

namespace terratin {

class CellSource {
public:
    virtual ~CellSource() = default;

    [[nodiscard]] virtual int width() const = 0;
    [[nodiscard]] virtual int height() const = 0;
    /// The raster's geotransform (HeightGrid::geoTransform).
    [[nodiscard]] virtual std::array<double, 6> geoTransform() const = 0;

    /// The cells of rows firstRow .. firstRow + rows - 1 and columns firstColumn .. firstColumn +
    /// columns - 1 (inside the raster, at least one each), as a grid whose firstRow and
    /// firstColumn say where it lies, so that its cells have their centres in the whole raster;
    /// NaN = no data, elevations rounded to float32 as HeightGrid::storeElevations does.
    [[nodiscard]] virtual HeightGrid window(int firstRow, int rows, int firstColumn,
                                            int columns) = 0;
};

/// A grid in memory as a CellSource: its windows are copies. The grid must outlive it.
class GridCells final : public CellSource {
public:
    explicit GridCells(const HeightGrid& grid) : m_grid(&grid) {}

    [[nodiscard]] int width() const override { return m_grid->width; }
    [[nodiscard]] int height() const override { return m_grid->height; }
    [[nodiscard]] std::array<double, 6> geoTransform() const override {
        return m_grid->geoTransform;
    }
    [[nodiscard]] HeightGrid window(int firstRow, int rows, int firstColumn, int columns) override;

private:
    const HeightGrid* m_grid;
};

} // namespace terratin
