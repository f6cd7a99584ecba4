// Quartic box spline evaluation (see box_spline.h).
#include "box_spline.h"

namespace lt {
namespace {

// Exponents (a, b) of the monomials s^a t^b, in the order of kBasis' columns.
const int kExp[15][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}, {3, 0}, {2, 1},
                         {1, 2}, {0, 3}, {4, 0}, {3, 1}, {2, 2}, {1, 3}, {0, 4}};

// Stam's Loop basis, times 12: basis i = sum_m kBasis[i][m] s^a t^b / 12.
constexpr float kBasis[12][15] = {
    {1, -2, -4, 0, 6, 6, 2, 0, -6, -4, -1, -2, 0, 2, 1},
    {1, 2, -2, 0, -6, 0, -4, 0, 6, 2, 2, 4, 0, -2, -1},
    {0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -1, -2, 0, 0, 0},
    {1, -4, -2, 6, 6, 0, -4, -6, 0, 2, 1, 2, 0, -2, -1},
    {6, 0, 0, -12, -12, -12, 8, 12, 12, 8, -1, -2, 0, -2, -1},
    {1, 4, 2, 6, 6, 0, -4, -6, -12, -4, -1, -2, 0, 4, 2},
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0},
    {1, -2, 2, 0, -6, 0, 2, 6, 0, -4, -1, -2, 0, 4, 2},
    {1, 2, 4, 0, 6, 6, -4, -12, -6, -4, 2, 4, 0, -2, -1},
    {0, 0, 0, 0, 0, 0, 2, 6, 6, 2, -1, -2, 0, -2, -1},
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -2, -1},
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 1},
};

// kBasis by column: kColumn[j][i] = kBasis[i][j].
struct Columns {
    float c[15][12];
};
constexpr Columns columns() {
    Columns out{};
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 15; ++j) out.c[j][i] = kBasis[i][j];
    return out;
}
constexpr Columns kColumn = columns();

// out[i] = sum over j of kBasis[i][j] * mono[j], j in ascending order, as the shaders
// add (by column, so that the 12 sums go side by side). A monomial that is exactly 0
// (at s = 0 or t = 0: the edge points) adds +-0 to each sum; a sum starts at +0 and so
// is never -0, and x + (+-0) is x for every other x: those terms change no bit and are
// left out, as box_spline.glsl's boxSplineEdgeWeights does (two thirds of them at t = 0).
void weightedSums(const float mono[15], float out[12]) {
    float sum[12] = {};  // local: out might alias mono, and would not vectorize
    for (int j = 0; j < 15; ++j) {
        if (mono[j] == 0.0f) continue;
        const float x = mono[j];
        for (int i = 0; i < 12; ++i) sum[i] = sum[i] + kColumn.c[j][i] * x;
    }
    for (int i = 0; i < 12; ++i) out[i] = sum[i];
}

// One phantom point: p = a + b - c.
struct Phantom {
    int p, a, b, c;
};

void apply(const Phantom& ph, float p[12][3]) {
    for (int k = 0; k < 3; ++k) p[ph.p][k] = (p[ph.a][k] + p[ph.b][k]) - p[ph.c][k];
}

}  // namespace

void boxSplineWeights(float s, float t, float w[12], float ds[12], float dt[12]) {
    // s^n and t^n multiplied out from 1, as the shaders' ipow does.
    float sp[5] = {1.0f}, tp[5] = {1.0f};
    for (int n = 1; n < 5; ++n) sp[n] = sp[n - 1] * s, tp[n] = tp[n - 1] * t;
    float m[15], ms[15], mt[15];
    for (int j = 0; j < 15; ++j) {
        int a = kExp[j][0], b = kExp[j][1];
        m[j] = sp[a] * tp[b];
        ms[j] = a > 0 ? float(a) * sp[a - 1] * tp[b] : 0.0f;
        mt[j] = b > 0 ? float(b) * sp[a] * tp[b - 1] : 0.0f;
    }
    const float scale = 1.0f / 12.0f;
    float sums[3][12];
    weightedSums(m, sums[0]);
    weightedSums(ms, sums[1]);
    weightedSums(mt, sums[2]);
    for (int i = 0; i < 12; ++i) {
        if (w) w[i] = sums[0][i] * scale;
        if (ds) ds[i] = sums[1][i] * scale;
        if (dt) dt[i] = sums[2][i] * scale;
    }
}

