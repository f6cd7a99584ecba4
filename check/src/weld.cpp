// Bitwise watertightness: weld a soup by the exact bits of its positions and count
// its edges (check_internal.h, weldTessellation).
#include "check_internal.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace lt {
// Named, not anonymous: PieceWeld::Impl holds these.
namespace welding {

uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

uint32_t keyBits(float x) {
    uint32_t b;
    std::memcpy(&b, &x, 4);
    return b == 0x80000000u ? 0u : b;  // -0 welds with +0: the same value
}

// Open addressing from exact position bits to welded vertex ids, growing at half load.
class VertexWeld {
public:
    explicit VertexWeld(size_t expected) { rehash(std::max<size_t>(64, expected)); }
    // The welded id of `p` (a new one when unseen); `isNew` says which.
    uint32_t insert(const float p[3], bool& isNew) {
        const uint32_t k[3] = {keyBits(p[0]), keyBits(p[1]), keyBits(p[2])};
        size_t slot = hash(k) & mask_;
        while (slots_[slot] != kEmpty) {
            const uint32_t* o = &keys_[3 * size_t(slots_[slot])];
            if (o[0] == k[0] && o[1] == k[1] && o[2] == k[2]) {
                isNew = false;
                return slots_[slot];
            }
            slot = (slot + 1) & mask_;
        }
        isNew = true;
        const uint32_t id = uint32_t(keys_.size() / 3);
        keys_.insert(keys_.end(), k, k + 3);
        slots_[slot] = id;
        if (2 * (size_t(id) + 1) > slots_.size()) rehash(slots_.size() * 2);
        return id;
    }

private:
    static constexpr uint32_t kEmpty = ~0u;
    static size_t hash(const uint32_t k[3]) {
        return size_t(mix(uint64_t(k[0]) << 32 ^ mix(uint64_t(k[1]) << 32 | k[2])));
    }
    void rehash(size_t want) {
        size_t cap = 64;
        while (cap < want) cap *= 2;
        slots_.assign(cap, kEmpty);
        mask_ = cap - 1;
        for (uint32_t id = 0; id < keys_.size() / 3; ++id) {
            size_t slot = hash(&keys_[3 * size_t(id)]) & mask_;
            while (slots_[slot] != kEmpty) slot = (slot + 1) & mask_;
            slots_[slot] = id;
        }
    }
    std::vector<uint32_t> slots_, keys_;
    size_t mask_ = 0;
};

// Bound on the distance between soup triangle t and the surface it samples.
float chordBound(const Tessellation& soup, size_t t) {
    const float* p = &soup.positions[9 * t];
    const float* nv = &soup.normals[9 * t];
    double e[3][3], longest = 0;
    for (int k = 0; k < 3; ++k) {
        double len = 0;
        for (int c = 0; c < 3; ++c) {
            e[k][c] = double(p[3 * ((k + 1) % 3) + c]) - double(p[3 * k + c]);
            len += e[k][c] * e[k][c];
        }
        longest = std::max(longest, std::sqrt(len));
    }
    double face[3] = {e[0][1] * e[2][2] - e[0][2] * e[2][1], e[0][2] * e[2][0] - e[0][0] * e[2][2],
                      e[0][0] * e[2][1] - e[0][1] * e[2][0]};
    const double fl = std::sqrt(face[0] * face[0] + face[1] * face[1] + face[2] * face[2]);
    // The cosine of the angle between a and b; -1 (pi) where either is zero.
    auto cosine = [](const double* a, const double* b) {
        double d = 0, la = 0, lb = 0;
        for (int c = 0; c < 3; ++c) d += a[c] * b[c], la += a[c] * a[c], lb += b[c] * b[c];
        if (!(la > 0 && lb > 0)) return -1.0;
        return std::clamp(d / std::sqrt(la * lb), -1.0, 1.0);
    };
    double n[3][3];
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) n[k][c] = nv[3 * k + c];
    // The face normal is -(e0 x e2) = e0 x (p2 - p0): facing like the CCW corners.
    for (double& x : face) x = -x;
    // The largest angle is the acos of the smallest cosine: one acos, not six (acos was
    // a tenth of loopcheck's time). A NaN cosine is passed over, as a NaN angle was.
    double least = 1;
    for (int k = 0; k < 3; ++k) {
        least = std::min(least, cosine(n[k], n[(k + 1) % 3]));
        if (fl > 0) least = std::min(least, cosine(n[k], face));
    }
    const double theta = std::acos(least);
    const double b = longest * theta / 4;
    return std::isfinite(b) ? float(b) : INFINITY;
}

