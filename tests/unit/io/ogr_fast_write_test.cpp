// The fast paths of the FlatGeobuf and Shapefile writers: features handed to GDAL in the order
// of the FlatGeobuf index with its temporary file in /vsimem/, and the Shapefile's DBF written
// without the per-record end-of-file mark and finished by a second session.

#include "terratin/io/tin_writer.hpp"

#include "mesh_readers.hpp"
#include "packed_rtree_order.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/geometry/triangle_attributes.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include "ogr_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace terratin::io {
namespace {

using test::TemporaryDirectory;

/// Delaunay TIN of `count` random points on a 1000 m square in UTM-sized coordinates, with
/// elevations that give every attribute non-trivial values.
TinMesh randomTin(std::size_t count, unsigned seed) {
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> coordinate(0.0, 1000.0);
    std::vector<Point3> points;
    for (std::size_t i = 0; i < count; ++i) {
        const double x = coordinate(random);
        const double y = coordinate(random);
        points.push_back({500'000.0 + x, 5'000'000.0 + y, 1200.0 + 0.3 * x - 0.1 * y});
    }
    return triangulate(points).mesh;
}

TinWriteOptions optionsFor(TinFormat format) {
    TinWriteOptions options;
    options.format = format;
    options.crsWkt = test::utm10nWkt();
    return options;
}

GDALDatasetUniquePtr openVector(const std::filesystem::path& path) {
    initialiseGdal();
    return GDALDatasetUniquePtr(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
}

std::vector<double> cornerKey(const TinMesh& mesh, std::size_t t) {
    std::vector<double> key;
    for (int k = 0; k < 3; ++k) {
        const Point3& p = mesh.vertices[mesh.triangles[3 * t + k]];
        key.insert(key.end(), {p.x, p.y, p.z});
    }
    return key;
}

std::vector<double> cornerKey(const OGRFeature& feature) {
    const OGRLinearRing* ring = feature.GetGeometryRef()->toPolygon()->getExteriorRing();
    std::vector<double> key;
    for (int k = 0; k < 3; ++k)
        key.insert(key.end(), {ring->getX(k), ring->getY(k), ring->getZ(k)});
    return key;
}

std::array<double, 14> allAttributes(const TinMesh& mesh, std::size_t t) {
    const TriangleAttributes a = computeTriangleAttributes(
        mesh.vertices[mesh.triangles[3 * t]], mesh.vertices[mesh.triangles[3 * t + 1]],
        mesh.vertices[mesh.triangles[3 * t + 2]]);
    return {a.z1,       a.z2,        a.z3,     a.zMin,   a.zMax, a.zMean, a.slopeDeg,
            a.slopePct, a.aspectDeg, a.area2d, a.area3d, a.nx,   a.ny,    a.nz};
}

std::set<std::string> vsimemFiles() {
    std::set<std::string> files;
    char** list = VSIReadDirRecursive("/vsimem/");
    for (char** entry = list; entry != nullptr && *entry != nullptr; ++entry)
        files.insert(*entry);
    CSLDestroy(list);
    return files;
}

TEST(PackedRtreeOrder, FollowsTheHilbertCurve_WhenCellsAreNeighbours) {
    // The order-1 curve visits (0,0) (0,1) (1,1) (1,0); at order 16 the same quadrants hold
    // indices [0, 2^30), [2^30, 2^31), ...
    using detail::hilbertIndex16;
    EXPECT_EQ(hilbertIndex16(0, 0), 0U);
    EXPECT_EQ(hilbertIndex16(0, 1U << 15) >> 30, 1U);
    EXPECT_EQ(hilbertIndex16(1U << 15, 1U << 15) >> 30, 2U);
    EXPECT_EQ(hilbertIndex16(65535, 0) >> 30, 3U);
    // Consecutive indices are neighbouring cells, all along a stretch of the curve.
    std::map<std::uint32_t, std::pair<int, int>> byIndex;
    for (int x = 0; x < 64; ++x)
        for (int y = 0; y < 64; ++y)
            byIndex[hilbertIndex16(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y))] =
                {x, y};
    ASSERT_EQ(byIndex.size(), 64U * 64U);
    std::uint32_t expected = 0;
    std::pair<int, int> previous = byIndex.begin()->second;
    for (const auto& [index, cell] : byIndex) {
        ASSERT_EQ(index, expected++) << "the first 64 x 64 cells are the first 4096 indices";
        EXPECT_EQ(std::abs(cell.first - previous.first) + std::abs(cell.second - previous.second),
                  index == 0 ? 0 : 1);
        previous = cell;
    }
}

TEST(FlatGeobufFastWrite, StoresFeaturesInTheOrderHandedOver_WhenIndexed) {
    // GDAL re-sorts whatever it gets; when our order is its own, the file holds the features
    // exactly in that order (up to ties of the Hilbert index, which random points do not have).
    TemporaryDirectory directory;
    const TinMesh mesh = randomTin(3000, 7);
    writeTin(mesh, directory / "tin.fgb", optionsFor(TinFormat::FlatGeobuf));
    const std::vector<std::uint32_t> order = detail::packedRtreeOrder(mesh);
    const auto dataset = openVector(directory / "tin.fgb");
    ASSERT_TRUE(dataset);
    std::size_t position = 0;
    std::size_t inOrder = 0;
    for (const auto& feature : *dataset->GetLayer(0)) {
        ASSERT_LT(position, order.size());
        inOrder += cornerKey(*feature) == cornerKey(mesh, order[position]) ? 1 : 0;
        ++position;
    }
    EXPECT_EQ(position, mesh.triangleCount());
    EXPECT_GE(inOrder, mesh.triangleCount() * 99 / 100);
}

TEST(FlatGeobufFastWrite, ReadsBackEveryTriangleAndAttributeExactly_WhenIndexed) {
    TemporaryDirectory directory;
    const TinMesh mesh = randomTin(5000, 11);
    writeTin(mesh, directory / "tin.fgb", optionsFor(TinFormat::FlatGeobuf));

    std::map<std::vector<double>, std::size_t> byCorners;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        byCorners[cornerKey(mesh, t)] = t;
    const auto dataset = openVector(directory / "tin.fgb");
    ASSERT_TRUE(dataset);
    OGRLayer* layer = dataset->GetLayer(0);
    ASSERT_EQ(layer->GetLayerDefn()->GetFieldCount(), 14);
    std::vector<bool> seen(mesh.triangleCount(), false);
    for (const auto& feature : *layer) {
        const auto found = byCorners.find(cornerKey(*feature));
        ASSERT_NE(found, byCorners.end()) << "a ring that is not a mesh triangle in CCW order";
        EXPECT_FALSE(seen[found->second]) << "triangle " << found->second << " twice";
        seen[found->second] = true;
        const std::array<double, 14> expected = allAttributes(mesh, found->second);
        for (int i = 0; i < 14; ++i)
            EXPECT_EQ(feature->GetFieldAsDouble(i), expected[static_cast<std::size_t>(i)])
                << "triangle " << found->second << " field " << i;
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), true),
              static_cast<std::ptrdiff_t>(mesh.triangleCount()));
}

TEST(FlatGeobufFastWrite, SpatialFilterFindsExactlyTheIntersectingTriangles_ForRandomWindows) {
    TemporaryDirectory directory;
    const TinMesh mesh = randomTin(4000, 3);
    writeTin(mesh, directory / "tin.fgb", optionsFor(TinFormat::FlatGeobuf));
    const auto dataset = openVector(directory / "tin.fgb");
    ASSERT_TRUE(dataset);
    OGRLayer* layer = dataset->GetLayer(0);

    // Every feature with its envelope and geometry, read once without a filter.
    std::vector<std::unique_ptr<OGRGeometry>> geometries;
    std::vector<OGREnvelope> envelopes;
    for (const auto& feature : *layer) {
        geometries.emplace_back(feature->GetGeometryRef()->clone());
        envelopes.emplace_back();
        geometries.back()->getEnvelope(&envelopes.back());
    }
    ASSERT_EQ(geometries.size(), mesh.triangleCount());

    // OGR keeps, of the index's candidates (envelopes that meet the window), those whose
    // geometry meets it: exactly with GEOS, by envelope alone without.
    const bool exact = OGRGeometryFactory::haveGEOS();
    std::mt19937_64 random(99);
    std::uniform_real_distribution<double> corner(-50.0, 1050.0);
    std::uniform_real_distribution<double> size(0.0, 300.0);
    for (int window = 0; window < 100; ++window) {
        const double minX = 500'000.0 + corner(random);
        const double minY = 5'000'000.0 + corner(random);
        // Some windows start exactly on a vertex, where ties between closed boxes decide.
        const double startX =
            window % 10 == 0 ? mesh.vertices[static_cast<std::size_t>(window)].x : minX;
        const double maxX = startX + size(random);
        const double maxY = minY + size(random);
        OGRPolygon box;
        {
            auto* ring = new OGRLinearRing();
            ring->addPoint(startX, minY);
            ring->addPoint(maxX, minY);
            ring->addPoint(maxX, maxY);
            ring->addPoint(startX, maxY);
            ring->addPoint(startX, minY);
            box.addRingDirectly(ring);
        }
        std::multiset<std::vector<double>> expected;
        for (std::size_t i = 0; i < geometries.size(); ++i) {
            const OGREnvelope& e = envelopes[i];
            const bool envelopeMeets =
                e.MaxX >= startX && e.MinX <= maxX && e.MaxY >= minY && e.MinY <= maxY;
            if (envelopeMeets && (!exact || box.Intersects(geometries[i].get()))) {
                const OGRLinearRing* ring = geometries[i]->toPolygon()->getExteriorRing();
                expected.insert({ring->getX(0), ring->getY(0), ring->getX(1), ring->getY(1)});
            }
        }
        layer->SetSpatialFilterRect(startX, minY, maxX, maxY);
        std::multiset<std::vector<double>> found;
        for (const auto& feature : *layer) {
            const OGRLinearRing* ring = feature->GetGeometryRef()->toPolygon()->getExteriorRing();
            found.insert({ring->getX(0), ring->getY(0), ring->getX(1), ring->getY(1)});
        }
        layer->SetSpatialFilter(nullptr);
        EXPECT_EQ(found, expected) << "window " << window;
    }
}

TEST(FlatGeobufFastWrite, LeavesNoOutputNorTemporaryFile_WhenCancelled) {
    for (const bool spatialIndex : {true, false}) {
        TemporaryDirectory directory;
        const TinMesh mesh = test::gridTin(300);
        ASSERT_GT(mesh.triangleCount(), 65'536U * 2) << "enough for progress reports mid-write";
        const std::set<std::string> vsimemBefore = vsimemFiles();
        TinWriteOptions options = optionsFor(TinFormat::FlatGeobuf);
        options.spatialIndex = spatialIndex;
        int calls = 0;
        const ProgressCallback cancelMidway = [&](double, std::string_view) { return ++calls < 3; };
        EXPECT_THROW(writeTin(mesh, directory / "tin.fgb", options, cancelMidway), Cancelled);
        EXPECT_TRUE(directory.entries().empty());
        EXPECT_EQ(vsimemFiles(), vsimemBefore);
    }
}

TEST(FlatGeobufFastWrite, FreesItsInMemoryTemporaryFile_WhenWritten) {
    TemporaryDirectory directory;
    const std::set<std::string> vsimemBefore = vsimemFiles();
    writeTin(randomTin(500, 5), directory / "tin.fgb", optionsFor(TinFormat::FlatGeobuf));
    EXPECT_EQ(vsimemFiles(), vsimemBefore);
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"tin.fgb"}));
}

