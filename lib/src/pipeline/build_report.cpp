// The build report as JSON and as the human summary lines.

#include "terratin/pipeline/build_pipeline.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace terratin {

namespace {

std::string jsonString(const std::string& text) {
    std::string quoted = "\"";
    for (const char c : text) {
        switch (c) {
        case '"':
            quoted += "\\\"";
            break;
        case '\\':
            quoted += "\\\\";
            break;
        case '\n':
            quoted += "\\n";
            break;
        case '\t':
            quoted += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char escaped[8];
                std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
                quoted += escaped;
            } else {
                quoted += c;
            }
        }
    }
    return quoted + "\"";
}

/// A double as JSON: shortest round-trip text; JSON has no NaN or infinity.
std::string jsonNumber(double value) {
    if (!std::isfinite(value))
        return "null";
    char text[32];
    const std::to_chars_result end = std::to_chars(text, text + sizeof text, value);
    return std::string(text, end.ptr);
}

// The helpers below write the report's sections, in order, into one stream; its format
// (6 decimals, fixed) is toJson's, for every number written with << rather than jsonNumber.

/// A coordinate system as {"name", "code"}.
void writeCrs(std::ostream& json, const std::string& name, const std::string& code) {
    json << "{\"name\": " << jsonString(name) << ", \"code\": " << jsonString(code) << "}";
}

const char* jsonBool(bool value) {
    return value ? "true" : "false";
}

/// The paths, the format and the output's CRS.
void writeRun(std::ostream& json, const BuildReport& report) {
    json << "\"input\": " << jsonString(report.input)
         << ", \"output\": " << jsonString(report.output)
         << ", \"format\": " << jsonString(report.format) << ", \"crs\": ";
    writeCrs(json, report.crsName, report.crsCode);
}

void writeCounts(std::ostream& json, const BuildReport& report) {
    json << ", \"counts\": {\"raster_cells\": " << report.rasterCells
         << ", \"skipped_cells\": " << report.skippedCells << ", \"points\": " << report.points
         << ", \"duplicates\": " << report.duplicates << ", \"vertices\": " << report.vertices
         << ", \"triangles\": " << report.triangles << "}";
}

void writeTriangulation(std::ostream& json, const BuildReport& report) {
    json << ", \"triangulation\": {\"method\": " << jsonString(report.method)
         << ", \"threads\": " << report.threads
         << ", \"history_bytes_per_point\": " << report.historyBytesPerPoint
         << ", \"mesh_bytes_per_point\": " << report.meshBytesPerPoint << "}";
}

/// Seconds per phase, then whether the TIN was validated.
void writeTimings(std::ostream& json, const BuildReport& report) {
    const BuildTimings& timings = report.timings;
    json << ", \"timings\": {\"read\": " << timings.read
         << ", \"triangulate\": " << timings.triangulate << ", \"validate\": " << timings.validate
         << ", \"write\": " << timings.write << ", \"total\": " << timings.total
         << ", \"reproject\": " << timings.reproject << ", \"constrain\": " << timings.constrain
         << "}, \"validated\": " << jsonBool(report.validated);
}

/// The coordinate systems from the inputs' to the TIN's, and the z factor.
void writeCoordinateSystems(std::ostream& json, const BuildReport& report) {
    json << ", \"source_crs\": ";
    writeCrs(json, report.sourceCrsName, report.sourceCrsCode);
    json << ", \"target_crs\": ";
    writeCrs(json, report.crsName, report.crsCode);
    json << ", \"zone\": " << jsonString(report.zone)
         << ", \"reprojected\": " << jsonBool(report.reprojected)
         << ", \"z_factor\": " << jsonNumber(report.zFactor);
}

/// Each input as read.
void writeInputs(std::ostream& json, const std::vector<InputReport>& inputs) {
    json << ", \"inputs\": [";
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const InputReport& input = inputs[i];
        json << (i > 0 ? ", " : "") << "{\"path\": " << jsonString(input.path)
             << ", \"kind\": " << jsonString(input.kind) << ", \"crs\": ";
        writeCrs(json, input.crsName, input.crsCode);
        json << ", \"records\": " << input.records << ", \"filtered_out\": " << input.filteredOut
             << ", \"skipped_cells\": " << input.skippedCells << ", \"points\": " << input.points
             << ", \"duplicates\": " << input.duplicates
             << ", \"reprojected\": " << jsonBool(input.reprojected) << "}";
    }
    json << "]";
}

void writeNotices(std::ostream& json, const std::vector<std::string>& notices) {
    json << ", \"notices\": [";
    for (std::size_t i = 0; i < notices.size(); ++i)
        json << (i > 0 ? ", " : "") << jsonString(notices[i]);
    json << "]";
}