// An edge's key from its welded ends: min << 32 | max.
inline uint64_t edgeKey(uint32_t a, uint32_t b) { return uint64_t(std::min(a, b)) << 32 | std::max(a, b); }

// Whether a triangle's welded corners `c` repeat one (no edges of its own).
inline bool degenerate(const uint32_t* c) { return c[0] == c[1] || c[1] == c[2] || c[2] == c[0]; }

struct EdgeSlot {
    uint64_t key = 0;  // edgeKey; 0 is empty (no triangle has an edge (0, 0))
    uint32_t use = 0;  // 3 t + k of the first use: soup triangle t, its edge k
    // Uses, and uses from min to max; each stops at 65535 (only 1, 2 and more matter).
    uint16_t count = 0, forward = 0;
};
static_assert(sizeof(EdgeSlot) == 16, "the table is loopcheck's largest at high factors");

// Edges by key, open addressing: it starts at twice the triangles (a closed mesh has
// 1.5 edges a triangle) and doubles past 3/4 load (an open soup has up to 3). An
// edge's probe starts in its smaller vertex's run of slots: welded ids follow the
// soup, so nearby triangles probe nearby slots (a random hash spent most of the weld
// in cache misses). The runs are of the ids `base` .. `base + vertices` (a piece's
// new ones); the few ids below, of earlier pieces, wrap round.
class EdgeTable {
public:
    EdgeTable(size_t triangles, size_t vertices, uint32_t base)
        : vertices_(std::max<size_t>(1, vertices)), base_(base) {
        size_t cap = 64;
        while (cap < 2 * triangles) cap *= 2;
        resize(cap);
    }
    // The slot of `key`, new (key set, counts 0) when unseen; valid until the next call.
    EdgeSlot& at(uint64_t key) {
        if (4 * (size_ + 1) > 3 * slots_.size()) resize(2 * slots_.size());
        EdgeSlot& e = slots_[probe(key)];
        if (e.key == 0) e.key = key, ++size_;
        return e;
    }
    const std::vector<EdgeSlot>& slots() const { return slots_; }
    size_t size() const { return size_; }

private:
    size_t probe(uint64_t key) const {
        size_t slot = (size_t(uint32_t(key >> 32) - base_) * stride_) & mask_;
        while (slots_[slot].key != 0 && slots_[slot].key != key) slot = (slot + 1) & mask_;
        return slot;
    }
    void resize(size_t cap) {
        std::vector<EdgeSlot> old(cap);
        old.swap(slots_);
        mask_ = cap - 1;
        stride_ = std::max<size_t>(1, cap / vertices_);
        for (const EdgeSlot& e : old)
            if (e.key != 0) slots_[probe(e.key)] = e;
    }
    std::vector<EdgeSlot> slots_;
    size_t size_ = 0, mask_ = 0, stride_ = 1, vertices_;
    uint32_t base_;
};

// The base edge of face `f` that soup vertices i and j both lie on, as a control
// edge kind; kInterior when none does.
uint8_t baseEdgeKind(const Tessellation& soup, const ControlTopology& topo, size_t i, size_t j) {
    const double eps = 1e-6;
    auto on = [&](size_t v, int e) {
        const double u = soup.uv[2 * v], w = soup.uv[2 * v + 1];
        return e == 0 ? std::fabs(w) <= eps : e == 1 ? std::fabs(u + w - 1.0) <= eps : std::fabs(u) <= eps;
    };
    const size_t f = soup.face[i];
    uint8_t kind = ControlTopology::kInterior;
    if (3 * f + 2 >= topo.edgeKind.size()) return kind;
    for (int e = 0; e < 3; ++e)
        if (on(i, e) && on(j, e)) kind = std::max(kind, topo.edgeKind[3 * f + size_t(e)]);
    return kind;
}

