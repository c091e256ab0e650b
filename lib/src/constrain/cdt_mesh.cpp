#include "cdt_mesh.hpp"

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace terratin::detail {

namespace {

// The largest triangle index a TinMesh neighbour (int32) can hold.
constexpr std::size_t kMaxTriangles =
    static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());

// The largest vertex index, below the sourceIndex markers of constrained_tin.hpp.
constexpr std::size_t kMaxVertices = std::numeric_limits<std::uint32_t>::max() - 4;

} // namespace

CdtMesh::CdtMesh(TinMesh mesh) : m_own(std::make_unique<Arrays>()), m_arrays(m_own.get()) {
    m_arrays->mesh = std::move(mesh);
    // As much room as the mesh has (reserveRoom): growing copies the whole array.
    m_arrays->constrained.reserve(m_arrays->mesh.triangles.capacity());
    m_arrays->constrained.assign(m_arrays->mesh.triangles.size(), 0);
    startVertexMap();
}

void CdtMesh::startVertexMap() {
    m_arrays->vertexTriangle.reserve(m_arrays->mesh.vertices.capacity());
    m_arrays->vertexTriangle.assign(m_arrays->mesh.vertices.size(), kUnknownTriangle);
}

CdtMesh::CdtMesh(CdtMesh& shared, Zone zone, SlotRange vertices, SlotRange triangles)
    : m_arrays(shared.m_arrays), m_zoned(true), m_zone(zone), m_vertexSlots(vertices),
      m_triangleSlots(triangles) {}

std::pair<SlotRange, SlotRange> CdtMesh::appendSlots(std::size_t vertices, std::size_t triangles) {
    TinMesh& mesh = m_arrays->mesh;
    const std::size_t firstVertex = mesh.vertices.size();
    const std::size_t firstTriangle = mesh.triangleCount();
    if (firstVertex + vertices > kMaxVertices || firstTriangle + triangles > kMaxTriangles)
        throw InvalidInputError("insertConstraints: too many vertices or triangles");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    mesh.vertices.resize(firstVertex + vertices, Point3{nan, nan, nan});
    mesh.sourceIndex.resize(firstVertex + vertices, kConstraintPointSource);
    m_arrays->vertexTriangle.resize(firstVertex + vertices, kUnknownTriangle);
    mesh.triangles.resize(3 * (firstTriangle + triangles), 0);
    mesh.neighbours.resize(3 * (firstTriangle + triangles), kNoNeighbour);
    m_arrays->constrained.resize(3 * (firstTriangle + triangles), 0);
    return {{firstVertex, firstVertex + vertices}, {firstTriangle, firstTriangle + triangles}};
}

std::vector<Zone> bandsHoldingAsMany(std::vector<double> coordinates, unsigned zones, bool alongY) {
    std::sort(coordinates.begin(), coordinates.end());
    std::vector<Zone> bands;
    double low = -std::numeric_limits<double>::infinity();
    for (unsigned z = 0; z < zones; ++z) {
        const double high = z + 1 == zones || coordinates.empty()
                                ? std::numeric_limits<double>::infinity()
                                : coordinates[(z + 1) * coordinates.size() / zones];
        bands.push_back({alongY, low, high});
        low = high;
    }
    return bands;
}

void renumberMoved(std::span<std::vector<std::uint32_t>> lists, std::size_t kept,
                   std::span<const std::uint32_t> movedTo) {
    for (std::vector<std::uint32_t>& list : lists)
        for (std::uint32_t& v : list)
            if (v >= kept)
                v = movedTo[v - kept];
}

namespace {

/// The slots of `unused` ([next, end) of each range), ascending.
std::vector<std::size_t> holesOf(std::span<const SlotRange> unused) {
    std::vector<std::size_t> holes;
    for (const SlotRange& range : unused)
        for (std::size_t i = range.next; i < range.end; ++i)
            holes.push_back(i);
    std::sort(holes.begin(), holes.end());
    return holes;
}

/// Calls move(from, to) for each hole below `count` minus the holes, taking the last slots
/// in use from the top: afterwards the slots in use are [0, count - holes).
template <class Move>
std::size_t fillHoles(const std::vector<std::size_t>& holes, std::size_t count, Move&& move) {
    const std::size_t kept = count - holes.size();
    std::size_t top = count;
    auto hole = holes.end();
    for (const std::size_t target : holes) {
        if (target >= kept)
            break;
        // The highest slot in use: skip the holes at the top.
        for (--top; hole != holes.begin() && *(hole - 1) == top; --top)
            --hole;
        move(top, target);
    }
    return kept;
}

} // namespace

