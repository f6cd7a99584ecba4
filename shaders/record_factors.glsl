// record_factors.glsl -- the edge factors of a draw record (gpu_layout.h): patch.tesc
// hands them to the tessellator, pattern_sort.comp picks a refinement pattern from
// them. Include after common.glsl.
//
// A record names a patch and one sub-triangle (A, B, C) of its domain: the whole
// triangle, or a piece of a non-plain patch split towards finer neighbours (paper
// Fig. 8). Domain points, in the patch's (s,t):
//
//     C2 (0,1)
//     |  \                ids: 0 C0, 1 C1, 2 C2 (corners)
//     M2   M1                  3 M0, 4 M1, 5 M2 (edge midpoints; Mi on edge i,
//     |      \                                   which joins Ci and C(i+1))
//     C0 -M0- C1
//   (0,0)     (1,0)
//
// Factors, level l, global factor F (sub_patches.h's PatchFactors):
//   sub-triangle edge between two corners         edge[i]    F / 2^l
//   between two midpoints (inner edge)             middle     F / 2^(l+1)
//   corner-midpoint on the patch edge (half edge)  half       F / 2^(l+1)
//   corner-midpoint across the patch               across     F / 2^l
// With LT_FLAG_LOD_SCREEN each of them comes from the edge's own end vertices
// instead, bounded by the value above: runtime/internal/lod.h, which this file follows
// operation for operation (precise; only + - * min max, and / and sqrt rounded
// correctly by exact_math.glsl, as the CPU rounds them), so the CPU evaluator and
// every device pick bit-identical factors.
#ifndef LT_RECORD_FACTORS_GLSL
#define LT_RECORD_FACTORS_GLSL

#include "exact_math.glsl"

const vec2 kDomain[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(0.5, 0), vec2(0.5, 0.5), vec2(0, 0.5));

bool isCorner(uint id) { return id < LT_DOMAIN_M0; }

struct Factors {
    float edge[3], halfA[3], halfB[3];  // halfA[i]: Ci - Mi, halfB[i]: Mi - C(i+1)
    float across, middle;
};

Factors uniformFactors(float coarse, float fine) {
    Factors f;
    for (int i = 0; i < 3; ++i) {
        f.edge[i] = coarse;
        f.halfA[i] = fine;
        f.halfB[i] = fine;
    }
    f.across = coarse;
    f.middle = fine;
    return f;
}

// lod.h's edgeFactor.
float lodEdgeFactor(vec3 a, vec3 b) {
    precise float dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    precise float squaredLength = dx * dx + dy * dy + dz * dz;
    float len = exactSqrt(squaredLength);
    precise float mx = (a.x + b.x) * 0.5 - pc.lod.x, my = (a.y + b.y) * 0.5 - pc.lod.y, mz = (a.z + b.z) * 0.5 - pc.lod.z;
    precise float squaredDistance = mx * mx + my * my + mz * mz;
    float dist = exactSqrt(squaredDistance);
    precise float scaled = len * pc.lod.w;
    return exactDivide(scaled, max(dist, 1e-20));
}

float clampFactor(float f, float cap) { return min(max(f, 1.0), max(cap, 1.0)); }

// lod.h's screenPatchFactors; `split`: the patch's LT_SPLIT_WORDS when the record
// has a midpoint (the patch is drawn split), else LT_NONE.
Factors screenFactors(vec3 corner[3], uint split, int level) {
    float cap = ldexp(pc.tessFactor, -level), capFine = ldexp(pc.tessFactor, -level - 1);
    Factors f;
    float across = 1.0;
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3;
        f.edge[i] = clampFactor(lodEdgeFactor(corner[i], corner[j]), cap);
        uint edgePoint = split == LT_NONE ? LT_NONE : word(split + 3u + uint(i));
        if (edgePoint != LT_NONE) {
            vec3 mid = vertexAt(edgePoint);
            f.halfA[i] = clampFactor(lodEdgeFactor(vertexAt(word(split + uint(i))), mid), capFine);
            f.halfB[i] = clampFactor(lodEdgeFactor(mid, vertexAt(word(split + uint(j)))), capFine);
            precise float whole = f.halfA[i] + f.halfB[i];
            across = max(across, whole);
        } else {  // halves unused: an edge that is not split has no midpoint
            f.halfA[i] = f.edge[i];
            f.halfB[i] = f.edge[i];
            across = max(across, f.edge[i]);
        }
    }
    f.across = across;
    precise float halfAcross = across * 0.5;
    f.middle = max(halfAcross, 1.0);
    return f;
}

float edgeFactor(uint a, uint b, Factors f) {
    if (isCorner(a) && isCorner(b)) return f.edge[b == (a + 1u) % 3u ? a : b];
    if (!isCorner(a) && !isCorner(b)) return f.middle;
    uint c = isCorner(a) ? a : b, m = (isCorner(a) ? b : a) - LT_DOMAIN_M0;
    if (c == m) return f.halfA[m];
    if (c == (m + 1u) % 3u) return f.halfB[m];
    return f.across;
}

// The outer factors of `record` in the tessellator's order (patch.tese's diagram:
// o.x the sub-triangle's edge C - A, o.y A - B, o.z B - C), before any spacing rule.
// corner: the patch's level-l corners, points 4, 5 and 8 of its 12.
vec3 recordOuterFactors(uint record, uint patchWords, uint info, vec3 corner[3]) {
    uint q0 = (record >> LT_RECORD_PATCH_BITS) & 7u, q1 = (record >> (LT_RECORD_PATCH_BITS + 3)) & 7u,
         q2 = (record >> (LT_RECORD_PATCH_BITS + 6)) & 7u;
    int level = int((info >> 8) & 0xffu);
    Factors f;
    if ((pc.flags & LT_FLAG_LOD_SCREEN) != 0u) {
        bool split = !isCorner(q0) || !isCorner(q1) || !isCorner(q2);
        f = screenFactors(corner, split ? word(patchWords + LT_PATCH_SPLIT) : LT_NONE, level);
    } else {
        f = uniformFactors(ldexp(pc.tessFactor, -level), ldexp(pc.tessFactor, -level - 1));
    }
    return vec3(edgeFactor(q2, q0, f), edgeFactor(q0, q1, f), edgeFactor(q1, q2, f));
}

#endif