// T-junctions among the open edges (see check.h): `open` holds directed edges (a, b).
void countTJunctions(const std::vector<float>& pos, const std::vector<std::pair<uint32_t, uint32_t>>& open,
                     WeldResult& out) {
    std::vector<std::pair<uint32_t, uint32_t>> byFrom(open);
    std::sort(byFrom.begin(), byFrom.end());
    auto P = [&](uint32_t v) { return &pos[3 * size_t(v)]; };
    struct Frame {
        uint32_t vertex;
        double t;
        int depth;
    };
    std::vector<Frame> stack;
    for (const auto& [a, b] : open) {
        double ab[3], len2 = 0;
        for (int c = 0; c < 3; ++c) ab[c] = double(P(b)[c]) - double(P(a)[c]), len2 += ab[c] * ab[c];
        if (!(len2 > 0)) continue;
        stack.assign(1, {b, 1.0, 0});
        uint64_t inner = 0;
        bool found = false;
        int budget = 1024;  // expansions per edge: branching is rare, never unbounded
        while (!stack.empty() && !found && budget-- > 0) {
            const Frame f = stack.back();
            stack.pop_back();
            auto it = std::lower_bound(byFrom.begin(), byFrom.end(), std::make_pair(f.vertex, 0u));
            for (; it != byFrom.end() && it->first == f.vertex; ++it) {
                const uint32_t y = it->second;
                if (y == a) {
                    if (f.depth >= 1) found = true, inner = uint64_t(f.depth);
                    continue;
                }
                if (f.depth >= 64) continue;
                double ay[3], t = 0;
                for (int c = 0; c < 3; ++c) ay[c] = double(P(y)[c]) - double(P(a)[c]), t += ay[c] * ab[c];
                t /= len2;
                double d2 = 0;
                for (int c = 0; c < 3; ++c) d2 += (ay[c] - t * ab[c]) * (ay[c] - t * ab[c]);
                if (t > 0 && t < f.t && d2 <= len2 / 64) stack.push_back({y, t, f.depth + 1});
            }
        }
        if (found) ++out.tJunctions, out.tJunctionVertices += inner;
    }
}

// One use of an edge that its piece did not settle (PieceWeld): what the count
// over every piece needs, and what the first failure's message says.
struct EdgeUse {
    uint64_t key;   // edgeKey of the welded ids
    uint64_t use;   // 3 t + k: soup triangle t of the pieces' soups in order, its edge k
    uint32_t a, b;  // the welded ids from corner k to k + 1
    uint32_t face;  // the triangle's base face
    float uv[4];    // (u, v) of corners k and k + 1
    double normal[3];
    uint8_t kind;  // baseEdgeKind
    bool folded;   // the base face is ControlTopology::folded
};

}  // namespace welding

struct PieceWeld::Impl {
    const ControlTopology* topology = nullptr;  // null: the weld alone (weldMesh)
    WeldedMesh local;
    WeldedMesh* mesh = nullptr;
    welding::VertexWeld weld{64};
    std::vector<float> firstNormal;      // per welded vertex, the normal of its first soup vertex
    std::vector<uint8_t> split;          // per welded vertex: a soup normal differs from it
    WeldResult partial;                  // the counts of the pieces so far
    uint64_t soupTriangles = 0;          // of the pieces so far
    std::vector<welding::EdgeUse> uses;  // of the edges their pieces did not settle
    bool pieces = false;                 // several: settledKeys kept
    std::vector<uint64_t> settledKeys;   // every piece's settled edges
    std::vector<uint64_t> again;         // settled in a piece, used in another (sorted)
    uint64_t againTriangles = 0;         // of the pieces given again so far

