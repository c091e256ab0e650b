#include "write_peers.hpp"

#include "attribute_columns.hpp"
#include "gpkg_geometry.hpp"
#include "packed_rtree.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/geometry/triangle_attributes.hpp"

#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>
#include <sqlite3.h>

#ifdef TERRATIN_HAVE_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace terratin::bench {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& what) {
    throw Error("terratin-bench: " + what + ": " + lastGdalErrorMessage());
}

GDALDatasetUniquePtr createGeoPackage(const fs::path& output) {
    initialiseGdal();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    GDALDatasetUniquePtr dataset(driver->Create(output.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!dataset)
        fail("cannot create " + output.string());
    return dataset;
}

OGRPolygon trianglePolygon(const Point3& a, const Point3& b, const Point3& c) {
    OGRLinearRing ring;
    ring.addPoint(a.x, a.y, a.z);
    ring.addPoint(b.x, b.y, b.z);
    ring.addPoint(c.x, c.y, c.z);
    ring.addPoint(a.x, a.y, a.z);
    OGRPolygon polygon;
    polygon.addRing(&ring);
    return polygon;
}

} // namespace

#ifdef TERRATIN_HAVE_CGAL

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vertex = CGAL::Triangulation_vertex_base_with_info_2<double, Kernel>;
using Delaunay =
    CGAL::Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<Vertex>>;

// GDAL: the valid cells' centres of band 1, each with its elevation.
std::vector<std::pair<Kernel::Point_2, double>> validCellCentres(GDALDataset& raster,
                                                                 const std::string& dem) {
    GDALRasterBand* band = raster.GetRasterBand(1);
    const int width = raster.GetRasterXSize();
    const int height = raster.GetRasterYSize();
    std::vector<double> cells(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    if (band->RasterIO(GF_Read, 0, 0, width, height, cells.data(), width, height, GDT_Float64, 0, 0,
                       nullptr) != CE_None)
        fail("cannot read " + dem);
    int hasNodata = 0;
    const double nodata = band->GetNoDataValue(&hasNodata);
    double gt[6];
    raster.GetGeoTransform(gt);
    std::vector<std::pair<Kernel::Point_2, double>> points;
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            const double z = cells[static_cast<std::size_t>(row) * width + col];
            if (hasNodata != 0 && z == nodata)
                continue;
            const double x = gt[0] + (col + 0.5) * gt[1] + (row + 0.5) * gt[2];
            const double y = gt[3] + (col + 0.5) * gt[4] + (row + 0.5) * gt[5];
            points.emplace_back(Kernel::Point_2(x, y), z);
        }
    return points;
}

// OGR: one Polygon Z per finite face, with its z_mean, in one transaction. Returns the faces
// written.
std::size_t writeFaces(const Delaunay& triangulation, const OGRSpatialReference* crs,
                       const fs::path& output) {
    GDALDatasetUniquePtr dataset = createGeoPackage(output);
    OGRLayer* layer =
        dataset->CreateLayer("tin", const_cast<OGRSpatialReference*>(crs), wkbPolygon25D, nullptr);
    OGRFieldDefn field("z_mean", OFTReal);
    if (layer == nullptr || layer->CreateField(&field) != OGRERR_NONE)
        fail("cannot create the layer of " + output.string());
    dataset->StartTransaction();
    std::size_t written = 0;
    for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end();
         ++face) {
        Point3 corners[3];
        for (int i = 0; i < 3; ++i)
            corners[i] = {face->vertex(i)->point().x(), face->vertex(i)->point().y(),
                          face->vertex(i)->info()};
        OGRFeatureUniquePtr feature(OGRFeature::CreateFeature(layer->GetLayerDefn()));
        OGRPolygon polygon = trianglePolygon(corners[0], corners[1], corners[2]);
        feature->SetGeometry(&polygon);
        feature->SetField(0, (corners[0].z + corners[1].z + corners[2].z) / 3.0);
        if (layer->CreateFeature(feature.get()) != OGRERR_NONE)
            fail("cannot write to " + output.string());
        ++written;
    }
    if (dataset->CommitTransaction() != OGRERR_NONE)
        fail("cannot commit " + output.string());
    return written;
}

} // namespace

