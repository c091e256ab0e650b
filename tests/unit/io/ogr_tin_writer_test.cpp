// The OGR outputs beyond the basics of tin_writer_test: FlatGeobuf, the attribute sets, the
// GeoPackage node and edge layers, appending layers to an existing GeoPackage, the spatial
// index switch and the QGIS style.

#include "terratin/io/tin_writer.hpp"

#include "mesh_readers.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/geometry/triangle_attributes.hpp"

#include <cpl_conv.h>
#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <libxml/parser.h>
#include <libxml/tree.h>

#include "ogr_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace terratin::io {
namespace {

const xmlChar* xmlText(const char* text) {
    return reinterpret_cast<const xmlChar*>(text);
}

using test::TemporaryDirectory;

const std::vector<std::string> kAllNames = {
    "z1",        "z2",         "z3",      "z_min",   "z_max", "z_mean", "slope_deg",
    "slope_pct", "aspect_deg", "area_2d", "area_3d", "nx",    "ny",     "nz"};
const std::vector<std::string> kBasicNames = {"z_min",     "z_max",      "z_mean",
                                              "slope_deg", "aspect_deg", "area_2d"};

using test::utm10nWkt;

GDALDatasetUniquePtr openVector(const std::filesystem::path& path) {
    initialiseGdal();
    return GDALDatasetUniquePtr(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
}

std::vector<std::string> fieldNames(OGRLayer& layer) {
    std::vector<std::string> names;
    const OGRFeatureDefn* definition = layer.GetLayerDefn();
    for (int i = 0; i < definition->GetFieldCount(); ++i)
        names.emplace_back(definition->GetFieldDefn(i)->GetNameRef());
    return names;
}

TinWriteOptions optionsFor(TinFormat format) {
    TinWriteOptions options;
    options.format = format;
    options.crsWkt = utm10nWkt();
    return options;
}

/// Every feature of every layer as text (geometry WKT with full precision, fields), by layer.
std::map<std::string, std::vector<std::string>> dumpLayers(const std::filesystem::path& path) {
    std::map<std::string, std::vector<std::string>> layers;
    const auto dataset = openVector(path);
    EXPECT_TRUE(dataset);
    if (!dataset)
        return layers;
    for (int i = 0; i < dataset->GetLayerCount(); ++i) {
        OGRLayer* layer = dataset->GetLayer(i);
        auto& rows = layers[layer->GetName()];
        for (const auto& feature : *layer) {
            std::string row = std::to_string(feature->GetFID()) + ":";
            if (const OGRGeometry* geometry = feature->GetGeometryRef()) {
                char* wkt = nullptr;
                geometry->exportToWkt(&wkt, wkbVariantIso);
                row += wkt;
                CPLFree(wkt);
            }
            for (int f = 0; f < feature->GetFieldCount(); ++f)
                row += std::string("|") + feature->GetFieldAsString(f);
            rows.push_back(row);
        }
    }
    return layers;
}

TEST(OgrTinWriterFormats, ReadsBackTrianglesAndAllAttributes_WhenFlatGeobuf) {
    TemporaryDirectory directory;
    const TinMesh mesh = test::gridTin(4);
    const TinWriteResult result =
        writeTin(mesh, directory / "tin.fgb", optionsFor(TinFormat::FlatGeobuf));
    EXPECT_EQ(result.features, mesh.triangleCount());
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"tin.fgb"}));

    const auto dataset = openVector(directory / "tin.fgb");
    ASSERT_TRUE(dataset);
    EXPECT_STREQ(dataset->GetDriver()->GetDescription(), "FlatGeobuf");
    OGRLayer* layer = dataset->GetLayer(0);
    EXPECT_EQ(layer->GetGeomType(), wkbPolygon25D);
    EXPECT_EQ(fieldNames(*layer), kAllNames);
    ASSERT_EQ(layer->GetFeatureCount(), static_cast<GIntBig>(mesh.triangleCount()));
    ASSERT_NE(layer->GetSpatialRef(), nullptr);
    EXPECT_STREQ(layer->GetSpatialRef()->GetAuthorityCode(nullptr), "26910");

    // The spatial index orders features along a Hilbert curve: match them by their corners.
    std::map<std::vector<double>, std::size_t> byCorners;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        std::vector<double> key;
        for (int k = 0; k < 3; ++k) {
            const Point3& p = mesh.vertices[mesh.triangles[3 * t + k]];
            key.insert(key.end(), {p.x, p.y, p.z});
        }
        byCorners[key] = t;
    }
    std::size_t seen = 0;
    for (const auto& feature : *layer) {
        const OGRLinearRing* ring = feature->GetGeometryRef()->toPolygon()->getExteriorRing();
        ASSERT_EQ(ring->getNumPoints(), 4);
        std::vector<double> key;
        for (int k = 0; k < 3; ++k)
            key.insert(key.end(), {ring->getX(k), ring->getY(k), ring->getZ(k)});
        const auto found = byCorners.find(key);
        ASSERT_NE(found, byCorners.end()) << "a ring that is not a mesh triangle in CCW order";
        const std::size_t t = found->second;
        const TriangleAttributes expected = computeTriangleAttributes(
            mesh.vertices[mesh.triangles[3 * t]], mesh.vertices[mesh.triangles[3 * t + 1]],
            mesh.vertices[mesh.triangles[3 * t + 2]]);
        EXPECT_EQ(feature->GetFieldAsDouble("z1"), expected.z1);
        EXPECT_EQ(feature->GetFieldAsDouble("slope_pct"), expected.slopePct);
        EXPECT_EQ(feature->GetFieldAsDouble("area_3d"), expected.area3d);
        EXPECT_EQ(feature->GetFieldAsDouble("nz"), expected.nz);
        ++seen;
    }
    EXPECT_EQ(seen, mesh.triangleCount());
}