    // `base`: the first welded id the piece made.
    void countEdges(const Tessellation& piece, const std::vector<uint32_t>& id, uint32_t base);
    // Use k of triangle t of `piece` kept, the piece's first triangle `first` of all.
    void keep(const Tessellation& piece, const std::vector<uint32_t>& id, size_t t, uint32_t k, uint64_t first);
    // Every use in `piece` of the edges `keys` (sorted) kept.
    void keepUses(const Tessellation& piece, const std::vector<uint32_t>& id, const std::vector<uint64_t>& keys,
                  uint64_t first);
};

void PieceWeld::Impl::keepUses(const Tessellation& piece, const std::vector<uint32_t>& id,
                               const std::vector<uint64_t>& keys, uint64_t first) {
    for (size_t t = 0; t < piece.triangleCount(); ++t) {
        const uint32_t* c = &id[3 * t];
        if (welding::degenerate(c)) continue;
        for (uint32_t k = 0; k < 3; ++k)
            if (std::binary_search(keys.begin(), keys.end(), welding::edgeKey(c[k], c[(k + 1) % 3])))
                keep(piece, id, t, k, first);
    }
}

void PieceWeld::Impl::keep(const Tessellation& piece, const std::vector<uint32_t>& id, size_t t, uint32_t k,
                           uint64_t first) {
    const ControlTopology& topo = *topology;
    const size_t i = 3 * t + k, j = 3 * t + (k + 1) % 3;
    welding::EdgeUse u{};
    u.a = id[i], u.b = id[j];
    u.key = welding::edgeKey(u.a, u.b);
    u.use = 3 * (first + t) + k;
    u.face = piece.face[i];
    u.uv[0] = piece.uv[2 * i], u.uv[1] = piece.uv[2 * i + 1], u.uv[2] = piece.uv[2 * j], u.uv[3] = piece.uv[2 * j + 1];
    geometricNormal(piece, t, u.normal);
    u.kind = welding::baseEdgeKind(piece, topo, i, j);
    u.folded = !topo.folded.empty() && topo.folded[u.face];
    uses.push_back(u);
}

PieceWeld::PieceWeld(const ControlTopology* topology, WeldedMesh* mesh, uint64_t triangles, bool pieces)
    : impl_(new Impl) {
    impl_->topology = topology;
    impl_->pieces = pieces && topology;
    if (impl_->pieces) impl_->settledKeys.reserve(3 * triangles / 2 + 64);  // a closed mesh's edges
    WeldedMesh& m = *(impl_->mesh = mesh ? mesh : &impl_->local);
    m = WeldedMesh{};
    // Exact-size buffers: growth by doubling would hold old and new at once.
    m.triangles.reserve(3 * triangles);
    m.chordBound.reserve(triangles);
    m.soupTriangle.reserve(triangles);
}
PieceWeld::~PieceWeld() = default;

void PieceWeld::add(const Tessellation& piece) {
    Impl& m = *impl_;
    WeldedMesh& mesh = *m.mesh;
    WeldResult& out = m.partial;
    const bool edges = m.topology != nullptr;
    const size_t n = piece.vertexCount(), triangles = piece.triangleCount();
    if (out.vertices == 0) m.weld = welding::VertexWeld(n / 4);  // the first piece
    std::vector<uint32_t> id(n);
    const uint32_t base = uint32_t(mesh.vertexCount());
    for (size_t i = 0; i < n; ++i) {
        const float* p = &piece.positions[3 * i];
        if (edges && !(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) ++out.nonFiniteVertices;
        bool isNew = false;
        id[i] = m.weld.insert(p, isNew);
        const float* normal = &piece.normals[3 * i];
        if (isNew) {
            mesh.positions.insert(mesh.positions.end(), p, p + 3);
            if (edges) m.firstNormal.insert(m.firstNormal.end(), normal, normal + 3), m.split.push_back(0);
        } else if (edges && !m.split[id[i]] && std::memcmp(&m.firstNormal[3 * size_t(id[i])], normal, 12) != 0) {
            m.split[id[i]] = 1;
            ++out.normalSplitVertices;
        }
    }
    out.vertices += n;
    out.triangles += triangles;
    if (mesh.chordBound.capacity() < mesh.chordBound.size() + triangles) {  // pieces not announced
        mesh.triangles.reserve(mesh.triangles.size() + 3 * triangles);
        mesh.chordBound.reserve(mesh.chordBound.size() + triangles);
        mesh.soupTriangle.reserve(mesh.soupTriangle.size() + triangles);
    }
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t* c = &id[3 * t];
        if (welding::degenerate(c)) {
            ++out.degenerateTriangles;
            continue;
        }
        mesh.triangles.insert(mesh.triangles.end(), c, c + 3);
        mesh.chordBound.push_back(welding::chordBound(piece, t));
        mesh.soupTriangle.push_back(uint32_t(m.soupTriangles + t));
    }
    if (edges) m.countEdges(piece, id, base);
    m.soupTriangles += triangles;
}

