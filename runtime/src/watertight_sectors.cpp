// Watertight rule 4 (watertight.h): one normal per sector at crease and boundary
// corners. Corners are joined into sectors with a union-find over
//   regular corner nodes  3 * (global patch index) + corner, levels in order
//   stencil nodes         after them, one per limit stencil, levels in order
// and each sector's normal is its first regular node's (the coarsest level's).
//
// Every node of a sector lies on one limit point, so its vertex has one ancestor
// (the control vertex or edge point its vertex points descend from: joins are
// across a level's edges, or from a corner to the end of a coarser edge, the same
// vertex's vertex point). Only sectors holding a masked node get a normal, so only
// nodes whose ancestor has a masked node anywhere are joined: a smooth, closed
// asset joins none, and the sectors that matter are the same as joining all.
#include "watertight.h"

#include "edge_map.h"
#include "parallel.h"
#include "sub_patches.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace lt {
namespace {

class UnionFind {
public:
    explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), uint32_t(0)); }
    uint32_t find(uint32_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    // The smaller root wins, so a sector's root is its first node.
    void join(uint32_t a, uint32_t b) {
        a = find(a), b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<uint32_t> parent_;
};

bool maskedEdge(const RegularPatch& p, int e) { return (p.boundaryMask >> e) & 1u; }
bool maskedCorner(const RegularPatch& p, int c) {
    return (p.boundaryMask & ((1u << c) | (1u << (c + 2) % 3) | (8u << c))) != 0;
}
int cornerOf(const RegularPatch& p, uint32_t vertex) {
    for (int c = 0; c < 3; ++c)
        if (p.points[kPatchCorner[c]] == vertex) return c;
    return -1;
}

// The joins of level l's nodes (pairs of union-find nodes) at vertices `kept`, from
// the level's own tables and the plan's roots: `node(l, k, c)` numbers regular
// corners, `stencilNode` the level's first stencil node.
template <class Node, class Kept>
std::vector<std::pair<uint32_t, uint32_t>> levelJoins(const Asset& asset, const WatertightPlan& plan, uint32_t l,
                                                      uint32_t stencilNode, const Node& node, const Kept& kept) {
    const Level& level = asset.levels[l];
    const WatertightLevel& wl = plan.levels[l];
    std::vector<std::pair<uint32_t, uint32_t>> joins;
    // Same level: corners joined across edges that are not boundary or sharp.
    EdgeMap edges;  // edge -> 3 * patch + edge (the first), of edges with a kept end
    for (uint32_t k = 0; k < level.regular.size(); ++k) {
        const RegularPatch& p = level.regular[k];
        for (int e = 0; e < 3; ++e) {
            uint32_t a = p.points[kPatchCorner[e]], b = p.points[kPatchCorner[(e + 1) % 3]];
            if (!kept(a) && !kept(b)) continue;
            auto [it, added] = edges.emplace(edgeKey(a, b), 3 * k + uint32_t(e));
            if (added) continue;
            const uint32_t other = *it;
            const RegularPatch& q = level.regular[other / 3];
            if (maskedEdge(p, e) || maskedEdge(q, int(other % 3))) continue;
            if (kept(a)) joins.emplace_back(node(l, k, e), node(l, other / 3, cornerOf(q, a)));
            if (kept(b)) joins.emplace_back(node(l, k, (e + 1) % 3), node(l, other / 3, cornerOf(q, b)));
        }
    }
    // Across levels: a corner at an end of a coarser root edge.
    for (uint32_t k = 0; k < level.regular.size(); ++k) {
        const RegularPatch& p = level.regular[k];
        for (int e = 0; e < 3; ++e) {
            uint32_t r = wl.regularEdge[3 * k + uint32_t(e)];
            if (r == kNoSource || maskedEdge(p, e)) continue;
            const EdgeRoot& root = plan.roots[r];
            const RegularPatch& coarse = asset.levels[root.level].regular[root.patch];
            uint32_t ca = coarse.points[kPatchCorner[root.edge]], cb = coarse.points[kPatchCorner[(root.edge + 1) % 3]];
            for (int c : {e, (e + 1) % 3}) {
                if (!kept(p.points[kPatchCorner[c]])) continue;
                // The fine corner's canonical parameter on its own edge, then the root's.
                bool atStart = (c == e) != edgeFlipped(p.points, e);
                float xc = root.offset + root.scale * (atStart ? 0.0f : 1.0f);
                if (xc != 0.0f && xc != 1.0f) continue;
                uint32_t vertex = (xc == 0.0f) == (ca < cb) ? ca : cb;
                joins.emplace_back(node(l, k, c), node(root.level, root.patch, cornerOf(coarse, vertex)));
            }
        }
    }
    // Irregular faces: a corner joins the regular patches across its face's edges.
    const LimitStencils& ls = level.limit;
    for (const IrregularFace& f : level.irregular)
        for (int c = 0; c < 3; ++c) {
            uint32_t s0 = f.corners[c], s1 = f.corners[(c + 1) % 3];
            const uint32_t v0 = ls.vertex[s0], v1 = ls.vertex[s1];
            if (!kept(v0) && !kept(v1)) continue;
            const uint32_t* it = edges.find(edgeKey(v0, v1));
            if (!it) continue;
            const RegularPatch& q = level.regular[*it / 3];
            if (maskedEdge(q, int(*it % 3))) continue;
            if (kept(v0)) joins.emplace_back(stencilNode + s0, node(l, *it / 3, cornerOf(q, v0)));
            if (kept(v1)) joins.emplace_back(stencilNode + s1, node(l, *it / 3, cornerOf(q, v1)));
        }
    return joins;
}

}  // namespace

