// box_spline.glsl -- the quartic box spline of a regular Loop patch, in the operation
// order of runtime/src/box_spline.cpp (so both round alike).
//
// Points (asset.h's and OpenSubdiv's order); the patch triangle is 4, 5, 8 with
// (s,t) = (0,0), (1,0), (0,1):
//
//          10-----11
//          / \   / \            boundaryMask bits 0..2: edge i is a boundary, its
//         /   \ /   \           3 outer points are phantoms (edge 0 -> 0,1,2;
//        7-----8-----9          edge 1 -> 6,9,11; edge 2 -> 10,7,3)
//       / \   / \   / \         bits 3..5: corner i is a boundary vertex without a
//      /   \ /   \ /   \        boundary edge of this patch (c0 -> 3,0;
//     3-----4-----5-----6       c1 -> 2,6; c2 -> 11,10)
//      \   / \   / \   /
//       \ /   \ /   \ /         phantom p = (a + b) - c, applied in the order below
//        0-----1-----2
//
// Basis: Stam (1999), 12 x 15 coefficients over the quartic monomials s^a t^b.

// Exponents (a, b) of the monomials, in the order of kBasis' columns.
const int kExpS[15] = int[15](0, 1, 0, 2, 1, 0, 3, 2, 1, 0, 4, 3, 2, 1, 0);
const int kExpT[15] = int[15](0, 0, 1, 0, 1, 2, 0, 1, 2, 3, 0, 1, 2, 3, 4);

// Stam's Loop basis, times 12: basis i = sum_m kBasis[i][m] s^a t^b / 12.
const float kBasis[12][15] = float[12][15](
    float[15](1, -2, -4, 0, 6, 6, 2, 0, -6, -4, -1, -2, 0, 2, 1),
    float[15](1, 2, -2, 0, -6, 0, -4, 0, 6, 2, 2, 4, 0, -2, -1),
    float[15](0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -1, -2, 0, 0, 0),
    float[15](1, -4, -2, 6, 6, 0, -4, -6, 0, 2, 1, 2, 0, -2, -1),
    float[15](6, 0, 0, -12, -12, -12, 8, 12, 12, 8, -1, -2, 0, -2, -1),
    float[15](1, 4, 2, 6, 6, 0, -4, -6, -12, -4, -1, -2, 0, 4, 2),
    float[15](0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0),
    float[15](1, -2, 2, 0, -6, 0, 2, 6, 0, -4, -1, -2, 0, 4, 2),
    float[15](1, 2, 4, 0, 6, 6, -4, -12, -6, -4, 2, 4, 0, -2, -1),
    float[15](0, 0, 0, 0, 0, 0, 2, 6, 6, 2, -1, -2, 0, -2, -1),
    float[15](0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -2, -1),
    float[15](0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 1));

// 1/12 as the CPU's 1.0f / 12.0f (written as bits: no constant folding in doubles).
#define LT_ONE_TWELFTH uintBitsToFloat(0x3daaaaabu)

float ipow(float x, int n) {
    precise float r = 1.0;
    for (int i = 0; i < n; ++i) r = r * x;
    return r;
}

// Weights of the 12 points for the position and the partial derivatives at (s,t).
// With `atEdge` (a constant at every call), t = 0 and the sums leave out the
// monomials that vanish there: those add exactly +-0 to sums that are never -0 (each
// starts at +0 and an exact cancellation rounds to +0), so the bits are the same.
void basisWeights(float s, float t, bool atEdge, out float w[12], out float ds[12], out float dt[12]) {
    precise float m[15], ms[15], mt[15];
    for (int j = 0; j < 15; ++j) {
        int a = kExpS[j], b = kExpT[j];
        m[j] = ipow(s, a) * ipow(t, b);
        ms[j] = a > 0 ? float(a) * ipow(s, a - 1) * ipow(t, b) : 0.0;
        mt[j] = b > 0 ? float(b) * ipow(s, a) * ipow(t, b - 1) : 0.0;
    }
    for (int i = 0; i < 12; ++i) {
        precise float sw = 0.0, ss = 0.0, st = 0.0;
        for (int j = 0; j < 15; ++j) {
            bool keepW = !atEdge || kExpT[j] == 0, keepT = !atEdge || kExpT[j] == 1;
            if (keepW) sw = sw + kBasis[i][j] * m[j];
            if (keepW) ss = ss + kBasis[i][j] * ms[j];
            if (keepT) st = st + kBasis[i][j] * mt[j];
        }
        precise float scaledW = sw * LT_ONE_TWELFTH, scaledS = ss * LT_ONE_TWELFTH, scaledT = st * LT_ONE_TWELFTH;
        w[i] = scaledW;
        ds[i] = scaledS;
        dt[i] = scaledT;
    }
}

