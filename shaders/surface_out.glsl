// surface_out.glsl -- the vertex every draw emits (tessellation evaluation shader for
// regular patches, ipp.vert for IPP corners): what transform feedback captures and
// what the fragment shader shades. The captured record matches lt::Tessellation and
// the CPU evaluator's emit(): position, unit normal, base face, (u,v) on the face,
// TEXCOORD_0, TANGENT, TEXCOORD_1, COLOR_0.
//
// LT_EVALUATE (evaluate.comp): the outputs are private variables, stored by the
// compute shader into an application's buffers (vulkan.h, recordEvaluate) or the
// compute path's batch (compute.vert reads them back).
// LT_CAPTURE: decorate the outputs for transform feedback (buffer 0, one
// LT_CAPTURE_STRIDE-byte record a vertex: x y z nx ny nz face u v s t tx ty tz tw s1 t1
// r g b a). Only capture
// pipelines use these modules, so render pipelines need no transformFeedback feature.
// Without LT_CAPTURE vulkan.h's interface is declared for any fragment shader:
// position, normal, style and TEXCOORD_0 always written (shade.frag reads them), the
// tangent with kSpecTangent, base face, (u,v), TEXCOORD_1 and COLOR_0 with
// kSpecAttributes (common.glsl); a capture writes all of them.
#ifdef LT_CAPTURE
layout(xfb_buffer = 0, xfb_stride = LT_CAPTURE_STRIDE) out;
layout(location = 0, xfb_offset = 0) out vec3 outPosition;
layout(location = 1, xfb_offset = 12) out vec3 outNormal;
layout(location = 2, xfb_offset = 24) flat out uint outFace;
layout(location = 3, xfb_offset = 28) out vec2 outUV;
layout(location = 5, xfb_offset = 36) out vec2 outTexcoord;
layout(location = 6, xfb_offset = 44) out vec4 outTangent;
layout(location = 7, xfb_offset = 60) out vec2 outTexcoord1;
layout(location = 8, xfb_offset = 68) out vec4 outColor;
#elif defined(LT_EVALUATE)
// evaluate.comp: the same values as private variables, which it stores.
vec3 outPosition, outNormal;
uint outFace, outStyle;
vec2 outUV, outTexcoord, outTexcoord1;
vec4 outTangent, outColor;
#else
layout(location = 0) out vec3 outPosition;    // object space (shade.frag's faceted normals)
layout(location = 1) out vec3 outNormal;
layout(location = 2) flat out uint outFace;   // base face
layout(location = 3) out vec2 outUV;          // (u, v) on the base face
layout(location = 4) flat out uint outStyle;  // level | class << 8 (for --color levels)
layout(location = 5) out vec2 outTexcoord;    // TEXCOORD_0 (for --color texcoords)
layout(location = 6) out vec4 outTangent;     // TANGENT, with kSpecTangent (vulkan.h)
layout(location = 7) out vec2 outTexcoord1;   // TEXCOORD_1
layout(location = 8) out vec4 outColor;       // COLOR_0
#endif

// An attribute of `width` floats per face corner (FACE_UVS, FACE_UV1S, FACE_COLORS
// at `at`; LT_NONE: `none`) at (u, v) on base face `face`: runtime.h's faceAttribute,
// operation order included, so that the GPU and the CPU emit the same bits:
//
//        c2 (u, v) = (0, 1)
//        | \  .
//        |   \        value = (w c0 + u c1) + v c2,  w = (1 - u) - v
//        c0 --- c1 (1, 0)
vec4 faceAttribute(uint at, uint width, uint face, float u, float v, vec4 none) {
    if (at == LT_NONE) return none;
    at += 3u * width * face;
    vec4 c0 = none, c1 = none, c2 = none;
    for (uint k = 0u; k < width; ++k) {
        c0[k] = uintBitsToFloat(tables.words[at + k]);
        c1[k] = uintBitsToFloat(tables.words[at + width + k]);
        c2[k] = uintBitsToFloat(tables.words[at + 2u * width + k]);
    }
    precise float w = 1.0 - u - v;
    precise vec4 value = w * c0 + u * c1 + v * c2;
    return value;
}