TEST(OgrTinWriterFormats, WritesTheChosenColumns_WhenAttributeSetIsNoneBasicOrAll) {
    for (const TinFormat format :
         {TinFormat::GeoPackage, TinFormat::Shapefile, TinFormat::FlatGeobuf}) {
        for (const auto& [set, names] : {std::pair{AttributeSet::None, std::vector<std::string>{}},
                                         std::pair{AttributeSet::Basic, kBasicNames},
                                         std::pair{AttributeSet::All, kAllNames}}) {
            TemporaryDirectory directory;
            TinWriteOptions options = optionsFor(format);
            options.attributes = set;
            const std::string name = format == TinFormat::GeoPackage  ? "tin.gpkg"
                                     : format == TinFormat::Shapefile ? "tin.shp"
                                                                      : "tin.fgb";
            writeTin(test::gridTin(3), directory / name, options);
            const auto dataset = openVector(directory / name);
            ASSERT_TRUE(dataset) << name;
            OGRLayer* layer = dataset->GetLayer(0);
            std::vector<std::string> written = fieldNames(*layer);
            // A DBF cannot be without columns: GDAL adds "FID" to an attribute-less Shapefile.
            if (format == TinFormat::Shapefile && set == AttributeSet::None)
                written.erase(std::remove(written.begin(), written.end(), "FID"), written.end());
            EXPECT_EQ(written, names) << name;
            EXPECT_EQ(layer->GetFeatureCount(), 8) << name;
        }
    }
}