/// What a "%24.12f" DBF column reads back as: the value rounded to 12 decimals.
double throughDbf(double value) {
    std::array<char, 64> text{};
    std::snprintf(text.data(), text.size(), "%24.12f", value);
    return std::strtod(text.data(), nullptr);
}

TEST(ShapefileFastWrite,
     ReadsBackEveryTriangleInOrderWithDbfRoundedAttributes_WhenWrittenInTwoSessions) {
    TemporaryDirectory directory;
    const TinMesh mesh = randomTin(3000, 13);
    writeTin(mesh, directory / "tin.shp", optionsFor(TinFormat::Shapefile));
    const auto dataset = openVector(directory / "tin.shp");
    ASSERT_TRUE(dataset);
    OGRLayer* layer = dataset->GetLayer(0);
    ASSERT_EQ(layer->GetFeatureCount(), static_cast<GIntBig>(mesh.triangleCount()));
    std::size_t t = 0;
    for (const auto& feature : *layer) {
        ASSERT_LT(t, mesh.triangleCount());
        // A Shapefile stores outer rings clockwise: the corners come back reversed, from the
        // first.
        const OGRLinearRing* ring = feature->GetGeometryRef()->toPolygon()->getExteriorRing();
        ASSERT_EQ(ring->getNumPoints(), 4);
        std::set<std::vector<double>> corners;
        for (int k = 0; k < 3; ++k)
            corners.insert({ring->getX(k), ring->getY(k), ring->getZ(k)});
        std::set<std::vector<double>> expectedCorners;
        for (int k = 0; k < 3; ++k) {
            const Point3& p = mesh.vertices[mesh.triangles[3 * t + static_cast<std::size_t>(k)]];
            expectedCorners.insert({p.x, p.y, p.z});
        }
        EXPECT_EQ(corners, expectedCorners) << "triangle " << t;
        const std::array<double, 14> expected = allAttributes(mesh, t);
        for (int i = 0; i < 14; ++i)
            EXPECT_EQ(feature->GetFieldAsDouble(i),
                      throughDbf(expected[static_cast<std::size_t>(i)]))
                << "triangle " << t << " field " << i;
        ++t;
    }
    EXPECT_EQ(t, mesh.triangleCount());
}