// The levels' joins are found as independent tasks and applied in level order; a
// sector's root is its smallest node whatever the order of the joins, so the plan
// is the same for every thread count.
void assignCreaseNormals(const Asset& asset, WatertightPlan& plan, bool masked, size_t threads) {
    const size_t levels = plan.levels.size();
    std::vector<uint32_t> firstPatch(levels + 1, 0), firstStencil(levels + 1, 0);
    for (size_t l = 0; l < levels; ++l) {
        firstPatch[l + 1] = firstPatch[l] + uint32_t(asset.levels[l].regular.size());
        firstStencil[l + 1] = firstStencil[l] + asset.levels[l].limit.count();
    }
    uint32_t stencilBase = 3 * firstPatch[levels];
    auto node = [&](size_t l, uint32_t k, int c) { return 3 * (firstPatch[l] + k) + uint32_t(c); };

    // Each vertex's ancestor, and the ancestors with a masked node (none: no sectors;
    // with one, the plan has every level).
    std::vector<uint32_t> ancestor;
    std::vector<uint8_t> marked;
    if (masked) {
        ancestor.resize(asset.totalVertexCount());
        for (uint32_t v = 0; v < asset.controlVertexCount(); ++v) ancestor[v] = v;
        for (size_t l = 1; l < levels; ++l) {
            const Refinement& r = asset.levels[l].refinement;
            for (uint32_t i = 0; i < r.vertexPointCount(); ++i)
                ancestor[r.firstVertex + i] = ancestor[r.vertexParent[i]];
            for (uint32_t i = r.vertexPointCount(); i < r.vertexCount(); ++i)
                ancestor[r.firstVertex + i] = r.firstVertex + i;
        }
        marked.assign(ancestor.size(), 0);
        for (size_t l = 0; l < levels; ++l) {
            const Level& level = asset.levels[l];
            for (const RegularPatch& p : level.regular)
                for (int c = 0; c < 3 && p.boundaryMask; ++c)
                    if (maskedCorner(p, c)) marked[ancestor[p.points[kPatchCorner[c]]]] = 1;
            for (uint32_t m : level.limit.masked) marked[ancestor[level.limit.vertex[m]]] = 1;
        }
    }
    auto kept = [&](uint32_t v) { return marked[ancestor[v]] != 0; };

    UnionFind sectors(ancestor.empty() ? 0 : stencilBase + firstStencil[levels]);
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> joins(ancestor.empty() ? 0 : levels);
    fmt::parallelTasks(joins.size(), setupThreads(stencilBase, threads), [&](size_t l, size_t) {
        joins[l] = levelJoins(asset, plan, uint32_t(l), stencilBase + firstStencil[l], node, kept);
    });
    for (const auto& level : joins)
        for (auto [a, b] : level) sectors.join(a, b);

    // Each sector's normal: its root, when that is a regular corner.
    std::unordered_map<uint32_t, uint32_t> normalOf;  // sector root -> index into plan.normals (few: crease corners)
    auto sectorNormal = [&](uint32_t n) {
        uint32_t root = sectors.find(n);
        if (root >= stencilBase) return kNoSource;
        auto [it, added] = normalOf.emplace(root, uint32_t(plan.normals.size()));
        if (added) {
            uint32_t patch = root / 3;
            size_t l = std::upper_bound(firstPatch.begin(), firstPatch.end(), patch) - firstPatch.begin() - 1;
            plan.normals.push_back({uint32_t(l), patch - firstPatch[l], uint8_t(root % 3)});
        }
        return it->second;
    };
    for (size_t l = 0; l < levels; ++l) {
        const Level& level = asset.levels[l];
        WatertightLevel& wl = plan.levels[l];
        wl.regularNormal.assign(3 * level.regular.size(), kNoSource);
        for (uint32_t k = 0; k < level.regular.size(); ++k)
            for (int c = 0; c < 3; ++c)
                if (maskedCorner(level.regular[k], c))
                    wl.regularNormal[3 * k + uint32_t(c)] = sectorNormal(node(l, k, c));
        const LimitStencils& ls = level.limit;
        wl.stencilNormal.assign(ls.count(), kNoSource);
        for (uint32_t m : ls.masked) {
            uint32_t n = sectorNormal(stencilBase + firstStencil[l] + m);
            if (n != kNoSource && plan.normals[n].level <= l) wl.stencilNormal[m] = n;
        }
    }
    assignBaseNormals(asset, plan);
}

