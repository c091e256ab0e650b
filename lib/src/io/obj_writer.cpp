#include "obj_writer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace terratin::io::detail {

namespace {

/// floor(min) of one coordinate when subtracting it and adding it back is exact for every
/// vertex, else 0.
double exactOrigin(const TinMesh& mesh, double Point3::*axis) {
    double lowest = mesh.vertices.front().*axis;
    for (const Point3& p : mesh.vertices)
        lowest = std::min(lowest, p.*axis);
    const double origin = std::floor(lowest);
    if (!std::isfinite(origin))
        return 0.0;
    for (const Point3& p : mesh.vertices) {
        const double value = p.*axis;
        const double local = value - origin;
        // Exact subtraction: undoing it recovers both operands.
        if (local + origin != value || value - local != origin)
            return 0.0;
    }
    return origin;
}

} // namespace

Point3 objLocalOrigin(const TinMesh& mesh) {
    if (mesh.vertices.empty())
        return {};
    return {exactOrigin(mesh, &Point3::x), exactOrigin(mesh, &Point3::y), 0.0};
}

std::uint64_t writeObj(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                       const ProgressTicker& ticker) {
    const std::uint64_t vertexCount = mesh.vertexCount();
    const std::uint64_t triangleCount = mesh.triangleCount();
    const Point3 origin = objLocalOrigin(mesh);

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

    for (std::uint64_t v = 0; v < vertexCount; ++v) {
        ticker.tick(v, "Writing vertices");
        const Point3& p = mesh.vertices[v];
        file.text("v ");
        file.number(p.x - origin.x);
        file.put(' ');
        file.number(p.y - origin.y);
        file.put(' ');
        file.number(p.z - origin.z);
        file.put('\n');
    }
    for (std::uint64_t t = 0; t < triangleCount; ++t) {
        ticker.tick(vertexCount + t, "Writing faces");
        file.put('f');
        for (int k = 0; k < 3; ++k) {
            file.put(' ');
            file.number(std::uint64_t{mesh.triangles[3 * t + k]} + 1);
        }
        file.put('\n');
    }
    return vertexCount + triangleCount;
}

} // namespace terratin::io::detail
