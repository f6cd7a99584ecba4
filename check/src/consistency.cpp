// Topology consistency of a baked asset (checks C1-C6 of looptess/tools/check.h).
//
// Loop's child topology, level l-1 -> l (V(p): vertex point of p, E(a,b): edge
// point of edge a-b; a face (a, b, c) splits into four):
//
//   ring(V(p))    = { E(p, q) : q in ring(p) }
//   ring(E(a,b))  = { V(a), V(b), E(b,c), E(c,a), E(a,d), E(d,b) }   faces (a,b,c), (b,a,d)
//
// Level 0's rings come from the control faces. A level's derived rings use its own
// tables (its vertex points' parents and stored rings, its edge points' ends and
// opposite vertices): a vertex kept only as a patch point may have neighbours the
// sparse tables do not keep, so a derived ring is complete or partial (its known
// members are true neighbours; infinitely sharp edge points store no opposite
// vertices, so their rings are partial too). Each check uses what is known and
// never reports a partial ring's missing members.
#include "check_internal.h"

#include <algorithm>
#include <string>
#include <unordered_map>

namespace lt {
namespace {

std::string str(uint64_t v) { return std::to_string(v); }

uint64_t pairKey(uint32_t a, uint32_t b) { return uint64_t(std::min(a, b)) << 32 | std::max(a, b); }

// The derived 1-rings of one level's vertices, indexed by local vertex number.
struct LevelRings {
    uint32_t first = 0, count = 0;
    std::vector<uint32_t> start, items;  // CSR, each ring sorted, global indices
    std::vector<uint8_t> complete;
};

class Checker {
public:
    Checker(const Asset& asset, const std::string& name) : a_(asset), name_(name) {}
    Status run();

private:
    const Asset& a_;
    const std::string& name_;
    std::vector<LevelRings> rings_;
    std::vector<std::unordered_map<uint32_t, uint32_t>> vertexChild_;  // [l]: level l-1 vertex -> V at level l
    // [l]: pair of level l-1 -> E at level l; several for multi-edges (two edges
    // between the same vertices, e.g. around valence-2 vertices).
    std::vector<std::unordered_multimap<uint64_t, uint32_t>> edgeChild_;

    Status fail(const std::string& where, int check, const std::string& what) const {
        return Status::error(Status::BadInput,
                             name_ + ": " + where + ": check C" + std::to_string(check) + ": " + what);
    }
    const LevelRings& ringsOf(uint32_t global) const {
        size_t m = rings_.size() - 1;
        while (m > 0 && global < rings_[m].first) --m;
        return rings_[m];
    }
    // 1: `b` is a neighbour of `a`, 0: it is not, -1: unknown (a's ring is partial).
    int adjacent(uint32_t a, uint32_t b) const {
        const LevelRings& r = ringsOf(a);
        if (a - r.first >= r.count) return -1;
        const uint32_t i = a - r.first;
        const uint32_t* s = r.items.data() + r.start[i];
        const uint32_t* e = r.items.data() + r.start[i + 1];
        if (std::binary_search(s, e, b)) return 1;
        return r.complete[i] ? 0 : -1;
    }
    // Fails unless a and b can be neighbours (checked from both sides).
    bool mayBeAdjacent(uint32_t a, uint32_t b) const { return adjacent(a, b) != 0 && adjacent(b, a) != 0; }

