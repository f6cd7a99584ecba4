// limit_stencil.glsl -- a limit stencil's evaluation (limit.comp, and ipp.vert for
// the tangent), as runtime/src/cpu_evaluate.cpp's Evaluator::evalStencil and
// cornerDerivatives.

// Position and tangents of stencil i of the level at `header`; true if masked.
bool evalStencil(uint header, uint i, out vec3 position, out vec3 tu, out vec3 tv) {
    uint ringStart = word(header + LT_L_LS_RING_START) + i;
    uint begin = word(ringStart), n = word(ringStart + 1u) - begin;
    uint weights = word(word(header + LT_L_LS_WEIGHTS) + i);
    bool smoothRule = weights == LT_NONE;
    float smoothPosition = 0.0;
    uint tangents = 0u;
    if (smoothRule) {
        uint entry = word(LT_H_SMOOTH_LIMIT) + 2u * n;
        smoothPosition = wordFloat(entry);
        tangents = word(entry + 1u);
    }

    vec3 centre = vertexAt(word(word(header + LT_L_LS_VERTEX) + i));
    precise vec3 a = vec3(0.0), b = vec3(0.0), e = vec3(0.0);
    for (uint j = 0u; j < n; ++j) {
        precise vec3 x = vertexAt(word(begin + j)) - centre;
        float wp = smoothRule ? smoothPosition : wordFloat(weights + j);
        float wu = smoothRule ? wordFloat(tangents + 2u * j) : wordFloat(weights + n + j);
        float wv = smoothRule ? wordFloat(tangents + 2u * j + 1u) : wordFloat(weights + 2u * n + j);
        a = a + wp * x;
        b = b + wu * x;
        e = e + wv * x;
    }
    precise vec3 p = centre + a;
    position = p;
    tu = b;
    tv = e;
    return !smoothRule;
}

// The derivatives along an IPP's s and t at its corner c (0..2) whose stencil, i of
// the level at `header`, has Loop's smooth masks: Evaluator::cornerDerivatives (spec
// "Tangents"). `vertices`: the global vertex of each corner's stencil. False for
// explicit weights or a corner missing from the ring.
bool cornerDerivatives(uint header, uint i, uint c, uvec3 vertices, out vec3 du, out vec3 dv) {
    du = vec3(0.0);
    dv = vec3(0.0);
    vec3 position, tu, tv;
    if (evalStencil(header, i, position, tu, tv)) return false;
    uint ringStart = word(header + LT_L_LS_RING_START) + i;
    uint begin = word(ringStart), n = word(ringStart + 1u) - begin;
    uint tangents = word(word(LT_H_SMOOTH_LIMIT) + 2u * n + 1u);
    vec3 d[3];
    for (uint x = 0u; x < 3u; ++x) {
        d[x] = vec3(0.0);
        if (x == c) continue;
        uint j = 0u;
        while (j < n && word(begin + j) != vertices[x]) ++j;
        if (j == n) return false;
        precise vec3 dir = wordFloat(tangents + 2u * j) * tu + wordFloat(tangents + 2u * j + 1u) * tv;
        d[x] = dir;
    }
    precise vec3 a = d[1] - d[0], b = d[2] - d[0];
    du = c == 0u ? d[1] : c == 1u ? -d[0] : a;
    dv = c == 0u ? d[2] : c == 1u ? b : -d[0];
    return true;
}
