#include "qgis_style.hpp"

#include "landxml_writer.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace terratin::io::detail {

namespace {

struct ColourStop {
    double at; // position on the ramp, 0..1
    int red, green, blue;
};

/// A hypsometric tint ramp in the manner of printed topographic maps.
constexpr std::array<ColourStop, 6> kTerrainRamp = {{
    {0.00, 44, 112, 56},
    {0.25, 141, 178, 88},
    {0.50, 232, 215, 125},
    {0.75, 161, 105, 60},
    {0.90, 190, 182, 172},
    {1.00, 255, 255, 255},
}};

std::string rampColour(double at) {
    std::size_t upper = 1;
    while (upper + 1 < kTerrainRamp.size() && kTerrainRamp[upper].at < at)
        ++upper;
    const ColourStop& a = kTerrainRamp[upper - 1];
    const ColourStop& b = kTerrainRamp[upper];
    const double t = std::clamp((at - a.at) / (b.at - a.at), 0.0, 1.0);
    const auto mix = [t](int from, int to) {
        return static_cast<int>(std::lround(from + t * (to - from)));
    };
    return std::to_string(mix(a.red, b.red)) + "," + std::to_string(mix(a.green, b.green)) + "," +
           std::to_string(mix(a.blue, b.blue)) + ",255";
}

std::string shortest(double value) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, value);
    return std::string(text, result.ptr);
}

} // namespace

std::string qgisTerrainStyle(const std::string& attribute, double zMin, double zMax) {
    const int classes = zMax > zMin ? kQgisStyleClasses : 1;
    std::ostringstream qml;
    qml << "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n"
        << "<qgis version=\"3.22.0\" styleCategories=\"Symbology\">\n"
        << "  <renderer-v2 type=\"graduatedSymbol\" attr=\"" << xmlEscaped(attribute)
        << "\" graduatedMethod=\"GraduatedColor\" symbollevels=\"0\" forceraster=\"0\" "
           "enableorderby=\"0\">\n"
        << "    <ranges>\n";
    for (int k = 0; k < classes; ++k) {
        // The outer bounds are the data's own, so every triangle falls in a class.
        const double lower = k == 0 ? zMin : zMin + (zMax - zMin) * k / classes;
        const double upper = k + 1 == classes ? zMax : zMin + (zMax - zMin) * (k + 1) / classes;
        char label[64];
        std::snprintf(label, sizeof label, "%.1f - %.1f", lower, upper);
        qml << "      <range lower=\"" << shortest(lower) << "\" upper=\"" << shortest(upper)
            << "\" symbol=\"" << k << "\" label=\"" << label << "\" render=\"true\"/>\n";
    }
    qml << "    </ranges>\n    <symbols>\n";
    for (int k = 0; k < classes; ++k) {
        const double at = classes == 1 ? 0.5 : (k + 0.5) / classes;
        qml << "      <symbol type=\"fill\" name=\"" << k
            << "\" alpha=\"1\" clip_to_extent=\"1\" force_rhr=\"0\">\n"
            << "        <layer class=\"SimpleFill\" enabled=\"1\" pass=\"0\" locked=\"0\">\n"
            << "          <Option type=\"Map\">\n"
            << "            <Option name=\"color\" type=\"QString\" value=\"" << rampColour(at)
            << "\"/>\n"
            << "            <Option name=\"style\" type=\"QString\" value=\"solid\"/>\n"
            << "            <Option name=\"outline_style\" type=\"QString\" value=\"no\"/>\n"
            << "          </Option>\n"
            << "        </layer>\n"
            << "      </symbol>\n";
    }
    qml << "    </symbols>\n"
        << "    <classificationMethod id=\"EqualInterval\"/>\n"
        << "  </renderer-v2>\n"
        << "</qgis>\n";
    return qml.str();
}

} // namespace terratin::io::detail
