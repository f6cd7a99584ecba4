// exact_math.glsl -- float division and square root rounded correctly (to nearest,
// as IEEE 754 and the CPU round them), on any Vulkan device.
//
// Vulkan lets a device compute x / y within 2.5 ULP and sqrt(x) as 1 / inversesqrt(x),
// so the same shader gives other bits on other devices. Where the bits decide which
// domain points are drawn (screen-space factors: record_factors.glsl, the CPU's
// lod.h), that would draw other points than the CPU evaluator. So the hardware's
// result is only a start: it is moved to its neighbour while the exact value lies
// beyond the midpoint between them, and the midpoint test is done in integers
// (umulExtended: a 32 x 32 -> 64-bit product, exact everywhere):
//
//       q-          mid-          q           mid+          q+
//   ----|-------------:-----------|-------------:-----------|----
//                     |<- exact a/b lies here ->|   q is RN(a/b)
//
//   mid+ = (2 mq + 1) 2^(eq - 1), mid- = (2 mq - 1) 2^(eq - 1), or (4 mq - 1) 2^(eq - 2)
//   when q is a power of two (its lower neighbour is twice as close); a float is
//   m 2^e with m its 24-bit integer significand. a / b lies above mid+ iff
//   ma 2^ea > mid+ mb 2^eb, and sqrt(x) above it iff mx 2^ex > mid+^2: products of
//   at most 25-bit integers, compared as 64-bit integers after a shift of the smaller
//   side. The exact quotient or root of floats never lies on a midpoint (it would
//   need 25 significant bits), so there is no tie to break.
//
// Inputs: positive normal floats with a normal result (the screen-space factors'
// lengths and distances), zero, or else (infinite, NaN, subnormal) the hardware's
// result is returned as it is.
#ifndef LT_EXACT_MATH_GLSL
#define LT_EXACT_MATH_GLSL

// f = significand * 2^exponent, significand in [2^23, 2^24).
void ltDecompose(float f, out uint significand, out int exponent) {
    uint bits = floatBitsToUint(f);
    significand = (bits & 0x7fffffu) | 0x800000u;
    exponent = int(bits >> 23) - 150;
}

bool ltNormalPositive(float f) {
    uint e = floatBitsToUint(f) >> 23;   // the sign bit makes negatives >= 256
    return e >= 1u && e <= 254u;
}

// Sign of (n << shift) - (hi, lo) for n < 2^26, 0 <= shift <= 38: -1, 0 or 1.
int ltCompareShifted(uint n, int shift, uint hi, uint lo) {
    uint nhi = shift >= 32 ? n << uint(shift - 32) : (shift == 0 ? 0u : n >> uint(32 - shift));
    uint nlo = shift >= 32 ? 0u : n << uint(shift);
    if (nhi != hi) return nhi > hi ? 1 : -1;
    if (nlo != lo) return nlo > lo ? 1 : -1;
    return 0;
}

// The midpoints beside q = mq 2^eq: mid+ (above) or mid- (below) as m 2^e.
void ltMidpoint(uint mq, int eq, bool above, out uint m, out int e) {
    if (above) {
        m = 2u * mq + 1u;
        e = eq - 1;
    } else if (mq == 0x800000u) {
        m = 4u * mq - 1u;
        e = eq - 2;
    } else {
        m = 2u * mq - 1u;
        e = eq - 1;
    }
}

// Sign of a / b - mid (the midpoint beside q), a, b, q positive normal.
int ltQuotientSide(float a, float b, float q, bool above) {
    uint ma, mb, mq, m, hi, lo;
    int ea, eb, eq, e;
    ltDecompose(a, ma, ea);
    ltDecompose(b, mb, eb);
    ltDecompose(q, mq, eq);
    ltMidpoint(mq, eq, above, m, e);
    umulExtended(m, mb, hi, lo);            // mid b = (m mb) 2^(e + eb), below 2^50
    int shift = ea - (e + eb);              // a = (ma << shift) 2^(e + eb)
    if (shift < 0) return -1;               // q is far above a / b (not a start the hardware gives)
    if (shift > 38) return 1;
    return ltCompareShifted(ma, shift, hi, lo);
}

// Sign of sqrt(x) - mid, x and s positive normal.
int ltRootSide(float x, float s, bool above) {
    uint mx, ms, m, hi, lo;
    int ex, es, e;
    ltDecompose(x, mx, ex);
    ltDecompose(s, ms, es);
    ltMidpoint(ms, es, above, m, e);
    umulExtended(m, m, hi, lo);             // mid^2 = m^2 2^(2e), below 2^52
    int shift = ex - 2 * e;
    if (shift < 0) return -1;
    if (shift > 38) return 1;
    return ltCompareShifted(mx, shift, hi, lo);
}

float ltNextUp(float f) { return uintBitsToFloat(floatBitsToUint(f) + 1u); }
float ltNextDown(float f) { return uintBitsToFloat(floatBitsToUint(f) - 1u); }

// a / b rounded to nearest, from the start q (the hardware's a / b).
float exactDivideFrom(float a, float b, float q) {
    if (a == 0.0 && ltNormalPositive(b)) return 0.0;
    for (int i = 0; i < 8; ++i) {   // a start within 2.5 ULP takes at most 3 steps
        if (!ltNormalPositive(a) || !ltNormalPositive(b) || !ltNormalPositive(q)) return q;
        if (ltQuotientSide(a, b, q, true) > 0) {
            q = ltNextUp(q);
        } else if (ltQuotientSide(a, b, q, false) < 0) {
            q = ltNextDown(q);
        } else {
            break;
        }
    }
    return q;
}

// sqrt(x) rounded to nearest, from the start s (the hardware's sqrt(x)).
float exactSqrtFrom(float x, float s) {
    if (x == 0.0) return 0.0;
    for (int i = 0; i < 8; ++i) {
        if (!ltNormalPositive(x) || !ltNormalPositive(s)) return s;
        if (ltRootSide(x, s, true) > 0) {
            s = ltNextUp(s);
        } else if (ltRootSide(x, s, false) < 0) {
            s = ltNextDown(s);
        } else {
            break;
        }
    }
    return s;
}

float exactDivide(float a, float b) { return exactDivideFrom(a, b, a / b); }
float exactSqrt(float x) { return exactSqrtFrom(x, sqrt(x)); }

#endif