void boxSplineWeights(float s, float t, out float w[12], out float ds[12], out float dt[12]) {
    basisWeights(s, t, false, w, ds, dt);
}

// boxSplineWeights(s, 0) bit for bit, with fewer terms: the compute passes' edge
// evaluations (watertight.glsl's evalCanonicalEdge).
void boxSplineEdgeWeights(float s, out float w[12], out float ds[12], out float dt[12]) {
    basisWeights(s, 0.0, true, w, ds, dt);
}

// p[i] = (p[a] + p[b]) - p[c]
#define LT_PHANTOM(i, a, b, c) { precise vec3 q = (p[a] + p[b]) - p[c]; p[i] = q; }

// Replaces the phantom points of a boundary patch (box_spline.cpp's fillPhantomPoints).
void fillPhantomPoints(uint mask, inout vec3 p[12]) {
    bool e0 = (mask & 1u) != 0u, e1 = (mask & 2u) != 0u, e2 = (mask & 4u) != 0u;
    if (e0) {
        if (e2) LT_PHANTOM(0, 4, 4, 8) else LT_PHANTOM(0, 4, 3, 7)
        LT_PHANTOM(1, 4, 5, 8)
        if (e1) LT_PHANTOM(2, 5, 5, 8) else LT_PHANTOM(2, 5, 6, 9)
    }
    if (e1) {
        if (e0) LT_PHANTOM(6, 5, 5, 4) else LT_PHANTOM(6, 5, 2, 1)
        LT_PHANTOM(9, 5, 8, 4)
        if (e2) LT_PHANTOM(11, 8, 8, 4) else LT_PHANTOM(11, 8, 10, 7)
    }
    if (e2) {
        if (e1) LT_PHANTOM(10, 8, 8, 5) else LT_PHANTOM(10, 8, 11, 9)
        LT_PHANTOM(7, 8, 4, 5)
        if (e0) LT_PHANTOM(3, 4, 4, 5) else LT_PHANTOM(3, 4, 0, 1)
    }
    if ((mask & 8u) != 0u) {
        LT_PHANTOM(3, 4, 7, 8)
        LT_PHANTOM(0, 4, 1, 5)
    }
    if ((mask & 16u) != 0u) {
        LT_PHANTOM(2, 5, 1, 4)
        LT_PHANTOM(6, 5, 9, 8)
    }
    if ((mask & 32u) != 0u) {
        LT_PHANTOM(11, 8, 9, 5)
        LT_PHANTOM(10, 8, 7, 4)
    }
}

// box_spline.cpp's sumWeighted: points q[0 .. n), summed over differences from q[4]
// (the weights sum to 1, the derivative weights to 0).
void sumWeighted(vec3 q[12], int n, float w[12], float ws[12], float wt[12], out vec3 pos, out vec3 du, out vec3 dv) {
    precise vec3 a = vec3(0.0), b = vec3(0.0), c = vec3(0.0);
    for (int i = 0; i < n; ++i) {
        precise vec3 x = q[i] - q[4];
        a = a + w[i] * x;
        b = b + ws[i] * x;
        c = c + wt[i] * x;
    }
    precise vec3 position = q[4] + a;
    pos = position;
    du = b;
    dv = c;
}

// Position and partial derivatives at (s,t).
void evalBoxSpline(vec3 p[12], float s, float t, out vec3 pos, out vec3 du, out vec3 dv) {
    float w[12], ws[12], wt[12];
    boxSplineWeights(s, t, w, ws, wt);
    sumWeighted(p, 12, w, ws, wt, pos, du, dv);
}