bool scriptPeerBuilt() {
    return true;
}

std::size_t runGdalCgalOgrScript(const std::string& dem, const fs::path& output) {
    initialiseGdal();
    GDALDatasetUniquePtr raster(GDALDataset::Open(dem.c_str(), GDAL_OF_RASTER));
    if (!raster)
        fail("cannot open " + dem);
    const std::vector<std::pair<Kernel::Point_2, double>> points = validCellCentres(*raster, dem);
    // CGAL: the Delaunay triangulation.
    Delaunay triangulation;
    triangulation.insert(points.begin(), points.end());
    return writeFaces(triangulation, raster->GetSpatialRef(), output);
}

#else

bool scriptPeerBuilt() {
    return false;
}

std::size_t runGdalCgalOgrScript(const std::string&, const fs::path&) {
    throw Error("terratin-bench was built without CGAL: no GDAL + CGAL + OGR script");
}

#endif

void writeWithOgrLoop(const std::vector<std::array<Point3, 3>>& triangles,
                      const std::string& crsWkt, const fs::path& output) {
    const auto columns = io::detail::attributeColumns(io::AttributeSet::All);
    GDALDatasetUniquePtr dataset = createGeoPackage(output);
    OGRSpatialReference srs;
    srs.importFromWkt(crsWkt.c_str());
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRLayer* layer = dataset->CreateLayer("tin", &srs, wkbPolygon25D, nullptr);
    if (layer == nullptr)
        fail("cannot create the layer of " + output.string());
    for (const auto& column : columns) {
        OGRFieldDefn field(column.name, OFTReal);
        if (layer->CreateField(&field) != OGRERR_NONE)
            fail("cannot create a field of " + output.string());
    }
    dataset->StartTransaction();
    for (const auto& [a, b, c] : triangles) {
        const TriangleAttributes values = computeTriangleAttributes(a, b, c);
        OGRFeatureUniquePtr feature(OGRFeature::CreateFeature(layer->GetLayerDefn()));
        OGRPolygon polygon = trianglePolygon(a, b, c);
        feature->SetGeometry(&polygon);
        for (std::size_t i = 0; i < columns.size(); ++i)
            feature->SetField(static_cast<int>(i), values.*(columns[i].member));
        if (layer->CreateFeature(feature.get()) != OGRERR_NONE)
            fail("cannot write to " + output.string());
    }
    if (dataset->CommitTransaction() != OGRERR_NONE)
        fail("cannot commit " + output.string());
}

std::vector<std::array<Point3, 3>> readTriangles(const fs::path& gpkg, std::string* crsWkt) {
    initialiseGdal();
    GDALDatasetUniquePtr dataset(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR));
    if (!dataset)
        fail("cannot open " + gpkg.string());
    OGRLayer* layer = dataset->GetLayer(0);
    if (crsWkt != nullptr && layer->GetSpatialRef() != nullptr) {
        char* wkt = nullptr;
        layer->GetSpatialRef()->exportToWkt(&wkt);
        *crsWkt = wkt;
        CPLFree(wkt);
    }
    std::vector<std::array<Point3, 3>> triangles;
    for (const auto& feature : *layer) {
        const OGRLinearRing* ring = feature->GetGeometryRef()->toPolygon()->getExteriorRing();
        std::array<Point3, 3> corners;
        for (int i = 0; i < 3; ++i)
            corners[static_cast<std::size_t>(i)] = {ring->getX(i), ring->getY(i), ring->getZ(i)};
        triangles.push_back(corners);
    }
    return triangles;
}

struct SqliteLimitPeer::Prepared {
    std::vector<std::uint8_t> blobs;
    std::vector<double> values;
    std::vector<std::pair<std::int64_t, std::vector<std::uint8_t>>> nodes;
    std::vector<std::pair<std::int64_t, std::int64_t>> parents;
    std::vector<std::int64_t> leafOf;
};

SqliteLimitPeer::SqliteLimitPeer() = default;
SqliteLimitPeer::~SqliteLimitPeer() = default;

