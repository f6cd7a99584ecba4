// exact_math_probe.comp -- test-only (tests/vulkan/test_exact_math.cpp): runs
// shaders/exact_math.glsl on a list of queries so that the test can compare the
// GPU's bits with the CPU's correctly rounded / and sqrt.
//
// Queries live in the tables buffer at word pc.base: count, then per query
// (operation, a bits, b bits, start bits): operation 0 exactDivideFrom(a, b, start),
// 1 exactSqrtFrom(a, start), 2 exactDivide(a, b), 3 exactSqrt(a); result i goes to
// the vertex buffer's float i. Compiled by tests/CMakeLists.txt.
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_VERTICES
#include "common.glsl"
#include "exact_math.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= word(pc.base)) return;
    uint q = pc.base + 1u + 4u * i, op = word(q);
    float a = wordFloat(q + 1u), b = wordFloat(q + 2u), start = wordFloat(q + 3u);
    float r = op == 0u ? exactDivideFrom(a, b, start) : op == 1u ? exactSqrtFrom(a, start) : op == 2u ? exactDivide(a, b) : exactSqrt(a);
    vertices.v[i] = r;
}
