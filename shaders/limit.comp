// limit.comp -- limit stencils of level pc.level (the runtime depth): one thread per
// stencil, position and unit normal of the limit surface at an IPP corner, as
// runtime/src/cpu_evaluate.cpp's Evaluator::irregular.
//
// Stencil i: vertex v, ring r_0 .. r_{n-1} starting at the neighbour with the
// smallest global index (paper 3.4.1), weights affine, summed over differences:
//
//   P  = v + sum_j wP_j (r_j - v)       wP: explicit, or SMOOTH_LIMIT[2n] for all j
//   Tu =     sum_j wU_j (r_j - v)       wU, wV: explicit, or the smooth table's
//   Tv =     sum_j wV_j (r_j - v)               (cos, sin)(2 pi j / n) pairs
//   N  = unit(Tu x Tv)
//
// Output: limit[9i ..] = P, N, D (unit displacement direction: N's, or rule 5's).
// With LT_FLAG_WATERTIGHT, a stencil whose point a regular patch also has takes that
// patch's evaluation: the watertight pass's results, which it runs after
// (gpu_layout.h).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_LIMIT
#include "common.glsl"
#include "box_spline.glsl"
#include "watertight.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

// Position and tangents of stencil i of the level at `header`; true if masked.
bool evalStencil(uint header, uint i, out vec3 position, out vec3 tu, out vec3 tv) {
    uint ringStart = word(header + LT_L_LS_RING_START) + i;
    uint begin = word(ringStart), n = word(ringStart + 1u) - begin;
    uint weights = word(word(header + LT_L_LS_WEIGHTS) + i);
    bool smoothRule = weights == LT_NONE;
    float smoothPosition = 0.0;
    uint tangents = 0u;
    if (smoothRule) {
        uint entry = word(LT_H_SMOOTH_LIMIT) + 2u * n;
        smoothPosition = wordFloat(entry);
        tangents = word(entry + 1u);
    }

    vec3 centre = vertexAt(word(word(header + LT_L_LS_VERTEX) + i));
    precise vec3 a = vec3(0.0), b = vec3(0.0), e = vec3(0.0);
    for (uint j = 0u; j < n; ++j) {
        precise vec3 x = vertexAt(word(begin + j)) - centre;
        float wp = smoothRule ? smoothPosition : wordFloat(weights + j);
        float wu = smoothRule ? wordFloat(tangents + 2u * j) : wordFloat(weights + n + j);
        float wv = smoothRule ? wordFloat(tangents + 2u * j + 1u) : wordFloat(weights + 2u * n + j);
        a = a + wp * x;
        b = b + wu * x;
        e = e + wv * x;
    }
    precise vec3 p = centre + a;
    position = p;
    tu = b;
    tv = e;
    return !smoothRule;
}
void main() {
    uint i = gl_GlobalInvocationID.x + pc.base;
    uint header = levelHeader(pc.level);
    if (i >= word(header + LT_L_LS_COUNT)) return;
    vec3 position, tu, tv;
    bool masked = evalStencil(header, i, position, tu, tv);
    vec3 n = crossProduct(tu, tv);
    vec3 dir = n;
    if ((pc.flags & LT_FLAG_WATERTIGHT) != 0u) {
        // Evaluator::irregular's watertight rules (watertight.h, rules 3 to 5).
        uint wt = word(header + LT_L_LS_WT) + 4u * i;
        uint source = word(wt), first = word(wt + 1u), sector = word(wt + 2u), baseNormal = word(wt + 3u);
        if (source != LT_NONE) {  // the watertight pass's evaluation of point source k
            uint at = word(LT_H_WT_POINT_RESULTS) + LT_WT_POINT_FLOATS * source;
            vec3 sharedNormal = limitVec3(at + 3u);
            if (!masked) n = sharedNormal;
            position = limitVec3(at);
            dir = sharedNormal;
        } else if (first != i) {
            vec3 firstU, firstV;
            evalStencil(header, first, position, firstU, firstV);
            dir = crossProduct(firstU, firstV);
        }
        if (masked && sector != LT_NONE) n = limitVec3(word(LT_H_WT_NORMAL_RESULTS) + LT_WT_NORMAL_FLOATS * sector);
        if (masked && baseNormal != LT_NONE) {  // rule 4b: level 0's stencil
            vec3 basePosition, baseU, baseV;
            evalStencil(levelHeader(0u), baseNormal, basePosition, baseU, baseV);
            n = crossProduct(baseU, baseV);
        }
    }
    vec3 normal = unitNormal(n), along = unitNormal(dir);
    uint at = LT_LIMIT_FLOATS * i;
    limit.v[at] = position.x;
    limit.v[at + 1u] = position.y;
    limit.v[at + 2u] = position.z;
    limit.v[at + 3u] = normal.x;
    limit.v[at + 4u] = normal.y;
    limit.v[at + 5u] = normal.z;
    limit.v[at + 6u] = along.x;
    limit.v[at + 7u] = along.y;
    limit.v[at + 8u] = along.z;
}
