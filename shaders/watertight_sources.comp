// watertight_sources.comp -- the watertight pass (gpu_layout.h): with
// LT_FLAG_WATERTIGHT, before the limit pass, every point source record (or, with
// LT_WT_NORMALS, every normal source record; with LT_WT_ROOTS, every root edge's
// canonical points) that the levels <= pc.level use,
// evaluated once per frame by watertight.glsl's own functions, so the draws read the
// same bits they would compute (runtime/src/cpu_evaluate.cpp's Evaluator::evalSource,
// evalNormalSource):
//
//   point source k:  limit[word(LT_H_WT_POINT_RESULTS) + 6k ..]  = position, n
//   normal source k: limit[word(LT_H_WT_NORMAL_RESULTS) + 3k ..] = n
//   root edge k:     limit[word(LT_H_WT_ROOT_RESULTS) + 30k ..] = its 10 points
//
// n = the canonical frame's ds x dt (point sources) or the patch's du x dv at its
// corner (normal sources); not unit. Three pipelines (points, normals, roots):
// a thread of one kind next to a thread of another would run both kinds' code.
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_LIMIT
#include "common.glsl"
#include "box_spline.glsl"
#include "watertight.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

void store(uint at, vec3 value) {
    limit.v[at] = value.x;
    limit.v[at + 1u] = value.y;
    limit.v[at + 2u] = value.z;
}

void main() {
    uint k = gl_GlobalInvocationID.x + pc.base;
    uint header = levelHeader(pc.level);
#if defined(LT_WT_NORMALS)
    if (k >= word(header + LT_L_WT_NORMAL_COUNT)) return;
    store(word(LT_H_WT_NORMAL_RESULTS) + LT_WT_NORMAL_FLOATS * k,
          evalNormalSource(word(LT_H_WT_NORMALS) + LT_WT_NORMAL_WORDS * k));
#elif defined(LT_WT_ROOTS)
    if (k >= word(header + LT_L_WT_ROOT_COUNT)) return;
    uint record = word(LT_H_WT_ROOT_EDGES) + LT_WT_ROOT_EDGE_WORDS * k;
    uint patchWords = patchWordsOf(word(record));
    int edge = int(word(record + 1u));
    vec3 q[12], e[12];
    loadPatchPoints(patchWords, q);
    rotateToEdge(q, edge, edgeFlipped(patchWords, edge), e);
    for (int i = 0; i < 10; ++i) store(word(LT_H_WT_ROOT_RESULTS) + LT_WT_ROOT_FLOATS * k + 3u * uint(i), e[i]);
#else
    if (k >= word(header + LT_L_WT_POINT_COUNT)) return;
    vec3 pos, n;
    evalPointSource(word(LT_H_WT_POINTS) + LT_WT_POINT_WORDS * k, pos, n);
    uint at = word(LT_H_WT_POINT_RESULTS) + LT_WT_POINT_FLOATS * k;
    store(at, pos);
    store(at + 3u, n);
#endif
}
