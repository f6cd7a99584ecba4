// baker/src/hard_edges.cpp -- lt::HardEdges (hard_edges.h).
#include "hard_edges.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

namespace lt {
namespace {

constexpr float kHardSharpness = 10.0f;

// Face uses of undirected edges: the edge, the face, and the corners at lo and hi.
struct EdgeCorners {
    uint32_t lo, hi, face;
    uint8_t cornerLo, cornerHi;
    bool operator<(const EdgeCorners& o) const {
        return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : face < o.face;
    }
};

}  // namespace

void HardEdges::addFace(const double* n0, const double* n1, const double* n2) {
    const double* n[3] = {n0, n1, n2};
    for (const double* c : n) {
        float unit[3] = {0, 0, 0};
        const double length = c ? std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) : 0.0;
        if (length > 0 && std::isfinite(length))
            for (int k = 0; k < 3; ++k) unit[k] = float(c[k] / length);
        normals_.insert(normals_.end(), unit, unit + 3);
    }
}

void HardEdges::erase(const std::vector<uint8_t>& drop) {
    assert(drop.size() == faceCount());
    size_t out = 0;
    for (size_t f = 0; f < drop.size(); ++f)
        if (!drop[f]) std::copy_n(&normals_[9 * f], 9, &normals_[9 * out++]);
    normals_.resize(9 * out);
}

size_t HardEdges::addCreases(InputMesh& mesh) const {
    assert(mesh.faceCount() == faceCount());
    std::vector<EdgeCorners> uses;
    uses.reserve(mesh.faces.size());
    for (uint32_t f = 0; f < mesh.faceCount(); ++f)
        for (uint8_t k = 0; k < 3; ++k) {
            const uint8_t j = uint8_t((k + 1) % 3);
            const uint32_t a = mesh.faces[3 * f + k], b = mesh.faces[3 * f + j];
            uses.push_back(a < b ? EdgeCorners{a, b, f, k, j} : EdgeCorners{b, a, f, j, k});
        }
    std::sort(uses.begin(), uses.end());
    std::vector<std::pair<uint32_t, uint32_t>> existing;
    for (const InputMesh::Crease& c : mesh.creases) existing.emplace_back(std::min(c.a, c.b), std::max(c.a, c.b));
    std::sort(existing.begin(), existing.end());

    const double limit = std::cos(kHardEdgeDegrees * 3.14159265358979323846 / 180.0);
    auto normal = [&](uint32_t face, uint8_t corner) { return &normals_[9 * size_t(face) + 3 * corner]; };
    auto apart = [&](const float* n, const float* m) {
        const bool unknown = (n[0] == 0 && n[1] == 0 && n[2] == 0) || (m[0] == 0 && m[1] == 0 && m[2] == 0);
        return !unknown && double(n[0]) * m[0] + double(n[1]) * m[1] + double(n[2]) * m[2] < limit;
    };
    size_t added = 0;
    for (size_t i = 0; i < uses.size();) {
        size_t j = i;
        while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
        const EdgeCorners &f = uses[i], &g = uses[j - 1];
        if (j - i == 2 && !std::binary_search(existing.begin(), existing.end(), std::make_pair(f.lo, f.hi)) &&
            (apart(normal(f.face, f.cornerLo), normal(g.face, g.cornerLo)) ||
             apart(normal(f.face, f.cornerHi), normal(g.face, g.cornerHi)))) {
            mesh.creases.push_back({f.lo, f.hi, kHardSharpness});
            ++added;
        }
        i = j;
    }
    return added;
}

}  // namespace lt
