// A TIN written piece by piece (--memory-limit) is the TIN written whole: the same
// PLY and Shapefile bytes, the same GeoPackage rows with a sound spatial index, the same
// FlatGeobuf features; what cannot be streamed is refused before anything is written, and a
// stream never finished leaves no file.

#include "gpkg_tin_stream.hpp"

#include "mesh_readers.hpp"
#include "ogr_test_support.hpp"
#include "sqlite_query.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace terratin::io {
namespace {

using detail::openTinStream;
using detail::TinPiece;
using test::TemporaryDirectory;

/// A TIN cut into pieces by ranges of its triangles, each piece numbering its vertices in the
/// order its triangles first use them, and the whole TIN numbered as the pieces give their
/// vertices: what a stream of the pieces must write.
struct CutTin {
    std::vector<TinMesh> pieces;
    std::vector<std::vector<std::uint32_t>> numbers;
    std::vector<std::vector<RasterCell>> cells;
    TinMesh whole;
};

CutTin cutTin(const TinMesh& tin, const std::vector<std::size_t>& firstTriangles, int width) {
    CutTin cut;
    std::map<std::uint32_t, std::uint32_t> wholeOf; // the tin's vertex -> the whole's
    for (std::size_t p = 0; p < firstTriangles.size(); ++p) {
        const std::size_t end =
            p + 1 < firstTriangles.size() ? firstTriangles[p + 1] : tin.triangleCount();
        TinMesh piece;
        std::vector<std::uint32_t> numbers;
        std::vector<RasterCell> cells;
        std::map<std::uint32_t, std::uint32_t> local;
        for (std::size_t i = 3 * firstTriangles[p]; i < 3 * end; ++i) {
            const std::uint32_t v = tin.triangles[i];
            auto [at, added] = local.emplace(v, static_cast<std::uint32_t>(piece.vertexCount()));
            if (added) {
                piece.vertices.push_back(tin.vertices[v]);
                cells.push_back(
                    {static_cast<std::int64_t>(v) / width, static_cast<std::int64_t>(v) % width});
                const auto [number, isNew] =
                    wholeOf.emplace(v, static_cast<std::uint32_t>(cut.whole.vertexCount()));
                if (isNew)
                    cut.whole.vertices.push_back(tin.vertices[v]);
                numbers.push_back(number->second);
            }
            piece.triangles.push_back(at->second);
            cut.whole.triangles.push_back(wholeOf.at(v));
        }
        cut.pieces.push_back(std::move(piece));
        cut.numbers.push_back(std::move(numbers));
        cut.cells.push_back(std::move(cells));
    }
    return cut;
}

void streamPieces(const CutTin& cut, const std::filesystem::path& output,
                  const TinWriteOptions& options) {
    auto writer = openTinStream(output, options, "--memory-limit");
    for (std::size_t p = 0; p < cut.pieces.size(); ++p)
        writer->append({&cut.pieces[p], cut.numbers[p], cut.cells[p]});
    writer->finish({});
}

std::string bytesOf(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

TinWriteOptions streamOptions(TinFormat format) {
    TinWriteOptions options;
    options.format = format;
    options.crsWkt = test::utm10nWkt();
    return options;
}

constexpr int kGrid = 9;
constexpr std::array kStreamedFormats{
    TinFormat::Ply,   TinFormat::GeoPackage, TinFormat::Shapefile, TinFormat::FlatGeobuf,
    TinFormat::TwoDm, TinFormat::Obj,        TinFormat::LandXml};

std::string outputName(TinFormat format) {
    switch (format) {
    case TinFormat::Ply:
        return "t.ply";
    case TinFormat::GeoPackage:
        return "t.gpkg";
    case TinFormat::Shapefile:
        return "t.shp";
    case TinFormat::FlatGeobuf:
        return "t.fgb";
    case TinFormat::TwoDm:
        return "t.2dm";
    case TinFormat::Obj:
        return "t.obj";
    default:
        return "t.xml";
    }
}
const std::vector<std::size_t> kPieces{0, 40, 41, 90};

TEST(TinStream, APlyWrittenPieceByPiece_IsThePlyOfTheWholeTin) {
    const TemporaryDirectory directory;
    const CutTin cut = cutTin(test::gridTin(kGrid), kPieces, kGrid);
    const TinWriteOptions options = streamOptions(TinFormat::Ply);
    streamPieces(cut, directory / "streamed.ply", options);
    writeTin(cut.whole, directory / "whole.ply", options);
    EXPECT_EQ(bytesOf(directory / "streamed.ply"), bytesOf(directory / "whole.ply"));
    test::expectSameMesh(test::readPly(directory / "streamed.ply"), cut.whole);
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"streamed.ply", "whole.ply"}));
}

