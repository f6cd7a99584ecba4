// displacement_probe.comp -- test-only (tests/vulkan/test_vulkan_displacement.cpp): runs
// shaders/displacement.glsl's sampleDisplacement on a list of queries so that the
// test can compare the GPU's bits with the CPU sampler's.
//
// Queries live in the tables buffer after the asset's tables, at word pc.base:
//   count, then (base face, u bits, v bits) per query;
// result i goes to the vertex buffer's float i. Compiled by tests/CMakeLists.txt:
//   glslangValidator -V --target-env vulkan1.2 -I<shaders> --vn lt_spv_displacement_probe ...
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_VERTICES
#include "common.glsl"
#include "displacement.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= word(pc.base)) return;
    uint q = pc.base + 1u + 3u * i;
    vertices.v[i] = sampleDisplacement(word(q), wordFloat(q + 1u), wordFloat(q + 2u));
}
