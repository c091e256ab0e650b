// LandXML read back through libxml2 (a real XML parser): well-formed, LandXML 1.2 namespace,
// the TIN surface's point and face counts, exact coordinates in northing-easting order, units
// and CRS.

#include "terratin/io/tin_writer.hpp"

#include "mesh_readers.hpp"
#include "temporary_directory.hpp"

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xpath.h>
#include <libxml/xpathInternals.h>

#include <gtest/gtest.h>

#include <charconv>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace terratin::io {
namespace {

const xmlChar* xmlText(const char* text) {
    return reinterpret_cast<const xmlChar*>(text);
}

using test::TemporaryDirectory;

constexpr const char* kNamespace = "http://www.landxml.org/schema/LandXML-1.2";

struct XmlDocFree {
    void operator()(xmlDoc* doc) const { xmlFreeDoc(doc); }
};
struct XPathContextFree {
    void operator()(xmlXPathContext* context) const { xmlXPathFreeContext(context); }
};
struct XPathObjectFree {
    void operator()(xmlXPathObject* object) const { xmlXPathFreeObject(object); }
};

/// A parsed document and XPath queries in the LandXML namespace (prefix "lx").
class LandXmlDocument {
public:
    explicit LandXmlDocument(const std::filesystem::path& path)
        : m_doc(xmlReadFile(path.c_str(), nullptr, XML_PARSE_NONET | XML_PARSE_HUGE)) {
        if (!m_doc)
            return;
        m_context.reset(xmlXPathNewContext(m_doc.get()));
        xmlXPathRegisterNs(m_context.get(), xmlText("lx"), xmlText(kNamespace));
    }
    [[nodiscard]] bool parsed() const { return m_doc != nullptr; }

