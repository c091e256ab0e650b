/// @file
/// Reprojection through OGRCoordinateTransformation (PROJ's best available operation between
/// the two CRSs, as gdalwarp and ogr2ogr use it).

#include "terratin/crs/reprojection.hpp"

#include "../number_text.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "wkt.hpp"

#include <ogr_spatialref.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <system_error>
#include <vector>

namespace terratin::crs {

using terratin::detail::numberText;

namespace {

constexpr std::string_view kStage = "CRS";
/// Points per call to PROJ: large enough to amortise the call, small enough for the x / y
/// scratch arrays (1 MiB) to stay in cache.
constexpr std::size_t kBlock = std::size_t{1} << 16;

OGRSpatialReference importOrThrow(const std::string& wkt, std::string_view what) {
    OGRSpatialReference srs;
    if (!detail::importWkt(wkt, srs))
        throw CrsError(
            std::string(kStage) + ": the " + std::string(what) +
            " CRS cannot be read: " + lastGdalErrorMessage("it is not WKT GDAL can parse"));
    return srs;
}

struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* transform) const {
        OGRCoordinateTransformation::DestroyCT(transform);
    }
};

std::string shortName(const OGRSpatialReference& srs) {
    const char* name = srs.GetName();
    return name != nullptr ? name : "unnamed CRS";
}

/// When `definition` reads as a file name (a path with '/', or a name ending in a file
/// extension such as ".prj") and no such file can be looked at: why not ("no such file or
/// directory", "too many levels of symbolic links"...). nullopt for anything else, which PROJ
/// judges: "EPSG:32633", WKT, a PROJ string, an OGC URL, an existing file.
std::optional<std::string> missingFileReason(const std::string& definition) {
    const bool notAName = definition.empty() || definition.front() == '+' ||
                          definition.find_first_of(" \t\n[]{}\"") != std::string::npos ||
                          definition.find("://") != std::string::npos;
    if (notAName)
        return std::nullopt;
    const std::filesystem::path path(definition);
    const std::string extension = path.extension().string();
    const bool fileLike = definition.find('/') != std::string::npos ||
                          (extension.size() >= 2 && extension.size() <= 5 &&
                           std::all_of(extension.begin() + 1, extension.end(),
                                       [](unsigned char c) { return std::isalpha(c) != 0; }));
    if (!fileLike)
        return std::nullopt;
    std::error_code error;
    if (std::filesystem::exists(std::filesystem::status(path, error)))
        return std::nullopt;
    return error && error != std::errc::no_such_file_or_directory
               ? error.message()
               : std::string("no such file or directory");
}

} // namespace

std::string crsFromUserInput(const std::string& definition, std::string_view option) {
    initialiseGdal();
    OGRSpatialReference srs;
    CPLErrorReset();
    if (definition.empty() || srs.SetFromUserInput(definition.c_str()) != OGRERR_NONE) {
        const std::string prefix =
            std::string(kStage) + ": " + std::string(option) + " '" + definition + "'";
        if (const std::optional<std::string> missing = missingFileReason(definition))
            throw CrsError(prefix + " names a file that cannot be read: " + *missing);
        throw CrsError(prefix + " is not a CRS PROJ knows: " +
                       lastGdalErrorMessage("not an authority code (EPSG:32633), WKT, PROJ "
                                            "string or file of one"));
    }
    // The TIN is triangulated in x, y of this CRS: a vertical-only CRS has no x, y, and a
    // geocentric one's x, y are a slice through the Earth: either would label a TIN with
    // nonsense. A compound CRS brings its horizontal part.
    if (!srs.IsProjected() && !srs.IsGeographic() && !srs.IsLocal()) {
        const char* kind = srs.IsGeocentric() ? "geocentric (x, y, z from the Earth's centre)"
                           : srs.IsVertical() ? "vertical only (heights, no x, y)"
                                              : "not horizontal";
        throw CrsError(std::string(kStage) + ": " + std::string(option) + " '" + definition +
                       "' is " + kind +
                       "; a TIN needs a horizontal CRS: projected or geographic, or compound "
                       "with one of them");
    }
    std::string wkt = detail::exportWkt(srs);
    if (wkt.empty())
        throw CrsError(std::string(kStage) + ": " + std::string(option) + " '" + definition +
                       "' cannot be written as WKT: " +
                       lastGdalErrorMessage("PROJ has no WKT1 or WKT2 form of it"));
    return wkt;
}

CrsDescription describeCrs(const std::string& wkt) {
    CrsDescription description;
    if (wkt.empty())
        return description;
    OGRSpatialReference srs = importOrThrow(wkt, "described");
    description.name = shortName(srs);
    description.geographic = srs.IsGeographic() != 0;
    description.projected = srs.IsProjected() != 0;
    if (!description.geographic) {
        const char* unit = nullptr;
        description.metresPerUnit = srs.GetLinearUnits(&unit);
        description.linearUnit = unit != nullptr ? unit : "";
    }
    // An EPSG code when the definition carries one, else when OGR can identify it exactly.
    OGRSpatialReference identified(srs);
    const char* authority = identified.GetAuthorityName(nullptr);
    if (authority == nullptr) {
        identified.AutoIdentifyEPSG();
        authority = identified.GetAuthorityName(nullptr);
    }
    const char* code = identified.GetAuthorityCode(nullptr);
    if (authority != nullptr && code != nullptr)
        description.code = std::string(authority) + ":" + code;
    return description;
}

