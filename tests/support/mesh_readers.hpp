#pragma once
// Minimal, strict readers for the mesh formats terratin writes (2DM, binary PLY, OBJ), written
// independently of the writers so that the tests check the files, not the writers' own idea
// of them. Every reader throws std::runtime_error on anything it does not expect.

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace terratin::test {

/// A mesh as read back from a file: vertices and 0-based triangle corners, plus what the
/// header said.
struct ReadMesh {
    std::vector<Point3> vertices;
    std::vector<std::uint32_t> triangles;
    /// 2DM: MESHNAME; OBJ: the "o" name.
    std::string name;
    /// PLY: the text after "comment crs: " (MDAL's key: value form); empty when absent.
    std::string crs;
    /// OBJ: the "# terratin-origin" line's values (already added to the vertices).
    Point3 origin;
    /// 2DM: the material id of every element.
    std::vector<int> materials;
};

/// 2DM: MESH2D, MESHNAME, ND id x y z (ids 1..N in order), E3T id n1 n2 n3 material.
ReadMesh readTwoDm(const std::filesystem::path& path);

/// PLY: binary_little_endian 1.0, vertex x y z as double, face list uchar int vertex_indices.
ReadMesh readPly(const std::filesystem::path& path);

/// OBJ: v x y z, f a b c (1-based, no slashes), the origin line, the object name.
ReadMesh readObj(const std::filesystem::path& path);

/// The TinMesh's vertices and triangles (the part every mesh format keeps).
void expectSameMesh(const ReadMesh& read, const TinMesh& mesh);

/// A small n x n grid TIN at UTM-like coordinates (500000, 5000000) + 10 m steps on the
/// saddle z = baseZ + 0.1 dx - 0.2 dy + 0.001 dx dy, counter-clockwise triangles (cell (i, j)
/// holds A = (00, 10, 11) and B = (00, 11, 01)), neighbours set (kNoNeighbour on the hull),
/// sourceIndex = identity.
TinMesh gridTin(int n, double baseZ = 1234.5);

} // namespace terratin::test
