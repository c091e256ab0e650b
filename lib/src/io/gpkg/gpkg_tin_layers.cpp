#include "gpkg_tin_layers.hpp"

#include "../attribute_columns.hpp"
#include "../chunk_pipeline.hpp"
#include "../writer_support.hpp"
#include "batched_insert.hpp"
#include "gpkg_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace terratin::io::detail {

namespace {

/// Rows per chunk of the pipeline: one progress report each.
constexpr std::size_t kChunkRows = kProgressInterval;

std::size_t chunkCount(std::size_t rows) {
    return (rows + kChunkRows - 1) / kChunkRows;
}

/// [begin, end) of rows in chunk k.
std::pair<std::size_t, std::size_t> chunkRange(std::size_t k, std::size_t rows) {
    const std::size_t begin = k * kChunkRows;
    return {begin, std::min(rows, begin + kChunkRows)};
}

/// Encodes blob i of [begin, end) with encode(i, span) into `blobs`.
template <std::size_t Bytes, class Encode>
void encodeBlobs(std::size_t begin, std::size_t end, std::vector<std::uint8_t>& blobs,
                 Encode&& encode) {
    blobs.resize((end - begin) * Bytes);
    for (std::size_t i = begin; i < end; ++i)
        encode(i, std::span<std::uint8_t, Bytes>(blobs.data() + (i - begin) * Bytes, Bytes));
}

template <std::size_t Bytes>
std::span<const std::uint8_t> blobOf(const std::vector<std::uint8_t>& blobs, std::size_t row) {
    return {blobs.data() + row * Bytes, Bytes};
}

const Point3& corner(const TinMesh& mesh, std::size_t t, std::size_t i) {
    return mesh.vertices[mesh.triangles[3 * t + i]];
}

RtreeBox boxOf(std::initializer_list<const Point3*> points) {
    double minX = (*points.begin())->x;
    double maxX = minX;
    double minY = (*points.begin())->y;
    double maxY = minY;
    for (const Point3* p : points) {
        minX = std::min(minX, p->x);
        maxX = std::max(maxX, p->x);
        minY = std::min(minY, p->y);
        maxY = std::max(maxY, p->y);
    }
    return enclosingRtreeBox(minX, maxX, minY, maxY);
}

/// Calls visit(t, k) for each edge owned by a triangle of [begin, end): the half-edge k of t
/// whose neighbour is on the hull or has a larger number, so that every edge comes once.
template <class Visit>
void forEachEdge(const TinMesh& mesh, std::size_t begin, std::size_t end, Visit&& visit) {
    for (std::size_t t = begin; t < end; ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::int32_t neighbour = mesh.neighbours[3 * t + k];
            if (neighbour == kNoNeighbour || static_cast<std::size_t>(neighbour) > t)
                visit(t, k);
        }
}

std::vector<std::string> columnNames(const GpkgFeatureTable& table,
                                     std::initializer_list<std::string> attributes) {
    std::vector<std::string> names{"fid", table.geometryColumn()};
    names.insert(names.end(), attributes.begin(), attributes.end());
    return names;
}

struct TriangleChunk {
    std::vector<std::uint8_t> blobs;
    std::vector<TriangleAttributes> attributes;
};

struct EdgeRow {
    std::uint32_t from = 0;
    std::uint32_t to = 0;
    std::uint64_t left = 0;
    std::int32_t right = kNoNeighbour;
    double length = 0.0;
    bool constrained = false;
};

struct EdgeChunk {
    std::vector<EdgeRow> rows;
    std::vector<std::uint8_t> blobs;
};

} // namespace

