// patch.tesc -- per drawn patch: phantom points, the sub-triangle's corners and the
// tessellation factors, exactly as runtime/src/cpu_evaluate.cpp's Evaluator::regular.
//
// A record (gpu_layout.h) names a patch and one sub-triangle of its domain; its
// factors (record_factors.glsl, also the diagram of domain points): the sub-triangle
// edges' factors, then the inner factor = max of the three outer factors.
// With fractional-odd spacing (LT_FLAG_FRACTIONAL_ODD) each outer factor less than
// 1/8 above an odd integer is drawn as that integer (snapOddFactor below).
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
#include "record_factors.glsl"

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

// sub_patches.h's snapOddFactor (LT_FLAG_FRACTIONAL_ODD): a factor less than 1/8
// above an odd integer is drawn as that integer (every step exact in float).
float snapOddFactor(float f) {
    precise float n = 2.0 * floor((f - 1.0) * 0.5) + 1.0;
    precise float above = f - n;
    return above < 0.125 ? n : f;
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
        vec3 corner[3] = vec3[3](vPoint[4], vPoint[5], vPoint[8]);
        vec3 o = recordOuterFactors(record, patchWords, info, corner);
        float o0 = o.x, o1 = o.y, o2 = o.z;
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
