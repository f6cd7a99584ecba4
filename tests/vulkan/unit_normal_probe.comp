// unit_normal_probe.comp -- test-only (tests/vulkan/test_exact_math.cpp): runs
// shaders/common.glsl's unitNormal on a list of vectors so that the test can compare
// the GPU's bits with the CPU's lt::unitNormal.
//
// Queries live in the tables buffer at word pc.base: count, then per query the
// vector's three float bits; result i goes to the vertex buffer's floats 3i .. 3i + 2.
// Compiled by tests/vulkan/CMakeLists.txt.
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_VERTICES
#include "common.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= word(pc.base)) return;
    uint q = pc.base + 1u + 3u * i;
    vec3 unit = unitNormal(vec3(wordFloat(q), wordFloat(q + 1u), wordFloat(q + 2u)));
    vertices.v[3u * i] = unit.x;
    vertices.v[3u * i + 1u] = unit.y;
    vertices.v[3u * i + 2u] = unit.z;
}
