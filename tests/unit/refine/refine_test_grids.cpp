#include "refine_test_grids.hpp"

#include "terratin/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace terratin::test {

HeightGrid makeGrid(int width, int height, const std::function<double(int, int)>& z) {
    HeightGrid grid;
    grid.width = width;
    grid.height = height;
    grid.geoTransform = {0.0, 1.0, 0.0, 0.0, 0.0, -1.0};
    grid.z.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col)
            grid.z[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(col)] = static_cast<float>(z(row, col));
    return grid;
}

RefineOptions validatedOptions(double maxError, unsigned threads) {
    RefineOptions options;
    options.maxError = maxError;
    options.threads = threads;
    options.validate = true;
    // Small test rasters would get one strip: three make every test run the strips, their
    // pairs and the shared step.
    options.strips = 3;
    return options;
}

HeightGrid roughTerrain(int width, int height, std::uint32_t seed) {
    return makeGrid(width, height, [seed](int row, int col) {
        std::uint32_t h = seed * 2654435761U ^ static_cast<std::uint32_t>(row) * 40503U ^
                          static_cast<std::uint32_t>(col) * 2246822519U;
        h ^= h >> 15;
        h *= 2246822519U;
        h ^= h >> 13;
        const double noise = static_cast<double>(h % 1000U) / 1000.0;
        const double x = col * 0.11 + seed;
        const double y = row * 0.07;
        // Whole metres and a noise in 0.25 m steps: float32-exact like an Int16 DEM.
        return std::round(120.0 + 80.0 * std::sin(x) * std::cos(y) + 40.0 * std::sin(0.3 * x + y)) +
               std::round(noise * 12.0) * 0.25;
    });
}

HeightGrid shoreWithPeninsulas(std::uint32_t seed) {
    const HeightGrid rough = roughTerrain(48, 40, seed);
    return makeGrid(48, 40, [&](int row, int col) {
        const double z =
            rough.z[static_cast<std::size_t>(row) * 48U + static_cast<std::size_t>(col)];
        if (row < 24)
            return z;
        if (row == 24 && col % 3 == (static_cast<int>(seed) + col / 12) % 3)
            return z; // a peninsula: its row above valid, its sides and below nodata
        return std::nan("");
    });
}

namespace {

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

double twice(const Point2& u, const Point2& v, const Point2& w) {
    return (v.x - u.x) * (w.y - u.y) - (v.y - u.y) * (w.x - u.x);
}

// Barycentric weights recomputed in double (the predicates' values are only signs).
double barycentric(const Point3& a, const Point3& b, const Point3& c, const Point2& p) {
    const double total = twice(planar(a), planar(b), planar(c));
    return (twice(planar(b), planar(c), p) * a.z + twice(planar(c), planar(a), p) * b.z +
            twice(planar(a), planar(b), p) * c.z) /
           total;
}

// Whether triangle t's corner cells lie on one line of the grid (sourceIndex = cell index).
bool collinearInGrid(const TinMesh& mesh, const HeightGrid& grid, std::size_t t) {
    long long col[3];
    long long row[3];
    for (std::size_t i = 0; i < 3; ++i) {
        const auto cell = static_cast<long long>(mesh.sourceIndex[mesh.triangles[3 * t + i]]);
        col[i] = cell % grid.width;
        row[i] = cell / grid.width;
    }
    return (col[1] - col[0]) * (row[2] - row[0]) == (col[2] - col[0]) * (row[1] - row[0]);
}

// A triangle with collinear corner cells is a segment (bent by a projection): the elevation
// at p is the linear one between the corners on either side of p along it.
double alongSegment(const TinMesh& mesh, std::size_t t, const Point2& p) {
    std::array<Point3, 3> corners{mesh.vertices[mesh.triangles[3 * t]],
                                  mesh.vertices[mesh.triangles[3 * t + 1]],
                                  mesh.vertices[mesh.triangles[3 * t + 2]]};
    // Order the corners along the segment: by distance from the farthest pair's first end.
    std::size_t first = 0;
    double longest = -1.0;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) {
            const double d = std::hypot(corners[i].x - corners[j].x, corners[i].y - corners[j].y);
            if (d > longest) {
                longest = d;
                first = i;
            }
        }
    const Point3 origin = corners[first];
    const auto distance = [&origin](const Point3& q) {
        return std::hypot(q.x - origin.x, q.y - origin.y);
    };
    std::sort(corners.begin(), corners.end(),
              [&](const Point3& u, const Point3& v) { return distance(u) < distance(v); });
    const double s = std::hypot(p.x - origin.x, p.y - origin.y);
    const std::size_t k = s <= distance(corners[1]) ? 0 : 1;
    const double from = distance(corners[k]);
    const double to = distance(corners[k + 1]);
    const double fraction = to > from ? std::clamp((s - from) / (to - from), 0.0, 1.0) : 0.0;
    return corners[k].z + fraction * (corners[k + 1].z - corners[k].z);
}

} // namespace