/// The simplification's target and result; only for a refined build.
void writeRefine(std::ostream& json, const BuildReport& report) {
    json << ", \"refine\": {\"max_error\": ";
    if (report.targetMaxError)
        json << *report.targetMaxError;
    else
        json << "null";
    json << ", \"achieved_max_error\": " << report.achievedMaxError << ", \"rmse\": " << report.rmse
         << ", \"points\": " << report.vertices << ", \"triangles\": " << report.triangles
         << ", \"stop\": " << jsonString(report.refineStop)
         << ", \"open_hole_cells\": " << report.openHoleCells
         << ", \"hole_triangles\": " << report.holeTriangles
         << ", \"uncovered_cells\": " << report.uncoveredCells << "}";
}

/// Breaklines and areas: what went in and what it did to the TIN.
void writeConstraints(std::ostream& json, const BuildReport& report) {
    json << ", \"constraints\": {\"breaklines\": " << report.breaklines
         << ", \"clipped_breaklines\": " << report.clippedBreaklines
         << ", \"added_vertices\": " << report.constraintVertices
         << ", \"crossings\": " << report.constraintCrossings
         << ", \"area_triangles\": " << report.areaTriangles
         << ", \"replace_polygons\": " << report.replacePolygons
         << ", \"replaced_points\": " << report.replacedPoints
         << ", \"check_passes\": " << report.constraintPasses
         << ", \"inserted_cells\": " << report.constraintCells << "}";
}

void writeWriting(std::ostream& json, const BuildReport& report) {
    json << ", \"writing\": {\"features\": " << report.writeFeatures
         << ", \"features_per_second\": " << report.writeFeaturesPerSecond
         << ", \"rows_seconds\": " << report.writeRowSeconds
         << ", \"index_seconds\": " << report.writeIndexSeconds << "}";
}

} // namespace

std::string toJson(const BuildReport& report) {
    std::ostringstream json;
    json.precision(6);
    json << std::fixed;
    json << "{";
    writeRun(json, report);
    writeCounts(json, report);
    writeTriangulation(json, report);
    writeTimings(json, report);
    writeCoordinateSystems(json, report);
    writeInputs(json, report.inputs);
    writeNotices(json, report.notices);
    if (report.refined)
        writeRefine(json, report);
    if (report.longEdgeTriangles > 0)
        json << ", \"long_edge_triangles\": " << report.longEdgeTriangles;
    writeConstraints(json, report);
    writeWriting(json, report);
    json << "}";
    return json.str();
}

std::string toSummaryLine(const BuildReport& report) {
    char line[512];
    if (report.refined) {
        std::snprintf(line, sizeof line,
                      "%llu points, %llu triangles (%llu over holes dropped); max error %.3f, "
                      "RMSE %.3f; read %.2f s, refine %.2f s, write %.2f s, total %.2f s",
                      static_cast<unsigned long long>(report.vertices),
                      static_cast<unsigned long long>(report.triangles),
                      static_cast<unsigned long long>(report.holeTriangles),
                      report.achievedMaxError, report.rmse, report.timings.read,
                      report.timings.triangulate, report.timings.write, report.timings.total);
        return line;
    }
    std::snprintf(line, sizeof line,
                  "%llu points (%llu duplicates, %llu nodata cells skipped) -> %llu triangles; "
                  "read %.2f s, triangulate %.2f s, write %.2f s (%.0f features/s), total %.2f s",
                  static_cast<unsigned long long>(report.points),
                  static_cast<unsigned long long>(report.duplicates),
                  static_cast<unsigned long long>(report.skippedCells),
                  static_cast<unsigned long long>(report.triangles), report.timings.read,
                  report.timings.triangulate, report.timings.write, report.writeFeaturesPerSecond,
                  report.timings.total);
    std::string text = line;
    if (report.filteredOut > 0)
        text += "; " + std::to_string(report.filteredOut) + " records filtered out";
    return text;
}

std::string toInputSummary(const BuildReport& report) {
    const auto label = [](const std::string& name, const std::string& code) {
        if (name.empty())
            return std::string("no CRS");
        return code.empty() ? name : name + " [" + code + "]";
    };
    std::string text;
    for (std::size_t i = 0; i < report.inputs.size(); ++i) {
        const InputReport& input = report.inputs[i];
        text += "input " + std::to_string(i + 1) + ": " + input.path + " (" + input.kind + ", " +
                label(input.crsName, input.crsCode) + "): " + std::to_string(input.records) +
                (input.kind == "raster"
                     ? " cells, " + std::to_string(input.skippedCells) + " nodata skipped"
                     : " records, " + std::to_string(input.filteredOut) + " filtered out") +
                ", " + std::to_string(input.points) + " points, " +
                std::to_string(input.duplicates) + " duplicates" +
                (input.reprojected ? ", reprojected" : "") + "\n";
    }
    text += "CRS: " + label(report.sourceCrsName, report.sourceCrsCode);
    if (report.reprojected || !report.zone.empty())
        text += " -> " + label(report.crsName, report.crsCode);
    if (!report.zone.empty())
        text += " (" + report.zone + ", chosen from the data's centre)";
    if (report.zFactor != 1.0) {
        char factor[64];
        std::snprintf(factor, sizeof factor, "%.10g", report.zFactor);
        text += std::string("; z scaled by ") + factor;
    }
    return text + "\n";
}

} // namespace terratin
