// patch.tese -- evaluates the box spline at each domain point the tessellator makes,
// as runtime/src/cpu_evaluate.cpp does at tess_domain.h's points.
//
// Tessellation coordinates. Vulkan's gl_TessCoord = (x, y, z), x + y + z = 1; on
// lavapipe the D3D11 reference tessellator makes them (16.16 fixed point, z =
// (1 - x) - y). Drawn with x to the right and y up, a sub-triangle (A, B, C) of the
// patch's (s,t) domain (patch.tesc) sits on the coordinates like this:
//
//          C  y = 1                 gl_TessLevelOuter[0]: edge x = 0, C - A
//          |\                       gl_TessLevelOuter[1]: edge y = 0, A - B
//   outer0 | \  outer2              gl_TessLevelOuter[2]: edge z = 0, B - C
//          |  \                     gl_TessLevelInner[0]: the interior
//          A---B  x = 1             (s,t) = z A + x B + y C
//        z = 1
//          outer1
//
// For a whole patch (A, B, C) = (0,0), (1,0), (0,1): (s,t) = (x, y), so outer 0 is
// the patch's edge 2 (s = 0), outer 1 its edge 0 (t = 0), outer 2 its edge 1
// (s + t = 1) in asset.h's / OpenSubdiv's numbering, and OpenSubdiv's (u,v) on the
// patch is (x, y). `cw`: with Vulkan's upper-left domain origin the triangles come
// out counter-clockwise in (x, y), hence in (s,t) (tess_domain.h's TessWinding::Cw).
//
// With LT_FLAG_WATERTIGHT, points on the patch's edges and corners follow
// watertight.glsl's rules (shared with the CPU evaluator), so every shared point
// comes out bit for bit the same from every patch that has it.
//
// LT_FRACTIONAL_ODD selects fractional_odd_spacing (else equal_spacing);
// LT_CAPTURE decorates the outputs for transform feedback (surface_out.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "box_spline.glsl"
#include "displacement.glsl"
#include "surface_out.glsl"
#define LT_WT_TESE
#include "watertight.glsl"

#ifdef LT_FRACTIONAL_ODD
layout(triangles, fractional_odd_spacing, cw) in;
#else
layout(triangles, equal_spacing, cw) in;
#endif

layout(location = 0) in vec3 tcPoint[][3];  // patch.tesc's vertex v: points 3v .. 3v + 2
layout(location = 12) patch in vec2 tcCorner[3];
layout(location = 15) patch in uvec4 tcParam;
// (locations 3-11 and 16-22: watertight.glsl's interface, written by patch.tesc)

void main() {
    vec3 tc = gl_TessCoord;
    vec2 a = tcCorner[0], b = tcCorner[1], c = tcCorner[2];
    precise float s = tc.z * a.x + tc.x * b.x + tc.y * c.x;
    precise float t = tc.z * a.y + tc.x * b.y + tc.y * c.y;
    vec3 p[12];
    for (int i = 0; i < 12; ++i) p[i] = tcPoint[i / 3][i % 3];
    vec3 position, n, dir, du = vec3(0.0), dv = vec3(0.0);
    if (kSpecWatertight) {
        evalWatertight(p, s, t, position, n, dir);
        vec3 own;
        if (kSpecTangent) evalBoxSpline(p, s, t, own, du, dv);  // the tangent's: this patch's own
    } else {
        evalBoxSpline(p, s, t, position, du, dv);
        n = crossProduct(du, dv);
        dir = n;
    }
    emitSurfaceVertex(position, unitNormal(n), unitNormal(dir), tcParam.x, tcParam.y, tcParam.z, tcParam.w, s, t,
                      du, dv);
}