TEST(ShapefileFastWrite, EndsTheDbfWithItsEndOfFileMark_WhenRecordsAreWrittenWithoutIt) {
    TemporaryDirectory directory;
    const TinMesh mesh = randomTin(200, 17);
    writeTin(mesh, directory / "tin.shp", optionsFor(TinFormat::Shapefile));
    std::ifstream dbf(directory / "tin.dbf", std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(dbf)),
                            std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 32U);
    // Header length at byte 8 (16 bits), record length at byte 10, little-endian.
    const auto u16 = [&](std::size_t at) {
        return static_cast<std::size_t>(static_cast<unsigned char>(bytes[at])) |
               static_cast<std::size_t>(static_cast<unsigned char>(bytes[at + 1])) << 8;
    };
    EXPECT_EQ(bytes.size(), u16(8) + mesh.triangleCount() * u16(10) + 1);
    EXPECT_EQ(bytes.back(), '\x1A');
}

TEST(ShapefileFastWrite, KeepsExtremeAttributesWithinTheDbfColumn_WhenJustBelowTheLimit) {
    // Elevations of +-9.9e21 fill 22 integer digits and a sign: the column is cut to 24
    // characters, the value reads back the same (see kDbfMaxMagnitude in ogr_tin_writer.cpp).
    TemporaryDirectory directory;
    TinMesh mesh;
    for (const Point3& p :
         {Point3{0.0, 0.0, -9.9e21}, Point3{1.0, 0.0, 9.9e21}, Point3{0.0, 1.0, 1.0e21}})
        mesh.vertices.push_back(p);
    for (const std::uint32_t v : {0U, 1U, 2U})
        mesh.triangles.push_back(v);
    mesh.neighbours.assign(3, kNoNeighbour);
    // Basic: the slope in percent of so steep a triangle would not fit.
    TinWriteOptions options = optionsFor(TinFormat::Shapefile);
    options.crsWkt.clear();
    options.attributes = AttributeSet::Basic;
    writeTin(mesh, directory / "tin.shp", options);
    const auto dataset = openVector(directory / "tin.shp");
    ASSERT_TRUE(dataset);
    OGRFeatureUniquePtr feature(dataset->GetLayer(0)->GetNextFeature());
    ASSERT_TRUE(feature);
    const TriangleAttributes expected =
        computeTriangleAttributes(mesh.vertices[0], mesh.vertices[1], mesh.vertices[2]);
    EXPECT_EQ(feature->GetFieldAsDouble("z_min"), -9.9e21);
    EXPECT_EQ(feature->GetFieldAsDouble("z_max"), 9.9e21);
    EXPECT_EQ(feature->GetFieldAsDouble("z_mean"), expected.zMean);
}

} // namespace
} // namespace terratin::io
