// ipp_eval.glsl -- a corner of an IPP of level pc.level (the runtime depth), a flat
// triangle between exact limit points: ipp.vert draws them, evaluate.comp writes them
// into an application's buffers. Include after common.glsl, displacement.glsl,
// surface_out.glsl and limit_stencil.glsl.

// Corner index % 3 of irregular face index / 3 of level pc.level: evaluated and
// emitted (emitSurfaceVertex).
void evalIppCorner(uint index) {
    uint corner = index % 3u;
    uint face = levelField(pc.level, LT_L_IRR_FACES) + LT_IRR_WORDS * (index / 3u);
    uint at = LT_LIMIT_FLOATS * word(face + corner);
    vec3 position = vec3(limit.v[at], limit.v[at + 1u], limit.v[at + 2u]);
    vec3 normal = vec3(limit.v[at + 3u], limit.v[at + 4u], limit.v[at + 5u]);
    vec3 along = vec3(limit.v[at + 6u], limit.v[at + 7u], limit.v[at + 8u]);
    float s = corner == 1u ? 1.0 : 0.0, t = corner == 2u ? 1.0 : 0.0;
    // The tangent's derivatives (Evaluator::irregular): the stencil's along the IPP's
    // edges where it is smooth, else the flat triangle's edges.
    vec3 du = vec3(0.0), dv = vec3(0.0);
    if (kSpecTangent) {
        uint header = levelHeader(pc.level), vertexOf = word(header + LT_L_LS_VERTEX);
        uvec3 stencils = uvec3(word(face), word(face + 1u), word(face + 2u));
        uvec3 vertices = uvec3(word(vertexOf + stencils.x), word(vertexOf + stencils.y), word(vertexOf + stencils.z));
        if (!cornerDerivatives(header, stencils[corner], corner, vertices, du, dv)) {
            uint a0 = LT_LIMIT_FLOATS * stencils.x, a1 = LT_LIMIT_FLOATS * stencils.y, a2 = LT_LIMIT_FLOATS * stencils.z;
            vec3 p0 = vec3(limit.v[a0], limit.v[a0 + 1u], limit.v[a0 + 2u]);
            precise vec3 e1 = vec3(limit.v[a1], limit.v[a1 + 1u], limit.v[a1 + 2u]) - p0;
            precise vec3 e2 = vec3(limit.v[a2], limit.v[a2 + 1u], limit.v[a2 + 2u]) - p0;
            du = e1;
            dv = e2;
        }
    }
    emitSurfaceVertex(position, normal, along, word(face + LT_IRR_FACE), word(face + LT_IRR_UV), word(face + LT_IRR_INFO), LT_CLASS_IPP,
                      s, t, du, dv);
}
