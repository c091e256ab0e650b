#include "cell_flags.hpp"

#include "grid_scan.hpp"

namespace terratin::detail {

namespace {
// Marks a nodata cell already assigned to a region while labelling; cleared afterwards.
constexpr std::uint8_t kSeen = 0x80;
} // namespace

CellFlags makeCellFlags(const HeightGrid& grid, std::size_t maxHole, bool fillHoles,
                        std::size_t& openHoleCells) {
    const std::size_t cells = grid.cellCount();
    CellFlags flags(cells, 0);
    bool anyNoData = false;
    for (std::size_t cell = 0; cell < cells; ++cell) {
        if (std::isnan(grid.z[cell])) {
            flags[cell] = kCellNoData;
            anyNoData = true;
        }
    }
    openHoleCells = 0;
    if (fillHoles || !anyNoData)
        return flags;

    const std::int64_t width = grid.width;
    const std::int64_t height = grid.height;
    std::vector<std::size_t> region;
    for (std::size_t seed = 0; seed < cells; ++seed) {
        if (flags[seed] != kCellNoData)
            continue;
        // Depth-first flood fill; `region` is both the stack and the list of the hole's cells.
        region.clear();
        region.push_back(seed);
        flags[seed] |= kSeen;
        for (std::size_t next = 0; next < region.size(); ++next) {
            const auto cell = static_cast<std::int64_t>(region[next]);
            const std::int64_t row = cell / width;
            const std::int64_t col = cell % width;
            for (std::int64_t dr = -1; dr <= 1; ++dr) {
                for (std::int64_t dc = -1; dc <= 1; ++dc) {
                    const std::int64_t r = row + dr;
                    const std::int64_t c = col + dc;
                    if (r < 0 || r >= height || c < 0 || c >= width)
                        continue;
                    const auto neighbour = static_cast<std::size_t>(r * width + c);
                    if (flags[neighbour] == kCellNoData) {
                        flags[neighbour] |= kSeen;
                        region.push_back(neighbour);
                    }
                }
            }
        }
        if (region.size() > maxHole) {
            for (const std::size_t cell : region)
                flags[cell] |= kCellOpenHole;
            openHoleCells += region.size();
        }
    }
    for (std::uint8_t& flag : flags)
        flag &= static_cast<std::uint8_t>(~kSeen);
    return flags;
}

} // namespace terratin::detail
