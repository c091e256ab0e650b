#include "results_table.hpp"

namespace terratin::bench {

namespace {

// `value` printed with `format` in a field of `width`, or `absent` right-aligned there.
std::string field(const std::optional<double>& value, const char* format, int width,
                  const char* absent = "-") {
    char text[64];
    if (value)
        std::snprintf(text, sizeof text, format, width, *value);
    else
        std::snprintf(text, sizeof text, "%*s", width, absent);
    return text;
}

// CSV leaves a missing value empty.
std::string csvField(const std::optional<double>& value, const char* format) {
    if (!value)
        return "";
    char text[64];
    std::snprintf(text, sizeof text, format, *value);
    return text;
}

} // namespace

void ResultTable::printHeader() {
    if (m_csv) {
        std::fprintf(m_stream,
                     "distribution,points,method,locate,threads_requested,threads_used,searchers,"
                     "helped_locations,triangles,runs,seconds,speed_up,history_bytes_per_point,"
                     "mesh_bytes_per_point,peak_bytes_per_point,vs_cgal,vs_gdal,unmeasured\n");
    } else {
        std::fprintf(m_stream, "%-8s %9s %-12s %-4s %3s %4s %10s %8s %9s %9s %9s %7s %7s\n", "dist",
                     "N", "method", "loc", "thr", "srch", "time [s]", "speed-up", "hist B/pt",
                     "mesh B/pt", "peak B/pt", "vs CGAL", "vs GDAL");
    }
    std::fflush(m_stream);
}

void ResultTable::printRow(const ResultRow& row) {
    if (m_csv) {
        std::fprintf(m_stream, "%s,%zu,%s,%s,%u,%u,%u,%zu,%zu,%u,%s,%s,%s,%s,%s,%s,%s,%s\n",
                     row.distribution.c_str(), row.points, row.method.c_str(), row.locate.c_str(),
                     row.threadsRequested, row.threadsUsed, row.searchers, row.helpedLocations,
                     row.triangles, row.runs, csvField(row.seconds, "%.6g").c_str(),
                     csvField(row.speedUp, "%.4f").c_str(),
                     csvField(row.historyBytesPerPoint, "%.2f").c_str(),
                     csvField(row.meshBytesPerPoint, "%.2f").c_str(),
                     csvField(row.peakBytesPerPoint, "%.2f").c_str(),
                     csvField(row.vsCgal, "%.4g").c_str(), csvField(row.vsGdal, "%.4g").c_str(),
                     row.seconds ? "" : row.unmeasured.c_str());
    } else {
        const std::string searchers = row.searchers > 0 ? std::to_string(row.searchers) : "-";
        std::fprintf(m_stream, "%-8s %9zu %-12s %-4s %3u %4s %s %s %s %s %s %s %s\n",
                     row.distribution.c_str(), row.points, row.method.c_str(),
                     row.locate.empty() ? "-" : row.locate.c_str(), row.threadsRequested,
                     searchers.c_str(),
                     field(row.seconds, "%*.4g", 10, row.unmeasured.c_str()).c_str(),
                     field(row.speedUp, "%*.2f", 8).c_str(),
                     field(row.historyBytesPerPoint, "%*.1f", 9).c_str(),
                     field(row.meshBytesPerPoint, "%*.1f", 9).c_str(),
                     field(row.peakBytesPerPoint, "%*.1f", 9, "n/a").c_str(),
                     field(row.vsCgal, "%*.3g", 7).c_str(), field(row.vsGdal, "%*.3g", 7).c_str());
    }
    std::fflush(m_stream);
}

void ResultTable::printSeparator() {
    if (!m_csv)
        std::fputc('\n', m_stream);
}

} // namespace terratin::bench
