// Watertight evaluation: the canonical edge and the source plan (watertight.h),
// whose tables are dense per-level arrays and EdgeMaps (edge_map.h).
#include "watertight.h"

#include "box_spline.h"
#include "edge_map.h"
#include "lod.h"
#include "parallel.h"
#include "sub_patches.h"

#include <algorithm>
#include <cassert>

namespace lt {

// Derived on the lattice of box_spline.h: edge 1 turned to 4 -> 5 maps the new
// point at lattice (i, j) to the old one at (1 - i - j, i); edge 2 applies it twice.
const uint8_t kEdgeRotation[3][12] = {
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11},
    {6, 9, 11, 2, 5, 8, 10, 1, 4, 7, 0, 3},
    {10, 7, 3, 11, 8, 4, 0, 9, 5, 1, 6, 2},
};

namespace {

// Uniform cubic B-spline weights of points 3, 4, 5, 6 on the segment 4 -> 5.
void cubicWeights(float x, float c[4]) {
    float y = 1.0f - x;
    float x2 = x * x, x3 = x2 * x;
    const float sixth = 1.0f / 6.0f;
    c[0] = (y * y * y) * sixth;
    c[1] = ((3.0f * x3 - 6.0f * x2) + 4.0f) * sixth;
    c[2] = (((3.0f * x2 - 3.0f * x3) + 3.0f * x) + 1.0f) * sixth;
    c[3] = x3 * sixth;
}

}  // namespace

void evalCanonicalEdge(const float p[12][3], const uint32_t points[12], uint8_t mask, int edge, float x, float pos[3],
                       float ds[3], float dt[3]) {
    evalCanonicalEdge(p, points, mask, edge, x, boxSplineWeights(x, 0.0f), pos, ds, dt);
}

void evalCanonicalEdge(const float p[12][3], const uint32_t points[12], uint8_t mask, int edge, float x,
                       const BoxWeights& weights, float pos[3], float ds[3], float dt[3]) {
    const uint8_t* r = kEdgeRotation[edge];
    bool flip = edgeFlipped(points, edge);
    const float* q[10];
    for (int i = 0; i < 10; ++i) q[i] = p[r[flip ? 9 - i : i]];
    sumWeighted(q, 10, weights.w, weights.ds, weights.dt, pos, ds, dt);  // points 10 and 11 weigh 0 on the edge
    if (mask & (1u << edge)) {
        // Boundary or infinitely sharp edge: the curve of the line points alone.
        float cw[4];
        cubicWeights(x, cw);
        for (int k = 0; k < 3; ++k) {
            float a = cw[0] * (q[3][k] - q[4][k]);
            a = a + cw[2] * (q[5][k] - q[4][k]);
            a = a + cw[3] * (q[6][k] - q[4][k]);
            pos[k] = q[4][k] + a;
        }
    }
}

size_t WatertightPlan::bytes() const {
    size_t n =
        points.size() * sizeof(PointSource) + roots.size() * sizeof(EdgeRoot) + normals.size() * sizeof(NormalSource);
    for (const WatertightLevel& l : levels)
        n += (l.regularCorner.size() + l.regularEdge.size() + l.stencilSource.size() + l.stencilPosition.size() +
              l.regularNormal.size() + l.stencilNormal.size() + l.stencilBaseNormal.size()) *
             sizeof(uint32_t);
    return n;
}

size_t setupThreads(size_t corners, size_t threads) {
    return corners < kParallelCorners ? 1 : fmt::threadCount(threads);
}

bool hasMaskedCorners(const Asset& asset) {
    for (const Level& level : asset.levels) {
        if (!level.limit.masked.empty()) return true;
        for (const RegularPatch& p : level.regular)
            if (p.boundaryMask) return true;
    }
    return false;
}