std::vector<std::uint32_t> CdtMesh::compact(std::span<const SlotRange> unusedVertices,
                                            std::span<const SlotRange> unusedTriangles) {
    TinMesh& mesh = m_arrays->mesh;
    MeshArray<std::uint32_t>& vertexTriangle = m_arrays->vertexTriangle;
    const std::size_t triangles = fillHoles(
        holesOf(unusedTriangles), mesh.triangleCount(), [&](std::size_t from, std::size_t to) {
            if (m_written != nullptr) // the slots were both written: the vector holds them
                (*m_written)[to] = (*m_written)[from];
            for (std::size_t i = 0; i < 3; ++i) {
                mesh.triangles[3 * to + i] = mesh.triangles[3 * from + i];
                mesh.neighbours[3 * to + i] = mesh.neighbours[3 * from + i];
                m_arrays->constrained[3 * to + i] = m_arrays->constrained[3 * from + i];
                vertexTriangle[mesh.triangles[3 * to + i]] = static_cast<std::uint32_t>(to);
                const std::int32_t n = mesh.neighbours[3 * to + i];
                if (n < 0)
                    continue;
                std::int32_t* links = &mesh.neighbours[3 * static_cast<std::size_t>(n)];
                *std::find(links, links + 3, static_cast<std::int32_t>(from)) =
                    static_cast<std::int32_t>(to);
            }
        });
    mesh.triangles.resize(3 * triangles);
    mesh.neighbours.resize(3 * triangles);
    m_arrays->constrained.resize(3 * triangles);

    const std::size_t vertexCount = mesh.vertices.size();
    const std::vector<std::size_t> vertexHoles = holesOf(unusedVertices);
    std::vector<std::uint32_t> movedTo(vertexHoles.size());
    std::vector<std::size_t> star;
    const std::size_t vertices =
        fillHoles(vertexHoles, vertexCount, [&](std::size_t from, std::size_t to) {
            star.clear();
            forEachHalfEdgeAround(static_cast<std::uint32_t>(from), [&](std::size_t h) {
                star.push_back(h);
                return false;
            });
            for (const std::size_t h : star) {
                const std::size_t corner = this->from(h) == from ? h : nextHalfEdge(h);
                mesh.triangles[corner] = static_cast<std::uint32_t>(to);
            }
            mesh.vertices[to] = mesh.vertices[from];
            mesh.sourceIndex[to] = mesh.sourceIndex[from];
            vertexTriangle[to] = vertexTriangle[from];
            movedTo[from - (vertexCount - vertexHoles.size())] = static_cast<std::uint32_t>(to);
        });
    mesh.vertices.resize(vertices);
    mesh.sourceIndex.resize(vertices);
    vertexTriangle.resize(vertices);
    return movedTo;
}

// Sequential, in triangle order: the same map whatever happened before.
void CdtMesh::completeVertexMap() const {
    const std::size_t triangleCount = m_arrays->mesh.triangleCount();
    for (std::size_t t = 0; t < triangleCount; ++t)
        for (std::size_t i = 0; i < 3; ++i) {
            std::uint32_t& triangle = m_arrays->vertexTriangle[m_arrays->mesh.triangles[3 * t + i]];
            if (triangle == kUnknownTriangle)
                triangle = static_cast<std::uint32_t>(t);
        }
}

void CdtMesh::rememberTriangleOf(std::size_t h) {
    rememberTriangle(from(h), h / 3);
    rememberTriangle(to(h), h / 3);
}

void CdtMesh::rememberTriangle(std::uint32_t v, std::size_t t) {
    if (inZone(v)) // another zone's vertex is its view's to note
        m_arrays->vertexTriangle[v] = static_cast<std::uint32_t>(t);
}

