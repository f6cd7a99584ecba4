// Displacement map sampling (see displacement.h). Every line here has a twin in
// shaders/displacement.glsl; change both together, in the same operation order.
#include "displacement.h"

namespace lt {
namespace {

// The sample q (0 .. 65535) at `index`, as a float (exact).
inline float sampleQ(const DisplacementMap& m, uint64_t index) { return float(m.values[index]); }

// Clamped to [0, 1]; NaN to 0.
inline float clamp01(float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; }

// The interpolated q at parameter t in [0, 1] along control-mesh edge `edge` from
// its smaller control vertex `lo` to `hi`: piecewise linear over the edge's R
// segments, whose ends are lo's sample, the edge's R - 1 samples and hi's. t = 0
// gives lo's sample and t = 1 hi's, exactly (q0 + 0 * d, and q0 + (q1 - q0) with
// integers below 2^16).
float edgeQ(const Asset& a, uint32_t lo, uint32_t hi, uint32_t edge, float t) {
    const DisplacementMap& m = a.displacement;
    const uint32_t R = m.resolution;
    const uint64_t interior = (R - 1) * uint64_t(R - 2) / 2;
    const uint64_t first = a.controlVertexCount() + uint64_t(a.faceCount()) * interior + uint64_t(edge) * (R - 1);
    const float x = t * float(R);  // exact: R is a power of two
    uint32_t k = uint32_t(x);      // floor (x >= 0)
    if (k > R - 1) k = R - 1;      // t = 1: the last segment, f = 1
    const float f = x - float(k);  // exact
    const float q0 = k == 0 ? sampleQ(m, lo) : sampleQ(m, first + k - 1);
    const float q1 = k + 1 == R ? sampleQ(m, hi) : sampleQ(m, first + k);
    return q0 + f * (q1 - q0);
}

// The interpolated q at an interior point (u > 0, v > 0, u + v < 1): barycentric
// over the triangle of the R-grid holding it. With (x, y) = R (u, v), cell (i, j) =
// floor(x, y) and (fx, fy) the fractions, the lower triangle (fx + fy <= 1) has
// corners (i, j), (i+1, j), (i, j+1), the upper one (i+1, j+1), (i, j+1), (i+1, j).
// Here i + j <= R - 1, and the upper triangle only occurs for i + j <= R - 2 (x + y
// < R exactly, and a float sum of fx + fy below 1 never rounds above 1).
float interiorQ(const Asset& a, uint32_t face, float u, float v) {
    const DisplacementMap& m = a.displacement;
    const float R = float(m.resolution);
    const float x = u * R, y = v * R;  // exact
    const uint32_t i = uint32_t(x), j = uint32_t(y);
    const float fx = x - float(i), fy = y - float(j);
    float q0, q1, q2, w0, w1, w2;
    if (fx + fy > 1.0f) {
        q0 = sampleQ(m, displacementSample(a, face, i + 1, j + 1));
        q1 = sampleQ(m, displacementSample(a, face, i, j + 1));
        q2 = sampleQ(m, displacementSample(a, face, i + 1, j));
        w0 = (fx + fy) - 1.0f;
        w1 = 1.0f - fx;
        w2 = 1.0f - fy;
    } else {
        q0 = sampleQ(m, displacementSample(a, face, i, j));
        q1 = sampleQ(m, displacementSample(a, face, i + 1, j));
        q2 = sampleQ(m, displacementSample(a, face, i, j + 1));
        w0 = (1.0f - fx) - fy;
        w1 = fx;
        w2 = fy;
    }
    return (w0 * q0 + w1 * q1) + w2 * q2;
}

}  // namespace

float sampleDisplacement(const Asset& asset, uint32_t baseFace, float u, float v) {
    const DisplacementMap& m = asset.displacement;
    if (!m.present()) return 0.0f;
    u = clamp01(u);
    v = clamp01(v);
    const uint32_t* c = &asset.faces[3 * size_t(baseFace)];
    const uint32_t* e = &m.faceEdges[3 * size_t(baseFace)];
    float q;
    if (v == 0.0f) {  // edge 0, c0 -> c1: u measures from c0
        q = c[0] < c[1] ? edgeQ(asset, c[0], c[1], e[0], u) : edgeQ(asset, c[1], c[0], e[0], 1.0f - u);
    } else if (u == 0.0f) {  // edge 2, c2 -> c0: v measures from c0
        q = c[0] < c[2] ? edgeQ(asset, c[0], c[2], e[2], v) : edgeQ(asset, c[2], c[0], e[2], 1.0f - v);
    } else if (u + v >= 1.0f) {  // edge 1, c1 -> c2: v measures from c1, u from c2
        q = c[1] < c[2] ? edgeQ(asset, c[1], c[2], e[1], v) : edgeQ(asset, c[2], c[1], e[1], u);
    } else {
        q = interiorQ(asset, baseFace, u, v);
    }
    return m.scale * (q * kUnorm16) + m.bias;
}

}  // namespace lt