void SqliteLimitPeer::prepare(const TinMesh& mesh) {
    using io::detail::kGpkgTriangleBytes;
    auto prepared = std::make_unique<Prepared>();
    const std::size_t count = mesh.triangleCount();
    prepared->blobs.resize(count * kGpkgTriangleBytes);
    prepared->values.reserve(count * 14);
    std::vector<io::detail::RtreeBox> boxes;
    for (std::size_t t = 0; t < count; ++t) {
        const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
        const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
        io::detail::encodeGpkgTriangle(
            a, b, c, 0,
            std::span<std::uint8_t, kGpkgTriangleBytes>(
                prepared->blobs.data() + t * kGpkgTriangleBytes, kGpkgTriangleBytes));
        const TriangleAttributes values = computeTriangleAttributes(a, b, c);
        for (const auto& column : io::detail::attributeColumns(io::AttributeSet::All))
            prepared->values.push_back(values.*(column.member));
        boxes.push_back(
            io::detail::enclosingRtreeBox(std::min({a.x, b.x, c.x}), std::max({a.x, b.x, c.x}),
                                          std::min({a.y, b.y, c.y}), std::max({a.y, b.y, c.y})));
    }
    const io::detail::PackedRtree tree(std::move(boxes), io::detail::RtreeNodeSize::forPage(65536));
    tree.forEachNode([&](const io::detail::PackedRtree::Node& node) {
        prepared->nodes.emplace_back(node.number, node.blob);
        if (node.parent != 0)
            prepared->parents.emplace_back(node.number, node.parent);
    });
    prepared->leafOf = tree.leafOfEntry();
    m_prepared = std::move(prepared);
}

namespace {

void exec(sqlite3* db, const std::string& sql) {
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK)
        throw Error(std::string("terratin-bench: SQLite: ") + sqlite3_errmsg(db));
}

sqlite3_stmt* prepareStatement(sqlite3* db, const std::string& sql) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr) != SQLITE_OK)
        throw Error(std::string("terratin-bench: SQLite: ") + sqlite3_errmsg(db));
    return statement;
}

void step(sqlite3* db, sqlite3_stmt* statement) {
    if (sqlite3_step(statement) != SQLITE_DONE)
        throw Error(std::string("terratin-bench: SQLite: ") + sqlite3_errmsg(db));
    sqlite3_reset(statement);
}

/// "INSERT INTO table VALUES (?, ...), ..." with `rows` rows of `columns` parameters.
std::string manyRowInsert(const std::string& table, int columns, int rows) {
    std::string row = "(?";
    for (int c = 1; c < columns; ++c)
        row += ", ?";
    row += ")";
    std::string sql = "INSERT INTO " + table + " VALUES " + row;
    for (int r = 1; r < rows; ++r)
        sql += ", " + row;
    return sql;
}

constexpr int kManyRows = 64;
// The table's columns: fid, geom and 14 attributes.
constexpr int kAttributes = 14;
constexpr int kColumns = 2 + kAttributes;

// A new database at `output` with the empty table "tin", in an open transaction.
sqlite3* createTinDatabase(const fs::path& output) {
    sqlite3* db = nullptr;
    fs::remove(output);
    if (sqlite3_open_v2(output.c_str(), &db,
                        SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX,
                        nullptr) != SQLITE_OK)
        throw Error("terratin-bench: cannot create " + output.string());
    exec(db, "PRAGMA page_size = 65536; PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF; "
             "PRAGMA locking_mode = EXCLUSIVE; PRAGMA cache_size = -16384");
    std::string table = "CREATE TABLE tin (fid INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, "
                        "geom POLYGON";
    for (int c = 0; c < kAttributes; ++c)
        table += ", a" + std::to_string(c) + " REAL";
    exec(db, table + ")");
    exec(db, "BEGIN");
    return db;
}

