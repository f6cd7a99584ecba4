// patch.tesc -- per drawn patch: phantom points, the sub-triangle's corners and the
// tessellation factors, exactly as runtime/src/cpu_evaluate.cpp's Evaluator::regular.
//
// A record (gpu_layout.h) names a patch and one sub-triangle (A, B, C) of its
// domain: the whole triangle, or a piece of a non-plain patch split towards finer
// neighbours (paper Fig. 8). Domain points, in the patch's (s,t):
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
//   inner factor = max of the three outer factors
// With fractional-odd spacing (LT_FLAG_FRACTIONAL_ODD) each outer factor less than
// 1/8 above an odd integer is drawn as that integer (snapOddFactor below).
// With LT_FLAG_LOD_SCREEN each of them comes from the edge's own end vertices
// instead, bounded by the value above: runtime/src/lod.h, which this file follows
// operation for operation (precise; only + - * / sqrt min max), so the CPU
// evaluator picks bit-identical factors.
// Which outer level is which edge: see the diagram in patch.tese.
//
// Outputs: 4 control points, each carrying 3 of the patch's 12 points (box_spline.glsl's
// numbering) and, for watertight draws, 3 canonical points of each rooted edge:
//
//   output vertex v     0         1         2         3
//   tcPoint[v][m]       0  1  2   3  4  5   6  7  8   9 10 11   point 3v + m
//   wtEdge[v][3K + m]   rooted edge K's canonical point 3v + m (10 and 11 not written)
//
// (lavapipe runs a patch's invocations as one SIMD batch of at most 8: 12 output
// vertices took two.) Per-patch outputs: watertight.glsl's interface.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "box_spline.glsl"

// Four output vertices, three of the patch's 12 points each: lavapipe runs a patch's
// invocations as one batch of up to 8 lanes, so 12 would take two.
layout(vertices = 4) out;

#define LT_WT_TESC
#include "watertight.glsl"

layout(location = 0) in vec3 vPoint[];
layout(location = 1) in uint vRecord[];

layout(location = 0) out vec3 tcPoint[][3];       // vertex v: points 3v .. 3v + 2 (phantoms filled)
layout(location = 12) patch out vec2 tcCorner[3]; // A, B, C in (s,t)
layout(location = 15) patch out uvec4 tcParam;    // base face, ui | vi << 16, info, class
// (locations 3-11 and 16-22: watertight.glsl's interface)

// p[i] by selects between constant indices (lavapipe indexes a local array lane by lane).
vec3 pickPoint(vec3 p[12], uint i) {
    vec3 v = p[0];
    for (int m = 1; m < 12; ++m) v = i == uint(m) ? p[m] : v;
    return v;
}

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
    precise float len = sqrt(dx * dx + dy * dy + dz * dz);
    precise float mx = (a.x + b.x) * 0.5 - pc.lod.x, my = (a.y + b.y) * 0.5 - pc.lod.y, mz = (a.z + b.z) * 0.5 - pc.lod.z;
    precise float dist = sqrt(mx * mx + my * my + mz * mz);
    precise float f = len * pc.lod.w / max(dist, 1e-20);
    return f;
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

// sub_patches.h's snapOddFactor (LT_FLAG_FRACTIONAL_ODD): a factor less than 1/8
// above an odd integer is drawn as that integer (every step exact in float).
float snapOddFactor(float f) {
    precise float n = 2.0 * floor((f - 1.0) * 0.5) + 1.0;
    precise float above = f - n;
    return above < 0.125 ? n : f;
}

float edgeFactor(uint a, uint b, Factors f) {
    if (isCorner(a) && isCorner(b)) return f.edge[b == (a + 1u) % 3u ? a : b];
    if (!isCorner(a) && !isCorner(b)) return f.middle;
    uint c = isCorner(a) ? a : b, m = (isCorner(a) ? b : a) - LT_DOMAIN_M0;
    if (c == m) return f.halfA[m];
    if (c == (m + 1u) % 3u) return f.halfB[m];
    return f.across;
}

void main() {
    uint record = vRecord[0];
    uint patchWords = word(LT_H_PATCHES) + LT_PATCH_WORDS * (record & LT_RECORD_PATCH_MASK);
    uint info = word(patchWords + LT_PATCH_INFO);

    vec3 p[12];
    for (int i = 0; i < 12; ++i) p[i] = vPoint[i];
    fillPhantomPoints(info & 0x3fu, p);
    for (int m = 0; m < 3; ++m) tcPoint[gl_InvocationID][m] = pickPoint(p, 3u * uint(gl_InvocationID) + uint(m));
    if (kSpecWatertight) prepareWatertight(patchWords);

    if (gl_InvocationID == 0) {
        uint q0 = (record >> LT_RECORD_PATCH_BITS) & 7u, q1 = (record >> (LT_RECORD_PATCH_BITS + 3)) & 7u,
             q2 = (record >> (LT_RECORD_PATCH_BITS + 6)) & 7u;
        int level = int((info >> 8) & 0xffu);
        Factors f;
        if ((pc.flags & LT_FLAG_LOD_SCREEN) != 0u) {
            vec3 corner[3] = vec3[3](vPoint[4], vPoint[5], vPoint[8]);
            bool split = !isCorner(q0) || !isCorner(q1) || !isCorner(q2);
            f = screenFactors(corner, split ? word(patchWords + LT_PATCH_SPLIT) : LT_NONE, level);
        } else {
            f = uniformFactors(ldexp(pc.tessFactor, -level), ldexp(pc.tessFactor, -level - 1));
        }
        float o0 = edgeFactor(q2, q0, f);
        float o1 = edgeFactor(q0, q1, f);
        float o2 = edgeFactor(q1, q2, f);
        if ((pc.flags & LT_FLAG_FRACTIONAL_ODD) != 0u) {
            o0 = snapOddFactor(o0);
            o1 = snapOddFactor(o1);
            o2 = snapOddFactor(o2);
        }
        gl_TessLevelOuter[0] = o0;
        gl_TessLevelOuter[1] = o1;
        gl_TessLevelOuter[2] = o2;
        gl_TessLevelInner[0] = max(o0, max(o1, o2));
        tcCorner[0] = kDomain[q0];
        tcCorner[1] = kDomain[q1];
        tcCorner[2] = kDomain[q2];
        bool whole = q0 == 0u && q1 == 1u && q2 == 2u;
        tcParam = uvec4(word(patchWords + LT_PATCH_FACE), word(patchWords + LT_PATCH_UV), info,
                        whole ? LT_CLASS_RPP : LT_CLASS_NPP);
    }
}
