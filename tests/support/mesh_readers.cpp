#include "mesh_readers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace terratin::test {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
    throw std::runtime_error(path.string() + ": " + what);
}

// Parses the whole token as a double, with from_chars (what a strict reader does).
double parseDouble(const std::string& token, const std::filesystem::path& path) {
    double value = 0.0;
    const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
    if (result.ec != std::errc() || result.ptr != token.data() + token.size())
        fail(path, "not a number: '" + token + "'");
    return value;
}

std::uint64_t parseIndex(const std::string& token, const std::filesystem::path& path) {
    std::uint64_t value = 0;
    const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
    if (result.ec != std::errc() || result.ptr != token.data() + token.size())
        fail(path, "not an index: '" + token + "'");
    return value;
}

std::vector<std::string> split(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> tokens;
    for (std::string token; in >> token;)
        tokens.push_back(token);
    return tokens;
}

template <typename T> T readLittleEndian(std::istream& in, const std::filesystem::path& path) {
    unsigned char bytes[sizeof(T)];
    if (!in.read(reinterpret_cast<char*>(bytes), sizeof bytes))
        fail(path, "truncated binary data");
    if constexpr (std::endian::native == std::endian::big)
        std::reverse(bytes, bytes + sizeof bytes);
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
}

} // namespace

ReadMesh readTwoDm(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in)
        fail(path, "cannot open");
    ReadMesh mesh;
    std::string line;
    if (!std::getline(in, line) || line != "MESH2D")
        fail(path, "first line is not MESH2D");
    while (std::getline(in, line)) {
        const auto tokens = split(line);
        if (tokens.empty())
            fail(path, "empty line");
        if (tokens[0] == "MESHNAME") {
            const auto open = line.find('"');
            const auto close = line.rfind('"');
            if (open == std::string::npos || close <= open)
                fail(path, "MESHNAME without quotes");
            mesh.name = line.substr(open + 1, close - open - 1);
        } else if (tokens[0] == "ND") {
            if (tokens.size() != 5)
                fail(path, "ND needs 4 values: " + line);
            if (parseIndex(tokens[1], path) != mesh.vertices.size() + 1)
                fail(path, "node ids are not 1..N in order: " + line);
            mesh.vertices.push_back({parseDouble(tokens[2], path), parseDouble(tokens[3], path),
                                     parseDouble(tokens[4], path)});
        } else if (tokens[0] == "E3T") {
            if (tokens.size() != 6)
                fail(path, "E3T needs 5 values: " + line);
            if (parseIndex(tokens[1], path) != mesh.triangles.size() / 3 + 1)
                fail(path, "element ids are not 1..N in order: " + line);
            for (int k = 2; k < 5; ++k) {
                const std::uint64_t node = parseIndex(tokens[k], path);
                if (node == 0)
                    fail(path, "node id 0 in " + line);
                mesh.triangles.push_back(static_cast<std::uint32_t>(node - 1));
            }
            mesh.materials.push_back(static_cast<int>(parseIndex(tokens[5], path)));
        } else {
            fail(path, "unknown card: " + line);
        }
    }
    return mesh;
}

ReadMesh readPly(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path, "cannot open");
    ReadMesh mesh;
    std::string line;
    std::vector<std::string> header;
    while (std::getline(in, line) && line != "end_header")
        header.push_back(line);
    if (line != "end_header")
        fail(path, "no end_header");
    const std::vector<std::string> expected = {"ply", "format binary_little_endian 1.0"};
    if (header.size() < 2 || header[0] != expected[0] || header[1] != expected[1])
        fail(path, "not a binary little-endian PLY");
    std::uint64_t vertexCount = 0;
    std::uint64_t faceCount = 0;
    std::vector<std::string> properties;
    for (std::size_t i = 2; i < header.size(); ++i) {
        const std::string& h = header[i];
        if (h.starts_with("comment crs: "))
            mesh.crs = h.substr(13);
        else if (h.starts_with("comment "))
            continue;
        else if (h.starts_with("element vertex "))
            vertexCount = parseIndex(h.substr(15), path);
        else if (h.starts_with("element face "))
            faceCount = parseIndex(h.substr(13), path);
        else if (h.starts_with("property "))
            properties.push_back(h);
        else
            fail(path, "unexpected header line: " + h);
    }
    const std::vector<std::string> expectedProperties = {"property double x", "property double y",
                                                         "property double z",
                                                         "property list uchar int vertex_indices"};
    if (properties != expectedProperties)
        fail(path, "unexpected properties");
    for (std::uint64_t v = 0; v < vertexCount; ++v) {
        const double x = readLittleEndian<double>(in, path);
        const double y = readLittleEndian<double>(in, path);
        const double z = readLittleEndian<double>(in, path);
        mesh.vertices.push_back({x, y, z});
    }
    for (std::uint64_t f = 0; f < faceCount; ++f) {
        if (readLittleEndian<std::uint8_t>(in, path) != 3)
            fail(path, "a face is not a triangle");
        for (int k = 0; k < 3; ++k) {
            const auto index = readLittleEndian<std::int32_t>(in, path);
            if (index < 0 || static_cast<std::uint64_t>(index) >= vertexCount)
                fail(path, "face index out of range");
            mesh.triangles.push_back(static_cast<std::uint32_t>(index));
        }
    }
    if (in.peek() != std::char_traits<char>::eof())
        fail(path, "bytes after the last face");
    return mesh;
}