TEST(TinStream, AGeoPackageWrittenPieceByPiece_HasTheWholeTinsRows_AndASoundIndex) {
    const TemporaryDirectory directory;
    const CutTin cut = cutTin(test::gridTin(kGrid), kPieces, kGrid);
    TinWriteOptions options = streamOptions(TinFormat::GeoPackage);
    options.nodes = true;
    streamPieces(cut, directory / "streamed.gpkg", options);
    std::vector<RasterCell> wholeCells(cut.whole.vertexCount());
    for (std::size_t p = 0; p < cut.pieces.size(); ++p)
        for (std::size_t v = 0; v < cut.numbers[p].size(); ++v)
            wholeCells[cut.numbers[p][v]] = cut.cells[p][v];
    options.vertexCells = wholeCells;
    writeTin(cut.whole, directory / "whole.gpkg", options);

    for (const std::string layer : {"tin", "nodes"}) {
        const std::string rows = "SELECT * FROM " + layer + " ORDER BY fid";
        const std::string streamed = test::sqliteRows(directory / "streamed.gpkg", rows);
        EXPECT_EQ(streamed, test::sqliteRows(directory / "whole.gpkg", rows)) << layer;
        EXPECT_NE(streamed.find('\n'), std::string::npos) << layer;
        EXPECT_EQ(test::rtreeCheck(directory / "streamed.gpkg", layer), "ok") << layer;
        const std::string extent =
            "SELECT min_x || ' ' || min_y || ' ' || max_x || ' ' || max_y FROM gpkg_contents "
            "WHERE table_name = '" +
            layer + "'";
        EXPECT_EQ(test::sqliteText(directory / "streamed.gpkg", extent),
                  test::sqliteText(directory / "whole.gpkg", extent));
        const std::string count =
            "SELECT feature_count FROM gpkg_ogr_contents WHERE table_name = '" + layer + "'";
        EXPECT_EQ(test::sqliteText(directory / "streamed.gpkg", count),
                  test::sqliteText(directory / "whole.gpkg", count));
    }
    // The same rows the whole index finds: the packed R-tree over the same boxes.
    const std::string tree = "SELECT * FROM rtree_tin_geom ORDER BY id";
    EXPECT_EQ(test::sqliteRows(directory / "streamed.gpkg", tree),
              test::sqliteRows(directory / "whole.gpkg", tree));
}

TEST(TinStream, A2dmAnObjAndALandXmlWrittenPieceByPiece_AreTheWholeTinsFiles) {
    // Their heads need the whole TIN: the OBJ's local origin (which a large offset, 1e6,
    // tests), LandXML's areas and elevation range.
    const TemporaryDirectory directory;
    TinMesh tin = test::gridTin(kGrid);
    for (Point3& p : tin.vertices)
        p.x += 1.0e6;
    tin.vertices.back().z -= 300.0; // the lowest vertex, in the last piece
    const CutTin cut = cutTin(tin, kPieces, kGrid);
    for (const TinFormat format : {TinFormat::TwoDm, TinFormat::Obj, TinFormat::LandXml}) {
        const std::string name = outputName(format);
        SCOPED_TRACE(name);
        const TinWriteOptions options = streamOptions(format);
        streamPieces(cut, directory / ("streamed-" + name), options);
        writeTin(cut.whole, directory / ("whole-" + name), options);
        std::string streamed = bytesOf(directory / ("streamed-" + name));
        std::string whole = bytesOf(directory / ("whole-" + name));
        if (format == TinFormat::LandXml) { // written at another second, perhaps
            const std::regex when(R"( date="[^"]*" time="[^"]*")");
            streamed = std::regex_replace(streamed, when, "");
            whole = std::regex_replace(whole, when, "");
        }
        EXPECT_EQ(streamed, whole);
        EXPECT_GT(streamed.size(), 1000U);
    }
    test::expectSameMesh(test::readObj(directory / "streamed-t.obj"), cut.whole);
    test::expectSameMesh(test::readTwoDm(directory / "streamed-t.2dm"), cut.whole);
}

