// corner_stencils.cpp -- the limit stencils of a level's IPP corners (corner_stencils.h).
#include "corner_stencils.h"

#include "face_corner.h"

#include "parallel.h"

#include <algorithm>
#include <string>
#include <tuple>

namespace lt {

namespace {

// Corners a thread range takes at least: each costs a limit stencil or more.
constexpr size_t kCornerGrain = 64;

struct Corner {
    uint32_t global;
    OsdIndex sector, own, vertex, face;  // own: the face whose corner is the stencil, or -1
    int ownLevel = kFaceCornerLevel;     // the level own's corner is refined to
    uint32_t shared = 0;                 // its sector's stencil (index into the sectors)
    auto key() const { return std::make_tuple(global, sector, own); }
    bool operator<(const Corner& o) const { return key() < o.key(); }
    bool operator==(const Corner& o) const { return key() == o.key(); }
};

// The emitted stencils of one range of corners, CSR ends relative to the range.
// Cache-line aligned: neighbouring parts are filled by different threads.
struct alignas(64) Part {
    std::vector<uint32_t> ring, ringEnd, masked, maskEnd;
    std::vector<float> position, tangentU, tangentV;
    OsdIndex refused = -1;  // the first vertex whose 1-ring OpenSubdiv refused
};

// Frees `v`'s memory now (clear() keeps the capacity): a level's sector stencils
// are the bake's largest transient, so nothing else should sit beside them longer
// than it must.
template <typename T>
void release(T& v) {
    T().swap(v);
}

// Appends `stencil` (of global vertex `g`'s numbering) to `part` as corner `index`
// of its range: the ring from the neighbour with the smallest global index; the
// vertex's own weight (entry 0) is implied by affinity.
void emit(const LimitStencil& stencil, const std::vector<uint32_t>& g, uint32_t index, Part& part) {
    size_t n = stencil.points.size() - 1, first = 0;
    for (size_t k = 1; k < n; ++k)
        if (g[stencil.points[1 + k]] < g[stencil.points[1 + first]]) first = k;
    for (size_t k = 0; k < n; ++k) part.ring.push_back(g[stencil.points[1 + (first + k) % n]]);
    part.ringEnd.push_back(uint32_t(part.ring.size()));
    if (stencil.smooth) return;
    part.masked.push_back(index);
    for (size_t k = 0; k < n; ++k) {
        size_t w = 1 + (first + k) % n;
        part.position.push_back(float(stencil.position[w]));
        part.tangentU.push_back(float(stencil.tangentU[w]));
        part.tangentV.push_back(float(stencil.tangentV[w]));
    }
    part.maskEnd.push_back(uint32_t(part.position.size()));
}

}  // namespace

Status buildCornerStencils(const Topology& topology, int l, int maxDepth, const StencilOrienter& orienter,
                           std::vector<StencilOrienter::Cache>& caches, const std::vector<uint32_t>& g,
                           const std::vector<OsdIndex>& faces, LimitStencils& ls, std::vector<uint32_t>& cornerOf) {
    const Far::TopologyLevel& topo = topology.level(l);
    const Far::TopologyRefiner& refiner = topology.refiner(l);
    const int local = topology.local(l);
    const size_t threads = caches.size();
    // Every stage below runs per face, sector or corner, each writing its own slot.
    std::vector<Corner> faceCorners(3 * faces.size());  // the keys of each face's corners
    fmt::parallelFor(faces.size(), threads, kCornerGrain, [&](size_t i, size_t) {
        const OsdIndex face = faces[i];
        auto fv = topo.GetFaceVertices(face);
        for (int k = 0; k < 3; ++k) {
            const OsdIndex v = fv[k];
            // No tangent plane by topology: a spike whose limit lies below float
            // resolution; the face's corner at the deepest level drawn (spec).
            const OsdIndex own = tangentPlaneAt(refiner, local, v, face) ? -1 : face;
            faceCorners[3 * i + size_t(k)] = {g[v], limitSector(refiner, local, v, face), own, v, face, maxDepth};
        }
    });
    // The sectors' stencils, each computed at the first corner (in face order) in
    // it; a slit's (no normal on the baked positions) gives each of its faces one
    // of its own.
    std::vector<std::pair<uint32_t, OsdIndex>> keys(faceCorners.size());
    for (size_t i = 0; i < faceCorners.size(); ++i) keys[i] = {faceCorners[i].global, faceCorners[i].sector};
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    fmt::parallelFor(faceCorners.size(), threads, kCornerGrain, [&](size_t i, size_t) {
        const std::pair<uint32_t, OsdIndex> key{faceCorners[i].global, faceCorners[i].sector};
        faceCorners[i].shared = uint32_t(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
    });
    std::vector<size_t> firstCorner(keys.size(), faceCorners.size());
    release(keys);
    for (size_t i = faceCorners.size(); i-- > 0;) firstCorner[faceCorners[i].shared] = i;
    std::vector<LimitStencil> sectors(firstCorner.size());
    fmt::parallelFor(sectors.size(), threads, kCornerGrain, [&](size_t s, size_t) {
        const Corner& c = faceCorners[firstCorner[s]];
        limitStencil(refiner, local, c.vertex, c.face, sectors[s]);
    });
    release(firstCorner);
    fmt::parallelFor(faceCorners.size(), threads, kCornerGrain, [&](size_t i, size_t worker) {
        Corner& c = faceCorners[i];
        if (c.own < 0 && orienter.degenerate(l, c.vertex, c.face, sectors[c.shared], caches[worker])) {
            c.own = c.face;
            c.ownLevel = kFaceCornerLevel;
        }
    });
    // Orient the sector stencils that some face uses for its normal.
    std::vector<uint8_t> oriented(sectors.size(), 0);
    for (const Corner& c : faceCorners)
        if (c.own < 0) oriented[c.shared] = 1;
    fmt::parallelFor(sectors.size(), threads, kCornerGrain, [&](size_t s, size_t worker) {
        if (oriented[s]) orienter.orient(l, sectors[s], caches[worker]);
    });
    std::vector<Corner> corners = faceCorners;  // unique keys, in the stencils' order
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    // Each face corner's stencil, now, so that the face corners are freed before the
    // stencils are emitted beside the sectors.
    cornerOf.resize(faceCorners.size());
    fmt::parallelFor(faceCorners.size(), threads, kCornerGrain, [&](size_t i, size_t) {
        cornerOf[i] = uint32_t(std::lower_bound(corners.begin(), corners.end(), faceCorners[i]) - corners.begin());
    });
    release(faceCorners);
    // Each range of corners emits into a part of its own; the parts are then
    // concatenated in order.
    const uint32_t base = ls.count();
    std::vector<Part> parts(fmt::rangeCount(corners.size(), threads, kCornerGrain));
    fmt::parallelRanges(corners.size(), threads, kCornerGrain, [&](size_t r, size_t begin, size_t end, size_t worker) {
        Part& part = parts[r];
        LimitStencil own;
        for (size_t i = begin; i < end; ++i) {
            const Corner& c = corners[i];
            const LimitStencil* stencil = &sectors[c.shared];
            if (c.own >= 0) {
                if (!orienter.faceStencil(l, c.vertex, c.own, c.ownLevel, maxDepth, *stencil, own, caches[worker])) {
                    part.refused = c.vertex;
                    return;
                }
                stencil = &own;
            }
            emit(*stencil, g, base + uint32_t(i), part);
        }
    });
    release(sectors);
    // Exact sizes: no growth by doubling, whose old and new blocks would coexist.
    size_t ring = 0, ends = 0, masked = 0, maskEnds = 0, weights = 0;
    for (const Part& part : parts) {
        if (part.refused >= 0)
            return Status::error(Status::Internal, "OpenSubdiv refused the 1-ring of level " + std::to_string(l) +
                                                       " vertex " + std::to_string(part.refused));
        ring += part.ring.size();
        ends += part.ringEnd.size();
        masked += part.masked.size();
        maskEnds += part.maskEnd.size();
        weights += part.position.size();
    }
    ls.vertex.reserve(ls.vertex.size() + corners.size());
    ls.start.reserve(ls.start.size() + 1 + ends);
    ls.ring.reserve(ls.ring.size() + ring);
    ls.masked.reserve(ls.masked.size() + masked);
    ls.maskStart.reserve(ls.maskStart.size() + 1 + maskEnds);
    for (std::vector<float>* w : {&ls.position, &ls.tangentU, &ls.tangentV}) w->reserve(w->size() + weights);
    for (const Corner& c : corners) ls.vertex.push_back(c.global);
    ls.start.push_back(0);
    for (Part& part : parts) {
        const uint32_t ringBase = uint32_t(ls.ring.size()), weightBase = uint32_t(ls.position.size());
        ls.ring.insert(ls.ring.end(), part.ring.begin(), part.ring.end());
        for (uint32_t end : part.ringEnd) ls.start.push_back(ringBase + end);
        if (!part.masked.empty() && ls.masked.empty()) ls.maskStart.push_back(0);
        ls.masked.insert(ls.masked.end(), part.masked.begin(), part.masked.end());
        for (uint32_t end : part.maskEnd) ls.maskStart.push_back(weightBase + end);
        ls.position.insert(ls.position.end(), part.position.begin(), part.position.end());
        ls.tangentU.insert(ls.tangentU.end(), part.tangentU.begin(), part.tangentU.end());
        ls.tangentV.insert(ls.tangentV.end(), part.tangentV.begin(), part.tangentV.end());
        part = Part{};
    }
    if (ls.count() == 0) ls.start.clear();
    return Status::ok();
}

}  // namespace lt
