#include "obj_writer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

namespace terratin::io::detail {

namespace {

double Point3::*const kAxes[2] = {&Point3::x, &Point3::y};

/// The exact local origin described in the header, of vertices seen one at a time in two
/// passes: every vertex to see(), then every vertex to check(), then origin().
class ObjOrigin {
public:
    void see(const Point3& p) {
        for (std::size_t axis = 0; axis < 2; ++axis)
            m_lowest[axis] = std::min(m_lowest[axis], p.*kAxes[axis]);
    }

    void check(const Point3& p) {
        for (std::size_t axis = 0; axis < 2; ++axis) {
            const double value = p.*kAxes[axis];
            const double origin = candidate(axis);
            const double local = value - origin;
            // Exact subtraction: undoing it recovers both operands.
            if (local + origin != value || value - local != origin)
                m_exact[axis] = false;
        }
    }

    [[nodiscard]] Point3 origin() const {
        return {m_exact[0] ? candidate(0) : 0.0, m_exact[1] ? candidate(1) : 0.0, 0.0};
    }

private:
    /// Per axis (x, y): the lowest value seen, and whether the candidate floor(lowest) has
    /// held for every vertex checked.
    std::array<double, 2> m_lowest{std::numeric_limits<double>::infinity(),
                                   std::numeric_limits<double>::infinity()};
    std::array<bool, 2> m_exact{true, true};

    [[nodiscard]] double candidate(std::size_t axis) const {
        const double origin = std::floor(m_lowest[axis]);
        return std::isfinite(origin) ? origin : 0.0;
    }
};

void putCrsLine(BufferedFile& file, const CrsSummary& crs) {
    file.text("# CRS: ");
    if (crs.empty()) {
        file.text("none");
    } else {
        file.text(crs.name);
        if (!crs.epsgCode.empty()) {
            file.text(" (EPSG:");
            file.text(crs.epsgCode);
            file.put(')');
        }
    }
    file.put('\n');
}

class ObjFormat : public MeshFormatBase {
public:
    static constexpr std::string_view kVertexMessage = "Writing vertices";
    static constexpr std::string_view kFaceMessage = "Writing faces";
    static constexpr bool kVerticesAfterFigures = true;

    void addVertex(const Point3& p) { m_origin.see(p); }
    void recheckVertex(const Point3& p) { m_origin.check(p); }

    void head(BufferedFile& file, const MeshFileInfo& info, std::uint64_t vertexCount,
              std::uint64_t triangleCount) {
        m_local = m_origin.origin();
        file.text("# TIN written by terratin ");
        file.text(info.softwareVersion);
        file.text(": ");
        file.number(vertexCount);
        file.text(" vertices, ");
        file.number(triangleCount);
        file.text(" triangles\n");
        putCrsLine(file, info.crs);
        file.text("# local origin: add (");
        file.number(m_local.x);
        file.text(", ");
        file.number(m_local.y);
        file.text(", ");
        file.number(m_local.z);
        file.text(") to every vertex to get CRS coordinates\n# terratin-origin ");
        file.number(m_local.x);
        file.put(' ');
        file.number(m_local.y);
        file.put(' ');
        file.number(m_local.z);
        file.text("\no ");
        file.text(info.name);
        file.put('\n');
    }

    void vertex(BufferedFile& file, std::uint64_t, const Point3& p) {
        file.text("v ");
        file.number(p.x - m_local.x);
        file.put(' ');
        file.number(p.y - m_local.y);
        file.put(' ');
        file.number(p.z - m_local.z);
        file.put('\n');
    }

    /// Vertex numbers count from 1.
    void face(BufferedFile& file, std::uint64_t, std::uint32_t a, std::uint32_t b,
              std::uint32_t c) {
        file.put('f');
        for (const std::uint32_t corner : {a, b, c}) {
            file.put(' ');
            file.number(std::uint64_t{corner} + 1);
        }
        file.put('\n');
    }

private:
    ObjOrigin m_origin;
    /// The origin, once the head is written.
    Point3 m_local{};
};

} // namespace

constinit const MeshWriter kObjWriter = meshWriterFor<ObjFormat>();

} // namespace terratin::io::detail
