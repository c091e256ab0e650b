/// @file
/// readLazPoints (see laz_points.hpp): each chunk's kept points gathered apart by its
/// worker, then appended in chunk order.

#include "laz_points.hpp"

#include "laz_error.hpp"
#include "laz_point_runs.hpp"

#include <algorithm>
#include <vector>

namespace terratin::io::laz {

namespace {

/// What one chunk gave: its kept points and how many it filtered out.
struct ChunkPoints {
    std::vector<Point3> points;
    std::uint64_t filteredOut = 0;
};

/// Points to reserve for `file`: its count, but no more than one per byte of the file, so a
/// header claiming billions of points in a small file cannot make the reader allocate them.
std::size_t pointsToReserve(const LazFile& file) {
    return static_cast<std::size_t>(std::min(file.header().pointCount, file.fileSize()));
}

} // namespace

void readLazPoints(const LazFile& file, const detail::LasRecordFilter& filter, unsigned threads,
                   const ProgressCallback& progress, PointCloud& cloud) {
    const std::size_t recordLength = file.header().recordLength;
    std::vector<ChunkPoints> chunks(file.chunks().size());
    const auto decodeRun = [&](std::size_t index, std::span<const std::byte> records) {
        ChunkPoints& out = chunks[index];
        const std::size_t count = records.size() / recordLength;
        for (std::size_t r = 0; r < count; ++r) {
            const std::span<const std::byte> record =
                records.subspan(r * recordLength, recordLength);
            if (filter.keeps(record))
                out.points.push_back(filter.point(record));
            else
                ++out.filteredOut;
        }
    };
    const double total = static_cast<double>(std::max<std::uint64_t>(1, file.header().pointCount));
    const auto takeRun = [&](std::size_t index) {
        ChunkPoints taken = std::move(chunks[index]);
        cloud.points.insert(cloud.points.end(), taken.points.begin(), taken.points.end());
        cloud.filteredOut += taken.filteredOut;
        const LazChunk& chunk = file.chunks()[index];
        return !progress ||
               progress(static_cast<double>(chunk.firstPoint + chunk.pointCount) / total,
                        "reading LAZ");
    };
    cloud.points.reserve(cloud.points.size() + pointsToReserve(file));
    ChunkRunOptions options;
    options.fields = FieldSelection::TinFields;
    options.threads = threads;
    if (!decodeChunksInOrder(file, options, decodeRun, takeRun))
        throw Cancelled(std::string(kLazStage) + ": cancelled while reading '" + file.name() + "'");
}

} // namespace terratin::io::laz