CdtMesh::CdtMesh(TinMesh mesh, MeshArray<std::uint8_t> constrained)
    : m_own(std::make_unique<Arrays>()), m_arrays(m_own.get()) {
    if (constrained.size() != mesh.triangles.size())
        throw std::logic_error("CdtMesh: one constrained flag per half-edge expected");
    m_arrays->mesh = std::move(mesh);
    m_arrays->constrained = std::move(constrained);
    startVertexMap();
}

void CdtMesh::throwUnlinked() {
    throw std::logic_error("CdtMesh: neighbour links are not mutual");
}

void CdtMesh::relink(std::int32_t outer, std::uint32_t edgeStart, std::size_t triangle) {
    if (outer >= 0)
        m_arrays->mesh
            .neighbours[3 * static_cast<std::size_t>(outer) + cornerOf(outer, edgeStart)] =
            static_cast<std::int32_t>(triangle);
}

void CdtMesh::setConstrained(std::size_t h, bool constrained) {
    setFlag(h, constrained);
    const std::size_t other = twin(h);
    if (other != kNoHalfEdge)
        setFlag(other, constrained);
}

std::size_t CdtMesh::halfEdgeLeaving(std::uint32_t v) const {
    if (m_zoned && (!inZone(v) || m_arrays->vertexTriangle[v] == kUnknownTriangle))
        throw ZoneRefusal{}; // a view may not read another zone's star, nor fill the map
    if (m_arrays->vertexTriangle[v] == kUnknownTriangle)
        completeVertexMap();
    const std::size_t base = 3 * static_cast<std::size_t>(m_arrays->vertexTriangle[v]);
    for (std::size_t i = 0; i < 3; ++i)
        if (m_arrays->mesh.triangles[base + i] == v)
            return base + i;
    throw std::logic_error("CdtMesh: vertex-to-triangle map is stale");
}

std::size_t CdtMesh::findEdge(std::uint32_t a, std::uint32_t b) const {
    std::size_t found = kNoHalfEdge;
    forEachHalfEdgeAround(a, [&](std::size_t h) {
        if (to(h) != b && from(h) != b)
            return false;
        found = h;
        return true;
    });
    return found;
}

std::size_t CdtMesh::find(const Edge& edge) const {
    if (edge.hint != kNoHalfEdge) {
        const std::uint32_t a = from(edge.hint);
        const std::uint32_t b = to(edge.hint);
        if ((a == edge.a && b == edge.b) || (a == edge.b && b == edge.a))
            return edge.hint;
    }
    return findEdge(edge.a, edge.b);
}

// A walk's next triangle is one of these: their loads (a cache miss each, the triangles of a
// large mesh being numbered in no spatial order) then overlap this step's tests instead of
// following them one by one. A prefetch never faults, but the addresses come from reads, which
// a view makes only across edges it may cross.
void CdtMesh::prefetchAround(std::size_t t) const {
    const TinMesh& mesh = m_arrays->mesh;
    for (std::size_t h = 3 * t; h < 3 * t + 3; ++h) {
        if (m_zoned && !inZone(from(h)) && !inZone(to(h)))
            continue;
        const std::int32_t across = mesh.neighbours[h];
        if (across < 0)
            continue;
        const std::size_t first = 3 * static_cast<std::size_t>(across);
        __builtin_prefetch(&mesh.neighbours[first]);
        for (std::size_t i = first; i < first + 3; ++i)
            __builtin_prefetch(&mesh.vertices[mesh.triangles[i]]);
    }
}

