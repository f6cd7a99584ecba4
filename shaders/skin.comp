// skin.comp -- looprender's posing of a scene's cages on the GPU (apps/looprender/
// scene_skin.h), not used by the library: a thread per control vertex morphs and skins
// it as poseControlPoints (viewer/scene.h) does on the CPU, operation for
// operation, every product and sum `precise`, the one division correctly rounded
// (exact_math.glsl), so the GPU's control points are the CPU's bit for bit. The
// surface then reads them (VulkanSurface::setControlPoints with a device buffer).
//
// Binding 0: the inputs, 32-bit words (floats as bits); binding 1: the outputs,
// floats. Push constants, word offsets into the inputs:
//   vertices n, rest (3 n floats), targets T and their deltas (T blocks of 3 n
//   floats) and weights (T floats), influences I per vertex, their joints (I n
//   uints) and weights (I n floats), joint matrices (16 floats each, column-major;
//   none: not skinned), and the first output float.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "exact_math.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Inputs {
    uint words[];
} inputs;
layout(std430, set = 0, binding = 1) writeonly buffer Outputs {
    float v[];
} outputs;

layout(push_constant) uniform Pose {
    uint vertices, rest, targets, deltas, targetWeights, influences, joints, jointWeights, matrices, skinned, out0, pad;
} pc;

float at(uint word) { return uintBitsToFloat(inputs.words[word]); }

void main() {
    uint v = gl_GlobalInvocationID.x;
    if (v >= pc.vertices) return;
    precise vec3 p = vec3(at(pc.rest + 3u * v), at(pc.rest + 3u * v + 1u), at(pc.rest + 3u * v + 2u));
    for (uint t = 0u; t < pc.targets; ++t) {
        float w = at(pc.targetWeights + t);
        if (w == 0.0) continue;
        uint d = pc.deltas + t * 3u * pc.vertices + 3u * v;
        precise vec3 moved = p + w * vec3(at(d), at(d + 1u), at(d + 2u));
        p = moved;
    }
    if (pc.skinned != 0u) {
        precise float m[16];
        for (int e = 0; e < 16; ++e) m[e] = 0.0;
        precise float total = 0.0;
        for (uint i = 0u; i < pc.influences; ++i) {
            float w = at(pc.jointWeights + pc.influences * v + i);
            if (w == 0.0) continue;
            uint j = pc.matrices + 16u * inputs.words[pc.joints + pc.influences * v + i];
            for (uint e = 0u; e < 16u; ++e) m[e] = m[e] + w * at(j + e);
            total = total + w;
        }
        if (total == 0.0) {
            for (int e = 0; e < 16; ++e) m[e] = e % 5 == 0 ? 1.0 : 0.0;
        } else if (total != 1.0) {
            float scale = exactDivide(1.0, total);
            for (int e = 0; e < 16; ++e) m[e] = m[e] * scale;
        }
        precise vec3 skinnedPoint;
        for (int c = 0; c < 3; ++c) skinnedPoint[c] = (m[c] * p.x + m[4 + c] * p.y) + (m[8 + c] * p.z + m[12 + c]);
        p = skinnedPoint;
    }
    outputs.v[pc.out0 + 3u * v] = p.x;
    outputs.v[pc.out0 + 3u * v + 1u] = p.y;
    outputs.v[pc.out0 + 3u * v + 2u] = p.z;
}
