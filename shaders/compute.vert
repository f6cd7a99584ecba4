// compute.vert -- DrawPath::Compute's vertex stage: the surface was evaluated in
// compute (evaluate.comp, LT_LAYOUT_DRAW) into the surface's batch buffer, so this
// only reads a vertex back and hands it on, with the outputs every looptess draw
// has (surface_out.glsl, vulkan.h "An application's own pipelines"). An indexed draw
// of the batch's triangles; vertex gl_VertexIndex of the batch at word
// LT_DRAW_WORDS(tangent, attributes) * gl_VertexIndex of binding LT_BINDING_DRAW:
//
//   0 position xyz | 3 normal xyz | 6 TEXCOORD_0 | 8 style | TANGENT | face, u v, TEXCOORD_1, COLOR_0
//                                                           kSpecTangent  kSpecAttributes
//
// LT_CAPTURE: decorated for transform feedback (surface_out.glsl); its pipeline is
// specialized with both kSpecTangent and kSpecAttributes, as its evaluation.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "displacement.glsl"   // surface_out.glsl's emitSurfaceVertex needs it (unused here)
#include "surface_out.glsl"

layout(std430, set = 0, binding = LT_BINDING_DRAW) readonly buffer Draw {
    float v[];
} draw;

vec2 drawVec2(uint at) { return vec2(draw.v[at], draw.v[at + 1u]); }
vec3 drawVec3(uint at) { return vec3(draw.v[at], draw.v[at + 1u], draw.v[at + 2u]); }
vec4 drawVec4(uint at) { return vec4(draw.v[at], draw.v[at + 1u], draw.v[at + 2u], draw.v[at + 3u]); }

void main() {
    uint at = LT_DRAW_WORDS(uint(kSpecTangent), uint(kSpecAttributes)) * uint(gl_VertexIndex);
    outPosition = drawVec3(at);
    outNormal = drawVec3(at + 3u);
    outTexcoord = drawVec2(at + 6u);
#ifndef LT_CAPTURE
    outStyle = floatBitsToUint(draw.v[at + 8u]);
#endif
    at += LT_DRAW_BASE_WORDS;
    outTangent = vec4(0.0, 0.0, 0.0, 1.0);
    if (kSpecTangent) {
        outTangent = drawVec4(at);
        at += LT_DRAW_TANGENT_WORDS;
    }
    if (kSpecAttributes) {
        outFace = floatBitsToUint(draw.v[at]);
        outUV = drawVec2(at + 1u);
        outTexcoord1 = drawVec2(at + 3u);
        outColor = drawVec4(at + 5u);
    }
    gl_Position = pc.mvp * vec4(outPosition, 1.0);
}
