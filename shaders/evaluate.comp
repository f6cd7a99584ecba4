// evaluate.comp -- one frame's surface as indexed triangles in an application's
// buffers (vulkan.h, recordEvaluate): the pattern path's vertices, evaluated by the
// same functions as pattern.vert and ipp.vert, so they are the draw's bits.
//
// Output layout (recordEvaluate's, and the CPU evaluator's EvalSettings::indexed):
//
//   vertices  per record in draw order, its pattern's (n + 1)(n + 2) / 2 points row
//             by row: point (i, j) at j (n + 1) - j (j - 1) / 2 + i,
//
//               (0,n)                     row j holds i = 0 .. n - j
//                 |  \
//               (0,1) (1,1) ..
//               (0,0) (1,0) .. (n,0)
//
//             then the IPPs' corners, 3 per IPP triangle;
//   indices   per record its pattern's n^2 triangles, in patterns.h's order (row by
//             row, each cell's up triangle then its down one), then the IPPs' 3 each.
//
// A dispatch (push constants): pc.base the record list, pc.level the pattern's n
// (LT_EVALUATE_IPPS: the level), pc.evaluate = (first vertex, first index, first
// record (LT_EVALUATE_IPPS: first IPP corner), threads). Specialization LT_SPEC_EVALUATE_KIND picks what it writes.
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_EVALUATE
#include "common.glsl"
#include "box_spline.glsl"
#include "displacement.glsl"
#include "surface_out.glsl"
#define LT_WT_VERT
#include "watertight.glsl"
#include "pattern_eval.glsl"
#include "limit_stencil.glsl"
#include "ipp_eval.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;
layout(constant_id = LT_SPEC_EVALUATE_KIND) const uint kKind = LT_EVALUATE_PATTERN_POINTS;

layout(std430, set = 1, binding = 0) writeonly buffer OutVertices {
    float v[];
} outVertices;
layout(std430, set = 1, binding = 1) writeonly buffer OutIndices {
    uint i[];
} outIndices;

void storeVertex(uint vertex) {
    uint at = LT_EVALUATE_FLOATS * vertex;
    outVertices.v[at] = outPosition.x;
    outVertices.v[at + 1u] = outPosition.y;
    outVertices.v[at + 2u] = outPosition.z;
    outVertices.v[at + 3u] = outNormal.x;
    outVertices.v[at + 4u] = outNormal.y;
    outVertices.v[at + 5u] = outNormal.z;
    outVertices.v[at + 6u] = outTangent.x;
    outVertices.v[at + 7u] = outTangent.y;
    outVertices.v[at + 8u] = outTangent.z;
    outVertices.v[at + 9u] = outTangent.w;
    outVertices.v[at + 10u] = outTexcoord.x;
    outVertices.v[at + 11u] = outTexcoord.y;
}

uint pointIndex(uint n, uint i, uint j) { return j * (n + 1u) - (j * (j - 1u)) / 2u + i; }

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= pc.evaluate.w) return;
    uint n = pc.level;
    if (kKind == LT_EVALUATE_IPPS) {   // pc.evaluate.z: the dispatch's first corner
        evalIppCorner(pc.evaluate.z + t);
        storeVertex(pc.evaluate.x + t);
        outIndices.i[pc.evaluate.y + t] = pc.evaluate.x + t;
        return;
    }
    if (kKind == LT_EVALUATE_PATTERN_POINTS) {
        uint points = (n + 1u) * (n + 2u) / 2u;
        uint r = t / points, k = t % points, j = 0u;
        while (k > n - j) {   // row j holds n + 1 - j points
            k -= n + 1u - j;
            ++j;
        }
        evalPatternPoint(word(pc.base + pc.evaluate.z + r), k, j, n);
        storeVertex(pc.evaluate.x + t);
        return;
    }
    // LT_EVALUATE_PATTERN_INDICES: triangle q of record r; row j has n - j up
    // triangles and n - j - 1 down ones, alternating: up(0) down(0) up(1) ..
    uint r = t / (n * n), q = t % (n * n), j = 0u;
    while (q >= 2u * (n - j) - 1u) {
        q -= 2u * (n - j) - 1u;
        ++j;
    }
    uint i = q / 2u;
    uvec3 c = (q & 1u) == 0u ? uvec3(pointIndex(n, i, j), pointIndex(n, i + 1u, j), pointIndex(n, i, j + 1u))
                             : uvec3(pointIndex(n, i + 1u, j), pointIndex(n, i + 1u, j + 1u), pointIndex(n, i, j + 1u));
    uint base = pc.evaluate.x + r * ((n + 1u) * (n + 2u) / 2u);
    outIndices.i[pc.evaluate.y + 3u * t] = base + c.x;
    outIndices.i[pc.evaluate.y + 3u * t + 1u] = base + c.y;
    outIndices.i[pc.evaluate.y + 3u * t + 2u] = base + c.z;
}
