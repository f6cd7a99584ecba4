// patch.vert -- pulls the 12 control points of each drawn patch: vertex 12 r + i of
// a draw is point i of record r of the list at pc.base (gpu_layout.h), so a draw of
// records [first, first + n) is vkCmdDraw(12 n, 1, 12 first, 0). No vertex buffers.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) out vec3 vPoint;
layout(location = 1) out uint vRecord;

void main() {
    uint index = uint(gl_VertexIndex);
    uint record = word(pc.base + index / 12u);
    uint patchWords = word(LT_H_PATCHES) + LT_PATCH_WORDS * (record & LT_RECORD_PATCH_MASK);
    vPoint = vertexAt(word(patchWords + index % 12u));
    vRecord = record;
}