// The `count` rows of "tin", kManyRows to a statement.
void insertTriangleRows(sqlite3* db, std::span<const std::uint8_t> blobs,
                        std::span<const double> values, std::size_t count) {
    sqlite3_stmt* many = prepareStatement(db, manyRowInsert("tin", kColumns, kManyRows));
    sqlite3_stmt* one = prepareStatement(db, manyRowInsert("tin", kColumns, 1));
    const auto bindRow = [&](sqlite3_stmt* statement, int first, std::size_t t) {
        sqlite3_bind_int64(statement, first, static_cast<sqlite3_int64>(t) + 1);
        sqlite3_bind_blob(statement, first + 1, blobs.data() + t * io::detail::kGpkgTriangleBytes,
                          static_cast<int>(io::detail::kGpkgTriangleBytes), SQLITE_STATIC);
        for (int c = 0; c < kAttributes; ++c)
            sqlite3_bind_double(statement, first + 2 + c,
                                values[t * kAttributes + static_cast<std::size_t>(c)]);
    };
    std::size_t t = 0;
    for (; count - t >= kManyRows; t += kManyRows) {
        for (int r = 0; r < kManyRows; ++r)
            bindRow(many, 1 + r * kColumns, t + static_cast<std::size_t>(r));
        step(db, many);
    }
    for (; t < count; ++t) {
        bindRow(one, 1, t);
        step(db, one);
    }
    sqlite3_finalize(many);
    sqlite3_finalize(one);
}

// The packed R-tree's nodes and their parents into the R*Tree's shadow tables.
void insertRtreeNodes(sqlite3* db,
                      std::span<const std::pair<std::int64_t, std::vector<std::uint8_t>>> nodes,
                      std::span<const std::pair<std::int64_t, std::int64_t>> parents) {
    sqlite3_stmt* node = prepareStatement(db, "INSERT INTO rtree_tin_geom_node VALUES (?, ?)");
    for (const auto& [number, blob] : nodes) {
        sqlite3_bind_int64(node, 1, number);
        sqlite3_bind_blob(node, 2, blob.data(), static_cast<int>(blob.size()), SQLITE_STATIC);
        step(db, node);
    }
    sqlite3_finalize(node);
    sqlite3_stmt* parent = prepareStatement(db, "INSERT INTO rtree_tin_geom_parent VALUES (?, ?)");
    for (const auto& [number, parentNumber] : parents) {
        sqlite3_bind_int64(parent, 1, number);
        sqlite3_bind_int64(parent, 2, parentNumber);
        step(db, parent);
    }
    sqlite3_finalize(parent);
}

// Each row's leaf of the packed R-tree into the R*Tree's rowid table.
void insertRtreeRowids(sqlite3* db, std::span<const std::int64_t> leafOf) {
    const std::size_t count = leafOf.size();
    sqlite3_stmt* rowids =
        prepareStatement(db, manyRowInsert("rtree_tin_geom_rowid", 2, kManyRows));
    sqlite3_stmt* rowid = prepareStatement(db, manyRowInsert("rtree_tin_geom_rowid", 2, 1));
    std::size_t e = 0;
    for (; count - e >= kManyRows; e += kManyRows) {
        for (int r = 0; r < kManyRows; ++r) {
            sqlite3_bind_int64(rowids, 1 + 2 * r, static_cast<sqlite3_int64>(e + r) + 1);
            sqlite3_bind_int64(rowids, 2 + 2 * r, leafOf[e + static_cast<std::size_t>(r)]);
        }
        step(db, rowids);
    }
    for (; e < count; ++e) {
        sqlite3_bind_int64(rowid, 1, static_cast<sqlite3_int64>(e) + 1);
        sqlite3_bind_int64(rowid, 2, leafOf[e]);
        step(db, rowid);
    }
    sqlite3_finalize(rowids);
    sqlite3_finalize(rowid);
}

} // namespace

void SqliteLimitPeer::write(const fs::path& output) const {
    const Prepared& p = *m_prepared;
    sqlite3* db = createTinDatabase(output);
    insertTriangleRows(db, p.blobs, p.values, p.leafOf.size());
    exec(db, "CREATE VIRTUAL TABLE rtree_tin_geom USING rtree(id, minx, maxx, miny, maxy)");
    exec(db, "DELETE FROM rtree_tin_geom_node");
    insertRtreeNodes(db, p.nodes, p.parents);
    insertRtreeRowids(db, p.leafOf);
    exec(db, "COMMIT");
    if (sqlite3_close(db) != SQLITE_OK)
        throw Error("terratin-bench: cannot close " + output.string());
}

} // namespace terratin::bench