bool sameCrs(const std::string& wktA, const std::string& wktB) {
    if (wktA.empty() || wktB.empty())
        return wktA.empty() && wktB.empty();
    if (wktA == wktB)
        return true;
    const OGRSpatialReference a = importOrThrow(wktA, "first compared");
    const OGRSpatialReference b = importOrThrow(wktB, "second compared");
    const char* const options[] = {"IGNORE_DATA_AXIS_TO_SRS_AXIS_MAPPING=YES",
                                   "CRITERION=EQUIVALENT_EXCEPT_AXIS_ORDER_GEOGCRS", nullptr};
    return a.IsSame(&b, options) != 0;
}

std::string geographicBaseCrs(const std::string& wkt) {
    const OGRSpatialReference srs = importOrThrow(wkt, "source");
    OGRSpatialReference geographic;
    if (srs.IsGeographic() == 0 && srs.IsProjected() == 0)
        throw CrsError(std::string(kStage) + ": '" + shortName(srs) +
                       "' is neither geographic nor projected");
    if (geographic.CopyGeogCSFrom(&srs) != OGRERR_NONE)
        throw CrsError(std::string(kStage) + ": '" + shortName(srs) +
                       "' has no geographic base CRS: " +
                       lastGdalErrorMessage("it is not based on a datum and ellipsoid"));
    return detail::exportWkt(geographic);
}

struct Reprojector::Impl {
    std::string sourceWkt;
    std::string targetWkt;
    std::string sourceName;
    std::string targetName;
    std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> transform;
};

Reprojector::Reprojector(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}

Reprojector::Reprojector(const std::string& sourceWkt, const std::string& targetWkt)
    : m_impl(std::make_unique<Impl>()) {
    initialiseGdal();
    const OGRSpatialReference source = importOrThrow(sourceWkt, "source");
    const OGRSpatialReference target = importOrThrow(targetWkt, "target");
    m_impl->sourceWkt = sourceWkt;
    m_impl->targetWkt = targetWkt;
    m_impl->sourceName = shortName(source);
    m_impl->targetName = shortName(target);
    CPLErrorReset();
    m_impl->transform.reset(OGRCreateCoordinateTransformation(&source, &target));
    if (!m_impl->transform)
        throw CrsError(std::string(kStage) + ": PROJ has no transformation from '" +
                       m_impl->sourceName + "' to '" + m_impl->targetName +
                       "': " + lastGdalErrorMessage("PROJ knows no operation between them"));
}

Reprojector::~Reprojector() = default;
Reprojector::Reprojector(Reprojector&&) noexcept = default;
Reprojector& Reprojector::operator=(Reprojector&&) noexcept = default;

void Reprojector::transform(std::span<Point3> points) const {
    std::vector<double> xs(std::min(points.size(), kBlock));
    std::vector<double> ys(xs.size());
    std::vector<int> ok(xs.size());
    std::size_t failures = 0;
    std::size_t firstFailure = 0;
    for (std::size_t first = 0; first < points.size(); first += kBlock) {
        const std::size_t count = std::min(kBlock, points.size() - first);
        for (std::size_t i = 0; i < count; ++i) {
            xs[i] = points[first + i].x;
            ys[i] = points[first + i].y;
        }
        // z = nullptr: a 2D transformation, elevations stay as they are.
        m_impl->transform->Transform(static_cast<int>(count), xs.data(), ys.data(), nullptr,
                                     nullptr, ok.data());
        for (std::size_t i = 0; i < count; ++i) {
            if (ok[i] == 0 || !std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
                if (failures++ == 0)
                    firstFailure = first + i;
                continue;
            }
            points[first + i].x = xs[i];
            points[first + i].y = ys[i];
        }
    }
    if (failures > 0) {
        const Point3& p = points[firstFailure];
        throw CrsError(std::string(kStage) + ": " + std::to_string(failures) + " of " +
                       std::to_string(points.size()) + " points cannot be transformed from '" +
                       m_impl->sourceName + "' to '" + m_impl->targetName + "', the first (" +
                       numberText(p.x) + ", " + numberText(p.y) +
                       ") (outside the target's area of use?)");
    }
}

Point2 Reprojector::transform(Point2 point) const {
    Point3 p{point.x, point.y, 0.0};
    transform(std::span<Point3>(&p, 1));
    return {p.x, p.y};
}

Reprojector Reprojector::inverse() const {
    return Reprojector(m_impl->targetWkt, m_impl->sourceWkt);
}

} // namespace terratin::crs
