// CPU evaluation of every patch at the tessellator's domain points.
//
// Sub-domains of a non-plain patch (paper Fig. 8). Corners C0, C1, C2 of the patch
// and midpoints M0, M1, M2 of its edges 0, 1, 2 (edge i joins Ci and C(i+1)):
//
//   split edges   sub-triangles (counter-clockwise in (s,t))
//   none          C0 C1 C2
//   i             Ci Mi C(i+2) | Mi C(i+1) C(i+2)
//   i, i+1        Mi C(i+1) M(i+1) | Ci Mi M(i+1) | Ci M(i+1) C(i+2)
//   all           C0 M0 M2 | M0 C1 M1 | M2 M1 C2 | M1 M2 M0
//
//        C2                    C2                   C2                  C2
//        |\                    |\                   |\                  |\       .
//        | \                   | \                  | \                 |  \     .
//        |  \                  |  \                 |   M1           M2 ----M1
//        |   \                 |   \                | /  \              | \   |\  .
//        |    \                |    \               |/    \             |  \  | \ .
//        C0----C1              C0-M0-C1             C0-M0--C1           C0---M0--C1
//         none                split 0          split 0, 1             split all
//
// Edge factors: a sub-triangle edge on half of a split edge takes the finer
// level's factor F/2^(l+1); an edge on an unsplit patch edge takes F/2^l; inner
// edges take F/2^(l+1) between two midpoints and F/2^l from a corner.
//
// Tessellator convention (tess_domain.h): a sub-triangle (A, B, C) maps the
// tessellation coordinate (x, y, z) to (s,t) = z A + x B + y C, so outer[0] is
// edge C-A, outer[1] edge A-B, outer[2] edge B-C.
#include "looptess/runtime.h"

#include "box_spline.h"
#include "tess_domain.h"

#include <array>
#include <cmath>
#include <map>

namespace lt {
namespace {

const float kDomain[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}};
enum : int { C0 = 0, M0 = 3 };

struct SubTriangle {
    int p[3];  // ids into kDomain
};

// Sub-triangles for a split mask, rotated from the base patterns above.
int subTriangles(uint8_t splitMask, SubTriangle out[4]) {
    auto C = [](int i) { return C0 + i % 3; };
    auto M = [](int i) { return M0 + i % 3; };
    int bits = (splitMask & 1) + ((splitMask >> 1) & 1) + ((splitMask >> 2) & 1);
    if (bits == 0) {
        out[0] = {{C(0), C(1), C(2)}};
        return 1;
    }
    if (bits == 3) {
        out[0] = {{C(0), M(0), M(2)}};
        out[1] = {{M(0), C(1), M(1)}};
        out[2] = {{M(2), M(1), C(2)}};
        out[3] = {{M(1), M(2), M(0)}};
        return 4;
    }
    if (bits == 1) {
        int i = splitMask == 1 ? 0 : splitMask == 2 ? 1 : 2;
        out[0] = {{C(i), M(i), C(i + 2)}};
        out[1] = {{M(i), C(i + 1), C(i + 2)}};
        return 2;
    }
    int i = splitMask == 3 ? 0 : splitMask == 6 ? 1 : 2;  // split edges i and i+1
    out[0] = {{M(i), C(i + 1), M(i + 1)}};
    out[1] = {{C(i), M(i), M(i + 1)}};
    out[2] = {{C(i), M(i + 1), C(i + 2)}};
    return 3;
}

bool isCorner(int id) { return id < M0; }

// Factor of the sub-triangle edge between domain points a and b.
float edgeFactor(int a, int b, float coarse, float fine) {
    if (isCorner(a) && isCorner(b)) return coarse;
    if (!isCorner(a) && !isCorner(b)) return fine;
    int c = isCorner(a) ? a - C0 : b - C0, m = isCorner(a) ? b - M0 : a - M0;
    bool onEdge = c == m || c == (m + 1) % 3;
    return onEdge ? fine : coarse;
}

void cross(const float a[3], const float b[3], float n[3]) {
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
}

class Evaluator {
public:
    Evaluator(const Asset& asset, const std::vector<float>& vertices, const EvalSettings& settings, Tessellation& out)
        : asset_(asset), v_(vertices), settings_(settings), out_(out) {}

    void regular(const RegularPatch& patch, uint32_t level, bool split);
    void irregular(const Level& level, const IrregularFace& face);

private:
    const TessDomain& domain(const float outer[3], float inner);
    void emit(const float pos[3], const float n[3], const PatchParam& param, float s, float t);