TEST(TinStream, AnObjOfMoreVerticesThanAReadBackChunk_IsTheWholeTinsObj) {
    // OBJ's vertices wait as raw doubles and are read back a MiB at a time: 250 x 250
    // vertices (1.5 MB) cut records across a chunk's end.
    const TemporaryDirectory directory;
    constexpr int kLarge = 250;
    const CutTin cut = cutTin(test::gridTin(kLarge), {0, 40000, 90000}, kLarge);
    const TinWriteOptions options = streamOptions(TinFormat::Obj);
    streamPieces(cut, directory / "streamed.obj", options);
    writeTin(cut.whole, directory / "whole.obj", options);
    EXPECT_EQ(bytesOf(directory / "streamed.obj"), bytesOf(directory / "whole.obj"));
    EXPECT_GT(cut.whole.vertexCount() * sizeof(Point3), std::size_t{1} << 20);
}

TEST(TinStream, AMeshJoinOfSeveralChunks_ReportsItsProgress_AndACancelThereLeavesNoFile) {
    // The join reads the temporaries back a MiB at a time and reports after each chunk, so
    // that a cancel reaches it; OBJ reads its raw vertices twice.
    constexpr int kLarge = 250;
    const CutTin cut = cutTin(test::gridTin(kLarge), {0, 40000, 90000}, kLarge);
    for (const TinFormat format : {TinFormat::Ply, TinFormat::Obj, TinFormat::LandXml}) {
        SCOPED_TRACE(outputName(format));
        const TemporaryDirectory directory;
        const std::filesystem::path output = directory / outputName(format);
        std::vector<double> joining;
        std::vector<std::string> messages;
        const auto record = [&](double fraction, std::string_view message) {
            messages.emplace_back(message);
            if (message == "Joining vertices and faces")
                joining.push_back(fraction);
            return true;
        };
        {
            auto writer = openTinStream(output, streamOptions(format), "--memory-limit");
            for (std::size_t p = 0; p < cut.pieces.size(); ++p)
                writer->append({&cut.pieces[p], cut.numbers[p], cut.cells[p]});
            writer->finish(record);
        }
        ASSERT_GE(joining.size(), 3U);
        EXPECT_EQ(joining.front(), 0.0);
        EXPECT_TRUE(std::is_sorted(joining.begin(), joining.end()));
        EXPECT_LE(joining.back(), 0.98);
        EXPECT_GT(joining.back(), 0.9);
        EXPECT_EQ(messages.back(), "Finishing");
        std::filesystem::remove(output);

        int reports = 0;
        auto writer = openTinStream(output, streamOptions(format), "--memory-limit");
        for (std::size_t p = 0; p < cut.pieces.size(); ++p)
            writer->append({&cut.pieces[p], cut.numbers[p], cut.cells[p]});
        EXPECT_THROW(writer->finish([&](double, std::string_view) { return ++reports < 2; }),
                     Cancelled);
        writer.reset();
        EXPECT_TRUE(directory.entries().empty());
    }
}