TEST(OgrTinWriterFormats, StoresExactAttributes_WhenGeoPackageWithAll) {
    TemporaryDirectory directory;
    const TinMesh mesh = test::gridTin(4);
    writeTin(mesh, directory / "tin.gpkg", optionsFor(TinFormat::GeoPackage));
    const auto dataset = openVector(directory / "tin.gpkg");
    ASSERT_TRUE(dataset);
    OGRLayer* layer = dataset->GetLayer(0);
    for (const auto& feature : *layer) {
        // fid = triangle number from 1.
        const auto t = static_cast<std::size_t>(feature->GetFID() - 1);
        ASSERT_LT(t, mesh.triangleCount());
        const TriangleAttributes e = computeTriangleAttributes(
            mesh.vertices[mesh.triangles[3 * t]], mesh.vertices[mesh.triangles[3 * t + 1]],
            mesh.vertices[mesh.triangles[3 * t + 2]]);
        const std::vector<double> expected = {
            e.z1,       e.z2,        e.z3,     e.zMin,   e.zMax, e.zMean, e.slopeDeg,
            e.slopePct, e.aspectDeg, e.area2d, e.area3d, e.nx,   e.ny,    e.nz};
        for (std::size_t i = 0; i < kAllNames.size(); ++i)
            EXPECT_EQ(feature->GetFieldAsDouble(kAllNames[i].c_str()), expected[i])
                << kAllNames[i] << " of triangle " << t;
    }
}

TEST(OgrTinWriterLayers, WritesNodesWithRowAndCol_WhenVertexCellsAreGiven) {
    TemporaryDirectory directory;
    const TinMesh mesh = test::gridTin(4);
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.nodes = true;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        options.vertexCells.push_back(
            {static_cast<std::int64_t>(3 - v / 4), static_cast<std::int64_t>(v % 4)});
    const TinWriteResult result = writeTin(mesh, directory / "tin.gpkg", options);
    EXPECT_EQ(result.features, mesh.triangleCount() + mesh.vertexCount());

    const auto dataset = openVector(directory / "tin.gpkg");
    ASSERT_TRUE(dataset);
    OGRLayer* nodes = dataset->GetLayerByName("nodes");
    ASSERT_NE(nodes, nullptr);
    EXPECT_EQ(nodes->GetGeomType(), wkbPoint25D);
    EXPECT_EQ(fieldNames(*nodes), (std::vector<std::string>{"id", "row", "col"}));
    ASSERT_EQ(nodes->GetFeatureCount(), static_cast<GIntBig>(mesh.vertexCount()));
    for (const auto& feature : *nodes) {
        const auto v = static_cast<std::size_t>(feature->GetFieldAsInteger64("id") - 1);
        ASSERT_LT(v, mesh.vertexCount());
        EXPECT_EQ(feature->GetFID(), static_cast<GIntBig>(v + 1));
        const OGRPoint* point = feature->GetGeometryRef()->toPoint();
        EXPECT_EQ(point->getX(), mesh.vertices[v].x);
        EXPECT_EQ(point->getY(), mesh.vertices[v].y);
        EXPECT_EQ(point->getZ(), mesh.vertices[v].z);
        EXPECT_EQ(feature->GetFieldAsInteger64("row"), options.vertexCells[v].row);
        EXPECT_EQ(feature->GetFieldAsInteger64("col"), options.vertexCells[v].col);
    }
}

TEST(OgrTinWriterLayers, WritesNodesWithoutRowCol_WhenInputIsNotARaster) {
    TemporaryDirectory directory;
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.nodes = true;
    options.layerName = "hood";
    writeTin(test::gridTin(3), directory / "tin.gpkg", options);
    const auto dataset = openVector(directory / "tin.gpkg");
    ASSERT_TRUE(dataset);
    OGRLayer* nodes = dataset->GetLayerByName("hood_nodes");
    ASSERT_NE(nodes, nullptr);
    EXPECT_EQ(fieldNames(*nodes), (std::vector<std::string>{"id"}));
    EXPECT_EQ(nodes->GetFeatureCount(), 9);
}

