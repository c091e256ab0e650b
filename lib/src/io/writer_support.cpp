#include "writer_support.hpp"

#include "atomic_output.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <cpl_conv.h>
#include <ogr_spatialref.h>

namespace terratin::io::detail {

void reportProgress(std::string_view stage, const ProgressCallback& progress, double fraction,
                    std::string_view message, const std::filesystem::path& output) {
    if (progress && !progress(fraction, message))
        throw Cancelled(std::string(stage) + ": cancelled; " + quoted(output) + " was not written");
}

CrsSummary summariseCrs(std::string_view stage, const std::string& wkt) {
    CrsSummary summary;
    if (wkt.empty())
        return summary;
    initialiseGdal();
    OGRSpatialReference srs;
    if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE)
        throw CrsError(std::string(stage) + ": the output CRS is not valid WKT: " +
                       lastGdalErrorMessage("GDAL cannot parse it"));
    if (const char* name = srs.GetName())
        summary.name = name;
    if (srs.IsProjected() || srs.IsLocal()) {
        const char* unit = nullptr;
        summary.metresPerUnit = srs.GetLinearUnits(&unit);
        if (unit != nullptr)
            summary.linearUnitName = unit;
    } else if (srs.IsGeographic()) {
        summary.linearUnitName = "degree";
        summary.metresPerUnit = 0.0;
    }
    OGRSpatialReference identified(srs);
    if (identified.AutoIdentifyEPSG() == OGRERR_NONE || identified.GetAuthorityCode(nullptr)) {
        const char* authority = identified.GetAuthorityName(nullptr);
        const char* code = identified.GetAuthorityCode(nullptr);
        if (authority != nullptr && code != nullptr && std::string_view(authority) == "EPSG")
            summary.epsgCode = code;
    }
    char* text = nullptr;
    const char* const options[] = {"FORMAT=WKT1", "MULTILINE=NO", nullptr};
    if (srs.exportToWkt(&text, options) != OGRERR_NONE || text == nullptr) {
        CPLFree(text);
        text = nullptr;
        const char* const wkt2[] = {"FORMAT=WKT2_2019", "MULTILINE=NO", nullptr};
        if (srs.exportToWkt(&text, wkt2) != OGRERR_NONE || text == nullptr) {
            CPLFree(text);
            throw CrsError(std::string(stage) + ": cannot export the output CRS as WKT: " +
                           lastGdalErrorMessage("PROJ has no WKT1 or WKT2 form of it"));
        }
    }
    summary.wkt = text;
    CPLFree(text);
    return summary;
}

std::string_view writerStage(TinFormat format) {
    return tinFormatInfo(format).writerStage;
}

} // namespace terratin::io::detail