void fillPhantomPoints(uint8_t mask, float p[12][3]) {
    bool e0 = mask & 1, e1 = mask & 2, e2 = mask & 4;
    if (e0) {
        apply(e2 ? Phantom{0, 4, 4, 8} : Phantom{0, 4, 3, 7}, p);
        apply({1, 4, 5, 8}, p);
        apply(e1 ? Phantom{2, 5, 5, 8} : Phantom{2, 5, 6, 9}, p);
    }
    if (e1) {
        apply(e0 ? Phantom{6, 5, 5, 4} : Phantom{6, 5, 2, 1}, p);
        apply({9, 5, 8, 4}, p);
        apply(e2 ? Phantom{11, 8, 8, 4} : Phantom{11, 8, 10, 7}, p);
    }
    if (e2) {
        apply(e1 ? Phantom{10, 8, 8, 5} : Phantom{10, 8, 11, 9}, p);
        apply({7, 8, 4, 5}, p);
        apply(e0 ? Phantom{3, 4, 4, 5} : Phantom{3, 4, 0, 1}, p);
    }
    if (mask & 8) {
        apply({3, 4, 7, 8}, p);
        apply({0, 4, 1, 5}, p);
    }
    if (mask & 16) {
        apply({2, 5, 1, 4}, p);
        apply({6, 5, 9, 8}, p);
    }
    if (mask & 32) {
        apply({11, 8, 9, 5}, p);
        apply({10, 8, 7, 4}, p);
    }
}

void sumWeighted(const float* const q[], int n, const float w[], const float ws[], const float wt[], float pos[3],
                 float du[3], float dv[3]) {
    for (int k = 0; k < 3; ++k) {
        float a = 0, b = 0, c = 0;
        for (int i = 0; i < n; ++i) {
            float x = q[i][k] - q[4][k];
            a = a + w[i] * x;
            b = b + ws[i] * x;
            c = c + wt[i] * x;
        }
        pos[k] = q[4][k] + a;
        du[k] = b;
        dv[k] = c;
    }
}

BoxWeights boxSplineWeights(float s, float t) {
    BoxWeights b;
    boxSplineWeights(s, t, b.w, b.ds, b.dt);
    return b;
}

void evalBoxSpline(const float p[12][3], const BoxWeights& b, float pos[3], float du[3], float dv[3]) {
    const float* q[12];
    for (int i = 0; i < 12; ++i) q[i] = p[i];
    sumWeighted(q, 12, b.w, b.ds, b.dt, pos, du, dv);
}

void evalBoxSpline(const float p[12][3], float s, float t, float pos[3], float du[3], float dv[3]) {
    evalBoxSpline(p, boxSplineWeights(s, t), pos, du, dv);
}

namespace {

// a += w x, b += ws x, c += wt x over n points: separate arrays (restrict), so that
// the compiler vectorizes it across the points.
void accumulate(const float* __restrict w, const float* __restrict ws, const float* __restrict wt, float x, size_t n,
                float* __restrict a, float* __restrict b, float* __restrict c) {
    for (size_t j = 0; j < n; ++j) {
        a[j] = a[j] + w[j] * x;
        b[j] = b[j] + ws[j] * x;
        c[j] = c[j] + wt[j] * x;
    }
}

}  // namespace

void evalBoxSplineBatch(const float p[12][3], const float* weights, size_t stride, size_t count, float* pos, float* du,
                        float* dv) {
    for (int k = 0; k < 3; ++k) {
        float x[12];
        for (int i = 0; i < 12; ++i) x[i] = p[i][k] - p[4][k];
        float* a = pos + size_t(k) * stride;
        float* b = du + size_t(k) * stride;
        float* c = dv + size_t(k) * stride;
        for (size_t j = 0; j < count; ++j) a[j] = b[j] = c[j] = 0.0f;
        for (int i = 0; i < 12; ++i)  // sumWeighted's order: point 0 first
            accumulate(weights + size_t(i) * stride, weights + size_t(12 + i) * stride,
                       weights + size_t(24 + i) * stride, x[i], count, a, b, c);
        const float centre = p[4][k];
        for (size_t j = 0; j < count; ++j) a[j] = centre + a[j];
    }
}

}  // namespace lt