    const Asset& asset_;
    const std::vector<float>& v_;
    EvalSettings settings_;
    Tessellation& out_;
    std::map<std::array<float, 4>, TessDomain> domains_;
};

const TessDomain& Evaluator::domain(const float outer[3], float inner) {
    std::array<float, 4> key = {outer[0], outer[1], outer[2], inner};
    auto it = domains_.find(key);
    if (it != domains_.end()) return it->second;
    TessDomain& d = domains_[key];
    TessSpacing spacing = settings_.spacing == Spacing::Equal ? TessSpacing::Equal : TessSpacing::FractionalOdd;
    tessellateTriangle(outer, inner, spacing, d, TessWinding::Cw);  // Cw: counter-clockwise in (x,y)
    return d;
}

void Evaluator::emit(const float pos[3], const float n[3], const PatchParam& param, float s, float t) {
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) {
        out_.positions.push_back(pos[k]);
        out_.normals.push_back(len > 0.0f ? n[k] / len : 0.0f);
    }
    float d = std::ldexp(1.0f, -int(param.level));
    float sign = param.rotated ? -1.0f : 1.0f;
    out_.face.push_back(param.baseFace);
    out_.uv.push_back(d * (float(param.ui) + sign * s));
    out_.uv.push_back(d * (float(param.vi) + sign * t));
}

void Evaluator::regular(const RegularPatch& patch, uint32_t level, bool split) {
    float p[12][3];
    for (int i = 0; i < 12; ++i)
        for (int k = 0; k < 3; ++k) p[i][k] = v_[size_t(patch.points[i]) * 3 + k];
    fillPhantomPoints(patch.boundaryMask, p);
    float coarse = std::ldexp(settings_.tessFactor, -int(level));
    float fine = std::ldexp(settings_.tessFactor, -int(level) - 1);
    SubTriangle subs[4];
    int count = subTriangles(split ? patch.splitMask : 0, subs);
    for (int k = 0; k < count; ++k) {
        const int* q = subs[k].p;
        float outer[3] = {edgeFactor(q[2], q[0], coarse, fine), edgeFactor(q[0], q[1], coarse, fine),
                          edgeFactor(q[1], q[2], coarse, fine)};
        float inner = std::max(outer[0], std::max(outer[1], outer[2]));
        const TessDomain& d = domain(outer, inner);
        const float *A = kDomain[q[0]], *B = kDomain[q[1]], *C = kDomain[q[2]];
        for (uint32_t index : d.triangles) {
            const float* tc = &d.coords[size_t(index) * 3];
            float s = tc[2] * A[0] + tc[0] * B[0] + tc[1] * C[0];
            float t = tc[2] * A[1] + tc[0] * B[1] + tc[1] * C[1];
            float pos[3], du[3], dv[3], n[3];
            evalBoxSpline(p, s, t, pos, du, dv);
            cross(du, dv, n);
            emit(pos, n, patch.param, s, t);
        }
    }
}

void Evaluator::irregular(const Level& level, const IrregularFace& face) {
    static const float corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    const LimitStencils& ls = level.limit;
    for (int c = 0; c < 3; ++c) {
        uint32_t st = face.corners[c];
        float pos[3], tu[3], tv[3], n[3];
        // Position weights sum to 1 and tangent weights to 0, so both are summed
        // over differences from the vertex (entry 0), as in the subdivision rules.
        const float* centre = &v_[size_t(ls.ring[ls.start[st]]) * 3];
        for (int k = 0; k < 3; ++k) {
            float a = 0, b = 0, e = 0;
            for (uint32_t j = ls.start[st] + 1; j < ls.start[st + 1]; ++j) {
                float x = v_[size_t(ls.ring[j]) * 3 + k] - centre[k];
                a = a + ls.position[j] * x;
                b = b + ls.tangentU[j] * x;
                e = e + ls.tangentV[j] * x;
            }
            pos[k] = centre[k] + a;
            tu[k] = b;
            tv[k] = e;
        }
        cross(tu, tv, n);
        emit(pos, n, face.param, corner[c][0], corner[c][1]);
    }
}

} // namespace

uint32_t runtimeDepth(const Asset& asset, float tessFactor) {
    uint32_t d = 0;
    while (d < asset.maxDepth() && std::ldexp(1.0f, int(d)) < tessFactor) ++d;
    return d;
}

void evaluateCpu(const Asset& asset, const float* controlPositions, const EvalSettings& settings, Tessellation& out) {
    out = Tessellation{};
    uint32_t depth = runtimeDepth(asset, settings.tessFactor);
    std::vector<float> vertices;
    subdivideCpu(asset, controlPositions, depth, vertices);
    Evaluator eval(asset, vertices, settings, out);
    for (uint32_t l = 0; l <= depth; ++l) {
        const Level& level = asset.levels[l];
        for (const RegularPatch& patch : level.regular) eval.regular(patch, l, l < depth);
        if (l == depth)
            for (const IrregularFace& face : level.irregular) eval.irregular(level, face);
    }
}

} // namespace lt
