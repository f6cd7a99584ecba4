// patterns.h -- refinement patterns: the draw path without the tessellator
// (DrawPath::Patterns), after Boubekeur and Schlick, "A Flexible Kernel for
// Adaptive Mesh Refinement on GPU" (2008). Private header of the runtime module;
// the CPU evaluator and the Vulkan path's pattern draws use the same patterns, so
// both evaluate the same domain points in the same order.
//
// Each edge of a drawn (sub-)triangle gets a power-of-two factor e = 1, 2, .., 64:
// its factor (the tessellator path's, sub_patches.h) rounded up. Edge k's points are
// then at j / e_k along it, whichever pattern draws it: two patches that share an
// edge evaluate the same points there, with no T-junction. With N = max(e0, e1, e2):
//
//   all three N      the uniform grid of N segments a side (n^2 triangles)
//   N = 2, unequal   the one or two midpoints fanned to the ring (2 or 3 triangles)
//   N >= 4, unequal  the grid's inner points (i, j >= 1, i + j <= N - 1: a triangle
//                    of N - 3 segments a side) with its cells, and three strips
//                    stitching each side's e_k segments to the inner triangle's side
//                    (two rows on parallel lines: every merge gives valid triangles)
//
// Coordinates are the tessellator's (tess_domain.h): gl_TessCoord-like (x, y, z),
//
//          y = 1  (0,1,0)             e0: edge x = 0 (the sub-triangle's C - A)
//          |\                         e1: edge y = 0 (A - B)
//       e0 | \  e2                    e2: edge z = 0 (B - C)
//          |  //   (0,0,1)----(1,0,0)                grid point (i, j): x = i / N, y = j / N,
//     z = 1  e1    x = 1              z = (1 - x) - y in float (as Mesa computes it)
//
// every coordinate exact in float (dyadic). Triangles are counter-clockwise in
// (x, y) (TessWinding::Cw's orientation). Uniform grid cells, row by row (j, then i):
//
//     (i,j+1) ---- (i+1,j+1)        up:   (i,j) (i+1,j) (i,j+1)
//        |  \   down  |             down: (i+1,j) (i+1,j+1) (i,j+1)
//        |  up  \     |
//      (i,j) ------ (i+1,j)
//
// At global factors a split patch (paper Fig. 8) is drawn whole, not as sub-
// triangles: a split edge's two halves have one factor, so its points are j / (2
// pow2(half)) along the whole edge (wholePatchPatternFactors). At a power-of-two
// global factor F >= 2^(l+1) every edge factor of a level-l patch is then F / 2^l:
// it draws exactly the triangles of uniform refinement of its domain to level
// log2(F). Screen-space factors differ per half, so split patches are drawn as the
// tessellator path draws them, as sub-triangles, each edge rounded up.
#pragma once

#include "sub_patches.h"
#include "tess_domain.h"

#include <cstdint>

namespace lt {

constexpr uint32_t kMaxPatternFactor = 64;

// f rounded up to a power of two in [1, 64]; NaN and f <= 1: 1.
uint32_t patternFactor(float f);

// A split regular patch (RegularPatch::splitMask) drawn whole at global factors,
// where both halves of a split edge have one factor h: the edge gets 2 pow2(h) (the
// halves' points, j / pow2(h) on each), the others pow2 of their own; `f` is the
// patch's uniformPatchFactors. Out: e in the tessellator's edge order for the whole
// triangle (C0, C1, C2): e[0] patch edge 2, e[1] edge 0, e[2] edge 1.
void wholePatchPatternFactors(const PatchFactors& f, uint8_t splitMask, uint32_t e[3]);

// The pattern of edge factors e[0..2] (powers of two in [1, 64]) into `out`
// (coords and triangles as tess_domain.h's). Deterministic.
void makePattern(const uint32_t e[3], TessDomain& out);

}  // namespace lt
