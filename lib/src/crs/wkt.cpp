#include "wkt.hpp"

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <memory>

namespace terratin::crs::detail {

namespace {
struct CplFree {
    void operator()(char* text) const { CPLFree(text); }
};
} // namespace

std::string exportWkt(const OGRSpatialReference& srs) {
    const char* const wkt2Options[] = {"FORMAT=WKT2_2019", nullptr};
    char* raw = nullptr;
    if (srs.exportToWkt(&raw, wkt2Options) != OGRERR_NONE || raw == nullptr || *raw == '\0') {
        CPLFree(raw);
        raw = nullptr;
        if (srs.exportToWkt(&raw) != OGRERR_NONE) {
            CPLFree(raw);
            return {};
        }
    }
    const std::unique_ptr<char, CplFree> owned(raw);
    return owned ? std::string(owned.get()) : std::string();
}

bool importWkt(const std::string& wkt, OGRSpatialReference& srs) {
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return !wkt.empty() && srs.importFromWkt(wkt.c_str()) == OGRERR_NONE;
}

} // namespace terratin::crs::detail