TEST(OgrTinWriterLayers, WritesEachEdgeOnceWithItsTwoTriangles_WhenEdgesAreAsked) {
    TemporaryDirectory directory;
    const TinMesh mesh = test::gridTin(4); // 18 triangles, 12 hull edges: 33 edges
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.edges = true;
    writeTin(mesh, directory / "tin.gpkg", options);
    const auto dataset = openVector(directory / "tin.gpkg");
    ASSERT_TRUE(dataset);
    OGRLayer* edges = dataset->GetLayerByName("edges");
    ASSERT_NE(edges, nullptr);
    EXPECT_EQ(edges->GetGeomType(), wkbLineString25D);
    EXPECT_EQ(fieldNames(*edges), (std::vector<std::string>{"node_from", "node_to", "tri_left",
                                                            "tri_right", "length", "constrained"}));
    ASSERT_EQ(edges->GetFeatureCount(), 33);

    // The directed edge (a, b) of triangle t in CCW order, for every triangle.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> halfEdges;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k)
            halfEdges[{mesh.triangles[3 * t + k], mesh.triangles[3 * t + (k + 1) % 3]}] = t;
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    int hull = 0;
    for (const auto& feature : *edges) {
        const auto from = static_cast<std::uint32_t>(feature->GetFieldAsInteger64("node_from") - 1);
        const auto to = static_cast<std::uint32_t>(feature->GetFieldAsInteger64("node_to") - 1);
        EXPECT_TRUE(seen.insert({std::min(from, to), std::max(from, to)}).second) << "repeated";
        EXPECT_EQ(feature->GetFieldAsInteger("constrained"), 0); // no breaklines
        const auto left = halfEdges.find({from, to});
        ASSERT_NE(left, halfEdges.end());
        EXPECT_EQ(feature->GetFieldAsInteger64("tri_left"), static_cast<GIntBig>(left->second + 1));
        const auto right = halfEdges.find({to, from});
        if (right == halfEdges.end()) {
            EXPECT_TRUE(feature->IsFieldNull(feature->GetFieldIndex("tri_right")));
            ++hull;
        } else {
            EXPECT_EQ(feature->GetFieldAsInteger64("tri_right"),
                      static_cast<GIntBig>(right->second + 1));
        }
        const Point3& a = mesh.vertices[from];
        const Point3& b = mesh.vertices[to];
        const OGRLineString* line = feature->GetGeometryRef()->toLineString();
        ASSERT_EQ(line->getNumPoints(), 2);
        EXPECT_EQ(line->getZ(0), a.z);
        EXPECT_EQ(line->getX(1), b.x);
        const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
        EXPECT_DOUBLE_EQ(feature->GetFieldAsDouble("length"),
                         std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    EXPECT_EQ(hull, 12);
}

TEST(OgrTinWriterLayers, RefusesNodesAndEdges_WhenOutputIsNotAGeoPackage) {
    TemporaryDirectory directory;
    for (const TinFormat format : {TinFormat::Shapefile, TinFormat::FlatGeobuf}) {
        TinWriteOptions options = optionsFor(format);
        options.edges = true;
        try {
            writeTin(test::gridTin(3), directory / "tin.shp", options);
            FAIL() << "no error";
        } catch (const InvalidInputError& error) {
            EXPECT_NE(std::string(error.what()).find("GeoPackage"), std::string::npos);
        }
    }
    EXPECT_TRUE(directory.entries().empty());
}

class AppendLayer : public ::testing::Test {
protected:
    void SetUp() override {
        TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
        options.layerName = "first";
        options.nodes = true;
        writeTin(test::gridTin(3), m_directory / "tin.gpkg", options);
        m_before = dumpLayers(m_directory / "tin.gpkg");
        m_bytes = test::fileBytes(m_directory / "tin.gpkg");
    }
    [[nodiscard]] std::filesystem::path output() const { return m_directory / "tin.gpkg"; }
    static TinWriteOptions appendOptions(const std::string& layer) {
        TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
        options.layerName = layer;
        options.appendLayer = true;
        return options;
    }

    TemporaryDirectory m_directory;
    std::map<std::string, std::vector<std::string>> m_before;
    std::string m_bytes;
};

TEST_F(AppendLayer, KeepsOtherLayersIntact_WhenAddingALayer) {
    TinWriteOptions options = appendOptions("second");
    options.edges = true;
    const TinMesh mesh = test::gridTin(4);
    writeTin(mesh, output(), options);

    auto after = dumpLayers(output());
    EXPECT_EQ(after.size(), 4u); // first, first_nodes, second, second_edges
    EXPECT_EQ(after["second"].size(), mesh.triangleCount());
    EXPECT_EQ(after["second_edges"].size(), 33u);
    after.erase("second");
    after.erase("second_edges");
    EXPECT_EQ(after, m_before) << "an existing layer changed";
    EXPECT_EQ(m_directory.entries(), (std::set<std::string>{"tin.gpkg"}));
}

TEST_F(AppendLayer, LeavesTheGeoPackageUntouched_WhenTheLayerExistsWithoutOverwrite) {
    try {
        writeTin(test::gridTin(4), output(), appendOptions("first"));
        FAIL() << "no error";
    } catch (const InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("first"), std::string::npos);
    }
    EXPECT_EQ(test::fileBytes(output()), m_bytes);
    EXPECT_EQ(m_directory.entries(), (std::set<std::string>{"tin.gpkg"}));
}

TEST_F(AppendLayer, LeavesTheGeoPackageUntouched_WhenCancelledMidWrite) {
    const TinMesh mesh = test::gridTin(200); // 79202 triangles: a report after 65536
    EXPECT_THROW(writeTin(mesh, output(), appendOptions("second"),
                          [](double fraction, std::string_view) { return fraction == 0.0; }),
                 Cancelled);
    EXPECT_EQ(test::fileBytes(output()), m_bytes);
    EXPECT_EQ(m_directory.entries(), (std::set<std::string>{"tin.gpkg"}));
}

TEST_F(AppendLayer, ReplacesOnlyThatLayer_WhenTheLayerExistsWithOverwrite) {
    TinWriteOptions options = appendOptions("first");
    options.overwrite = true;
    const TinMesh mesh = test::gridTin(5);
    writeTin(mesh, output(), options);
    auto after = dumpLayers(output());
    EXPECT_EQ(after["first"].size(), mesh.triangleCount());
    EXPECT_EQ(after["first_nodes"], m_before["first_nodes"]);
}

TEST_F(AppendLayer, RefusesAFileThatIsNotAGeoPackage_WhenAppending) {
    std::ofstream(m_directory / "notes.gpkg") << "not a database";
    EXPECT_THROW(writeTin(test::gridTin(3), m_directory / "notes.gpkg", appendOptions("x")),
                 InvalidInputError);
    EXPECT_EQ(test::fileBytes(m_directory / "notes.gpkg"), "not a database");
    EXPECT_EQ(m_directory.entries(), (std::set<std::string>{"tin.gpkg", "notes.gpkg"}));
}

TEST(OgrTinWriterIndex, HasNoSpatialIndex_WhenGeoPackageSpatialIndexIsOff) {
    TemporaryDirectory directory;
    for (const bool index : {false, true}) {
        TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
        options.spatialIndex = index;
        options.overwrite = true;
        writeTin(test::gridTin(3), directory / "tin.gpkg", options);
        const auto dataset = openVector(directory / "tin.gpkg");
        ASSERT_TRUE(dataset);
        EXPECT_EQ(dataset->GetLayer(0)->TestCapability(OLCFastSpatialFilter) != 0, index);
        EXPECT_EQ(dataset->GetLayer(0)->GetFeatureCount(), 8);
    }
}

TEST(QgisStyle, WritesGraduatedZMeanStyle_WhenAsked) {
    TemporaryDirectory directory;
    const TinMesh mesh = test::gridTin(4);
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.qgisStyle = true;
    writeTin(mesh, directory / "hood.gpkg", options);
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"hood.gpkg", "hood.qml"}));

    xmlDoc* doc = xmlReadFile((directory / "hood.qml").c_str(), nullptr, XML_PARSE_NONET);
    ASSERT_NE(doc, nullptr) << "the .qml is not well-formed XML";
    const xmlNode* root = xmlDocGetRootElement(doc);
    EXPECT_STREQ(reinterpret_cast<const char*>(root->name), "qgis");
    const xmlNode* renderer = nullptr;
    for (const xmlNode* node = root->children; node != nullptr; node = node->next)
        if (node->type == XML_ELEMENT_NODE &&
            std::string(reinterpret_cast<const char*>(node->name)) == "renderer-v2")
            renderer = node;
    ASSERT_NE(renderer, nullptr);
    const auto attribute = [](const xmlNode* node, const char* name) {
        xmlChar* value = xmlGetProp(node, xmlText(name));
        std::string text = value != nullptr ? reinterpret_cast<const char*>(value) : "";
        xmlFree(value);
        return text;
    };
    EXPECT_EQ(attribute(renderer, "type"), "graduatedSymbol");
    EXPECT_EQ(attribute(renderer, "attr"), "z_mean");
    std::vector<std::pair<double, double>> ranges;
    for (const xmlNode* node = renderer->children; node != nullptr; node = node->next)
        if (node->type == XML_ELEMENT_NODE &&
            std::string(reinterpret_cast<const char*>(node->name)) == "ranges")
            for (const xmlNode* range = node->children; range != nullptr; range = range->next)
                if (range->type == XML_ELEMENT_NODE)
                    ranges.emplace_back(std::stod(attribute(range, "lower")),
                                        std::stod(attribute(range, "upper")));
    xmlFreeDoc(doc);
    ASSERT_EQ(ranges.size(), 16u);
    // Contiguous classes from the lowest to the highest vertex: every z_mean falls in one.
    double lowest = mesh.vertices.front().z, highest = lowest;
    for (const Point3& p : mesh.vertices) {
        lowest = std::min(lowest, p.z);
        highest = std::max(highest, p.z);
    }
    EXPECT_EQ(ranges.front().first, lowest);
    EXPECT_EQ(ranges.back().second, highest);
    for (std::size_t k = 1; k < ranges.size(); ++k)
        EXPECT_EQ(ranges[k].first, ranges[k - 1].second);
}

