// refinement_table.cpp -- one level's refinement table (refinement_table.h).
#include "refinement_table.h"

#include "parallel.h"

#include <algorithm>

namespace lt {
namespace {

constexpr uint32_t kNotKept = ~0u;  // bake.cpp's global index of a vertex not kept
// Vertices a thread range takes at least (parallel.h): each costs well under a
// microsecond to a few.
constexpr size_t kGrain = 1024;

}  // namespace

Status buildRefinement(const Topology& topology, int l, const std::vector<uint32_t>& parentGlobal,
                       const std::vector<uint32_t>& global, const std::vector<OsdIndex>& order, uint32_t points,
                       size_t threads, Refinement& r) {
    const Far::TopologyLevel& parent = topology.level(l - 1);
    const Far::TopologyRefiner& refiner = topology.refiner(l - 1);
    const int local = topology.local(l - 1);
    r.firstVertex = global[order[0]];
    // Parent of each kept child, found from the parent's child links.
    std::vector<OsdIndex> vertexParent(size_t(topology.level(l).GetNumVertices()), -1), edgeParent(vertexParent);
    fmt::parallelFor(size_t(parent.GetNumVertices()), threads, kGrain, [&](size_t p, size_t) {
        OsdIndex c = parent.GetVertexChildVertex(OsdIndex(p));
        if (c >= 0) vertexParent[c] = OsdIndex(p);
    });
    fmt::parallelFor(size_t(parent.GetNumEdges()), threads, kGrain, [&](size_t e, size_t) {
        OsdIndex c = parent.GetEdgeChildVertex(OsdIndex(e));
        if (c >= 0) edgeParent[c] = OsdIndex(e);
    });
    // Vertex points: each range of them fills a part of its own (CSR ends relative
    // to the range), concatenated in order below. Cache-line aligned, as the parts
    // next to each other are filled by different threads.
    struct alignas(64) Part {
        std::vector<uint32_t> ring, ringEnd, masked, maskEnd;
        std::vector<float> weights;
    };
    r.vertexParent.resize(points);
    std::vector<Part> parts(fmt::rangeCount(points, threads, kGrain));
    fmt::parallelRanges(points, threads, kGrain, [&](size_t range, size_t begin, size_t end, size_t) {
        Part& part = parts[range];
        std::vector<double> weights;
        for (size_t i = begin; i < end; ++i) {
            OsdIndex p = vertexParent[order[i]];
            r.vertexParent[i] = parentGlobal[p];
            // The ring from the neighbour with the smallest global index (as limit
            // stencils): the sum's order then does not depend on OpenSubdiv's numbering.
            auto edges = parent.GetVertexEdges(p);
            const int n = edges.size();
            int first = 0;
            for (int k = 1; k < n; ++k)
                if (parentGlobal[otherEnd(parent, edges[k], p)] < parentGlobal[otherEnd(parent, edges[first], p)])
                    first = k;
            for (int k = 0; k < n; ++k) part.ring.push_back(parentGlobal[otherEnd(parent, edges[(first + k) % n], p)]);
            part.ringEnd.push_back(uint32_t(part.ring.size()));
            if (vertexMask(refiner, local, p, weights)) {
                part.masked.push_back(uint32_t(i));
                for (int k = 0; k < n; ++k) part.weights.push_back(float(weights[1 + (first + k) % n]));
                part.maskEnd.push_back(uint32_t(part.weights.size()));
            }
        }
    });
    r.vertexRingStart.push_back(0);
    r.maskStart.push_back(0);
    for (const Part& part : parts) {
        const uint32_t ringBase = uint32_t(r.vertexRing.size()), weightBase = uint32_t(r.maskWeights.size());
        r.vertexRing.insert(r.vertexRing.end(), part.ring.begin(), part.ring.end());
        for (uint32_t e : part.ringEnd) r.vertexRingStart.push_back(ringBase + e);
        r.maskedVertex.insert(r.maskedVertex.end(), part.masked.begin(), part.masked.end());
        r.maskWeights.insert(r.maskWeights.end(), part.weights.begin(), part.weights.end());
        for (uint32_t e : part.maskEnd) r.maskStart.push_back(weightBase + e);
    }
    // Edge points: four vertices each; creased ones by range, concatenated in order.
    const size_t edgePoints = order.size() - points;
    r.edgeVerts.resize(4 * edgePoints);
    struct alignas(64) Creases {
        std::vector<uint32_t> edge;
        std::vector<float> weight;
    };
    std::vector<Creases> creases(fmt::rangeCount(edgePoints, threads, kGrain));
    fmt::parallelRanges(edgePoints, threads, kGrain, [&](size_t range, size_t begin, size_t end, size_t) {
        for (size_t j = begin; j < end; ++j) {
            OsdIndex e = edgeParent[order[points + j]];
            auto ev = parent.GetEdgeVertices(e);
            uint32_t a = parentGlobal[ev[0]], b = parentGlobal[ev[1]];
            float w = edgeCreaseWeight(refiner, local, e);
            uint32_t opp[2] = {a, a};
            if (w < 1.0f) {
                auto faces = parent.GetEdgeFaces(e);
                for (int k = 0; k < 2; ++k) {
                    for (OsdIndex v : parent.GetFaceVertices(faces[k]))
                        if (v != ev[0] && v != ev[1]) opp[k] = parentGlobal[v];
                }
            }
            const uint32_t verts[4] = {a, b, opp[0], opp[1]};
            std::copy(verts, verts + 4, r.edgeVerts.begin() + std::ptrdiff_t(4 * j));
            if (w > 0.0f) {
                creases[range].edge.push_back(uint32_t(j));
                creases[range].weight.push_back(w);
            }
        }
    });
    for (const Creases& c : creases) {
        r.creaseEdge.insert(r.creaseEdge.end(), c.edge.begin(), c.edge.end());
        r.creaseWeight.insert(r.creaseWeight.end(), c.weight.begin(), c.weight.end());
    }
    for (uint32_t x : r.edgeVerts)
        if (x == kNotKept) return Status::error(Status::Internal, "edge point reads a vertex that was not kept");
    for (uint32_t x : r.vertexRing)
        if (x == kNotKept) return Status::error(Status::Internal, "vertex point reads a vertex that was not kept");
    return Status::ok();
}

}  // namespace lt
