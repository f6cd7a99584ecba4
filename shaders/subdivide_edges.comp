// subdivide_edges.comp -- edge-point pass of level pc.level (paper 3.1, Fig. 5):
// one thread per edge point, as runtime/src/cpu_subdivide.cpp's refineLevel.
//
// Edge point i of level l from the edge a-b of level l-1 and the opposite vertices
// c, d of its two triangles (d == c on a boundary):
//
//          c
//         / \              e = ends * (a + b) + opposite * (c + d)
//        /   \             smooth: ends = 3/8, opposite = 1/8; a crease of
//       a --e-- b                  weight w: the pair from EP_WEIGHTS, computed on
//        \   /                     the CPU by subdivide_rules.h's edgeWeights(w)
//         \ /
//          d
//
// Output: vertices[firstVertex(l) + vertexPointCount(l) + i].
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_VERTICES
#include "common.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

void main() {
    uint i = gl_GlobalInvocationID.x + pc.base;
    uint header = levelHeader(pc.level);
    if (i >= word(header + LT_L_EP_COUNT)) return;
    uint e = word(header + LT_L_EP_VERTS) + 4u * i;
    uint pair = word(word(header + LT_L_EP_WEIGHTS) + i);
    float ends = pair == LT_NONE ? 0.375 : wordFloat(pair);
    float opposite = pair == LT_NONE ? 0.125 : wordFloat(pair + 1u);

    precise vec3 endSum = vertexAt(word(e)) + vertexAt(word(e + 1u));
    precise vec3 oppositeSum = vertexAt(word(e + 2u)) + vertexAt(word(e + 3u));
    precise vec3 result = ends * endSum + opposite * oppositeSum;
    uint out3 = 3u * (word(header + LT_L_FIRST_VERTEX) + word(header + LT_L_VP_COUNT) + i);
    vertices.v[out3] = result.x;
    vertices.v[out3 + 1u] = result.y;
    vertices.v[out3 + 2u] = result.z;
}
