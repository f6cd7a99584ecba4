// surface_out.glsl -- the vertex every draw emits (tessellation evaluation shader for
// regular patches, ipp.vert for IPP corners): what transform feedback captures and
// what the fragment shader shades. The captured record matches lt::Tessellation and
// the CPU evaluator's emit(): position, unit normal, base face, (u,v) on the face.
//
// LT_CAPTURE: decorate the outputs for transform feedback (buffer 0, one
// LT_CAPTURE_STRIDE-byte record a vertex: x y z nx ny nz face u v). Only capture
// pipelines use these modules, so render pipelines need no transformFeedback feature.
// Without LT_CAPTURE only what shade.frag reads is written (the normal and the
// style), so no output goes unconsumed.
#ifdef LT_CAPTURE
layout(xfb_buffer = 0, xfb_stride = LT_CAPTURE_STRIDE) out;
layout(location = 0, xfb_offset = 0) out vec3 outPosition;
layout(location = 1, xfb_offset = 12) out vec3 outNormal;
layout(location = 2, xfb_offset = 24) flat out uint outFace;
layout(location = 3, xfb_offset = 28) out vec2 outUV;
#else
layout(location = 0) out vec3 outPosition;    // object space (shade.frag's faceted normals)
layout(location = 1) out vec3 outNormal;
layout(location = 4) flat out uint outStyle;  // level | class << 8 (for --color levels)
#endif

// (s,t) on a patch of level l covers (u,v) = d (ui, vi) + d (s,t) (rotated ? -1 : 1),
// d = 2^-l, on the base face (asset.h's PatchParam). `info` is LT_PATCH_INFO's
// packing (level in bits 8..15, rotated in bit 16); `patchClass` an LT_CLASS_*.
// With LT_FLAG_DISPLACE and a map (displacement.glsl, included before this file),
// the position moves along the unit direction `along` by the map's value at (u,v),
// as runtime/src/cpu_evaluate.cpp's emit().
void emitSurfaceVertex(vec3 position, vec3 normal, vec3 along, uint face, uint uvPacked, uint info, uint patchClass,
                       float s, float t) {
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
#ifdef LT_CAPTURE
    outPosition = position;
    outFace = face;
    outUV = vec2(u, v);
#else
    outPosition = position;
    outStyle = ((info >> 8) & 0xffu) | patchClass << 8;
#endif
    gl_Position = pc.mvp * vec4(position, 1.0);
}
