// tess_domain.h - CPU copy of the GPU tessellator for the triangle domain.
// Private header of the runtime module.
//
// Why: CI renders on Mesa's lavapipe, whose fixed-function tessellator is
// Microsoft's D3D11 reference tessellator (16.16 fixed point). To compare CPU
// and GPU captures bit for bit, the CPU evaluator must see exactly the
// gl_TessCoord values and the triangles the GPU produces for one patch. This
// module reproduces that tessellator's rules for triangle patches, written
// from the algorithm's description (not a copy of its source).
//
// ---------------------------------------------------------------------------
// The triangle domain (gl_TessCoord = (x, y, z), x + y + z = 1)
//
//      y                      corner y=1 : (0,1,0)   <- point 0 of the outer ring
//      ^
//    1 *  (0,1,0)
//      |\                     outer[0] controls edge x==0 (left),
//      | \                      walked from corner y=1 down to corner z=1
//      |  \  outer[2]         outer[1] controls edge y==0 (bottom),
//      |   \ edge z==0          walked from corner z=1 to corner x=1
//      |    \                 outer[2] controls edge z==0 (hypotenuse),
//      |     \                  walked from corner x=1 up to corner y=1
//      *------*---> x         inner    controls the interior rings
//  (0,0,1)   (1,0,0)
//  corner z=1  corner x=1
//
// The outer ring is walked y=1 -> z=1 -> x=1 -> y=1: counterclockwise in
// this picture (x right, y up), clockwise in Vulkan's default upper-left
// domain origin, where the v (= y) axis points down.
//
// Point order (indices into TessDomain::coords):
//   1. the outer ring: edge x==0 (from y=1, without its last point z=1),
//      then edge y==0 (from z=1, without x=1), then edge z==0 (from x=1,
//      without y=1). So point 0 is corner y=1, point n0-1 is corner z=1,
//      point n0+n1-2 is corner x=1, where n_e is the point count of edge e.
//   2. the interior rings from the outside in, each ring walked the same way
//      (edge parallel to x==0 first, then y==0, then z==0),
//   3. for an even inner partition, the centre point (1/3, 1/3, 1/3) in 16.16.
// Triangle order: ring by ring from the outside in, within a ring edge x==0,
// y==0, z==0, each edge stitched from its start to its end; then the centre
// triangle for an odd inner partition.
//
// Points along one edge: the tessellator places the points of the first half
// of the edge (counted from either end) in 16.16 fixed point and mirrors the
// second half as 1 - t, so the point set of an edge is exactly symmetric:
// whenever t is on an edge, 1 - t is too (exactly, in fixed point and float).
// A shared edge of two patches therefore gets the same points from both sides
// when both use the same factor for it.
//
// Winding: TessWinding names the vertex-order qualifier of the evaluation
// shader (`layout(triangles, cw) in;` / `ccw`) with Vulkan's default domain
// origin (VK_TESSELLATION_DOMAIN_ORIGIN_UPPER_LEFT). In the picture above
// (x right, y up):
//   TessWinding::Cw  -> triangles have positive signed area in (x, y)
//                       (they turn the same way as the outer ring walk),
//   TessWinding::Ccw -> negative signed area in (x, y).
// (lavapipe flips the qualifier for the upper-left origin and hands it to the
// D3D11 tessellator, whose "clockwise" means clockwise with v pointing down;
// checked on lavapipe by transform feedback, see tests/runtime/test_tess_domain.cpp.)
//
// Factor rules (as the GPU applies them):
//   - any outer factor NaN, <= 0 or denormal: the patch is culled (empty
//     output); lavapipe flushes denormals to zero, as D3D11 does. The inner
//     factor never culls.
//   - clamp: Equal [1, 64], FractionalOdd [1, 63], FractionalEven [2, 64];
//     NaN inner -> lower bound, +inf -> upper bound.
//   - Equal: each clamped factor is rounded up to an integer (5.3 -> 6
//     segments, 7 points); the parity (odd/even) is chosen per factor.
//   - FractionalOdd: if any outer factor is above 1, the inner factor is at
//     least 1 + 2^-16 (a tiny inner triangle instead of none).
//   - factors become 16.16 fixed point (round half to even); all points are
//     computed in 16.16; x = fx / 65536 and y = fy / 65536 exactly, and
//     z = (1.0f - x) - y in float, as Mesa's draw module computes it.
//   - Equal or FractionalOdd with every factor exactly 1 after processing:
//     3 points (y=1, z=1, x=1 corners in that order) and 1 triangle.
//   - uniform Equal level n gives 3(m+1)^2 points and 6m(m+1)+1 triangles for
//     n = 2m+1, and 3m(m+1)+1 points and 6m^2 triangles for n = 2m.
// ---------------------------------------------------------------------------
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lt {

// Partitioning of the tessellator (SPIR-V SpacingEqual, SpacingFractionalOdd,
// SpacingFractionalEven; GLSL equal_spacing, fractional_odd_spacing,
// fractional_even_spacing).
enum class TessSpacing : uint8_t { Equal, FractionalOdd, FractionalEven };

// Vertex order qualifier of the evaluation shader, Vulkan upper-left origin.
// GLSL's default when a shader omits it is ccw.
enum class TessWinding : uint8_t { Cw, Ccw };

// Output of tessellateTriangle. The caller owns it and should reuse it from
// patch to patch: the vectors are cleared, never shrunk, so a reused object
// stops allocating once it has seen the largest patch.
struct TessDomain {
    std::vector<float> coords;        // 3 floats a point: gl_TessCoord (x, y, z), bitwise
    std::vector<uint32_t> triangles;  // 3 point indices a triangle

    size_t pointCount() const { return coords.size() / 3; }
    size_t triangleCount() const { return triangles.size() / 3; }
    bool empty() const { return coords.empty(); }
};

// Largest output of one patch (uniform level 64): 3169 points, 6144 triangles.
constexpr size_t kTessMaxPoints = 3169;
constexpr size_t kTessMaxTriangles = 6144;

// Tessellates one triangle patch exactly as lavapipe does.
//   outer[0..2]: gl_TessLevelOuter[0..2] (edges x==0, y==0, z==0),
//   inner:       gl_TessLevelInner[0],
//   any float is accepted (NaN, inf, negative, huge): see "Factor rules".
// On return `out` holds the points and triangles in the GPU's order; both are
// empty when the patch is culled. `outer` must point to 3 floats.
// Thread-safe (no shared state); does not allocate once `out` has capacity.
void tessellateTriangle(const float outer[3], float inner, TessSpacing spacing, TessDomain& out,
                        TessWinding winding = TessWinding::Ccw);

// A tessellation factor in 16.16 fixed point as the tessellator converts it
// (round half to even). `f` must be finite, in [0, 32768). Exposed for tests.
uint32_t tessFactorToFixed(float f);

}  // namespace lt