TEST(QgisStyle, RefusesExistingStyleAndWritesNothing_WhenNotOverwriting) {
    TemporaryDirectory directory;
    std::ofstream(directory / "hood.qml") << "my own style";
    TinWriteOptions options = optionsFor(TinFormat::FlatGeobuf);
    options.qgisStyle = true;
    EXPECT_THROW(writeTin(test::gridTin(3), directory / "hood.fgb", options), InvalidInputError);
    EXPECT_EQ(test::fileBytes(directory / "hood.qml"), "my own style");
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"hood.qml"}));
    options.attributes = AttributeSet::None;
    options.overwrite = true;
    EXPECT_THROW(writeTin(test::gridTin(3), directory / "hood.fgb", options), InvalidInputError);
}

TEST(ShapefileLimits, RefusesWithGeoPackageAdvice_WhenAllAttributesPassTwoGigabytes) {
    // 6.5 M triangles: the .shp (1.1 GB) fits, the .dbf with 14 columns of 24 bytes (2.2 GB)
    // does not; with the 6 basic columns (0.95 GB) it would.
    TemporaryDirectory directory;
    TinMesh mesh;
    mesh.vertices = {{0.0, 0.0, 0.0}};
    mesh.sourceIndex = {0};
    mesh.triangles.assign(3 * std::size_t{6'500'000}, 0);
    try {
        writeTin(mesh, directory / "big.shp", optionsFor(TinFormat::Shapefile));
        FAIL() << "no error";
    } catch (const InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("GeoPackage"), std::string::npos);
        EXPECT_NE(std::string(error.what()).find("2 GB"), std::string::npos);
    }
    EXPECT_TRUE(directory.entries().empty());
}

} // namespace
} // namespace terratin::io
