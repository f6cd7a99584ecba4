// subdivide_vertices.comp -- vertex-point pass of level pc.level (paper 3.1): one
// thread per vertex point, as runtime/src/cpu_subdivide.cpp's refineLevel.
//
// Vertex point i of level l, parent vertex v with ring r_0 .. r_{n-1} (level l-1):
//
//        r2 ---- r1
//       /  \    /  \             v' = v + sum_j w_j (r_j - v)
//      /    \  /    \            w_j = SMOOTH_EDGE[n] (Loop's beta(n)) for the
//    r3 ----  v ---- r0                smooth rule, else the explicit mask
//      \    /  \    /                  (creases, corners, boundaries, ...)
//       \  /    \  /
//        r4 ---- r5              summed over j in ring order, per coordinate
//
// Output: vertices[firstVertex(l) + i].
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_VERTICES
#include "common.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

void main() {
    uint i = gl_GlobalInvocationID.x + pc.base;
    uint header = levelHeader(pc.level);
    if (i >= word(header + LT_L_VP_COUNT)) return;
    uint parent = word(word(header + LT_L_VP_PARENT) + i);
    uint ringStart = word(header + LT_L_VP_RING_START) + i;
    uint begin = word(ringStart), end = word(ringStart + 1u);
    uint mask = word(word(header + LT_L_VP_WEIGHTS) + i);
    float smoothWeight = mask == LT_NONE ? wordFloat(word(LT_H_SMOOTH_EDGE) + (end - begin)) : 0.0;

    vec3 p = vertexAt(parent);
    precise vec3 sum = vec3(0.0);
    for (uint j = begin; j < end; ++j) {
        float w = mask == LT_NONE ? smoothWeight : wordFloat(mask + (j - begin));
        sum = sum + w * (vertexAt(word(j)) - p);
    }
    precise vec3 result = p + sum;
    uint out3 = 3u * (word(header + LT_L_FIRST_VERTEX) + i);
    vertices.v[out3] = result.x;
    vertices.v[out3 + 1u] = result.y;
    vertices.v[out3 + 2u] = result.z;
}
