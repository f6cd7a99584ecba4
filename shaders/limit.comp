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
#include "limit_stencil.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

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