    [[nodiscard]] double number(const std::string& xpath) const {
        std::unique_ptr<xmlXPathObject, XPathObjectFree> result(
            xmlXPathEvalExpression(xmlText(xpath.c_str()), m_context.get()));
        return result ? xmlXPathCastToNumber(result.get()) : -1.0;
    }
    [[nodiscard]] std::vector<std::string> texts(const std::string& xpath) const {
        std::vector<std::string> values;
        std::unique_ptr<xmlXPathObject, XPathObjectFree> result(
            xmlXPathEvalExpression(xmlText(xpath.c_str()), m_context.get()));
        if (!result || result->nodesetval == nullptr)
            return values;
        for (int i = 0; i < result->nodesetval->nodeNr; ++i) {
            xmlChar* content = xmlNodeGetContent(result->nodesetval->nodeTab[i]);
            values.emplace_back(reinterpret_cast<const char*>(content));
            xmlFree(content);
        }
        return values;
    }
    [[nodiscard]] std::string text(const std::string& xpath) const {
        const auto values = texts(xpath);
        return values.size() == 1 ? values.front()
                                  : std::string("<" + std::to_string(values.size()) + " nodes>");
    }

private:
    std::unique_ptr<xmlDoc, XmlDocFree> m_doc;
    std::unique_ptr<xmlXPathContext, XPathContextFree> m_context;
};

std::vector<double> numbers(const std::string& text) {
    std::vector<double> values;
    std::istringstream in(text);
    for (std::string token; in >> token;) {
        double value = 0.0;
        const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
        EXPECT_EQ(result.ptr, token.data() + token.size()) << token;
        values.push_back(value);
    }
    return values;
}

std::string epsgWkt(int code) {
    OGRSpatialReference srs;
    EXPECT_EQ(srs.importFromEPSG(code), OGRERR_NONE);
    char* wkt = nullptr;
    EXPECT_EQ(srs.exportToWkt(&wkt), OGRERR_NONE);
    std::string result = wkt != nullptr ? wkt : "";
    CPLFree(wkt);
    return result;
}

TEST(LandXmlWriter, ParsesWithPointAndFaceCounts_WhenReadByLibxml2) {
    TemporaryDirectory directory;
    TinMesh mesh = test::gridTin(5);
    mesh.vertices[3].z = 0.1 + 0.2;
    TinWriteOptions options;
    options.format = TinFormat::LandXml;
    options.crsWkt = epsgWkt(26910);
    options.layerName = "Ground & <terrain>";
    const TinWriteResult result = writeTin(mesh, directory / "tin.xml", options);
    EXPECT_EQ(result.features, mesh.vertexCount() + mesh.triangleCount());

    const LandXmlDocument doc(directory / "tin.xml");
    ASSERT_TRUE(doc.parsed());
    EXPECT_EQ(doc.text("/lx:LandXML/@version"), "1.2");
    EXPECT_EQ(doc.number("count(//lx:Surfaces/lx:Surface/lx:Definition[@surfType='TIN'])"), 1.0);
    EXPECT_EQ(doc.number("count(//lx:Definition/lx:Pnts/lx:P)"),
              static_cast<double>(mesh.vertexCount()));
    EXPECT_EQ(doc.number("count(//lx:Definition/lx:Faces/lx:F)"),
              static_cast<double>(mesh.triangleCount()));
    EXPECT_EQ(doc.text("//lx:Surface/@name"), "Ground & <terrain>");
    EXPECT_EQ(doc.text("/lx:LandXML/lx:Units/lx:Metric/@linearUnit"), "meter");
    EXPECT_EQ(doc.text("/lx:LandXML/lx:CoordinateSystem/@epsgCode"), "26910");
    EXPECT_EQ(doc.text("/lx:LandXML/lx:CoordinateSystem/@name"), "NAD83 / UTM zone 10N");
    EXPECT_EQ(doc.number("//lx:Definition/@elevMin"), 0.1 + 0.2); // vertex 3, set above

    // Points: id = vertex number from 1, "northing easting elevation", exact.
    const auto ids = doc.texts("//lx:Pnts/lx:P/@id");
    const auto points = doc.texts("//lx:Pnts/lx:P");
    ASSERT_EQ(points.size(), mesh.vertexCount());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        EXPECT_EQ(ids[v], std::to_string(v + 1));
        const auto values = numbers(points[v]);
        ASSERT_EQ(values.size(), 3u);
        EXPECT_EQ(values[0], mesh.vertices[v].y);
        EXPECT_EQ(values[1], mesh.vertices[v].x);
        EXPECT_EQ(values[2], mesh.vertices[v].z);
    }
    const auto faces = doc.texts("//lx:Faces/lx:F");
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const auto values = numbers(faces[t]);
        ASSERT_EQ(values.size(), 3u);
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(values[k], mesh.triangles[3 * t + k] + 1.0);
    }
    // The planimetric area of the 40 m x 40 m grid.
    EXPECT_DOUBLE_EQ(doc.number("//lx:Definition/@area2DSurf"), 1600.0);
    EXPECT_GT(doc.number("//lx:Definition/@area3DSurf"), 1600.0);
}

TEST(LandXmlWriter, DeclaresImperialUnits_WhenCrsIsInUsSurveyFeet) {
    TemporaryDirectory directory;
    TinWriteOptions options;
    options.format = TinFormat::LandXml;
    options.crsWkt = epsgWkt(2229); // NAD83 / California zone 5 (ftUS)
    writeTin(test::gridTin(3), directory / "tin.landxml", options);
    const LandXmlDocument doc(directory / "tin.landxml");
    ASSERT_TRUE(doc.parsed());
    EXPECT_EQ(doc.text("/lx:LandXML/lx:Units/lx:Imperial/@linearUnit"), "USSurveyFoot");
    EXPECT_EQ(doc.text("/lx:LandXML/lx:CoordinateSystem/@epsgCode"), "2229");
}

TEST(LandXmlWriter, WritesNoCoordinateSystem_WhenThereIsNoCrs) {
    TemporaryDirectory directory;
    TinWriteOptions options;
    options.format = TinFormat::LandXml;
    writeTin(test::gridTin(3), directory / "tin.xml", options);
    const LandXmlDocument doc(directory / "tin.xml");
    ASSERT_TRUE(doc.parsed());
    EXPECT_EQ(doc.number("count(//lx:CoordinateSystem)"), 0.0);
    EXPECT_EQ(doc.number("count(//lx:P)"), 9.0);
}

} // namespace
} // namespace terratin::io
