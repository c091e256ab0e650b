#include "peers.hpp"

#include "terratin/error.hpp"

#ifdef TERRATIN_HAVE_GDAL
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_alg.h>

#include <limits>
#include <string>
#include <vector>
#endif

namespace terratin::bench {

#ifdef TERRATIN_HAVE_GDAL

namespace {

class GdalPeer final : public Peer {
public:
    GdalPeer() = default;
    GdalPeer(const GdalPeer&) = delete;
    GdalPeer& operator=(const GdalPeer&) = delete;
    ~GdalPeer() override { release(); }

    [[nodiscard]] std::string_view name() const override { return "gdal"; }

    [[nodiscard]] std::string description() const override {
        return std::string("GDAL ") + GDALVersionInfo("RELEASE_NAME") +
               ": GDALTriangulationCreateDelaunay (qhull)";
    }

    void prepare(std::span<const Point3> points) override {
        if (points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
            throw InvalidInputError("GdalPeer: more points than GDAL's int count can hold");
        m_x.clear();
        m_y.clear();
        m_x.reserve(points.size());
        m_y.reserve(points.size());
        for (const Point3& point : points) {
            m_x.push_back(point.x);
            m_y.push_back(point.y);
        }
    }

    std::size_t triangulate() override {
        release();
        CPLErrorReset();
        m_triangulation =
            GDALTriangulationCreateDelaunay(static_cast<int>(m_x.size()), m_x.data(), m_y.data());
        if (m_triangulation == nullptr)
            throw Error(std::string("GdalPeer: GDALTriangulationCreateDelaunay failed: ") +
                        CPLGetLastErrorMsg());
        return static_cast<std::size_t>(m_triangulation->nFacets);
    }

    void release() override {
        if (m_triangulation != nullptr)
            GDALTriangulationFree(m_triangulation);
        m_triangulation = nullptr;
    }

private:
    std::vector<double> m_x;
    std::vector<double> m_y;
    GDALTriangulation* m_triangulation = nullptr;
};

} // namespace

bool gdalBuilt() {
    return true;
}

bool gdalHasTriangulation() {
    return GDALHasTriangulation() != 0;
}

std::unique_ptr<Peer> makeGdalPeer() {
    if (!gdalHasTriangulation())
        throw Error("GdalPeer: this GDAL was built without qhull, so it cannot triangulate");
    return std::make_unique<GdalPeer>();
}

#else

bool gdalBuilt() {
    return false;
}

bool gdalHasTriangulation() {
    return false;
}

std::unique_ptr<Peer> makeGdalPeer() {
    throw Error("GdalPeer: terratin-bench was built without GDAL (TERRATIN_BUILD_IO=OFF)");
}

#endif

} // namespace terratin::bench
