#include "landxml_writer.hpp"

#include "terratin/geometry/triangle_attributes.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

namespace terratin::io::detail {

namespace {

/// Relative tolerance when recognising a foot in the CRS's unit: the international foot is
/// 0.3048 m exactly and the US survey foot 1200/3937 m; they differ by 2e-6 relative, far
/// more than the rounding in a WKT's printed factor.
constexpr double kUnitTolerance = 1e-9;

constexpr double kInternationalFootM = 0.3048;
constexpr double kUsSurveyFootM = 1200.0 / 3937.0;

/// The Definition element's figures: the TIN's 2D and 3D areas (summed in triangle order) and
/// its elevations' range.
struct LandXmlSurface {
    double area2d = 0.0;
    double area3d = 0.0;
    double elevMin = std::numeric_limits<double>::infinity();
    double elevMax = -std::numeric_limits<double>::infinity();
};

std::string unitsElement(const CrsSummary& crs) {
    const auto near = [&](double metres) {
        return std::fabs(crs.metresPerUnit - metres) <= kUnitTolerance * metres;
    };
    if (near(kUsSurveyFootM) || near(kInternationalFootM)) {
        const char* linear = near(kUsSurveyFootM) ? "USSurveyFoot" : "foot";
        return std::string("<Units><Imperial areaUnit=\"squareFoot\" linearUnit=\"") + linear +
               "\" volumeUnit=\"cubicFeet\" temperatureUnit=\"fahrenheit\" "
               "pressureUnit=\"inchHG\"/></Units>\n";
    }
    return "<Units><Metric areaUnit=\"squareMeter\" linearUnit=\"meter\" "
           "volumeUnit=\"cubicMeter\" temperatureUnit=\"celsius\" "
           "pressureUnit=\"milliBars\"/></Units>\n";
}

} // namespace

std::string xmlEscaped(std::string_view text) {
    std::string escaped;
    escaped.reserve(text.size());
    for (const char ch : text) {
        switch (ch) {
        case '&':
            escaped += "&amp;";
            break;
        case '<':
            escaped += "&lt;";
            break;
        case '>':
            escaped += "&gt;";
            break;
        case '"':
            escaped += "&quot;";
            break;
        case '\'':
            escaped += "&apos;";
            break;
        default:
            escaped += ch;
        }
    }
    return escaped;
}

namespace {

/// The breaklines as LandXML 1.2 <SourceData><Breaklines>: each a <Breakline> whose
/// <PntList3D> lists northing easting elevation of every point, as <P> does.
void writeBreaklines(const MeshFileInfo& info, BufferedFile& file) {
    if (info.breaklines == nullptr || info.breaklines->empty())
        return;
    file.text("<SourceData>\n<Breaklines>\n");
    for (const std::vector<Point3>& line : *info.breaklines) {
        file.text("<Breakline brkType=\"standard\">\n<PntList3D>");
        for (std::size_t i = 0; i < line.size(); ++i) {
            if (i > 0)
                file.put(' ');
            file.number(line[i].y);
            file.put(' ');
            file.number(line[i].x);
            file.put(' ');
            file.number(line[i].z);
        }
        file.text("</PntList3D>\n</Breakline>\n");
    }
    file.text("</Breaklines>\n</SourceData>\n");
}

/// Everything before the first point: the header, the surface's Definition with `surface`'s
/// figures, "<Pnts>".
void putHead(BufferedFile& file, const MeshFileInfo& info, const LandXmlSurface& surface) {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char date[16];
    char time[16];
    std::strftime(date, sizeof date, "%Y-%m-%d", &utc);
    std::strftime(time, sizeof time, "%H:%M:%S", &utc);

    file.text("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
              "<LandXML xmlns=\"http://www.landxml.org/schema/LandXML-1.2\" "
              "xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
              "xsi:schemaLocation=\"http://www.landxml.org/schema/LandXML-1.2 "
              "http://www.landxml.org/schema/LandXML-1.2/LandXML-1.2.xsd\" "
              "version=\"1.2\" date=\"");
    file.text(date);
    file.text("\" time=\"");
    file.text(time);
    file.text("\">\n");
    file.text(unitsElement(info.crs));
    if (!info.crs.empty()) {
        file.text("<CoordinateSystem name=\"");
        file.text(xmlEscaped(info.crs.name));
        file.put('"');
        if (!info.crs.epsgCode.empty()) {
            file.text(" epsgCode=\"");
            file.text(info.crs.epsgCode);
            file.put('"');
        }
        file.text(" ogcWktCode=\"");
        file.text(xmlEscaped(info.crs.wkt));
        file.text("\"/>\n");
    }
    file.text("<Application name=\"terratin\" manufacturer=\"terratin\" version=\"");
    file.text(xmlEscaped(info.softwareVersion));
    file.text("\"/>\n<Surfaces>\n<Surface name=\"");
    file.text(xmlEscaped(info.name));
    file.text("\">\n");
    writeBreaklines(info, file);
    file.text("<Definition surfType=\"TIN\" area2DSurf=\"");
    file.number(surface.area2d);
    file.text("\" area3DSurf=\"");
    file.number(surface.area3d);
    file.text("\" elevMax=\"");
    file.number(surface.elevMax);
    file.text("\" elevMin=\"");
    file.number(surface.elevMin);
    file.text("\">\n<Pnts>\n");
}

class LandXmlFormat : public MeshFormatBase {
public:
    static constexpr std::string_view kVertexMessage = "Writing points";
    static constexpr std::string_view kFaceMessage = "Writing faces";

    void addVertex(const Point3& p) {
        m_surface.elevMin = std::min(m_surface.elevMin, p.z);
        m_surface.elevMax = std::max(m_surface.elevMax, p.z);
    }
    void addTriangle(const Point3& a, const Point3& b, const Point3& c) {
        const TriangleAttributes attributes = computeTriangleAttributes(a, b, c);
        m_surface.area2d += attributes.area2d;
        m_surface.area3d += attributes.area3d;
    }

    void head(BufferedFile& file, const MeshFileInfo& info, std::uint64_t, std::uint64_t) {
        putHead(file, info, m_surface);
    }

    /// Point ids count from 1; northing before easting.
    void vertex(BufferedFile& file, std::uint64_t number, const Point3& p) {
        file.text("<P id=\"");
        file.number(number + 1);
        file.text("\">");
        file.number(p.y);
        file.put(' ');
        file.number(p.x);
        file.put(' ');
        file.number(p.z);
        file.text("</P>\n");
    }

    void between(BufferedFile& file) { file.text("</Pnts>\n<Faces>\n"); }

    /// Point ids count from 1.
    void face(BufferedFile& file, std::uint64_t, std::uint32_t a, std::uint32_t b,
              std::uint32_t c) {
        file.text("<F>");
        file.number(std::uint64_t{a} + 1);
        file.put(' ');
        file.number(std::uint64_t{b} + 1);
        file.put(' ');
        file.number(std::uint64_t{c} + 1);
        file.text("</F>\n");
    }

    void trailer(BufferedFile& file) {
        file.text("</Faces>\n</Definition>\n</Surface>\n</Surfaces>\n</LandXML>\n");
    }

private:
    LandXmlSurface m_surface;
};

} // namespace

constinit const MeshWriter kLandXmlWriter = meshWriterFor<LandXmlFormat>();

} // namespace terratin::io::detail