// The piece's edges: a well-oriented pair is settled here, every other edge's uses
// are kept (EdgeUse) for finish (a pair whose edge another piece uses too is found
// by needsAgain).
void PieceWeld::Impl::countEdges(const Tessellation& piece, const std::vector<uint32_t>& id, uint32_t base) {
    using namespace welding;
    EdgeTable edges(piece.triangleCount(), mesh->vertexCount() - base, base);
    for (size_t t = 0; t < piece.triangleCount(); ++t) {
        const uint32_t* c = &id[3 * t];
        if (degenerate(c)) continue;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t a = c[k], b = c[(k + 1) % 3];
            EdgeSlot& e = edges.at(edgeKey(a, b));
            if (e.count == 0) e.use = uint32_t(3 * t + k);
            if (e.count < UINT16_MAX) ++e.count;
            if (a < b && e.forward < UINT16_MAX) ++e.forward;
        }
    }
    // The edges used twice or more that are kept: all their uses, found again below.
    std::vector<uint64_t> twice;
    uint64_t settled = 0;
    for (const EdgeSlot& e : edges.slots()) {
        if (e.key == 0) continue;
        const size_t t = e.use / 3;
        const uint32_t k = e.use % 3;
        if (e.count == 2 && e.forward == 1) {
            ++settled;
            if (pieces) settledKeys.push_back(e.key);
            continue;
        }
        if (e.count == 1)
            keep(piece, id, t, k, soupTriangles);
        else
            twice.push_back(e.key);
    }
    partial.edges += settled;
    if (twice.empty()) return;
    std::sort(twice.begin(), twice.end());
    keepUses(piece, id, twice, soupTriangles);
}

bool PieceWeld::needsAgain() {
    Impl& m = *impl_;
    std::vector<uint64_t>& settled = m.settledKeys;
    if (!m.pieces || settled.empty()) return false;
    std::sort(settled.begin(), settled.end());
    std::vector<uint64_t> kept;  // the keys of the uses kept
    kept.reserve(m.uses.size());
    for (const welding::EdgeUse& u : m.uses) kept.push_back(u.key);
    std::sort(kept.begin(), kept.end());
    // Settled in two pieces, or settled in one and kept in another. Their settled
    // pairs leave the edge count: finish counts each of them once from its uses.
    std::vector<uint64_t>& again = m.again;
    for (size_t i = 0; i < settled.size(); ++i) {
        const bool twice = (i + 1 < settled.size() && settled[i + 1] == settled[i]) ||
                           (i > 0 && settled[i - 1] == settled[i]) ||
                           std::binary_search(kept.begin(), kept.end(), settled[i]);
        if (!twice) continue;
        --m.partial.edges;
        if (again.empty() || again.back() != settled[i]) again.push_back(settled[i]);
    }
    std::vector<uint64_t>().swap(settled);
    if (again.empty()) return false;
    // Every use of them is found again, the kept ones too.
    auto within = [&](const welding::EdgeUse& u) { return std::binary_search(again.begin(), again.end(), u.key); };
    m.uses.erase(std::remove_if(m.uses.begin(), m.uses.end(), within), m.uses.end());
    return true;
}

