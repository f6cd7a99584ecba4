// numbering.cpp -- steps 2 and 3 of lt::bake (numbering.h).
#include "numbering.h"

#include "parallel.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

namespace lt {
namespace {

constexpr uint8_t kRingNeeded = 2;  // a needed vertex whose 1-ring is marked too

// Whether vertex `v` of `topo` has all of its 1-ring (its limit stencil's and its
// vertex rule's points): a face between each pair of consecutive edges.
bool ringComplete(const Far::TopologyLevel& topo, OsdIndex v) {
    const int edges = topo.GetVertexEdges(v).size(), faces = topo.GetVertexFaces(v).size();
    return topo.IsVertexNonManifold(v) || faces == edges - (topo.IsVertexBoundary(v) ? 1 : 0);
}

// The first i in [0, count) for which `fails(i)` is true (count when none), with
// `fails` run for every i before it on `threads` threads (parallel.h): the same
// answer for every thread count.
template <class F>
size_t firstFailure(size_t count, size_t threads, F&& fails) {
    std::vector<size_t> first(fmt::rangeCount(count, threads, kFaceGrain), count);
    fmt::parallelRanges(count, threads, kFaceGrain, [&](size_t r, size_t begin, size_t end, size_t) {
        for (size_t i = begin; i < end && first[r] == count; ++i)
            if (fails(i)) first[r] = i;
    });
    return first.empty() ? count : *std::min_element(first.begin(), first.end());
}

// A relaxed atomic store (NeededVertices).
void mark(std::atomic<uint8_t>& n, uint8_t value = 1) { n.store(value, std::memory_order_relaxed); }

// Marks `v` of `topo` and its 1-ring needed; false when the ring is incomplete.
bool needLimitRing(const Far::TopologyLevel& topo, OsdIndex v, std::atomic<uint8_t>* needed) {
    if (needed[v].load(std::memory_order_relaxed) == kRingNeeded) return true;  // a corner of several irregular faces
    if (!ringComplete(topo, v)) return false;
    for (OsdIndex e : topo.GetVertexEdges(v)) {
        std::atomic<uint8_t>& n = needed[otherEnd(topo, e, v)];
        if (!n.load(std::memory_order_relaxed)) mark(n);
    }
    mark(needed[v], kRingNeeded);
    return true;
}

}  // namespace

// A level's closure reads the level above, complete before it starts.
Status collectNeeded(const Topology& topology, int levels, const std::vector<std::vector<Candidate>>& candidates,
                     const std::vector<std::vector<PatchPoints>>& points, size_t threads,
                     NeededVertices& neededVertices) {
    auto level = [&](int l) -> const Far::TopologyLevel& { return topology.level(l); };
    neededVertices.resize(size_t(levels));
    for (int l = 0; l < levels; ++l)
        neededVertices[l].reset(new std::atomic<uint8_t>[size_t(level(l).GetNumVertices())]());
    for (int l = 0; l < levels; ++l) {
        const std::vector<Candidate>& cands = candidates[l];
        std::atomic<uint8_t>* needed = neededVertices[l].get();
        fmt::parallelFor(points[l].size(), threads, kFaceGrain, [&](size_t k, size_t) {
            for (OsdIndex p : points[l][k].points) mark(needed[p]);
        });
        const size_t bad = firstFailure(cands.size(), threads, [&](size_t k) {
            const Candidate& c = cands[k];
            if (c.regular) return false;
            for (OsdIndex v : level(l).GetFaceVertices(c.face))
                if (!needLimitRing(level(l), v, needed)) return true;
            return false;
        });
        if (bad == cands.size()) continue;
        OsdIndex v = 0;
        for (OsdIndex corner : level(l).GetFaceVertices(cands[bad].face))
            if (!ringComplete(level(l), corner)) {
                v = corner;
                break;
            }
        return Status::error(Status::Internal, "level " + std::to_string(l) + " vertex " + std::to_string(v) +
                                                   " has an incomplete ring for its limit stencil");
    }
    // Close downwards: what each needed vertex's rule reads one level up.
    for (int l = levels - 1; l >= 1; --l) {
        const auto& parent = level(l - 1);
        const std::atomic<uint8_t>* child = neededVertices[l].get();
        std::atomic<uint8_t>* needed = neededVertices[l - 1].get();
        const size_t vertices = size_t(parent.GetNumVertices());
        const size_t badVertex = firstFailure(vertices, threads, [&](size_t i) {
            const OsdIndex p = OsdIndex(i), c = parent.GetVertexChildVertex(p);
            if (c < 0 || !child[c].load(std::memory_order_relaxed)) return false;
            if (!ringComplete(parent, p)) return true;
            mark(needed[p]);
            for (OsdIndex e : parent.GetVertexEdges(p)) mark(needed[otherEnd(parent, e, p)]);
            return false;
        });
        if (badVertex < vertices)
            return Status::error(Status::Internal, "level " + std::to_string(l - 1) + " vertex " +
                                                       std::to_string(badVertex) + " is needed but incomplete");
        const size_t edges = size_t(parent.GetNumEdges());
        const size_t badEdge = firstFailure(edges, threads, [&](size_t i) {
            const OsdIndex e = OsdIndex(i), c = parent.GetEdgeChildVertex(e);
            if (c < 0 || !child[c].load(std::memory_order_relaxed)) return false;
            for (OsdIndex v : parent.GetEdgeVertices(e)) mark(needed[v]);
            if (edgeCreaseWeight(topology.refiner(l - 1), topology.local(l - 1), e) >= 1.0f) return false;
            auto faces = parent.GetEdgeFaces(e);
            if (faces.size() != 2) return true;
            for (OsdIndex f : faces)
                for (OsdIndex v : parent.GetFaceVertices(f)) mark(needed[v]);
            return false;
        });
        if (badEdge < edges)
            return Status::error(Status::Internal, "level " + std::to_string(l - 1) + " edge " +
                                                       std::to_string(badEdge) + " is needed but incomplete");
    }
    return Status::ok();
}

// Level by level: each range of the parent level's kept vertices lists the children
// it keeps, in order, on a thread of its own; the lists are joined in range order.
void number(const Topology& topology, int levels, const NeededVertices& neededVertices, size_t threads,
            Numbering& out) {
    out.global.assign(size_t(levels), {});
    out.order.assign(size_t(levels), {});
    out.pointCount.assign(size_t(levels), 0);
    uint32_t next = 0;
    for (int l = 0; l < levels; ++l) {
        const auto& topo = topology.level(l);
        std::vector<OsdIndex>& order = out.order[l];
        if (l == 0) {
            order.resize(size_t(topo.GetNumVertices()));
            std::iota(order.begin(), order.end(), OsdIndex(0));
        } else {
            // Ordered by the parents' global indices, not OpenSubdiv's numbering, so a
            // vertex's neighbours keep their relative order whatever else the level
            // keeps (and whichever refiner made it): edits elsewhere leave the rings'
            // first neighbours and the canonical edge directions, hence every rounding,
            // unchanged. A needed child's parent vertex, or its parent edge's ends, are
            // kept (collectNeeded), so walking the parent level's kept vertices in order
            // gives that order with no sort: vertex points by their parent, edge points
            // by their smaller end, then by the larger among that end's edges.
            const auto& parent = topology.level(l - 1);
            const auto& pg = out.global[l - 1];
            const std::vector<OsdIndex>& from = out.order[l - 1];
            const std::atomic<uint8_t>* needed = neededVertices[l].get();
            auto kept = [&](OsdIndex c) { return c >= 0 && needed[c].load(std::memory_order_relaxed); };
            const size_t ranges = fmt::rangeCount(from.size(), threads, kFaceGrain);
            std::vector<std::vector<OsdIndex>> points(ranges), edgePoints(ranges);
            fmt::parallelRanges(from.size(), threads, kFaceGrain, [&](size_t r, size_t begin, size_t end, size_t) {
                for (size_t i = begin; i < end; ++i)
                    if (OsdIndex c = parent.GetVertexChildVertex(from[i]); kept(c)) points[r].push_back(c);
                std::vector<std::pair<uint32_t, OsdIndex>> ends;  // (larger end's global index, edge point)
                for (size_t i = begin; i < end; ++i) {
                    const OsdIndex a = from[i];
                    ends.clear();
                    for (OsdIndex e : parent.GetVertexEdges(a)) {
                        const OsdIndex c = parent.GetEdgeChildVertex(e);
                        if (!kept(c)) continue;
                        const uint32_t b = pg[otherEnd(parent, e, a)];
                        if (b > pg[a]) ends.push_back({b, c});
                    }
                    std::sort(ends.begin(), ends.end());
                    for (const auto& e : ends) edgePoints[r].push_back(e.second);
                }
            });
            for (const auto& part : points) order.insert(order.end(), part.begin(), part.end());
            out.pointCount[l] = uint32_t(order.size());
            for (const auto& part : edgePoints) order.insert(order.end(), part.begin(), part.end());
        }
        std::vector<uint32_t>& global = out.global[l];
        global.assign(size_t(topo.GetNumVertices()), ~0u);
        fmt::parallelFor(order.size(), threads, kFaceGrain,
                         [&](size_t k, size_t) { global[size_t(order[k])] = next + uint32_t(k); });
        next += uint32_t(order.size());
    }
}

}  // namespace lt
