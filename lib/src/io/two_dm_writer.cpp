#include "two_dm_writer.hpp"

namespace terratin::io::detail {

std::uint64_t writeTwoDm(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                         const ProgressTicker& ticker) {
    const std::uint64_t vertexCount = mesh.vertexCount();
    const std::uint64_t triangleCount = mesh.triangleCount();
    file.text("MESH2D\nMESHNAME \"");
    file.text(info.name);
    file.text("\"\n");
    for (std::uint64_t v = 0; v < vertexCount; ++v) {
        ticker.tick(v, "Writing nodes");
        const Point3& p = mesh.vertices[v];
        file.text("ND ");
        file.number(v + 1);
        file.put(' ');
        file.number(p.x);
        file.put(' ');
        file.number(p.y);
        file.put(' ');
        file.number(p.z);
        file.put('\n');
    }
    for (std::uint64_t t = 0; t < triangleCount; ++t) {
        ticker.tick(vertexCount + t, "Writing elements");
        file.text("E3T ");
        file.number(t + 1);
        for (int k = 0; k < 3; ++k) {
            file.put(' ');
            file.number(std::uint64_t{mesh.triangles[3 * t + k]} + 1);
        }
        file.text(" 1\n");
    }
    return vertexCount + triangleCount;
}

} // namespace terratin::io::detail