void assignBaseNormals(const Asset& asset, WatertightPlan& plan) {
    const Level& base = asset.levels[0];
    std::vector<uint32_t> irregularOf(asset.faceCount(), kNoSource);  // base face -> level 0 irregular face
    for (uint32_t k = base.irregular.size(); k-- > 0;) irregularOf[base.irregular[k].param.baseFace] = k;
    auto masked = [](const LimitStencils& ls, uint32_t st) {
        return std::binary_search(ls.masked.begin(), ls.masked.end(), st);
    };
    for (size_t l = 0; l < plan.levels.size(); ++l) {
        const Level& level = asset.levels[l];
        WatertightLevel& wl = plan.levels[l];
        wl.stencilBaseNormal.assign(level.limit.count(), kNoSource);
        if (l == 0) continue;
        const int32_t size = int32_t(1) << l;  // the base face's side, in level-l steps
        for (const IrregularFace& f : level.irregular)
            for (int c = 0; c < 3; ++c) {
                const uint32_t st = f.corners[c];
                if (!masked(level.limit, st) || wl.stencilNormal[st] != kNoSource) continue;
                // Corner c's place on the base face: (ui, vi) + (s, t), or - (s, t) rotated.
                const int32_t sign = f.param.rotated ? -1 : 1;
                const int32_t u = int32_t(f.param.ui) + sign * (c == 1), v = int32_t(f.param.vi) + sign * (c == 2);
                const int baseCorner = u == 0 && v == 0 ? 0 : u == size && v == 0 ? 1 : u == 0 && v == size ? 2 : -1;
                const uint32_t irregular = irregularOf[f.param.baseFace];
                if (baseCorner < 0 || irregular == kNoSource) continue;
                const uint32_t s0 = base.irregular[irregular].corners[baseCorner];
                if (masked(base.limit, s0) && plan.levels[0].stencilNormal[s0] == kNoSource &&
                    wl.stencilBaseNormal[st] == kNoSource)
                    wl.stencilBaseNormal[st] = s0;
            }
    }
}

}  // namespace lt
