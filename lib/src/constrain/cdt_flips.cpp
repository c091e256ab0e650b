// CdtMesh's changes of a vertex's insertion (cdt_mesh.hpp): the split of the triangle or the
// edge that holds it, and the flips that restore the constrained Delaunay property, beside
// cdt_mesh.cpp's storage and search and cdt_cavity.cpp's cavity of a segment.

#include "cdt_mesh.hpp"

#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <stdexcept>

namespace terratin::detail {

// Triangle (a, b, c) of h becomes (a, b, v), (b, c, v), (c, a, v). Its outer edges keep their
// neighbours and flags; the neighbours across b-c and c-a, which now face the new triangles,
// are pointed at them.
void CdtMesh::splitTriangle(std::size_t h, std::uint32_t v, std::vector<std::size_t>& toCheck) {
    const std::size_t t = h / 3;
    const std::uint32_t a = m_arrays->mesh.triangles[3 * t];
    const std::uint32_t b = m_arrays->mesh.triangles[3 * t + 1];
    const std::uint32_t c = m_arrays->mesh.triangles[3 * t + 2];
    const std::int32_t outer[3] = {m_arrays->mesh.neighbours[3 * t],
                                   m_arrays->mesh.neighbours[3 * t + 1],
                                   m_arrays->mesh.neighbours[3 * t + 2]};
    const std::uint8_t flags[3] = {m_arrays->constrained[3 * t], m_arrays->constrained[3 * t + 1],
                                   m_arrays->constrained[3 * t + 2]};
    const std::size_t t1 = addTriangle();
    const std::size_t t2 = addTriangle();
    const std::size_t fans[3] = {t, t1, t2};
    const std::uint32_t starts[3] = {a, b, c};
    for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t fan = fans[k];
        // (start, next start, v): the outer edge, then v's edges shared with the next and the
        // previous fan triangle.
        writeCorners(fan, starts[k], starts[(k + 1) % 3], v);
        m_arrays->mesh.neighbours[3 * fan] = outer[k];
        m_arrays->mesh.neighbours[3 * fan + 1] = static_cast<std::int32_t>(fans[(k + 1) % 3]);
        m_arrays->mesh.neighbours[3 * fan + 2] = static_cast<std::int32_t>(fans[(k + 2) % 3]);
        m_arrays->constrained[3 * fan] = flags[k];
        m_arrays->constrained[3 * fan + 1] = 0;
        m_arrays->constrained[3 * fan + 2] = 0;
        toCheck.push_back(3 * fan);
    }
    relink(outer[1], c, t1);
    relink(outer[2], a, t2);
}

// Edge a -> b of h, in triangle (a, b, c), with d across: (a, v, c), (v, b, c) and, across,
// (b, v, d), (v, a, d). Both halves keep the edge's flag.
void CdtMesh::splitEdge(std::size_t h, std::uint32_t v, std::vector<std::size_t>& toCheck) {
    const std::size_t g = twin(h);
    const std::size_t t = h / 3;
    const std::uint32_t a = from(h);
    const std::uint32_t b = to(h);
    const std::uint32_t c = from(previousHalfEdge(h));
    const bool edgeFlag = isConstrained(h);
    const std::size_t outerBc = twin(nextHalfEdge(h));
    const std::size_t outerCa = twin(previousHalfEdge(h));
    const bool flagBc = isConstrained(nextHalfEdge(h));
    const bool flagCa = isConstrained(previousHalfEdge(h));

    const std::size_t t1 = addTriangle();
    writeTriangle(t, a, v, c);
    writeTriangle(t1, v, b, c);
    link(3 * t + 1, 3 * t1 + 2);
    link(3 * t + 2, outerCa);
    setFlag(3 * t + 2, flagCa);
    link(3 * t1 + 1, outerBc);
    setFlag(3 * t1 + 1, flagBc);
    setFlag(3 * t, edgeFlag);
    setFlag(3 * t1, edgeFlag);
    toCheck.push_back(3 * t + 2);
    toCheck.push_back(3 * t1 + 1);
    if (g == kNoHalfEdge) {
        link(3 * t, kNoHalfEdge);
        link(3 * t1, kNoHalfEdge);
        return;
    }

    const std::size_t u = g / 3;
    const std::uint32_t d = from(previousHalfEdge(g));
    const std::size_t outerAd = twin(nextHalfEdge(g));
    const std::size_t outerDb = twin(previousHalfEdge(g));
    const bool flagAd = isConstrained(nextHalfEdge(g));
    const bool flagDb = isConstrained(previousHalfEdge(g));
    const std::size_t u1 = addTriangle();
    writeTriangle(u, b, v, d);
    writeTriangle(u1, v, a, d);
    link(3 * u, 3 * t1);
    link(3 * u1, 3 * t);
    link(3 * u + 1, 3 * u1 + 2);
    link(3 * u + 2, outerDb);
    setFlag(3 * u + 2, flagDb);
    link(3 * u1 + 1, outerAd);
    setFlag(3 * u1 + 1, flagAd);
    setFlag(3 * u, edgeFlag);
    setFlag(3 * u1, edgeFlag);
    toCheck.push_back(3 * u + 2);
    toCheck.push_back(3 * u1 + 1);
}