// TEXCOORD_0 (runtime.h's faceTexcoord); (0, 0) without it.
vec2 faceTexcoord(uint face, float u, float v) {
    return faceAttribute(tables.words[LT_H_FACE_UVS], 2u, face, u, v, vec4(0.0)).xy;
}

// TANGENT at a point of base face `face` with unit normal n and derivatives pu, pv
// along the face's u and v: runtime.h's faceTangent, operation order included.
vec4 faceTangent(uint face, vec3 pu, vec3 pv, vec3 n) {
    uint at = tables.words[LT_H_FACE_UVS] + 6u * face;
    vec2 c0 = vec2(uintBitsToFloat(tables.words[at]), uintBitsToFloat(tables.words[at + 1u]));
    vec2 c1 = vec2(uintBitsToFloat(tables.words[at + 2u]), uintBitsToFloat(tables.words[at + 3u]));
    vec2 c2 = vec2(uintBitsToFloat(tables.words[at + 4u]), uintBitsToFloat(tables.words[at + 5u]));
    precise vec2 e1 = c1 - c0, e2 = c2 - c0;
    precise float det = e1.x * e2.y - e2.x * e1.y;
    float w = det < 0.0 ? -1.0 : 1.0;
    precise vec3 g = (e2.y * pu - e1.y * pv) * w;
    bool degenerate = g.x == 0.0 && g.y == 0.0 && g.z == 0.0;
    g = degenerate ? pu : g;
    w = degenerate ? 1.0 : w;
    precise float along = n.x * g.x + n.y * g.y + n.z * g.z;
    precise vec3 inPlane = g - n * along;
    return vec4(unitNormal(inPlane), w);
}

// (s,t) on a patch of level l covers (u,v) = d (ui, vi) + d (s,t) (rotated ? -1 : 1),
// d = 2^-l, on the base face (asset.h's PatchParam). `info` is LT_PATCH_INFO's
// packing (level in bits 8..15, rotated in bit 16); `patchClass` an LT_CLASS_*.
// With LT_FLAG_DISPLACE and a map (displacement.glsl, included before this file),
// the position moves along the unit direction `along` by the map's value at (u,v),
// as runtime/src/cpu_evaluate.cpp's emit().
// `pu`, `pv`: the derivatives along the patch's s and t, for the tangent.
void emitSurfaceVertex(vec3 position, vec3 normal, vec3 along, uint face, uint uvPacked, uint info, uint patchClass,
                       float s, float t, vec3 pu, vec3 pv) {
    float d = ldexp(1.0, -int((info >> 8) & 0xffu));
    float sign = (info & 0x10000u) != 0u ? -1.0 : 1.0;
    precise float u = d * (float(uvPacked & 0xffffu) + sign * s);
    precise float v = d * (float(uvPacked >> 16) + sign * t);
    if (kSpecDisplace && (pc.flags & LT_FLAG_DISPLACE) != 0u && hasDisplacement()) {
        float h = sampleDisplacement(face, u, v);
        precise vec3 moved = position + along * h;
        position = moved;
    }
    outNormal = normal;
    outTexcoord = faceTexcoord(face, u, v);
    outPosition = position;
#if defined(LT_CAPTURE)
    const bool attributes = true;
    outTangent = vec4(0.0, 0.0, 0.0, 1.0);
#elif defined(LT_EVALUATE)
    const bool attributes = kSpecAttributes;   // recordEvaluate's pipelines: off (not stored)
    outTangent = vec4(0.0, 0.0, 0.0, 1.0);
#else
    const bool attributes = kSpecAttributes;
#endif
    precise vec3 signedPu = sign * pu, signedPv = sign * pv;
    if (kSpecTangent && tables.words[LT_H_FACE_UVS] != LT_NONE) outTangent = faceTangent(face, signedPu, signedPv, normal);
    if (attributes) {
        outFace = face;
        outUV = vec2(u, v);
        outTexcoord1 = faceAttribute(tables.words[LT_H_FACE_UV1S], 2u, face, u, v, vec4(0.0)).xy;
        outColor = faceAttribute(tables.words[LT_H_FACE_COLORS], 4u, face, u, v, vec4(1.0));
    }
#ifndef LT_CAPTURE
    outStyle = ((info >> 8) & 0xffu) | patchClass << 8;
#endif
#ifndef LT_EVALUATE
    gl_Position = pc.mvp * vec4(position, 1.0);
#endif
}
