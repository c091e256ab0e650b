#include "peers.hpp"

#include "terratin/error.hpp"

#ifdef TERRATIN_HAVE_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/version_macros.h>

#include <optional>
#include <vector>
#endif

namespace terratin::bench {

#ifdef TERRATIN_HAVE_CGAL

namespace {

class CgalPeer final : public Peer {
public:
    [[nodiscard]] std::string_view name() const override { return "cgal"; }

    [[nodiscard]] std::string description() const override {
        return "CGAL " CGAL_VERSION_STR ": Delaunay_triangulation_2<Epick>, range insert";
    }

    void prepare(std::span<const Point3> points) override {
        m_points.clear();
        m_points.reserve(points.size());
        for (const Point3& point : points)
            m_points.emplace_back(point.x, point.y);
    }

    std::size_t triangulate() override {
        m_triangulation.emplace();
        m_triangulation->insert(m_points.begin(), m_points.end());
        return m_triangulation->number_of_faces();
    }

    void release() override { m_triangulation.reset(); }

private:
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Triangulation = CGAL::Delaunay_triangulation_2<Kernel>;

    std::vector<Kernel::Point_2> m_points;
    std::optional<Triangulation> m_triangulation;
};

} // namespace

bool cgalBuilt() {
    return true;
}

std::unique_ptr<Peer> makeCgalPeer() {
    return std::make_unique<CgalPeer>();
}

#else

bool cgalBuilt() {
    return false;
}

std::unique_ptr<Peer> makeCgalPeer() {
    throw Error("CgalPeer: terratin-bench was built without CGAL (install libcgal-dev, "
                "configure again)");
}

#endif

} // namespace terratin::bench