void PieceWeld::addAgain(const Tessellation& piece) {
    Impl& m = *impl_;
    std::vector<uint32_t> id(piece.vertexCount());
    for (size_t i = 0; i < id.size(); ++i) {
        bool isNew = false;
        id[i] = m.weld.insert(&piece.positions[3 * i], isNew);
        assert(!isNew && "the pieces given again are the pieces given");
    }
    m.keepUses(piece, id, m.again, m.againTriangles);
    m.againTriangles += piece.triangleCount();
}

void PieceWeld::finish(WeldResult& out) {
    Impl& m = *impl_;
    out = m.partial;
    WeldedMesh& mesh = *m.mesh;
    out.weldedVertices = mesh.vertexCount();
    m.weld = welding::VertexWeld(64);
    std::vector<float>().swap(m.firstNormal);
    std::vector<uint8_t>().swap(m.split);
    mesh.positions.push_back(0.0f);  // Embree reads 16 bytes for the last vertex
    if (!m.topology) return;
    using welding::EdgeUse;
    std::vector<EdgeUse>& uses = m.uses;
    std::sort(uses.begin(), uses.end(),
              [](const EdgeUse& x, const EdgeUse& y) { return x.key != y.key ? x.key < y.key : x.use < y.use; });
    std::vector<std::pair<uint32_t, uint32_t>> open;
    const EdgeUse* first = nullptr;  // the failing edge of the lowest soup triangle
    const char* firstKind = "";
    auto failed = [&](const EdgeUse& e, const char* what) {
        if (!first || e.use < first->use) first = &e, firstKind = what;
    };
    for (size_t lo = 0, hi = 0; lo < uses.size(); lo = hi) {
        const EdgeUse& e = uses[lo];  // its first use
        uint64_t count = 0, forward = 0;
        // Such an edge is the surface touching itself where every triangle on it is of
        // a folded control face (a triangle doubled back: its two sheets round to the
        // same floats), or where its triangles face opposite ways: the limit surface
        // folds there, and the points on either side of the fold round to the same
        // floats (a valence-3 fan of faces 0.1 wide beside faces 30 long, coplanar,
        // folds in its plane at F = 64); else it fails.
        bool unfolded = false, opposed = false;
        for (hi = lo; hi < uses.size() && uses[hi].key == e.key; ++hi) {
            const EdgeUse& u = uses[hi];
            ++count, forward += u.a < u.b;
            unfolded = unfolded || !u.folded;
            const double* n = u.normal;
            opposed = opposed || n[0] * e.normal[0] + n[1] * e.normal[1] + n[2] * e.normal[2] < 0;
        }
        ++out.edges;
        if (count == 2 && forward == 1) continue;
        if (count == 1) {
            ++out.openEdges;
            if (e.kind == ControlTopology::kBoundary)
                ++out.boundaryEdges;
            else
                ++out.crackEdges, open.emplace_back(e.a, e.b), failed(e, "crack");
        } else if (count >= 3) {
            ++out.nonManifoldEdges;
            if (e.kind == ControlTopology::kNonManifold) continue;
            if (!unfolded || opposed) {
                ++out.contactEdges;
                continue;
            }
            ++out.unexpectedNonManifoldEdges;
            failed(e, "non-manifold edge");
        } else if (e.kind != ControlTopology::kNonManifold) {
            ++out.misorientedEdges;
            failed(e, "misoriented edge");
        }
    }
    welding::countTJunctions(mesh.positions, open, out);
    if (first) {
        char text[160];
        std::snprintf(text, sizeof text, "%s: face %u (u, v) = (%.9g, %.9g) to (%.9g, %.9g)", firstKind, first->face,
                      double(first->uv[0]), double(first->uv[1]), double(first->uv[2]), double(first->uv[3]));
        out.firstFailure = text;
    }
    std::vector<EdgeUse>().swap(uses);
}

void weldMesh(const Tessellation& soup, WeldedMesh& out) {
    PieceWeld weld(nullptr, &out);
    weld.add(soup);
    WeldResult unused;
    weld.finish(unused);
}

void weldTessellation(const Tessellation& soup, const ControlTopology& topology, WeldResult& out, WeldedMesh* welded) {
    PieceWeld weld(&topology, welded);
    weld.add(soup);
    weld.finish(out);
}

}  // namespace lt