void insertTriangleRows(SqliteConnection& connection, const GpkgFeatureTable& table,
                        const TinMesh& mesh, AttributeSet attributes, std::int64_t firstFid,
                        const RowProgress& progress) {
    const auto columns = attributeColumns(attributes);
    std::vector<std::string> names = columnNames(table, {});
    for (const auto& column : columns)
        names.emplace_back(column.name);
    BatchedInsert insert(connection, table.table(), names);
    const std::size_t rows = mesh.triangleCount();
    const std::int32_t srsId = table.srsId();

    const auto prepare = [&](std::size_t k, TriangleChunk& chunk) {
        const auto [begin, end] = chunkRange(k, rows);
        if (!columns.empty())
            computeAttributes(mesh, begin, end, chunk.attributes);
        encodeBlobs<kGpkgTriangleBytes>(begin, end, chunk.blobs, [&](std::size_t t, auto out) {
            encodeGpkgTriangle(corner(mesh, t, 0), corner(mesh, t, 1), corner(mesh, t, 2), srsId,
                               out);
        });
    };
    const auto consume = [&](std::size_t k, const TriangleChunk& chunk) {
        // Named variables, not a structured binding: clang before 16 (the fuzz preset's
        // clang 14) cannot capture a binding in the lambda below.
        const std::size_t begin = chunkRange(k, rows).first;
        const std::size_t end = chunkRange(k, rows).second;
        progress(begin);
        insert.insert(end - begin, [&](SqliteStatement& statement, int p, std::size_t row) {
            statement.bindInteger(p, static_cast<std::int64_t>(begin + row) + firstFid);
            statement.bindBlob(p + 1, blobOf<kGpkgTriangleBytes>(chunk.blobs, row));
            for (std::size_t i = 0; i < columns.size(); ++i)
                statement.bindReal(p + 2 + static_cast<int>(i),
                                   chunk.attributes[row].*(columns[i].member));
        });
    };
    runBesideOneWriter<TriangleChunk>(chunkCount(rows), prepare, consume);
}

void insertNodeRows(SqliteConnection& connection, const GpkgFeatureTable& table,
                    const TinMesh& mesh, std::span<const RasterCell> cells, std::int64_t firstFid,
                    const RowProgress& progress) {
    const bool withCells = !cells.empty();
    BatchedInsert insert(connection, table.table(),
                         withCells ? columnNames(table, {"id", "row", "col"})
                                   : columnNames(table, {"id"}));
    const std::size_t rows = mesh.vertexCount();
    const std::int32_t srsId = table.srsId();

    const auto prepare = [&](std::size_t k, std::vector<std::uint8_t>& blobs) {
        const auto [begin, end] = chunkRange(k, rows);
        encodeBlobs<kGpkgPointBytes>(begin, end, blobs, [&](std::size_t v, auto out) {
            encodeGpkgPoint(mesh.vertices[v], srsId, out);
        });
    };
    const auto consume = [&](std::size_t k, const std::vector<std::uint8_t>& blobs) {
        // Named variables, not a structured binding: clang before 16 (the fuzz preset's
        // clang 14) cannot capture a binding in the lambda below.
        const std::size_t begin = chunkRange(k, rows).first;
        const std::size_t end = chunkRange(k, rows).second;
        progress(begin);
        insert.insert(end - begin, [&](SqliteStatement& statement, int p, std::size_t row) {
            const std::size_t v = begin + row;
            const auto id = static_cast<std::int64_t>(v) + firstFid;
            statement.bindInteger(p, id);
            statement.bindBlob(p + 1, blobOf<kGpkgPointBytes>(blobs, row));
            statement.bindInteger(p + 2, id);
            if (withCells) {
                statement.bindInteger(p + 3, cells[v].row);
                statement.bindInteger(p + 4, cells[v].col);
            }
        });
    };
    runBesideOneWriter<std::vector<std::uint8_t>>(chunkCount(rows), prepare, consume);
}

