#include "obj_writer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace terratin::io::detail {

namespace {

double Point3::*const kAxes[2] = {&Point3::x, &Point3::y};

} // namespace

void ObjOrigin::see(const Point3& p) {
    for (std::size_t axis = 0; axis < 2; ++axis)
        m_lowest[axis] = std::min(m_lowest[axis], p.*kAxes[axis]);
}

double ObjOrigin::candidate(std::size_t axis) const {
    const double origin = std::floor(m_lowest[axis]);
    return std::isfinite(origin) ? origin : 0.0;
}

void ObjOrigin::check(const Point3& p) {
    for (std::size_t axis = 0; axis < 2; ++axis) {
        const double value = p.*kAxes[axis];
        const double origin = candidate(axis);
        const double local = value - origin;
        // Exact subtraction: undoing it recovers both operands.
        if (local + origin != value || value - local != origin)
            m_exact[axis] = false;
    }
}

Point3 ObjOrigin::origin() const {
    return {m_exact[0] ? candidate(0) : 0.0, m_exact[1] ? candidate(1) : 0.0, 0.0};
}

Point3 objLocalOrigin(const TinMesh& mesh) {
    ObjOrigin origin;
    for (const Point3& p : mesh.vertices)
        origin.see(p);
    for (const Point3& p : mesh.vertices)
        origin.check(p);
    return origin.origin();
}

void putObjHead(BufferedFile& file, const MeshFileInfo& info, std::uint64_t vertexCount,
                std::uint64_t triangleCount, const Point3& origin) {
    file.text("# TIN written by terratin ");
    file.text(info.softwareVersion);
    file.text(": ");
    file.number(vertexCount);
    file.text(" vertices, ");
    file.number(triangleCount);
    file.text(" triangles\n# CRS: ");
    if (info.crs.empty()) {
        file.text("none");
    } else {
        file.text(info.crs.name);
        if (!info.crs.epsgCode.empty()) {
            file.text(" (EPSG:");
            file.text(info.crs.epsgCode);
            file.put(')');
        }
    }
    file.text("\n# local origin: add (");
    file.number(origin.x);
    file.text(", ");
    file.number(origin.y);
    file.text(", ");
    file.number(origin.z);
    file.text(") to every vertex to get CRS coordinates\n# terratin-origin ");
    file.number(origin.x);
    file.put(' ');
    file.number(origin.y);
    file.put(' ');
    file.number(origin.z);
    file.text("\no ");
    file.text(info.name);
    file.put('\n');
}

void putObjVertex(BufferedFile& file, const Point3& p, const Point3& origin) {
    file.text("v ");
    file.number(p.x - origin.x);
    file.put(' ');
    file.number(p.y - origin.y);
    file.put(' ');
    file.number(p.z - origin.z);
    file.put('\n');
}

void putObjFace(BufferedFile& file, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    file.put('f');
    for (const std::uint32_t corner : {a, b, c}) {
        file.put(' ');
        file.number(std::uint64_t{corner} + 1);
    }
    file.put('\n');
}

std::uint64_t writeObj(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                       const ProgressTicker& ticker) {
    const std::uint64_t vertexCount = mesh.vertexCount();
    const std::uint64_t triangleCount = mesh.triangleCount();
    const Point3 origin = objLocalOrigin(mesh);
    putObjHead(file, info, vertexCount, triangleCount, origin);
    for (std::uint64_t v = 0; v < vertexCount; ++v) {
        ticker.tick(v, "Writing vertices");
        putObjVertex(file, mesh.vertices[v], origin);
    }
    for (std::uint64_t t = 0; t < triangleCount; ++t) {
        ticker.tick(vertexCount + t, "Writing faces");
        putObjFace(file, mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                   mesh.triangles[3 * t + 2]);
    }
    return vertexCount + triangleCount;
}

} // namespace terratin::io::detail