void buildWatertightPlan(const Asset& asset, WatertightPlan& plan, size_t threads, uint32_t depth) {
    plan = WatertightPlan{};
    const bool masked = hasMaskedCorners(asset);
    depth = masked ? asset.maxDepth() : std::min(depth, asset.maxDepth());
    plan.levels.resize(depth + 1);
    for (uint32_t l = 0; l <= depth; ++l) {
        WatertightLevel& wl = plan.levels[l];
        wl.regularCorner.assign(3 * asset.levels[l].regular.size(), kNoSource);
        wl.regularEdge.assign(3 * asset.levels[l].regular.size(), kNoSource);
        const LimitStencils& ls = asset.levels[l].limit;
        wl.stencilSource.assign(ls.count(), kNoSource);
        // The first stencil of each vertex, by its place in the level (a valid asset's
        // stencils are of level l's vertices).
        const VertexRange range = levelRange(asset, l);
        std::vector<uint32_t> first(range.count, kNoSource);
        wl.stencilPosition.resize(ls.count());
        for (uint32_t k = 0; k < ls.count(); ++k) {
            uint32_t& f = first[ls.vertex[k] - range.begin];
            if (f == kNoSource) f = k;
            wl.stencilPosition[k] = f;
        }
    }

    // origin[v]: the vertex whose limit point v is: a control vertex, an edge point,
    // or a vertex whose limit an edit of its level moved (`edited`); vertex points
    // inherit their parent's.
    const VertexRange last = levelRange(asset, depth);
    std::vector<uint32_t> origin(last.begin + last.count);
    std::vector<bool> edited(origin.size(), false);
    for (uint32_t v = 0; v < asset.controlVertexCount(); ++v) origin[v] = v;
    for (uint32_t l = 0; l <= depth; ++l) {
        const Refinement& r = asset.levels[l].refinement;
        for (uint32_t i = 0; i < r.vertexPointCount(); ++i) origin[r.firstVertex + i] = origin[r.vertexParent[i]];
        for (uint32_t i = r.vertexPointCount(); i < r.vertexCount(); ++i) origin[r.firstVertex + i] = r.firstVertex + i;
        for (uint32_t v : editedLimitVertices(asset, l)) origin[v] = v, edited[v] = true;
    }
    std::vector<uint32_t> source(origin.size(), kNoSource);
    plan.points.reserve(origin.size());  // a point per origin at most: pages are touched as used
    auto sourceOf = [&](uint32_t v, const PointSource& candidate) {
        uint32_t& s = source[origin[v]];
        if (s == kNoSource) {
            s = uint32_t(plan.points.size());
            plan.points.push_back(candidate);
        }
        return s;
    };

    // Root edges of this level by (min, max) vertex; each level's map is made from
    // the previous one's children and this level's patch edges. Both maps are sized
    // once for the largest level (the two halves of each edge point's edge at most,
    // and the level's patch edges), and so are the roots.
    size_t most = 0, rootCount = 0;
    for (uint32_t l = 0; l <= depth; ++l) {
        const size_t halves = l ? 2 * size_t(asset.levels[l].refinement.edgePointCount()) : 0;
        most = std::max(most, halves + 3 * asset.levels[l].regular.size());
        rootCount += halves + 3 * asset.levels[l].regular.size();
    }
    plan.roots.reserve(rootCount);
    EdgeMap roots, childRoots;
    childRoots.reset(most);
    for (uint32_t l = 0; l <= depth; ++l) {
        const Level& level = asset.levels[l];
        WatertightLevel& wl = plan.levels[l];
        roots.swap(childRoots);
        childRoots.reset(most);
        for (uint32_t k = 0; k < level.regular.size(); ++k) {
            const RegularPatch& patch = level.regular[k];
            for (int e = 0; e < 3; ++e) {
                uint32_t a = patch.points[kPatchCorner[e]], b = patch.points[kPatchCorner[(e + 1) % 3]];
                auto [it, added] = roots.emplace(edgeKey(a, b), uint32_t(plan.roots.size()));
                const uint32_t rootIndex = *it;
                if (added) plan.roots.push_back({l, k, uint8_t(e), 0.0f, 1.0f});
                const EdgeRoot& root = plan.roots[rootIndex];
                // A boundary or sharp edge's two sides gather different phantoms: the
                // second side evaluates the first's edge too (one displacement
                // direction, rule 5; the normal stays its own, rule 4).
                bool shared = (patch.boundaryMask >> e & 1u) && !(root.level == l && root.patch == k);
                if (root.level < l || shared) wl.regularEdge[3 * k + e] = rootIndex;
            }
        }
        for (uint32_t k = 0; k < level.regular.size(); ++k) {
            const RegularPatch& patch = level.regular[k];
            for (int c = 0; c < 3; ++c) {
                uint32_t v = patch.points[kPatchCorner[c]];
                uint32_t r = wl.regularEdge[3 * k + c];
                float x = edgeFlipped(patch.points, c) ? 1.0f : 0.0f;
                PointSource ps{l, k, uint8_t(c), x};
                if (r != kNoSource) {
                    const EdgeRoot& root = plan.roots[r];
                    ps = {root.level, root.patch, root.edge, root.offset + root.scale * x};
                }
                wl.regularCorner[3 * k + c] = sourceOf(v, ps);
            }
        }
        for (uint32_t k = 0; k < level.limit.count(); ++k) {
            uint32_t s = source[origin[level.limit.vertex[k]]];
            if (s != kNoSource && plan.points[s].level <= l) wl.stencilSource[k] = s;
        }
        if (l == depth) break;
        // The children of each root edge at level l+1, and the edge points on them.
        const Refinement& next = asset.levels[l + 1].refinement;
        const VertexRange range = levelRange(asset, l);  // holds every parent of a level l + 1 point
        std::vector<uint32_t> vertexChild(range.count, kNoSource);
        for (uint32_t i = 0; i < next.vertexPointCount(); ++i)
            vertexChild[next.vertexParent[i] - range.begin] = next.firstVertex + i;
        for (uint32_t i = 0; i < next.edgePointCount(); ++i) {
            uint32_t a = next.edgeVerts[4 * i], b = next.edgeVerts[4 * i + 1];
            const uint32_t* it = roots.find(edgeKey(a, b));
            const uint32_t ca = vertexChild[a - range.begin], cb = vertexChild[b - range.begin];
            if (!it || ca == kNoSource || cb == kNoSource) continue;
            uint32_t m = next.firstVertex + next.vertexPointCount() + i;
            uint32_t rootIndex = *it;
            EdgeRoot root = plan.roots[rootIndex];
            // Parent parameter of the half a' -> m: x / 2 from the canonical start,
            // 1 - x / 2 from the end; composed with the root's map.
            for (auto [end, child] : {std::pair{a, ca}, std::pair{b, cb}}) {
                bool fromStart = end == (a < b ? a : b);
                EdgeRoot half = root;
                half.offset = fromStart ? root.offset : root.offset + root.scale;
                half.scale = fromStart ? root.scale * 0.5f : root.scale * -0.5f;
                childRoots.emplace(edgeKey(child, m), uint32_t(plan.roots.size()));
                plan.roots.push_back(half);
            }
            if (!edited[m])
                sourceOf(m, PointSource{root.level, root.patch, root.edge, root.offset + root.scale * 0.5f});
        }
    }
    assignCreaseNormals(asset, plan, masked, threads);
}

}  // namespace lt
