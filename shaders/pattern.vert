// pattern.vert -- regular patches without the tessellator (DrawPath::Patterns;
// runtime/src/patterns.h): each patch is an instance of the uniform refinement
// pattern of N segments a side, N = pc.level, and this shader evaluates the box
// spline at its points as patch.tesc and patch.tese together do at the
// tessellator's (the same functions, the same rounding), so the CPU evaluator's
// pattern mode gives the same bits.
//
// A draw of records [first, first + n) of the record list at pc.base (gpu_layout.h;
// the level's `whole` list: one record per regular patch, its whole domain) with
// pattern N: vkCmdDrawIndexed(3 N^2, n, pattern N's first index, 0, first). Each index
// names a grid point by its position, index = j * 65 + i:
//
//     (0,N) y                 (x, y) = (i / N, j / N), z = (1 - x) - y: exact for a
//       | \                   power-of-two N, and the same floats as the CPU's
//       |   \                 pattern (patterns.h) and as the tessellator's
//     (0,0)--(N,0) x          gl_TessCoord would be at those points
//
// LT_CAPTURE: decorated for transform feedback (surface_out.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "box_spline.glsl"
#include "displacement.glsl"
#include "surface_out.glsl"
#define LT_WT_VERT
#include "watertight.glsl"

const vec2 kDomain[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(0.5, 0), vec2(0.5, 0.5), vec2(0, 0.5));

void main() {
    uint record = word(pc.base + uint(gl_InstanceIndex));
    uint patchWords = word(LT_H_PATCHES) + LT_PATCH_WORDS * (record & LT_RECORD_PATCH_MASK);
    uint info = word(patchWords + LT_PATCH_INFO);
    vec3 p[12];
    for (int i = 0; i < 12; ++i) p[i] = vertexAt(word(patchWords + uint(i)));
    fillPhantomPoints(info & 0x3fu, p);
    if (kSpecWatertight)
        for (int v = 0; v < 4; ++v) prepareWatertightSlot(patchWords, v);

    uint index = uint(gl_VertexIndex);
    float n = float(pc.level);
    float x = float(index % 65u) / n, y = float(index / 65u) / n;
    precise float z = (1.0 - x) - y;
    vec2 a = kDomain[(record >> LT_RECORD_PATCH_BITS) & 7u], b = kDomain[(record >> (LT_RECORD_PATCH_BITS + 3)) & 7u],
         c = kDomain[(record >> (LT_RECORD_PATCH_BITS + 6)) & 7u];
    precise float s = z * a.x + x * b.x + y * c.x;
    precise float t = z * a.y + x * b.y + y * c.y;

    vec3 position, nn, dir, du = vec3(0.0), dv = vec3(0.0);
    if (kSpecWatertight) {
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