TEST(TinStream, AShapefileWrittenPieceByPiece_IsTheShapefileOfTheWholeTin) {
    const TemporaryDirectory directory;
    std::filesystem::create_directory(directory / "streamed");
    std::filesystem::create_directory(directory / "whole");
    const CutTin cut = cutTin(test::gridTin(kGrid), kPieces, kGrid);
    const TinWriteOptions options = streamOptions(TinFormat::Shapefile);
    streamPieces(cut, directory / "streamed" / "tin.shp", options);
    writeTin(cut.whole, directory / "whole" / "tin.shp", options);
    const std::set<std::string> files{"tin.shp", "tin.shx", "tin.dbf", "tin.prj", "tin.cpg"};
    EXPECT_EQ(TemporaryDirectory::entriesOf(directory / "streamed"), files);
    for (const std::string& file : files)
        EXPECT_EQ(bytesOf(directory / "streamed" / file), bytesOf(directory / "whole" / file))
            << file;
}

/// Each feature of the only layer of `path` as its geometry's WKT and its fields, sorted: a
/// FlatGeobuf's index decides the order its features are stored in.
std::vector<std::string> sortedFeatures(const std::filesystem::path& path) {
    GDALDatasetUniquePtr dataset(
        GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
    EXPECT_NE(dataset, nullptr) << path;
    std::vector<std::string> features;
    if (dataset == nullptr)
        return features;
    OGRLayer* layer = dataset->GetLayer(0);
    for (auto& feature : *layer) {
        std::string text = feature->GetGeometryRef()->exportToWkt();
        for (int field = 0; field < feature->GetFieldCount(); ++field)
            text += std::string(" ") + feature->GetFieldAsString(field);
        features.push_back(std::move(text));
    }
    std::sort(features.begin(), features.end());
    return features;
}

TEST(TinStream, AFlatGeobufWrittenPieceByPiece_HasTheWholeTinsFeatures_AndItsIndex) {
    const TemporaryDirectory directory;
    const CutTin cut = cutTin(test::gridTin(kGrid), kPieces, kGrid);
    for (const bool index : {true, false}) {
        TinWriteOptions options = streamOptions(TinFormat::FlatGeobuf);
        options.spatialIndex = index;
        options.overwrite = true;
        streamPieces(cut, directory / "streamed.fgb", options);
        writeTin(cut.whole, directory / "whole.fgb", options);
        const std::vector<std::string> streamed = sortedFeatures(directory / "streamed.fgb");
        EXPECT_EQ(streamed.size(), cut.whole.triangleCount());
        EXPECT_EQ(streamed, sortedFeatures(directory / "whole.fgb"));
        GDALDatasetUniquePtr dataset(GDALDataset::Open((directory / "streamed.fgb").c_str(),
                                                       GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
        ASSERT_NE(dataset, nullptr);
        EXPECT_EQ(dataset->GetLayer(0)->TestCapability(OLCFastSpatialFilter) != 0, index);
        EXPECT_EQ(directory.entries(), (std::set<std::string>{"streamed.fgb", "whole.fgb"}));
    }
}

TEST(TinStream, AStyleBesideAStream_IsTheWholeTinsStyle) {
    // --qgis-style: the style colours the elevations' range, which only the last piece
    // completes (the pieces' vertices are in no order of height).
    const TemporaryDirectory directory;
    TinMesh tin = test::gridTin(kGrid);
    tin.vertices.back().z += 500.0; // the highest vertex, in the last piece
    const CutTin cut = cutTin(tin, kPieces, kGrid);
    for (const std::string name : {"t.gpkg", "t.shp", "t.fgb"}) {
        SCOPED_TRACE(name);
        TinWriteOptions options = streamOptions(name == "t.gpkg"  ? TinFormat::GeoPackage
                                                : name == "t.shp" ? TinFormat::Shapefile
                                                                  : TinFormat::FlatGeobuf);
        options.qgisStyle = true;
        std::filesystem::create_directory(directory / "streamed");
        std::filesystem::create_directory(directory / "whole");
        streamPieces(cut, directory / "streamed" / name, options);
        writeTin(cut.whole, directory / "whole" / name, options);
        const std::string style = bytesOf(directory / "streamed" / "t.qml");
        EXPECT_NE(style.find("z_mean"), std::string::npos);
        EXPECT_EQ(style, bytesOf(directory / "whole" / "t.qml"));
        std::filesystem::remove_all(directory / "streamed");
        std::filesystem::remove_all(directory / "whole");
    }
}

TEST(TinStream, AStyleThatAppearedMeanwhile_IsKept_AndTheDataTakenBack) {
    const TemporaryDirectory directory;
    const CutTin cut = cutTin(test::gridTin(kGrid), kPieces, kGrid);
    TinWriteOptions options = streamOptions(TinFormat::GeoPackage);
    options.qgisStyle = true;
    auto writer = openTinStream(directory / "t.gpkg", options, "--memory-limit");
    for (std::size_t p = 0; p < cut.pieces.size(); ++p)
        writer->append({&cut.pieces[p], cut.numbers[p], cut.cells[p]});
    std::ofstream(directory / "t.qml") << "someone's style";
    EXPECT_THROW(writer->finish({}), InvalidInputError);
    writer.reset();
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"t.qml"}));
    EXPECT_EQ(bytesOf(directory / "t.qml"), "someone's style");
}