void insertEdgeRows(SqliteConnection& connection, const GpkgFeatureTable& table,
                    const TinMesh& mesh, std::span<const std::uint8_t> constrainedEdges,
                    const RowProgress& progress) {
    BatchedInsert insert(connection, table.table(),
                         columnNames(table, {"node_from", "node_to", "tri_left", "tri_right",
                                             "length", "constrained"}));
    // Chunks are ranges of triangles; the fid of an edge counts the edges of the chunks before.
    const std::size_t triangles = mesh.triangleCount();
    const std::size_t chunks = chunkCount(triangles);
    std::vector<std::uint64_t> edgesBefore(chunks + 1, 0);
    for (std::size_t k = 0; k < chunks; ++k) {
        const auto [begin, end] = chunkRange(k, triangles);
        std::uint64_t edges = 0;
        forEachEdge(mesh, begin, end, [&](std::size_t, std::size_t) { ++edges; });
        edgesBefore[k + 1] = edgesBefore[k] + edges;
    }
    const std::int32_t srsId = table.srsId();

    const auto prepare = [&](std::size_t k, EdgeChunk& chunk) {
        const auto [begin, end] = chunkRange(k, triangles);
        chunk.rows.clear();
        forEachEdge(mesh, begin, end, [&](std::size_t t, std::size_t i) {
            const std::uint32_t from = mesh.triangles[3 * t + i];
            const std::uint32_t to = mesh.triangles[3 * t + (i + 1) % 3];
            const Point3& a = mesh.vertices[from];
            const Point3& b = mesh.vertices[to];
            chunk.rows.push_back({from, to, t + 1, mesh.neighbours[3 * t + i],
                                  std::hypot(std::hypot(b.x - a.x, b.y - a.y), b.z - a.z),
                                  !constrainedEdges.empty() && constrainedEdges[3 * t + i] != 0});
        });
        encodeBlobs<kGpkgSegmentBytes>(
            0, chunk.rows.size(), chunk.blobs, [&](std::size_t e, auto out) {
                const EdgeRow& row = chunk.rows[e];
                encodeGpkgSegment(mesh.vertices[row.from], mesh.vertices[row.to], srsId, out);
            });
    };
    const auto consume = [&](std::size_t k, const EdgeChunk& chunk) {
        progress(edgesBefore[k]);
        insert.insert(chunk.rows.size(), [&](SqliteStatement& statement, int p, std::size_t e) {
            const EdgeRow& row = chunk.rows[e];
            statement.bindInteger(p, static_cast<std::int64_t>(edgesBefore[k] + e) + 1);
            statement.bindBlob(p + 1, blobOf<kGpkgSegmentBytes>(chunk.blobs, e));
            statement.bindInteger(p + 2, static_cast<std::int64_t>(row.from) + 1);
            statement.bindInteger(p + 3, static_cast<std::int64_t>(row.to) + 1);
            statement.bindInteger(p + 4, static_cast<std::int64_t>(row.left));
            if (row.right == kNoNeighbour)
                statement.bindNull(p + 5);
            else
                statement.bindInteger(p + 5, static_cast<std::int64_t>(row.right) + 1);
            statement.bindReal(p + 6, row.length);
            statement.bindInteger(p + 7, row.constrained ? 1 : 0);
        });
    };
    runBesideOneWriter<EdgeChunk>(chunks, prepare, consume);
}

std::uint64_t edgeCount(const TinMesh& mesh) {
    const auto hull = static_cast<std::uint64_t>(
        std::count(mesh.neighbours.begin(), mesh.neighbours.end(), kNoNeighbour));
    return (3 * static_cast<std::uint64_t>(mesh.triangleCount()) + hull) / 2;
}

std::vector<RtreeBox> triangleBoxes(const TinMesh& mesh) {
    std::vector<RtreeBox> boxes(mesh.triangleCount());
    for (std::size_t t = 0; t < boxes.size(); ++t)
        boxes[t] = boxOf({&corner(mesh, t, 0), &corner(mesh, t, 1), &corner(mesh, t, 2)});
    return boxes;
}

std::vector<RtreeBox> nodeBoxes(const TinMesh& mesh) {
    std::vector<RtreeBox> boxes(mesh.vertexCount());
    for (std::size_t v = 0; v < boxes.size(); ++v)
        boxes[v] = boxOf({&mesh.vertices[v]});
    return boxes;
}

std::vector<RtreeBox> edgeBoxes(const TinMesh& mesh) {
    std::vector<RtreeBox> boxes;
    boxes.reserve(edgeCount(mesh));
    forEachEdge(mesh, 0, mesh.triangleCount(), [&](std::size_t t, std::size_t i) {
        boxes.push_back(boxOf({&corner(mesh, t, i), &corner(mesh, t, (i + 1) % 3)}));
    });
    return boxes;
}

Extent2d meshExtent(const TinMesh& mesh) {
    if (mesh.vertices.empty())
        return {};
    Extent2d extent{mesh.vertices[0].x, mesh.vertices[0].y, mesh.vertices[0].x, mesh.vertices[0].y};
    for (const Point3& p : mesh.vertices) {
        extent.minX = std::min(extent.minX, p.x);
        extent.minY = std::min(extent.minY, p.y);
        extent.maxX = std::max(extent.maxX, p.x);
        extent.maxY = std::max(extent.maxY, p.y);
    }
    return extent;
}

} // namespace terratin::io::detail
