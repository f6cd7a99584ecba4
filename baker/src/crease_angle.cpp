// crease_angle.cpp -- lt::addCreasesByAngle: automatic sharp edges by dihedral angle.
#include "looptess/tools/baker.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lt {
namespace {

constexpr float kInfinitelySharp = 10.0f;

using Vec3 = std::array<double, 3>;

// Unnormalized normal of triangle f (zero for degenerate or out-of-range faces).
Vec3 faceNormal(const InputMesh& mesh, size_t f) {
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) {
        uint32_t v = mesh.faces[3 * f + k];
        if (v >= mesh.vertexCount()) return {0, 0, 0};
        for (int c = 0; c < 3; ++c) p[k][c] = mesh.positions[3 * size_t(v) + c];
    }
    Vec3 e1, e2;
    for (int c = 0; c < 3; ++c) {
        e1[c] = p[1][c] - p[0][c];
        e2[c] = p[2][c] - p[0][c];
    }
    return {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
}

// Angle between two normals in radians; negative when either is zero.
double normalAngle(const Vec3& n, const Vec3& m) {
    Vec3 x = {n[1] * m[2] - n[2] * m[1], n[2] * m[0] - n[0] * m[2], n[0] * m[1] - n[1] * m[0]};
    double dot = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
    double cross = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    bool zero = (n[0] == 0 && n[1] == 0 && n[2] == 0) || (m[0] == 0 && m[1] == 0 && m[2] == 0);
    return zero ? -1.0 : std::atan2(cross, dot);
}

// Face uses of undirected edges, sorted by edge then face.
struct EdgeFace {
    uint32_t lo, hi, face;
    bool operator<(const EdgeFace& o) const { return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : face < o.face; }
};

}  // namespace

void addCreasesByAngle(InputMesh& mesh, float degrees) {
    assert(degrees >= 0 && degrees <= 180);
    const double limit = double(degrees) * 3.14159265358979323846 / 180.0;

    std::vector<EdgeFace> uses;
    uses.reserve(mesh.faces.size());
    for (uint32_t f = 0; f < mesh.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = mesh.faces[3 * f + k], b = mesh.faces[3 * f + (k + 1) % 3];
            uses.push_back({std::min(a, b), std::max(a, b), f});
        }
    std::sort(uses.begin(), uses.end());

    std::vector<std::pair<uint32_t, uint32_t>> existing;  // explicit creases win
    for (const InputMesh::Crease& c : mesh.creases) existing.emplace_back(std::min(c.a, c.b), std::max(c.a, c.b));
    std::sort(existing.begin(), existing.end());

    for (size_t i = 0; i < uses.size();) {
        size_t j = i;
        while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
        const EdgeFace& e = uses[i];
        bool manifold = j - i == 2 && e.lo != e.hi;
        if (manifold && !std::binary_search(existing.begin(), existing.end(), std::make_pair(e.lo, e.hi))) {
            double angle = normalAngle(faceNormal(mesh, e.face), faceNormal(mesh, uses[i + 1].face));
            if (angle > limit) mesh.creases.push_back({e.lo, e.hi, kInfinitelySharp});
        }
        i = j;
    }
}

}  // namespace lt
