// pattern.vert -- regular patches without the tessellator (DrawPath::Patterns;
// runtime/internal/patterns.h): each patch is an instance of the uniform refinement
// pattern of N segments a side, N = pc.level, and this shader evaluates the box
// spline at its points as patch.tesc and patch.tese together do at the
// tessellator's (the same functions, the same rounding), so the CPU evaluator's
// pattern mode gives the same bits.
//
// A draw of records [first, first + n) of the record list at pc.base (gpu_layout.h;
// global factors: the level's `whole` list, one record per regular patch, its whole
// domain; screen-space factors: pattern_sort.comp's sorted list, the records of one
// pattern) with pattern P: vkCmdDrawIndexed(P's index count, n, P's first index, 0,
// first), direct or indirect. Each index names a point of the grid of N segments a
// side, N = 2^c the largest edge factor of P (every point of P is on that grid,
// patterns.h), by its position: index = c * LT_PATTERN_GRID_INDICES + j * 65 + i.
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

#include "pattern_eval.glsl"

void main() {
    uint index = uint(gl_VertexIndex) % LT_PATTERN_GRID_INDICES;
    uint n = 1u << (uint(gl_VertexIndex) / LT_PATTERN_GRID_INDICES);
    evalPatternPoint(word(pc.base + uint(gl_InstanceIndex)), index % 65u, index / 65u, n);
}
