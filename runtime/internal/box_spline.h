// Private to the runtime: the quartic box spline of a regular Loop patch.
//
// Points (OpenSubdiv's order; the patch triangle is 4, 5, 8 with (s,t) = (0,0),
// (1,0), (0,1)):
//
//          10-----11
//          / \   / \             .
//         /   \ /   \            .
//        7-----8-----9
//       / \   / \   / \          .
//      /   \ /   \ /   \         .
//     3-----4-----5-----6
//      \   / \   / \   /
//       \ /   \ /   \ /
//        0-----1-----2
//
// Basis: Stam, "Evaluation of Loop subdivision surfaces" (1999), as a 12 x 15
// coefficient matrix over the quartic monomials in (s,t).
#pragma once

#include <cstddef>
#include <cstdint>

namespace lt {

// Weights of the 12 points for the position and the two partial derivatives at
// (s,t). Any of the outputs may be null.
void boxSplineWeights(float s, float t, float w[12], float ds[12], float dt[12]);

// Replaces the phantom points of a boundary patch by extrapolation from real ones
// (point = a + b - c, as OpenSubdiv's boundary masks do): `mask` is
// RegularPatch::boundaryMask, `p` the 12 points (3 floats each).
void fillPhantomPoints(uint8_t mask, float p[12][3]);

// The weighted sums of points q[0 .. n) (n >= 5) with affine weights w (position)
// and ws, wt (derivatives: weights summing to 0), summed over differences from
// q[4], so rounding scales with the patch, not the coordinates. The one operation
// order of every box-spline sum (shaders/box_spline.glsl's sumWeighted).
void sumWeighted(const float* const q[], int n, const float w[], const float ws[], const float wt[], float pos[3],
                 float du[3], float dv[3]);

// Evaluates position and partial derivatives of a patch with points `p` at (s,t).
void evalBoxSpline(const float p[12][3], float s, float t, float pos[3], float du[3], float dv[3]);

// The 12 points' weights at one (s,t): boxSplineWeights' three outputs.
struct BoxWeights {
    float w[12], ds[12], dt[12];
};
BoxWeights boxSplineWeights(float s, float t);

// evalBoxSpline with the weights of its (s,t) computed before: the same bits, for
// callers that evaluate many patches at the same domain points.
void evalBoxSpline(const float p[12][3], const BoxWeights& b, float pos[3], float du[3], float dv[3]);

// evalBoxSpline at many points of one patch, the same bits at each: `weights` holds
// the points' weights by kind and point, w of point j at [i][j], ds at [12 + i][j],
// dt at [24 + i][j] for point i (`stride` floats a row, rows 0 .. 35), and the
// results go to pos, du, dv by coordinate and point (pos[k * stride + j]). The
// points' differences from point 4 are taken once, and each point's sums run in
// sumWeighted's order, so the loop over points vectorizes.
void evalBoxSplineBatch(const float p[12][3], const float* weights, size_t stride, size_t count, float* pos, float* du,
                        float* dv);

}  // namespace lt
