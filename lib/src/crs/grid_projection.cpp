#include "terratin/crs/grid_projection.hpp"

#include "terratin/crs/reprojection.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <optional>

namespace terratin::crs {

namespace {

/// Rows a task reprojects at a time: a few thousand cells per PROJ call.
constexpr std::size_t kRowGrain = 4;

} // namespace

std::vector<Point2> projectCellCentres(const HeightGrid& grid, const std::string& sourceWkt,
                                       const std::string& targetWkt) {
    const Reprojector first(sourceWkt, targetWkt); // a CRS error is thrown here, once
    // PROJ objects are not thread-safe: one Reprojector per thread.
    tbb::enumerable_thread_specific<std::optional<Reprojector>> reprojectors;
    const auto width = static_cast<std::size_t>(grid.width);
    std::vector<Point2> positions(grid.cellCount());
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, static_cast<std::size_t>(grid.height), kRowGrain),
        [&](const tbb::blocked_range<std::size_t>& rows) {
            std::optional<Reprojector>& reprojector = reprojectors.local();
            if (!reprojector)
                reprojector.emplace(sourceWkt, targetWkt);
            std::vector<Point3> centres;
            centres.reserve(rows.size() * width);
            for (std::size_t row = rows.begin(); row < rows.end(); ++row)
                for (std::size_t col = 0; col < width; ++col) {
                    const Point2 centre = grid.cellCentre(static_cast<std::int64_t>(row),
                                                          static_cast<std::int64_t>(col));
                    centres.push_back({centre.x, centre.y, 0.0});
                }
            reprojector->transform(centres);
            Point2* out = positions.data() + rows.begin() * width;
            for (const Point3& p : centres)
                *out++ = {p.x, p.y};
        });
    return positions;
}

} // namespace terratin::crs