TEST(TinStream, ANewVertexNumberedOutOfTurn_IsRefused_AndNothingIsLeft) {
    const TemporaryDirectory directory;
    CutTin cut = cutTin(test::gridTin(kGrid), kPieces, kGrid);
    cut.numbers[1].back() += 1; // skips a number
    for (const TinFormat format : kStreamedFormats) {
        const std::filesystem::path output = directory / outputName(format);
        EXPECT_THROW(streamPieces(cut, output, streamOptions(format)), InvalidInputError);
        EXPECT_TRUE(directory.entries().empty()) << outputName(format);
    }
}

TEST(TinStream, AStreamNeverFinished_OrWithoutTriangles_LeavesNoFile) {
    const TemporaryDirectory directory;
    const CutTin cut = cutTin(test::gridTin(kGrid), kPieces, kGrid);
    for (const TinFormat format : kStreamedFormats) {
        const std::filesystem::path output = directory / outputName(format);
        {
            auto writer = openTinStream(output, streamOptions(format), "--memory-limit");
            writer->append({&cut.pieces[0], cut.numbers[0], cut.cells[0]});
        }
        EXPECT_TRUE(directory.entries().empty());
        auto empty = openTinStream(output, streamOptions(format), "--memory-limit");
        EXPECT_THROW(empty->finish({}), InvalidInputError);
        empty.reset();
        EXPECT_TRUE(directory.entries().empty());
    }
}

TEST(TinStream, WhatCannotBeWrittenPieceByPiece_IsRefusedBeforeAnyFile) {
    const TemporaryDirectory directory;
    const auto refusal = [&](TinWriteOptions options, const std::string& name) {
        try {
            openTinStream(directory / name, options, "--memory-limit");
        } catch (const InvalidInputError& error) {
            return std::string(error.what());
        }
        return std::string("<accepted>");
    };
    EXPECT_NE(refusal(streamOptions(TinFormat::Shapefile), "t.dbf").find("must end in .shp"),
              std::string::npos);
    TinWriteOptions edges = streamOptions(TinFormat::GeoPackage);
    edges.edges = true;
    EXPECT_NE(refusal(edges, "t.gpkg").find("without edges"), std::string::npos);
    TinWriteOptions append = streamOptions(TinFormat::GeoPackage);
    append.appendLayer = true;
    EXPECT_NE(refusal(append, "t.gpkg").find("append_layer"), std::string::npos);
    TinWriteOptions style = streamOptions(TinFormat::Ply);
    style.qgisStyle = true;
    EXPECT_NE(refusal(style, "t.ply").find("qgis_style"), std::string::npos);
    std::ofstream(directory / "old.ply") << "old";
    EXPECT_NE(refusal(streamOptions(TinFormat::Ply), "old.ply").find("overwrite"),
              std::string::npos);
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"old.ply"}));
}

} // namespace
} // namespace terratin::io
