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
// Factors, level l, global factor F: coarse = F / 2^l, fine = F / 2^(l+1).
//   sub-triangle edge between two corners         coarse
//   between two midpoints (inner edge)             fine
//   corner-midpoint on the patch edge (half edge)  fine
//   corner-midpoint across the patch               coarse
//   inner factor = max of the three outer factors
// Which outer level is which edge: see the diagram in patch.tese.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "box_spline.glsl"

layout(vertices = 12) out;

layout(location = 0) in vec3 vPoint[];
layout(location = 1) in uint vRecord[];

layout(location = 0) out vec3 tcPoint[];
layout(location = 1) patch out vec2 tcCorner[3];  // A, B, C in (s,t)
layout(location = 4) patch out uvec4 tcParam;     // base face, ui | vi << 16, info, class

const vec2 kDomain[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(0.5, 0), vec2(0.5, 0.5), vec2(0, 0.5));

bool isCorner(uint id) { return id < LT_DOMAIN_M0; }

float edgeFactor(uint a, uint b, float coarse, float fine) {
    if (isCorner(a) && isCorner(b)) return coarse;
    if (!isCorner(a) && !isCorner(b)) return fine;
    uint c = isCorner(a) ? a : b, m = (isCorner(a) ? b : a) - LT_DOMAIN_M0;
    bool onEdge = c == m || c == (m + 1u) % 3u;
    return onEdge ? fine : coarse;
}

void main() {
    uint record = vRecord[0];
    uint patchWords = word(LT_H_PATCHES) + LT_PATCH_WORDS * (record & LT_RECORD_PATCH_MASK);
    uint info = word(patchWords + LT_PATCH_INFO);

    vec3 p[12];
    for (int i = 0; i < 12; ++i) p[i] = vPoint[i];
    fillPhantomPoints(info & 0x3fu, p);
    tcPoint[gl_InvocationID] = p[gl_InvocationID];

    if (gl_InvocationID == 0) {
        uint q0 = (record >> LT_RECORD_PATCH_BITS) & 7u, q1 = (record >> (LT_RECORD_PATCH_BITS + 3)) & 7u,
             q2 = (record >> (LT_RECORD_PATCH_BITS + 6)) & 7u;
        int level = int((info >> 8) & 0xffu);
        float coarse = ldexp(pc.tessFactor, -level), fine = ldexp(pc.tessFactor, -level - 1);
        float o0 = edgeFactor(q2, q0, coarse, fine);
        float o1 = edgeFactor(q0, q1, coarse, fine);
        float o2 = edgeFactor(q1, q2, coarse, fine);
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
