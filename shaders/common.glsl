// common.glsl -- buffers, push constants and table accessors of every looptess
// shader (layout in gpu_layout.h). Include after #version and
// "#extension GL_GOOGLE_include_directive : require".
//
// Defines a shader may set before including:
//   LT_WRITE_VERTICES  the vertex buffer is writable (subdivision passes)
//   LT_WRITE_LIMIT     the limit buffer is writable (limit pass)
//   LT_WRITE_TABLES    the tables are writable (pattern_sort.comp: the sort region)
// Everything else is read-only, so vertex-pipeline stages need no
// vertexPipelineStoresAndAtomics.
//
// Arithmetic that must round like the CPU evaluator (runtime/src/*.cpp, built with
// -ffp-contract=off) is marked `precise`: no fusing, no reassociation.
#include "gpu_layout.h"

#ifdef LT_WRITE_TABLES
layout(std430, set = 0, binding = LT_BINDING_TABLES) buffer Tables {
#else
layout(std430, set = 0, binding = LT_BINDING_TABLES) readonly buffer Tables {
#endif
    uint words[];
} tables;

#ifdef LT_WRITE_VERTICES
layout(std430, set = 0, binding = LT_BINDING_VERTICES) buffer Vertices {
#else
layout(std430, set = 0, binding = LT_BINDING_VERTICES) readonly buffer Vertices {
#endif
    float v[];
} vertices;

#ifdef LT_WRITE_LIMIT
layout(std430, set = 0, binding = LT_BINDING_LIMIT) buffer Limit {
#else
layout(std430, set = 0, binding = LT_BINDING_LIMIT) readonly buffer Limit {
#endif
    float v[];
} limit;

layout(push_constant) uniform PushConstants {
    mat4 mvp;          // object space to clip space (draws)
    vec4 light;        // xyz: unit direction towards the light, object space (draws)
    float tessFactor;  // global factor F (tessellated draws)
    uint level;        // level of a compute pass or of the IPP draw
    uint base;         // compute: first thread of this dispatch; draws: records offset
    uint flags;        // LT_FLAG_* (draws)
    vec4 lod;          // xyz: the eye, w: scale k (LT_FLAG_LOD_SCREEN draws; runtime/internal/lod.h)
    uvec4 evaluate;    // evaluate.comp: first output vertex, first output index, first record, threads
} pc;

// Features a draw pipeline is built with (pipelines.cpp's GraphicsKey). Code a
// pipeline never runs is compiled out, not merely skipped: on lavapipe, watertight
// code behind a push-constant flag made draws that never ran it about 4x slower
// (lavapipe skips a branch only when no lane of a batch takes it, and runs both sides
// otherwise). And a pipeline that always runs it tests kSpecWatertight alone, not the
// flag as well: a branch on a push constant, even one every lane takes, cost the
// watertight draw about 15% of its time (spot, F = 8 and 32). kSpecDisplace is tested
// with LT_FLAG_DISPLACE (it also keeps watertight.glsl's second box-spline
// evaluation: rule 5's direction; GpuTables::smoothCreaseRoots).
layout(constant_id = LT_SPEC_WATERTIGHT) const bool kSpecWatertight = true;
layout(constant_id = LT_SPEC_DISPLACE) const bool kSpecDisplace = true;
// TANGENT costs the tessellation evaluation one more box-spline evaluation at shared
// points and ipp.vert a stencil's, and the other optional outputs (base face, (u,v),
// TEXCOORD_1, COLOR_0) cost lavapipe's draws 5-8% even where no fragment shader reads
// them (spot, F = 8): only pipelines whose consumer reads them pay.
layout(constant_id = LT_SPEC_TANGENT) const bool kSpecTangent = false;
layout(constant_id = LT_SPEC_ATTRIBUTES) const bool kSpecAttributes = false;

uint word(uint offset) { return tables.words[offset]; }
float wordFloat(uint offset) { return uintBitsToFloat(tables.words[offset]); }
uint levelHeader(uint level) { return LT_H_SIZE + level * LT_L_SIZE; }
uint levelField(uint level, uint field) { return tables.words[LT_H_SIZE + level * LT_L_SIZE + field]; }

vec3 vertexAt(uint index) {
    return vec3(vertices.v[3u * index], vertices.v[3u * index + 1u], vertices.v[3u * index + 2u]);
}

// Cross product written out, in the CPU evaluator's order (cross() may differ).
vec3 crossProduct(vec3 a, vec3 b) {
    precise vec3 n;
    n.x = a.y * b.z - a.z * b.y;
    n.y = a.z * b.x - a.x * b.z;
    n.z = a.x * b.y - a.y * b.x;
    return n;
}

// Unit vector as the CPU evaluator's detail::unitVector (runtime/src/face_attributes.h,
// which states the rule): sqrt and division are correctly rounded,
// normalize()/inversesqrt are not, so neither is used. Never zero, never
// non-finite: a vector with no direction (zero, subnormal, infinite, NaN) gives (0, 0, 1).
vec3 unitNormal(vec3 n) {
    const float kMin = uintBitsToFloat(0x00800000u), kMax = uintBitsToFloat(0x7f7fffffu);
    precise float squared = n.x * n.x + n.y * n.y + n.z * n.z;
    precise float len = sqrt(squared);
    precise vec3 unit = vec3(n.x / len, n.y / len, n.z / len);
    if (squared >= kMin && squared <= kMax) return unit;
    vec3 magnitude = abs(n);
    bool finite = magnitude.x <= kMax && magnitude.y <= kMax && magnitude.z <= kMax;
    float m = magnitude.x > 0.0 ? magnitude.x : 0.0;
    m = magnitude.y > m ? magnitude.y : m;
    m = magnitude.z > m ? magnitude.z : m;
    if (!finite || m < kMin) return vec3(0.0, 0.0, 1.0);
    precise vec3 b = vec3(n.x / m, n.y / m, n.z / m);
    precise float scaledLen = sqrt(b.x * b.x + b.y * b.y + b.z * b.z);
    precise vec3 scaled = vec3(b.x / scaledLen, b.y / scaledLen, b.z / scaledLen);
    return scaled;
}