CoverageCheck checkCoverage(const TinMesh& mesh, const HeightGrid& grid, std::size_t maxHole,
                            std::span<const Point2> positions) {
    CoverageCheck check;
    const std::size_t cells = grid.cellCount();
    std::vector<std::uint8_t> covered(cells, 0);
    std::vector<Point2> centre(cells);
    for (std::size_t cell = 0; cell < cells; ++cell)
        centre[cell] = positions.empty() ? grid.cellCentre(cell) : positions[cell];
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
        const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
        const double xMin = std::min({a.x, b.x, c.x});
        const double xMax = std::max({a.x, b.x, c.x});
        const double yMin = std::min({a.y, b.y, c.y});
        const double yMax = std::max({a.y, b.y, c.y});
        for (std::size_t cell = 0; cell < cells; ++cell) {
            const Point2& p = centre[cell];
            if (p.x < xMin || p.x > xMax || p.y < yMin || p.y > yMax)
                continue;
            const double wa = predicates::orient2d(planar(b), planar(c), p);
            const double wb = predicates::orient2d(planar(c), planar(a), p);
            const double wc = predicates::orient2d(planar(a), planar(b), p);
            if (wa < 0.0 || wb < 0.0 || wc < 0.0)
                continue;
            covered[cell] = 1;
            if (std::isnan(grid.z[cell]))
                continue;
            const double z =
                collinearInGrid(mesh, grid, t) ? alongSegment(mesh, t, p) : barycentric(a, b, c, p);
            check.maxError = std::max(check.maxError, std::fabs(z - grid.z[cell]));
        }
    }
    // Holes: 8-connected nodata regions.
    std::vector<int> region(cells, -1);
    std::vector<std::size_t> sizes;
    for (std::size_t seed = 0; seed < cells; ++seed) {
        if (!std::isnan(grid.z[seed]) || region[seed] >= 0)
            continue;
        const int id = static_cast<int>(sizes.size());
        std::vector<std::size_t> stack{seed};
        region[seed] = id;
        std::size_t size = 0;
        while (!stack.empty()) {
            const std::size_t cell = stack.back();
            stack.pop_back();
            ++size;
            const int row = static_cast<int>(cell / static_cast<std::size_t>(grid.width));
            const int col = static_cast<int>(cell % static_cast<std::size_t>(grid.width));
            for (int dr = -1; dr <= 1; ++dr)
                for (int dc = -1; dc <= 1; ++dc) {
                    const int r = row + dr;
                    const int c = col + dc;
                    if (r < 0 || c < 0 || r >= grid.height || c >= grid.width)
                        continue;
                    const std::size_t n = static_cast<std::size_t>(r) * grid.width + c;
                    if (std::isnan(grid.z[n]) && region[n] < 0) {
                        region[n] = id;
                        stack.push_back(n);
                    }
                }
        }
        sizes.push_back(size);
    }
    for (std::size_t cell = 0; cell < cells; ++cell) {
        if (std::isnan(grid.z[cell])) {
            if (covered[cell] && sizes[static_cast<std::size_t>(region[cell])] > maxHole)
                ++check.coveredOpenHoleCells;
        } else if (!covered[cell]) {
            ++check.uncoveredValid;
        }
    }
    return check;
}

void expectWithinError(const TinMesh& mesh, const HeightGrid& grid, double maxError) {
    const CoverageCheck check = checkCoverage(mesh, grid, grid.cellCount());
    EXPECT_LE(check.maxError, maxError + 1e-6);
    EXPECT_EQ(check.uncoveredValid, 0U);
}

void expectEmptyCircumcircles(const TinMesh& mesh) {
    std::size_t violations = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Point2 a = planar(mesh.vertices[mesh.triangles[3 * t]]);
        const Point2 b = planar(mesh.vertices[mesh.triangles[3 * t + 1]]);
        const Point2 c = planar(mesh.vertices[mesh.triangles[3 * t + 2]]);
        for (const Point3& v : mesh.vertices)
            if (predicates::incircle(a, b, c, planar(v)) > 0.0)
                ++violations;
    }
    EXPECT_EQ(violations, 0U);
}

} // namespace terratin::test
