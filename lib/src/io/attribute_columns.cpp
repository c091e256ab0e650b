#include "attribute_columns.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <string_view>

namespace terratin::io::detail {

namespace {

using A = TriangleAttributes;

constexpr std::array<AttributeColumn, 6> kBasicColumns = {{
    {"z_min", &A::zMin},
    {"z_max", &A::zMax},
    {"z_mean", &A::zMean},
    {"slope_deg", &A::slopeDeg},
    {"aspect_deg", &A::aspectDeg},
    {"area_2d", &A::area2d},
}};

constexpr std::array<AttributeColumn, 14> kAllColumns = {{
    {"z1", &A::z1},
    {"z2", &A::z2},
    {"z3", &A::z3},
    {"z_min", &A::zMin},
    {"z_max", &A::zMax},
    {"z_mean", &A::zMean},
    {"slope_deg", &A::slopeDeg},
    {"slope_pct", &A::slopePct},
    {"aspect_deg", &A::aspectDeg},
    {"area_2d", &A::area2d},
    {"area_3d", &A::area3d},
    {"nx", &A::nx},
    {"ny", &A::ny},
    {"nz", &A::nz},
}};

/// The DBF format limits field names to 10 characters; the Shapefile writer relies on it.
constexpr std::size_t kDbfMaxFieldName = 10;

template <std::size_t N> constexpr bool namesFitDbf(const std::array<AttributeColumn, N>& columns) {
    for (const auto& column : columns)
        if (std::string_view(column.name).size() > kDbfMaxFieldName)
            return false;
    return true;
}
static_assert(namesFitDbf(kBasicColumns) && namesFitDbf(kAllColumns),
              "attribute names must fit a DBF field name");

/// Triangles per TBB task: large enough that scheduling costs nothing next to the two atan2.
constexpr std::size_t kGrain = 4096;

} // namespace

std::span<const AttributeColumn> attributeColumns(AttributeSet set) {
    switch (set) {
    case AttributeSet::None:
        return {};
    case AttributeSet::Basic:
        return kBasicColumns;
    case AttributeSet::All:
        return kAllColumns;
    }
    return {};
}

void computeAttributes(const TinMesh& mesh, std::size_t begin, std::size_t end,
                       std::vector<TriangleAttributes>& out) {
    out.resize(end - begin);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t t = range.begin(); t != range.end(); ++t)
                              out[t - begin] = computeTriangleAttributes(
                                  mesh.vertices[mesh.triangles[3 * t]],
                                  mesh.vertices[mesh.triangles[3 * t + 1]],
                                  mesh.vertices[mesh.triangles[3 * t + 2]]);
                      });
}

} // namespace terratin::io::detail
