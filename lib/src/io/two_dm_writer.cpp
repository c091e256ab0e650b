#include "two_dm_writer.hpp"

namespace terratin::io::detail {

void putTwoDmHead(BufferedFile& file, const MeshFileInfo& info) {
    file.text("MESH2D\nMESHNAME \"");
    file.text(info.name);
    file.text("\"\n");
}

void putTwoDmNode(BufferedFile& file, std::uint64_t number, const Point3& p) {
    file.text("ND ");
    file.number(number + 1);
    file.put(' ');
    file.number(p.x);
    file.put(' ');
    file.number(p.y);
    file.put(' ');
    file.number(p.z);
    file.put('\n');
}

void putTwoDmElement(BufferedFile& file, std::uint64_t number, std::uint32_t a, std::uint32_t b,
                     std::uint32_t c) {
    file.text("E3T ");
    file.number(number + 1);
    for (const std::uint32_t corner : {a, b, c}) {
        file.put(' ');
        file.number(std::uint64_t{corner} + 1);
    }
    file.text(" 1\n");
}

std::uint64_t writeTwoDm(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                         const ProgressTicker& ticker) {
    const std::uint64_t vertexCount = mesh.vertexCount();
    const std::uint64_t triangleCount = mesh.triangleCount();
    putTwoDmHead(file, info);
    for (std::uint64_t v = 0; v < vertexCount; ++v) {
        ticker.tick(v, "Writing nodes");
        putTwoDmNode(file, v, mesh.vertices[v]);
    }
    for (std::uint64_t t = 0; t < triangleCount; ++t) {
        ticker.tick(vertexCount + t, "Writing elements");
        putTwoDmElement(file, t, mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                        mesh.triangles[3 * t + 2]);
    }
    return vertexCount + triangleCount;
}

} // namespace terratin::io::detail