    void buildLevel0();
    void buildLevel(uint32_t l);
    Status checkLevel0Primitives() const;
    Status checkRefinement(uint32_t l) const;
    Status checkPrimitives(uint32_t l) const;
};

void Checker::buildLevel0() {
    LevelRings& r = rings_[0];
    r.first = 0;
    r.count = a_.controlVertexCount();
    std::vector<std::vector<uint32_t>> nb(r.count);
    for (size_t f = 0; f + 2 < a_.faces.size(); f += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t x = a_.faces[f + size_t(k)], y = a_.faces[f + size_t(k + 1) % 3];
            nb[x].push_back(y);
            nb[y].push_back(x);
        }
    r.start.assign(1, 0);
    for (auto& n : nb) {
        std::sort(n.begin(), n.end());
        n.erase(std::unique(n.begin(), n.end()), n.end());
        r.items.insert(r.items.end(), n.begin(), n.end());
        r.start.push_back(uint32_t(r.items.size()));
    }
    r.complete.assign(r.count, 1);
}

void Checker::buildLevel(uint32_t l) {
    const Refinement& ref = a_.levels[l].refinement;
    auto& vchild = vertexChild_[l];
    auto& echild = edgeChild_[l];
    const uint32_t V = ref.vertexPointCount(), E = ref.edgePointCount();
    for (uint32_t i = 0; i < V; ++i) vchild.emplace(ref.vertexParent[i], ref.firstVertex + i);
    for (uint32_t k = 0; k < E; ++k)
        echild.emplace(pairKey(ref.edgeVerts[4 * k], ref.edgeVerts[4 * k + 1]), ref.firstVertex + V + k);
    LevelRings& r = rings_[l];
    r.first = ref.firstVertex;
    r.count = V + E;
    r.start.assign(1, 0);
    r.complete.assign(r.count, 1);
    std::vector<uint32_t> ring;
    // The edge points of edge x-y. `all`: every edge between x and y is a
    // neighbour; otherwise only one is (the one in a given face), and several
    // candidates leave the ring partial.
    auto edgePoint = [&](uint32_t x, uint32_t y, uint32_t i, bool all) {
        const auto range = echild.equal_range(pairKey(x, y));
        const size_t n = size_t(std::distance(range.first, range.second));
        if (n == 0 || (n > 1 && !all))
            r.complete[i] = 0;
        else
            for (auto it = range.first; it != range.second; ++it) ring.push_back(it->second);
    };
    auto vertexPoint = [&](uint32_t x, uint32_t i) {
        auto it = vchild.find(x);
        if (it == vchild.end())
            r.complete[i] = 0;
        else
            ring.push_back(it->second);
    };
    for (uint32_t i = 0; i < r.count; ++i) {
        ring.clear();
        if (i < V) {
            const uint32_t p = ref.vertexParent[i];
            for (uint32_t j = ref.vertexRingStart[i]; j < ref.vertexRingStart[i + 1]; ++j)
                edgePoint(p, ref.vertexRing[j], i, true);
        } else {
            const uint32_t* e = &ref.edgeVerts[4 * size_t(i - V)];
            vertexPoint(e[0], i);
            vertexPoint(e[1], i);
            // Opposite vertices equal to an end are not stored (infinitely sharp
            // edges): those faces' edge points are unknown. d == c: one face.
            for (int j = 2; j < 4; ++j) {
                if (e[j] == e[0] || e[j] == e[1])
                    r.complete[i] = 0;
                else if (j == 2 || e[3] != e[2]) {
                    edgePoint(e[1], e[j], i, false);
                    edgePoint(e[j], e[0], i, false);
                }
            }
        }
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
        r.items.insert(r.items.end(), ring.begin(), ring.end());
        r.start.push_back(uint32_t(r.items.size()));
    }
}

Status Checker::checkLevel0Primitives() const {
    const Level& l0 = a_.levels[0];
    for (size_t i = 0; i < l0.regular.size(); ++i) {
        const RegularPatch& p = l0.regular[i];
        const uint32_t* c = &a_.faces[3 * size_t(p.param.baseFace)];
        if (p.points[4] != c[0] || p.points[5] != c[1] || p.points[8] != c[2])
            return fail("levels[0].regularPoints[" + str(12 * i) + "]", 1,
                        "patch " + str(i) + " has corners " + str(p.points[4]) + ", " + str(p.points[5]) + ", " +
                            str(p.points[8]) + ", its base face " + str(p.param.baseFace) + " has " + str(c[0]) + ", " +
                            str(c[1]) + ", " + str(c[2]));
    }
    for (size_t i = 0; i < l0.irregular.size(); ++i) {
        const IrregularFace& f = l0.irregular[i];
        const uint32_t* c = &a_.faces[3 * size_t(f.param.baseFace)];
        for (int k = 0; k < 3; ++k)
            if (l0.limit.vertex[f.corners[k]] != c[k])
                return fail("levels[0].irregularCorners[" + str(3 * i + size_t(k)) + "]", 1,
                            "irregular face " + str(i) + " corner " + str(uint64_t(k)) + " is vertex " +
                                str(l0.limit.vertex[f.corners[k]]) + ", corner " + str(uint64_t(k)) +
                                " of its base face " + str(f.param.baseFace) + " is " + str(c[k]));
    }
    return Status::ok();
}

Status Checker::checkRefinement(uint32_t l) const {
    const Refinement& ref = a_.levels[l].refinement;
    const LevelRings& parents = rings_[l - 1];
    const std::string level = "levels[" + str(l) + "].";
    std::vector<uint32_t> ring;
    for (uint32_t i = 0; i < ref.vertexPointCount(); ++i) {
        const uint32_t p = ref.vertexParent[i], pi = p - parents.first;
        ring.assign(ref.vertexRing.begin() + ref.vertexRingStart[i],
                    ref.vertexRing.begin() + ref.vertexRingStart[i + 1]);
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());  // multi-edges name a vertex twice
        const uint32_t* s = parents.items.data() + parents.start[pi];
        const uint32_t* e = parents.items.data() + parents.start[pi + 1];
        const std::string where = level + "vertexRing[" + str(ref.vertexRingStart[i]) + "]";
        const std::string who = "vertex point " + str(i) + " (parent vertex " + str(p) + ")";
        for (const uint32_t* x = s; x != e; ++x)
            if (!std::binary_search(ring.begin(), ring.end(), *x))
                return fail(where, 2, who + ": its ring misses neighbour " + str(*x));
        if (parents.complete[pi] && ring.size() != size_t(e - s))
            for (uint32_t x : ring)
                if (!std::binary_search(s, e, x))
                    return fail(where, 2, who + ": its ring has vertex " + str(x) + ", not a neighbour");
    }
    for (uint32_t k = 0; k < ref.edgePointCount(); ++k) {
        const uint32_t* v = &ref.edgeVerts[4 * size_t(k)];
        const std::string where = level + "edgeVerts[" + str(4 * uint64_t(k)) + "]";
        const std::string who = "edge point " + str(k) + " (" + str(v[0]) + ", " + str(v[1]) + ")";
        if (!mayBeAdjacent(v[0], v[1])) return fail(where, 3, who + ": its ends are not neighbours");
        for (int j = 2; j < 4; ++j) {
            if (v[j] == v[0] || v[j] == v[1]) continue;  // no opposite vertex stored (sharp or boundary)
            if (!mayBeAdjacent(v[j], v[0]) || !mayBeAdjacent(v[j], v[1]))
                return fail(where, 3, who + ": opposite vertex " + str(v[j]) + " is not a neighbour of both ends");
        }
    }
    return Status::ok();
}

// Neighbour pairs of the 12-point patch (asset.h's diagram).
constexpr int kLattice[][2] = {{0, 1}, {1, 2}, {3, 4}, {4, 5}, {5, 6},  {7, 8},  {8, 9},  {10, 11},
                               {0, 3}, {0, 4}, {1, 4}, {1, 5}, {2, 5},  {2, 6},  {3, 7},  {4, 7},
                               {4, 8}, {5, 8}, {5, 9}, {6, 9}, {7, 10}, {8, 10}, {8, 11}, {9, 11}};

uint16_t phantomPoints(uint8_t mask) {
    static const int edge[3][3] = {{0, 1, 2}, {6, 9, 11}, {10, 7, 3}};
    static const int corner[3][2] = {{3, 0}, {2, 6}, {11, 10}};
    uint16_t bits = 0;
    for (int i = 0; i < 3; ++i) {
        if (mask & (1u << i))
            for (int p : edge[i]) bits = uint16_t(bits | 1u << p);
        if (mask & (1u << (3 + i)))
            for (int p : corner[i]) bits = uint16_t(bits | 1u << p);
    }
    return bits;
}

Status Checker::checkPrimitives(uint32_t l) const {
    const Level& level = a_.levels[l];
    const std::string at = "levels[" + str(l) + "].";
    for (size_t i = 0; i < level.regular.size(); ++i) {
        const RegularPatch& p = level.regular[i];
        const uint16_t phantom = phantomPoints(p.boundaryMask);
        for (const auto& pair : kLattice) {
            if (phantom & (1u << pair[0]) || phantom & (1u << pair[1])) continue;
            if (!mayBeAdjacent(p.points[pair[0]], p.points[pair[1]]))
                return fail(at + "regularPoints[" + str(12 * i + size_t(pair[0])) + "]", 4,
                            "patch " + str(i) + ": points " + str(uint64_t(pair[0])) + " and " +
                                str(uint64_t(pair[1])) + " (vertices " + str(p.points[pair[0]]) + ", " +
                                str(p.points[pair[1]]) + ") are not neighbours");
        }
    }
    const LimitStencils& ls = level.limit;
    for (size_t i = 0; i < level.irregular.size(); ++i) {
        const IrregularFace& f = level.irregular[i];
        for (int k = 0; k < 3; ++k) {
            const uint32_t x = ls.vertex[f.corners[k]], y = ls.vertex[f.corners[(k + 1) % 3]];
            if (!mayBeAdjacent(x, y))
                return fail(
                    at + "irregularCorners[" + str(3 * i + size_t(k)) + "]", 5,
                    "irregular face " + str(i) + ": corners " + str(x) + " and " + str(y) + " are not neighbours");
        }
    }
    std::vector<uint32_t> ring;
    std::vector<bool> masked(ls.count(), false);
    for (uint32_t m : ls.masked) masked[m] = true;
    for (uint32_t s = 0; s < ls.count(); ++s) {
        const uint32_t v = ls.vertex[s];
        const LevelRings& r = ringsOf(v);
        const uint32_t vi = v - r.first;
        for (uint32_t j = ls.start[s]; j < ls.start[s + 1]; ++j)
            if (adjacent(v, ls.ring[j]) == 0)
                return fail(
                    at + "limitRing[" + str(j) + "]", 6,
                    "stencil " + str(s) + " of vertex " + str(v) + " names " + str(ls.ring[j]) + ", not a neighbour");
        if (masked[s] || !r.complete[vi]) continue;
        ring.assign(ls.ring.begin() + ls.start[s], ls.ring.begin() + ls.start[s + 1]);
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
        if (ring.size() != r.start[vi + 1] - r.start[vi])
            return fail(at + "limitRing[" + str(ls.start[s]) + "]", 6,
                        "smooth stencil " + str(s) + " of vertex " + str(v) + " names " + str(ring.size()) +
                            " neighbours, the vertex has " + str(r.start[vi + 1] - r.start[vi]));
    }
    return Status::ok();
}

Status Checker::run() {
    const uint32_t levels = uint32_t(a_.levels.size());
    rings_.resize(levels);
    vertexChild_.resize(levels);
    edgeChild_.resize(levels);
    buildLevel0();
    for (uint32_t l = 1; l < levels; ++l) buildLevel(l);
    if (Status st = checkLevel0Primitives(); !st) return st;
    for (uint32_t l = 1; l < levels; ++l)
        if (Status st = checkRefinement(l); !st) return st;
    for (uint32_t l = 0; l < levels; ++l)
        if (Status st = checkPrimitives(l); !st) return st;
    return Status::ok();
}

}  // namespace

Status checkConsistency(const Asset& asset, const std::string& name) { return Checker(asset, name).run(); }

Status checkStructure(const uint8_t* data, size_t size, const std::string& name, Asset& asset) {
    if (Status st = readAssetGlb(data, size, name, asset); !st) return st;
    return checkConsistency(asset, name);
}

Status checkSceneStructure(const uint8_t* data, size_t size, const std::string& name,
                           std::vector<SceneSurface>& surfaces) {
    if (Status st = readSceneGlb(data, size, name, surfaces); !st) return st;
    for (const SceneSurface& s : surfaces)
        if (Status st = checkConsistency(s.asset, surfaceName(name, surfaces, s)); !st) return st;
    return Status::ok();
}

std::string surfaceName(const std::string& file, const std::vector<SceneSurface>& surfaces, const SceneSurface& s) {
    if (surfaces.size() == 1) return file;
    return file + ": meshes[" + std::to_string(s.mesh) + "]" + (s.name.empty() ? "" : " (" + s.name + ")");
}

}  // namespace lt
