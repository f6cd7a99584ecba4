// Private to the runtime: how a regular patch is cut into the sub-triangles that
// are tessellated, and their edge factors (paper 3.2.2, Fig. 8; 3.3).
//
// The CPU evaluator (cpu_evaluate.cpp) and the Vulkan path's draw plan use these;
// the tessellation control shader (shaders/patch.tesc) applies the same rules.
//
// Domain points of a patch, in its (s,t), by id:
//
//     C2 (0,1)
//     |  \  .             0 C0, 1 C1, 2 C2: corners
//     M2   M1             3 M0, 4 M1, 5 M2: midpoints of edges 0, 1, 2
//     |      \            (edge i joins Ci and C(i+1))
//     C0 -M0- C1
//
//   split edges   sub-triangles (counter-clockwise in (s,t))
//   none          C0 C1 C2
//   i             Ci Mi C(i+2) | Mi C(i+1) C(i+2)
//   i, i+1        Mi C(i+1) M(i+1) | Ci Mi M(i+1) | Ci M(i+1) C(i+2)
//   all           C0 M0 M2 | M0 C1 M1 | M2 M1 C2 | M1 M2 M0
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lt {

constexpr int kDomainM0 = 3;  // first midpoint id

// The points of a RegularPatch at its corners C0, C1, C2 (asset.h: the patch
// triangle 4, 5, 8), and the key of the edge between two global vertices.
inline constexpr int kPatchCorner[3] = {4, 5, 8};
inline uint64_t edgeKey(uint32_t a, uint32_t b) { return a < b ? uint64_t(a) << 32 | b : uint64_t(b) << 32 | a; }

struct SubTriangle {
    int p[3];  // domain point ids A, B, C
};

// Sub-triangles for a split mask (RegularPatch::splitMask); returns their count (1..4).
inline int subTriangles(uint8_t splitMask, SubTriangle out[4]) {
    auto C = [](int i) { return i % 3; };
    auto M = [](int i) { return kDomainM0 + i % 3; };
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

// Edge factors of one patch of level l, by the kind of sub-triangle edge:
//
//     C2                     edge[i]     the whole patch edge i (Ci - C(i+1))
//     |  \                   half[i][0]  Ci - Mi   } halves of a split edge i,
//     M2 - M1                half[i][1]  Mi - C(i+1) } the finer level's edges
//     |  \ |  \               across      corner - midpoint through the patch
//     C0 - M0 - C1            middle      midpoint - midpoint
//
// Global factor F: coarse = F / 2^l for edge and across, fine = F / 2^(l+1) for
// half and middle. Screen-space LOD fills them per edge (lod.h).
struct PatchFactors {
    float edge[3];
    float half[3][2];
    float across;
    float middle;
};

inline PatchFactors uniformPatchFactors(float coarse, float fine) {
    PatchFactors f;
    for (int i = 0; i < 3; ++i) {
        f.edge[i] = coarse;
        f.half[i][0] = f.half[i][1] = fine;
    }
    f.across = coarse;
    f.middle = fine;
    return f;
}

// The factor of level l's regular patches at global factor F: F / 2^l, exact in
// float (runtime.h). The shaders compute it as ldexp(F, -l) too.
inline float levelFactor(float tessFactor, uint32_t level) { return std::ldexp(tessFactor, -int(level)); }

// The factors of a level-l patch at global factor F: coarse F / 2^l, fine F / 2^(l+1).
inline PatchFactors levelPatchFactors(float tessFactor, uint32_t level) {
    return uniformPatchFactors(levelFactor(tessFactor, level), levelFactor(tessFactor, level + 1));
}

// Factor of the sub-triangle edge between domain points a and b.
inline float subEdgeFactor(int a, int b, const PatchFactors& f) {
    bool ca = a < kDomainM0, cb = b < kDomainM0;
    if (ca && cb) return f.edge[b == (a + 1) % 3 ? a : b];
    if (!ca && !cb) return f.middle;
    int c = ca ? a : b, m = (ca ? b : a) - kDomainM0;
    if (c == m) return f.half[m][0];
    if (c == (m + 1) % 3) return f.half[m][1];
    return f.across;
}

// Fractional-odd spacing: a factor f a little above an odd integer n splits an edge
// into n + 2 segments, two of them short, and shrinks the innermost ring of the
// triangle to a point (f = n + e):
//
//     n = 3, e = 0.9        n = 3, e = 0.001          e < kOddSnapWidth: drawn as n
//     |--|-|---|-|--|       |---||-----||---|         |-----|-----|-----|
//       the innermost ring: a triangle e / 2f of the edge wide
//
// The tessellator's fixed-point domain points of such a ring are distinct, but their
// evaluated positions are not: float rounding welds some of them and not others, and
// the welded surface folds (edges used by four triangles; a closed mesh at
// screen-space factors). A factor less than kOddSnapWidth above an odd
// integer is therefore drawn as that integer, on the CPU here and on the GPU in
// patch.tesc, operation for operation (every step below is exact in float). The
// ring is then at least 1 / (16 f) of its edge wide; a factor crossing n + 1/8
// pops that ring in, where without the snap it would grow from a point.
constexpr float kOddSnapWidth = 0.125f;
inline float snapOddFactor(float f) {
    float n = 2.0f * std::floor((f - 1.0f) * 0.5f) + 1.0f;  // the largest odd integer <= f (f >= 1)
    return f - n < kOddSnapWidth ? n : f;
}

// Outer and inner factors of sub-triangle (A, B, C) in the tessellator's order:
// outer[0] edge C-A, outer[1] edge A-B, outer[2] edge B-C (tess_domain.h); the
// inner factor is the largest outer one. `odd`: fractional-odd spacing (snapOddFactor).
inline void subTriangleFactors(const SubTriangle& q, const PatchFactors& f, bool odd, float outer[3], float& inner) {
    outer[0] = subEdgeFactor(q.p[2], q.p[0], f);
    outer[1] = subEdgeFactor(q.p[0], q.p[1], f);
    outer[2] = subEdgeFactor(q.p[1], q.p[2], f);
    if (odd)
        for (int e = 0; e < 3; ++e) outer[e] = snapOddFactor(outer[e]);
    inner = std::max(outer[0], std::max(outer[1], outer[2]));
}

}  // namespace lt