ReadMesh readObj(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in)
        fail(path, "cannot open");
    ReadMesh mesh;
    bool haveOrigin = false;
    std::vector<Point3> local;
    std::string line;
    while (std::getline(in, line)) {
        const auto tokens = split(line);
        if (tokens.empty())
            continue;
        if (tokens[0] == "#") {
            if (tokens.size() == 5 && tokens[1] == "terratin-origin") {
                mesh.origin = {parseDouble(tokens[2], path), parseDouble(tokens[3], path),
                               parseDouble(tokens[4], path)};
                haveOrigin = true;
            }
        } else if (tokens[0] == "o") {
            mesh.name = line.substr(2);
        } else if (tokens[0] == "v") {
            if (tokens.size() != 4)
                fail(path, "v needs 3 values: " + line);
            local.push_back({parseDouble(tokens[1], path), parseDouble(tokens[2], path),
                             parseDouble(tokens[3], path)});
        } else if (tokens[0] == "f") {
            if (tokens.size() != 4)
                fail(path, "f is not a triangle: " + line);
            for (int k = 1; k < 4; ++k) {
                const std::uint64_t index = parseIndex(tokens[k], path);
                if (index == 0)
                    fail(path, "index 0 in " + line);
                mesh.triangles.push_back(static_cast<std::uint32_t>(index - 1));
            }
        } else {
            fail(path, "unknown statement: " + line);
        }
    }
    if (!haveOrigin)
        fail(path, "no terratin-origin line");
    for (const Point3& p : local)
        mesh.vertices.push_back({p.x + mesh.origin.x, p.y + mesh.origin.y, p.z + mesh.origin.z});
    return mesh;
}

void expectSameMesh(const ReadMesh& read, const TinMesh& mesh) {
    ASSERT_EQ(read.vertices.size(), mesh.vertices.size());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        // Exact: the writers print shortest round-trip decimals or raw doubles.
        EXPECT_EQ(read.vertices[v].x, mesh.vertices[v].x) << "vertex " << v;
        EXPECT_EQ(read.vertices[v].y, mesh.vertices[v].y) << "vertex " << v;
        EXPECT_EQ(read.vertices[v].z, mesh.vertices[v].z) << "vertex " << v;
    }
    EXPECT_TRUE(std::equal(read.triangles.begin(), read.triangles.end(), mesh.triangles.begin(),
                           mesh.triangles.end()));
}

TinMesh gridTin(int n, double baseZ) {
    TinMesh mesh;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double dx = 10.0 * i;
            const double dy = 10.0 * j;
            mesh.vertices.push_back(
                {500000.0 + dx, 5000000.0 + dy, baseZ + 0.1 * dx - 0.2 * dy + 0.001 * dx * dy});
            mesh.sourceIndex.push_back(static_cast<std::uint32_t>(mesh.sourceIndex.size()));
        }
    const int cells = n - 1;
    auto vertex = [n](int i, int j) { return static_cast<std::uint32_t>(j * n + i); };
    auto triA = [cells](int i, int j) { return 2 * (j * cells + i); };
    auto triB = [cells](int i, int j) { return 2 * (j * cells + i) + 1; };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            mesh.triangles.insert(mesh.triangles.end(),
                                  {vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)});
            mesh.neighbours.insert(mesh.neighbours.end(),
                                   {j > 0 ? triB(i, j - 1) : kNoNeighbour,
                                    i + 1 < cells ? triB(i + 1, j) : kNoNeighbour, triB(i, j)});
            mesh.triangles.insert(mesh.triangles.end(),
                                  {vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)});
            mesh.neighbours.insert(mesh.neighbours.end(),
                                   {triA(i, j), j + 1 < cells ? triA(i, j + 1) : kNoNeighbour,
                                    i > 0 ? triA(i - 1, j) : kNoNeighbour});
        }
    return mesh;
}

} // namespace terratin::test