MeshLocation CdtMesh::locate(const Point2& p, std::size_t startTriangle) {
    std::size_t t = startTriangle;
    std::size_t cameThrough = kNoHalfEdge;
    for (;;) {
        prefetchAround(t);
        // xorshift64: the random first edge is what makes the walk terminate on any mesh.
        m_walkRandom ^= m_walkRandom << 13U;
        m_walkRandom ^= m_walkRandom >> 7U;
        m_walkRandom ^= m_walkRandom << 17U;
        const std::size_t first = m_walkRandom % 3;
        bool moved = false;
        for (std::size_t k = 0; k < 3 && !moved; ++k) {
            const std::size_t h = 3 * t + (first + k) % 3;
            if (h == cameThrough || predicates::orient2d(xy(from(h)), xy(to(h)), p) >= 0.0)
                continue;
            if (m_zoned) // before the link is read: another zone may write it
                requireCrossable(h);
            if (m_arrays->mesh.neighbours[h] < 0)
                return {MeshLocation::Kind::OutsideHull, h, 0};
            cameThrough = twin(h);
            t = cameThrough / 3;
            moved = true;
        }
        if (!moved)
            break;
    }
    MeshLocation where{MeshLocation::Kind::InTriangle, 3 * t, 0};
    for (std::size_t i = 0; i < 3; ++i) {
        const std::size_t h = 3 * t + i;
        if (xy(from(h)) == p) {
            rememberTriangle(from(h), t);
            return {MeshLocation::Kind::OnVertex, h, from(h)};
        }
        if (predicates::orient2d(xy(from(h)), xy(to(h)), p) == 0.0)
            where = {MeshLocation::Kind::OnEdge, h, 0};
    }
    return where;
}

void CdtMesh::requireInsertable(const MeshLocation& where) const {
    if (!m_zoned)
        return;
    requireOwned(where.halfEdge / 3);
    if (where.kind == MeshLocation::Kind::OnEdge)
        if (const std::size_t g = twin(where.halfEdge); g != kNoHalfEdge)
            requireOwned(g / 3);
    if (m_vertexSlots.next == m_vertexSlots.end || m_triangleSlots.end - m_triangleSlots.next < 2)
        throw ZoneRefusal{};
}

std::size_t CdtMesh::addTriangle() {
    if (m_zoned) // requireInsertable made sure of the room
        return m_triangleSlots.next++;
    const std::size_t t = m_arrays->mesh.triangleCount();
    if (t >= kMaxTriangles)
        throw InvalidInputError("insertConstraints: too many triangles");
    for (int i = 0; i < 3; ++i) {
        m_arrays->mesh.triangles.push_back(0);
        m_arrays->mesh.neighbours.push_back(kNoNeighbour);
        m_arrays->constrained.push_back(0);
    }
    return t;
}

std::uint32_t CdtMesh::addVertex(const Point3& p, std::uint32_t source) {
    if (m_zoned) {
        const std::size_t v = m_vertexSlots.next++;
        m_arrays->mesh.vertices[v] = p;
        m_arrays->mesh.sourceIndex[v] = source;
        return static_cast<std::uint32_t>(v);
    }
    const std::size_t v = m_arrays->mesh.vertices.size();
    if (v >= kMaxVertices)
        throw InvalidInputError("insertConstraints: too many vertices");
    m_arrays->mesh.vertices.push_back(p);
    m_arrays->mesh.sourceIndex.push_back(source);
    m_arrays->vertexTriangle.push_back(kUnknownTriangle);
    return static_cast<std::uint32_t>(v);
}

void CdtMesh::writeCorners(std::size_t t, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (m_written != nullptr) {
        if (t >= m_written->size())
            m_written->resize(t + 1, 0);
        (*m_written)[t] = 1;
    }
    m_arrays->mesh.triangles[3 * t] = a;
    m_arrays->mesh.triangles[3 * t + 1] = b;
    m_arrays->mesh.triangles[3 * t + 2] = c;
    m_arrays->vertexTriangle[a] = static_cast<std::uint32_t>(t);
    m_arrays->vertexTriangle[b] = static_cast<std::uint32_t>(t);
    m_arrays->vertexTriangle[c] = static_cast<std::uint32_t>(t);
}

void CdtMesh::writeTriangle(std::size_t t, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    writeCorners(t, a, b, c);
    for (std::size_t i = 0; i < 3; ++i) {
        m_arrays->mesh.neighbours[3 * t + i] = kNoNeighbour;
        m_arrays->constrained[3 * t + i] = 0;
    }
}

void CdtMesh::link(std::size_t h, std::size_t other) {
    if (other == kNoHalfEdge) {
        m_arrays->mesh.neighbours[h] = kNoNeighbour;
        return;
    }
    m_arrays->mesh.neighbours[h] = static_cast<std::int32_t>(other / 3);
    m_arrays->mesh.neighbours[other] = static_cast<std::int32_t>(h / 3);
}

} // namespace terratin::detail