void CdtMesh::legalise(std::uint32_t v, std::vector<std::size_t>& toCheck) {
    while (!toCheck.empty()) {
        const std::size_t h = toCheck.back();
        toCheck.pop_back();
        if (isConstrained(h) || from(previousHalfEdge(h)) != v)
            continue;
        const std::size_t g = twin(h);
        if (g == kNoHalfEdge)
            continue;
        const std::uint32_t opposite = from(previousHalfEdge(g));
        // v inside the circle of the triangle across h makes their quadrilateral convex.
        if (predicates::incircleTieBroken(xy(from(h)), xy(to(h)), xy(v), xy(opposite)) <= 0)
            continue;
        if (!owns(g / 3)) { // a view's fan triangle beside another zone's
            m_pending.push_back({from(h), to(h), h});
            continue;
        }
        flipAcross(h, g);
        toCheck.push_back(3 * (h / 3));
        toCheck.push_back(3 * (g / 3));
    }
}

void CdtMesh::flipAndRecord(std::size_t h, std::vector<std::size_t>& touched) {
    flipAndRecord(h, twin(h), touched);
}

void CdtMesh::flipAndRecord(std::size_t h, std::size_t g, std::vector<std::size_t>& touched) {
    const std::size_t t = h / 3;
    const std::size_t u = g / 3;
    flipAcross(h, g);
    // Triangle t is now (a, d, c), triangle u (d, b, c); 3t + 1 and 3u + 2 are the diagonal.
    touched.insert(touched.end(), {3 * t + 1, 3 * t, 3 * u, 3 * u + 1, 3 * t + 2});
}

void CdtMesh::restoreDelaunay(std::vector<std::size_t>& stack) {
    while (!stack.empty()) {
        const std::size_t h = stack.back();
        stack.pop_back();
        if (isConstrained(h))
            continue;
        const std::size_t g = twin(h);
        if (g == kNoHalfEdge)
            continue;
        const std::uint32_t opposite = from(previousHalfEdge(g));
        if (predicates::incircleTieBroken(xy(from(h)), xy(to(h)), xy(from(previousHalfEdge(h))),
                                          xy(opposite)) <= 0)
            continue;
        if (owns(h / 3) && owns(g / 3))
            flipAndRecord(h, g, stack);
        else
            m_pending.push_back({from(h), to(h), h});
    }
}

void CdtMesh::makePendingFlips(CdtMesh& view) {
    std::vector<std::size_t> stack;
    for (const Edge& edge : view.takePending())
        if (const std::size_t h = find(edge); h != kNoHalfEdge)
            stack.push_back(h);
    restoreDelaunay(stack);
}

void CdtMesh::flip(std::size_t h) {
    flipAcross(h, twin(h));
}

// Triangle t = (a, b, c) of h and u = (b, a, d) of its twin g become t = (a, d, c) and
// u = (d, b, c). Edges c-a and d-b stay in their triangles; b-c moves from t to u and a-d
// from u to t, so only their outer neighbours are pointed anew.
void CdtMesh::flipAcross(std::size_t h, std::size_t g) {
    const std::size_t t = h / 3;
    const std::size_t u = g / 3;
    const std::uint32_t a = from(h);
    const std::uint32_t b = to(h);
    const std::uint32_t c = from(previousHalfEdge(h));
    const std::uint32_t d = from(previousHalfEdge(g));
    const std::int32_t outerBc = m_arrays->mesh.neighbours[nextHalfEdge(h)];
    const std::int32_t outerCa = m_arrays->mesh.neighbours[previousHalfEdge(h)];
    const std::int32_t outerAd = m_arrays->mesh.neighbours[nextHalfEdge(g)];
    const std::int32_t outerDb = m_arrays->mesh.neighbours[previousHalfEdge(g)];
    const std::uint8_t flagBc = m_arrays->constrained[nextHalfEdge(h)];
    const std::uint8_t flagCa = m_arrays->constrained[previousHalfEdge(h)];
    const std::uint8_t flagAd = m_arrays->constrained[nextHalfEdge(g)];
    const std::uint8_t flagDb = m_arrays->constrained[previousHalfEdge(g)];

    writeCorners(t, a, d, c);
    writeCorners(u, d, b, c);
    const std::int32_t tNeighbours[3] = {outerAd, static_cast<std::int32_t>(u), outerCa};
    const std::int32_t uNeighbours[3] = {outerDb, outerBc, static_cast<std::int32_t>(t)};
    const std::uint8_t tFlags[3] = {flagAd, 0, flagCa};
    const std::uint8_t uFlags[3] = {flagDb, flagBc, 0};
    for (std::size_t i = 0; i < 3; ++i) {
        m_arrays->mesh.neighbours[3 * t + i] = tNeighbours[i];
        m_arrays->mesh.neighbours[3 * u + i] = uNeighbours[i];
        m_arrays->constrained[3 * t + i] = tFlags[i];
        m_arrays->constrained[3 * u + i] = uFlags[i];
    }
    relink(outerBc, c, u);
    relink(outerAd, d, t);
}

} // namespace terratin::detail
