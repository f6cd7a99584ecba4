// pattern_eval.glsl -- a point of a refinement pattern on a regular patch (patterns.h):
// pattern.vert draws them, evaluate.comp writes them into an application's buffers.
// Include after common.glsl, box_spline.glsl, displacement.glsl, surface_out.glsl and
// watertight.glsl (with LT_WT_VERT).

#include "record_factors.glsl"   // kDomain

// Grid point (i, j) of the uniform pattern of n segments on `record`'s sub-triangle:
// evaluated and emitted (emitSurfaceVertex) as patch.tesc and patch.tese together do.
void evalPatternPoint(uint record, uint i, uint j, uint n) {
    uint patchWords = word(LT_H_PATCHES) + LT_PATCH_WORDS * (record & LT_RECORD_PATCH_MASK);
    uint info = word(patchWords + LT_PATCH_INFO);
    vec3 p[12];
    for (int i = 0; i < 12; ++i) p[i] = vertexAt(word(patchWords + uint(i)));
    fillPhantomPoints(info & 0x3fu, p);

    // i / n and j / n for a power of two n, as a product with 2^-log2(n): exact on any
    // device (a division need not be), and the CPU's i / n.
    float inverse = uintBitsToFloat(uint(127 - findLSB(n)) << 23);
    precise float x = float(i) * inverse, y = float(j) * inverse;
    precise float z = (1.0 - x) - y;
    vec2 a = kDomain[(record >> LT_RECORD_PATCH_BITS) & 7u], b = kDomain[(record >> (LT_RECORD_PATCH_BITS + 3)) & 7u],
         c = kDomain[(record >> (LT_RECORD_PATCH_BITS + 6)) & 7u];
    precise float s = z * a.x + x * b.x + y * c.x;
    precise float t = z * a.y + x * b.y + y * c.y;

    vec3 position, nn, dir, du = vec3(0.0), dv = vec3(0.0);
    if (kSpecWatertight) {
        prepareWatertightPoint(patchWords, s, t);
        evalWatertight(p, s, t, position, nn, dir);
        vec3 own;
        if (kSpecTangent) evalBoxSpline(p, s, t, own, du, dv);  // the tangent's: this patch's own
    } else {
        evalBoxSpline(p, s, t, position, du, dv);
        nn = crossProduct(du, dv);
        dir = nn;
    }
    uint patchClass = word(patchWords + LT_PATCH_SPLIT) != LT_NONE ? LT_CLASS_NPP : LT_CLASS_RPP;
    emitSurfaceVertex(position, unitNormal(nn), unitNormal(dir), word(patchWords + LT_PATCH_FACE), word(patchWords + LT_PATCH_UV),
                      info, patchClass, s, t, du, dv);
}
