// apply_edits.comp -- hierarchical edit pass of level pc.level (asset.h's
// VertexEdits; paper 3.1 and 4.3): one thread per edited vertex, as
// runtime/src/cpu_subdivide.cpp's applyEdits. Runs after the level's vertex-point
// and edge-point passes (level 0: after the control point copy) and before
// anything reads the level:
//
//   level l:  vertex points | edge points --barrier--> edits --barrier--> level l+1, limit, draws
//
// Edited vertex i (ED_VERTEX[i], global index) takes its edits k = ED_START[i] ..
// ED_START[i+1] - 1 in order, per coordinate, in float:
//   set: p = value_k      add: p = p + value_k      subtract: p = p - value_k
// An edited vertex has one thread and the vertices are distinct: no races, and the
// result does not depend on the order threads run in.
//
// value_k = EDIT_VALUES[3k .. 3k+3), copied from the host each frame
// (VulkanSurface::setEditValues).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_VERTICES
#include "common.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

void main() {
    uint i = gl_GlobalInvocationID.x + pc.base;
    uint header = levelHeader(pc.level);
    if (i >= word(header + LT_L_ED_COUNT)) return;
    uint v = word(word(header + LT_L_ED_VERTEX) + i);
    uint startAt = word(header + LT_L_ED_START) + i;
    uint begin = word(startAt), end = word(startAt + 1u);
    uint ops = word(LT_H_EDIT_OPS), values = word(LT_H_EDIT_VALUES);

    precise vec3 p = vertexAt(v);
    for (uint k = begin; k < end; ++k) {
        uint op = word(ops + k);
        vec3 x = vec3(wordFloat(values + 3u * k), wordFloat(values + 3u * k + 1u), wordFloat(values + 3u * k + 2u));
        if (op == LT_EDIT_SET) p = x;
        else if (op == LT_EDIT_ADD) p = p + x;
        else p = p - x;
    }
    vertices.v[3u * v] = p.x;
    vertices.v[3u * v + 1u] = p.y;
    vertices.v[3u * v + 2u] = p.z;
}
