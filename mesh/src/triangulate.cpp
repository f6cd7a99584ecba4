// lt::triangulatePolygons (looptess/tools/triangulate.h).
#include "looptess/tools/triangulate.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace lt {
namespace {

struct Vec {
    double x = 0, y = 0, z = 0;
};
Vec operator-(const Vec& a, const Vec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec cross(const Vec& a, const Vec& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

uint64_t edgeKey(uint32_t a, uint32_t b) { return a < b ? uint64_t(a) << 32 | b : uint64_t(b) << 32 | a; }

// A split candidate: the fan from `corner`, ranked by what it would do to the mesh.
struct Candidate {
    uint32_t corner = 0;
    uint32_t conflicts = 0;  // diagonals that are edges of other faces, or join a vertex to itself
    uint32_t folds = 0;      // triangles against the polygon's normal, or of zero area
    double length2 = 0;      // a quad's diagonal, squared
};

class Splitter {
public:
    Splitter(const std::vector<float>& positions, const std::vector<uint32_t>& counts,
             const std::vector<uint32_t>& indices, Triangulation& out)
        : positions_(positions), counts_(counts), indices_(indices), out_(out) {}

    void run() {
        uses_.reserve(indices_.size());
        forEachPolygon([&](uint32_t, size_t first, uint32_t n) {
            for (uint32_t k = 0; k < n; ++k) ++uses_[edgeKey(vertex(first, k, n), vertex(first, k + 1, n))];
        });
        forEachPolygon([&](uint32_t p, size_t first, uint32_t n) {
            if (n == 3)
                emit(p, first, 0, 1, 2);
            else
                split(p, first, n);
        });
    }

private:
    // Calls f(polygon, first face-vertex, corners) for each polygon of 3 corners or
    // more that `indices` holds whole.
    template <typename F>
    void forEachPolygon(F&& f) const {
        size_t first = 0;
        for (uint32_t p = 0; p < counts_.size(); ++p) {
            const uint32_t n = counts_[p];
            if (n > indices_.size() - std::min(first, indices_.size())) return;
            if (n >= 3) f(p, first, n);
            first += n;
        }
    }

    uint32_t vertex(size_t first, uint32_t k, uint32_t n) const { return indices_[first + k % n]; }

    Vec point(uint32_t v) const {
        if (3 * size_t(v) + 2 >= positions_.size()) return {};
        const float* q = &positions_[3 * size_t(v)];
        return {q[0], q[1], q[2]};
    }

    // Whether triangle (a, b, c) faces against `normal` or has zero area relative to
    // its longest edge (as mesh_clean's zeroAreaTriangle measures it).
    bool folds(uint32_t a, uint32_t b, uint32_t c, const Vec& unitNormal) const {
        const Vec pa = point(a), pb = point(b), pc = point(c);
        const Vec e0 = pb - pa, e1 = pc - pb, e2 = pa - pc;
        const double longest = std::max({dot(e0, e0), dot(e1, e1), dot(e2, e2)});
        return !(dot(cross(e0, pc - pa), unitNormal) > 1e-7 * longest);
    }

    Candidate rank(size_t first, uint32_t n, uint32_t k, const Vec& unitNormal) const {
        Candidate c;
        c.corner = k;
        const uint32_t apex = vertex(first, k, n);
        for (uint32_t j = 1; j + 1 < n; ++j) {
            const uint32_t b = vertex(first, k + j, n), d = vertex(first, k + j + 1, n);
            if (j + 1 < n - 1) {  // apex-d is a diagonal (of a repeated vertex: no edge at all)
                auto it = uses_.find(edgeKey(apex, d));
                c.conflicts += apex == d || (it != uses_.end() && it->second > 0);
            }
            c.folds += folds(apex, b, d, unitNormal);
        }
        if (n == 4) {
            const Vec diagonal = point(vertex(first, k + 2, n)) - point(apex);
            c.length2 = dot(diagonal, diagonal);
        }
        return c;
    }

    // Whether `a` is a better split than `b` (triangulate.h's order).
    static bool better(const Candidate& a, const Candidate& b, uint32_t n) {
        if (a.conflicts != b.conflicts) return a.conflicts < b.conflicts;
        if (a.folds != b.folds) return a.folds < b.folds;
        if (n == 4) {
            const double tie = 1e-6 * std::max(a.length2, b.length2);
            if (std::abs(a.length2 - b.length2) > tie) return a.length2 < b.length2;
        }
        return a.corner < b.corner;
    }

    void split(uint32_t p, size_t first, uint32_t n) {
        Vec normal;  // Newell's
        for (uint32_t k = 0; k < n; ++k) {
            const Vec a = point(vertex(first, k, n)), b = point(vertex(first, k + 1, n));
            normal.x += (a.y - b.y) * (a.z + b.z);
            normal.y += (a.z - b.z) * (a.x + b.x);
            normal.z += (a.x - b.x) * (a.y + b.y);
        }
        const double length = std::sqrt(dot(normal, normal));
        if (length > 0) normal = {normal.x / length, normal.y / length, normal.z / length};
        const uint32_t tries = n == 4 ? 2 : std::min(n, kMaxFanCorners);
        Candidate best = rank(first, n, 0, normal);
        for (uint32_t k = 1; k < tries; ++k) {
            const Candidate c = rank(first, n, k, normal);
            if (better(c, best, n)) best = c;
        }
        if (best.conflicts > 0)
            out_.unsplittable.push_back(p);
        else if (best.folds > 0)
            out_.folded.push_back(p);
        const uint32_t k = best.corner;
        for (uint32_t j = 1; j + 1 < n; ++j) {
            emit(p, first, k, (k + j) % n, (k + j + 1) % n);
            if (j + 1 < n - 1) uses_[edgeKey(vertex(first, k, n), vertex(first, k + j + 1, n))] += 2;
        }
    }

    void emit(uint32_t p, size_t first, uint32_t a, uint32_t b, uint32_t c) {
        out_.corners.insert(out_.corners.end(), {uint32_t(first + a), uint32_t(first + b), uint32_t(first + c)});
        out_.polygon.push_back(p);
    }

    const std::vector<float>& positions_;
    const std::vector<uint32_t>& counts_;
    const std::vector<uint32_t>& indices_;
    Triangulation& out_;
    std::unordered_map<uint64_t, uint32_t> uses_;  // faces at each edge, either way
};

}  // namespace

Triangulation triangulatePolygons(const std::vector<float>& positions, const std::vector<uint32_t>& counts,
                                  const std::vector<uint32_t>& indices) {
    Triangulation out;
    Splitter(positions, counts, indices, out).run();
    std::unordered_map<uint32_t, uint32_t> polygonsAt;  // vertex -> polygons; 0: one of a triangle
    for (size_t p = 0, c = 0; p < counts.size(); c += counts[p++])
        for (size_t k = 0; k < counts[p]; ++k) {
            auto [it, added] = polygonsAt.try_emplace(indices[c + k], 0);
            it->second = added && counts[p] > 3 ? 1 : 2;
        }
    for (const auto& [vertex, polygons] : polygonsAt)
        if (polygons == 1) out.polygonCorners.push_back(vertex);
    std::sort(out.polygonCorners.begin(), out.polygonCorners.end());
    return out;
}

void keepPolygonCorners(const std::vector<uint32_t>& polygonCorners, InputMesh& mesh) {
    if (mesh.boundary != BoundaryInterpolation::EdgeAndCorner) return;
    std::vector<uint32_t> tagged;
    for (const InputMesh::Corner& c : mesh.corners) tagged.push_back(c.vertex);
    std::sort(tagged.begin(), tagged.end());
    for (uint32_t v : polygonCorners)
        if (!std::binary_search(tagged.begin(), tagged.end(), v)) mesh.corners.push_back({v, 10.0f});
}

}  // namespace lt
