// tess_domain.cpp - the D3D11 tessellator's triangle domain, in 16.16 fixed
// point. See tess_domain.h for the conventions and the factor rules.
//
// Contents
//   [FIXED]    16.16 helpers and the factor conversion
//   [EDGE]     EdgeRule: how many points an edge gets and where they go
//   [FACTORS]  clamping, rounding and parity of the four factors
//   [POINTS]   the outer ring, the interior rings and the centre
//   [STITCH]   triangles between two consecutive rings
//   [API]      tessellateTriangle
//
// Arithmetic is unsigned 32-bit throughout, like the GPU's, so wrap-around
// (should it ever happen) would match too.

#include "tess_domain.h"

#include <cassert>
#include <cmath>
#include <limits>

namespace lt {
namespace {

// ===========================================================================
// [FIXED]
// ===========================================================================

using Fx = uint32_t;  // 16.16 fixed point, unsigned

constexpr int kFracBits = 16;
constexpr Fx kOne = 1u << kFracBits;
constexpr Fx kHalf = kOne >> 1;
constexpr Fx kFracMask = kOne - 1;
constexpr Fx kIntMask = 0x7fff0000u;
constexpr Fx kOneThird = 0x5555u;   // 1/3 truncated
constexpr Fx kTwoThirds = 0xaaaau;  // 2/3 truncated

constexpr int kMaxFactor = 64;

Fx fxFloor(Fx a) { return a & kIntMask; }
Fx fxCeil(Fx a) { return (a & kFracMask) ? fxFloor(a) + kOne : a; }

// 1/n in 16.16, rounded to nearest (n = 1..64). Entry 0 is never used.
struct ReciprocalTable {
    Fx v[kMaxFactor + 1];
    constexpr ReciprocalTable() : v() {
        v[0] = 0xffffffffu;
        for (uint32_t n = 1; n <= kMaxFactor; ++n) v[n] = (kOne + n / 2) / n;
    }
};
constexpr ReciprocalTable kReciprocal;

// Exact: fx <= 2^16 here, both parts are representable.
float fxToFloat(Fx a) {
    return static_cast<float>(a >> kFracBits) + static_cast<float>(a & kFracMask) * (1.0f / static_cast<float>(kOne));
}

// ===========================================================================
// [EDGE] One tessellation factor applied to a unit segment.
//
// The segment is split into two mirrored halves. Half a factor f is h = f/2
// (for odd parity h = f/2 + 1/2, so that an odd factor has a middle
// segment). Each half gets ceil(h) points counted from its end (for even
// parity the middle point 1/2 is extra). When h is fractional, the points
// are a lerp, by frac(h), between the positions for floor(h) and ceil(h)
// segments a half; one point (the "split point", chosen by a ruler function
// so that points appear in a stable order as f grows) exists only on the
// ceil side and slides out of its floor neighbour.
// ===========================================================================

struct EdgeRule {
    bool odd = false;
    Fx halfFraction = 0;      // frac(h)
    int halfPoints = 0;       // ceil(h): points a half, mirror excluded
    int splitPoint = 0;       // index that exists only with ceil(h)
    Fx invFloorSegments = 0;  // 1 / (segments of the whole edge at floor(h))
    Fx invCeilSegments = 0;   // 1 / (segments of the whole edge at ceil(h))

    // Points on the whole edge, both ends included.
    int pointCount() const { return odd ? 2 * halfPoints : 2 * halfPoints + 1; }
};

// Clears the highest set bit of v (v >= 0).
int clearTopBit(int v) {
    for (int bit = 30; bit >= 0; --bit)
        if (v & (1 << bit)) return v & ~(1 << bit);
    return 0;
}

EdgeRule makeEdgeRule(Fx factor, bool odd) {
    EdgeRule r;
    r.odd = odd;
    Fx half = (factor + 1) / 2;  // +1: round
    // A factor of 1 with even parity is treated like 2 (one point in the middle).
    if (odd || half == kHalf) half += kHalf;
    const Fx lo = fxFloor(half);
    const Fx hi = fxCeil(half);
    r.halfFraction = half - lo;
    r.halfPoints = static_cast<int>(hi >> kFracBits);
    const int loInt = static_cast<int>(lo >> kFracBits);
    if (lo == hi)
        r.splitPoint = r.halfPoints + 1;  // never reached
    else if (odd)
        r.splitPoint = (loInt == 1) ? 0 : (clearTopBit(loInt - 1) << 1) + 1;
    else
        r.splitPoint = (clearTopBit(loInt) << 1) + 1;
    int loSegments = static_cast<int>((lo * 2) >> kFracBits);
    int hiSegments = static_cast<int>((hi * 2) >> kFracBits);
    if (odd) {
        loSegments -= 1;
        hiSegments -= 1;
    }
    assert(loSegments >= 1 && hiSegments <= kMaxFactor);
    r.invFloorSegments = kReciprocal.v[loSegments];
    r.invCeilSegments = kReciprocal.v[hiSegments];
    return r;
}

// Position in [0, 1] of point `i` (0 .. pointCount()-1) along the edge.
Fx placePoint(const EdgeRule& r, int i) {
    bool mirrored = false;
    if (i >= r.halfPoints) {
        i = 2 * r.halfPoints - i - (r.odd ? 1 : 0);
        mirrored = true;
    }
    if (i == r.halfPoints) return kHalf;  // even parity: the exact middle
    const Fx onCeil = static_cast<Fx>(i);
    const Fx onFloor = (i > r.splitPoint) ? onCeil - 1 : onCeil;
    const Fx atFloor = onFloor * r.invFloorSegments;
    const Fx atCeil = onCeil * r.invCeilSegments;
    Fx t = atFloor * (kOne - r.halfFraction) + atCeil * r.halfFraction;
    t = (t + kHalf) >> kFracBits;
    return mirrored ? kOne - t : t;
}

// ===========================================================================
// [FACTORS]
// ===========================================================================

struct Factors {
    bool culled = false;
    bool minimal = false;  // every factor is 1: a single triangle
    EdgeRule outer[3];
    EdgeRule inner;
    int outerPoints[3] = {0, 0, 0};
    int innerPoints = 0;  // points across the inner partition (at least 3 or 4)
};

// min(hi, max(lo, f)); NaN -> lo. Denormals compare as 0 (below lo anyway).
float clampFactor(float f, float lo, float hi) {
    if (std::isnan(f) || !(f > lo)) return lo;
    return (f > hi) ? hi : f;
}

bool isEvenInteger(float f) { return (static_cast<int>(f) & 1) == 0; }

Factors processFactors(const float outerIn[3], float innerIn, TessSpacing spacing) {
    Factors p;
    // Culled: NaN, <= 0, or a denormal (the GPU flushes denormals to zero).
    for (int e = 0; e < 3; ++e) {
        if (!(outerIn[e] >= std::numeric_limits<float>::min())) {
            p.culled = true;
            return p;
        }
    }
    const bool integer = spacing == TessSpacing::Equal;
    const float lo = (spacing == TessSpacing::FractionalEven) ? 2.0f : 1.0f;
    const float hi = (spacing == TessSpacing::FractionalOdd) ? 63.0f : 64.0f;

    float outer[3];
    for (int e = 0; e < 3; ++e) {
        outer[e] = clampFactor(outerIn[e], lo, hi);
        if (integer) outer[e] = std::ceil(outer[e]);
    }
    float innerLo = lo;
    if (spacing == TessSpacing::FractionalOdd) {
        // 1 + 2^-17: above it an outer factor converts to more than 1.0 in 16.16.
        const float aboveOne = 1.0f + 1.0f / 131072.0f;
        if (outer[0] > aboveOne || outer[1] > aboveOne || outer[2] > aboveOne)
            innerLo = 1.0f + 1.0f / 65536.0f;  // keep an inner ring
    }
    float inner = clampFactor(innerIn, innerLo, hi);
    if (integer) inner = std::ceil(inner);

    bool outerOdd[3];
    bool innerOdd;
    if (integer) {
        for (int e = 0; e < 3; ++e) outerOdd[e] = !isEvenInteger(outer[e]);
        innerOdd = !(isEvenInteger(inner) || inner == 1.0f);
    } else {
        const bool odd = spacing == TessSpacing::FractionalOdd;
        for (int e = 0; e < 3; ++e) outerOdd[e] = odd;
        innerOdd = odd;
    }

    Fx outerFx[3];
    for (int e = 0; e < 3; ++e) outerFx[e] = tessFactorToFixed(outer[e]);
    const Fx innerFx = tessFactorToFixed(inner);

    if (spacing != TessSpacing::FractionalEven && innerFx == kOne && outerFx[0] == kOne && outerFx[1] == kOne &&
        outerFx[2] == kOne) {
        p.minimal = true;
        return p;
    }
    for (int e = 0; e < 3; ++e) {
        p.outer[e] = makeEdgeRule(outerFx[e], outerOdd[e]);
        p.outerPoints[e] = p.outer[e].pointCount();
    }
    p.inner = makeEdgeRule(innerFx, innerOdd);
    // An inner factor of 1 still gets one ring (degenerate transition).
    const int minInner = innerOdd ? 4 : 3;
    p.innerPoints = p.inner.pointCount() < minInner ? minInner : p.inner.pointCount();
    return p;
}

// Number of interior rings that carry points (the outer ring excluded).
int interiorRingCount(const Factors& p) { return (p.innerPoints >> 1) - 1; }

size_t countPoints(const Factors& p) {
    size_t n = static_cast<size_t>(p.outerPoints[0] + p.outerPoints[1] + p.outerPoints[2] - 3);
    for (int ring = 1; ring <= interiorRingCount(p); ++ring) n += 3 * static_cast<size_t>(p.innerPoints - 1 - 2 * ring);
    if (!p.inner.odd) n += 1;
    return n;
}

size_t countTriangles(const Factors& p) {
    size_t n = 0;
    int outerPoints[3] = {p.outerPoints[0], p.outerPoints[1], p.outerPoints[2]};
    const int rings = (p.innerPoints + 1) >> 1;  // the centre point counts as a ring
    for (int ring = 1; ring < rings; ++ring) {
        const int innerEdgePoints = p.innerPoints - 2 * ring;
        for (int e = 0; e < 3; ++e) {
            n += static_cast<size_t>(innerEdgePoints + outerPoints[e] - 2);
            outerPoints[e] = innerEdgePoints;
        }
    }
    if (p.inner.odd) n += 1;
    return n;
}

// ===========================================================================
// [POINTS]
// ===========================================================================

void pushPoint(TessDomain& out, Fx u, Fx v) {
    const float x = fxToFloat(u);
    const float y = fxToFloat(v);
    out.coords.push_back(x);
    out.coords.push_back(y);
    out.coords.push_back((1.0f - x) - y);  // as the GPU derives gl_TessCoord.z
}

void generatePoints(const Factors& p, TessDomain& out) {
    // Outer ring. Edge 0 (u == 0) runs v: 1 -> 0, edge 1 (v == 0) runs u: 0 -> 1,
    // edge 2 (w == 0) runs u: 1 -> 0. Each edge omits its last point (the next
    // edge's first).
    for (int e = 0; e < 3; ++e) {
        const int last = p.outerPoints[e] - 1;
        for (int i = 0; i < last; ++i) {
            const Fx t = placePoint(p.outer[e], e == 1 ? i : last - i);
            if (e == 0)
                pushPoint(out, 0, t);
            else if (e == 1)
                pushPoint(out, t, 0);
            else
                pushPoint(out, t, kOne - t);
        }
    }
    // Interior rings. Ring r reuses the inner partition's points r .. n-1-r on
    // each edge, pushed inward: the edge-normal coordinate is the inner point r
    // scaled by 2/3 (barycentric distance to the edge), and the along-edge
    // coordinate loses half of it so the ring stays centred.
    for (int ring = 1; ring <= interiorRingCount(p); ++ring) {
        const int first = ring;
        const int last = p.innerPoints - 1 - ring;
        Fx inward = placePoint(p.inner, ring) * kTwoThirds;
        inward = (inward + kHalf) >> kFracBits;
        const Fx shift = (inward + 1) / 2;  // +1: round
        for (int e = 0; e < 3; ++e) {
            for (int i = first; i < last; ++i) {
                const Fx t = placePoint(p.inner, e == 1 ? i : last - (i - first)) - shift;
                if (e == 0)
                    pushPoint(out, inward, t);
                else if (e == 1)
                    pushPoint(out, t, inward);
                else
                    pushPoint(out, t, kOne - t - inward);
            }
        }
    }
    if (!p.inner.odd) pushPoint(out, kOneThird, kOneThird);
}

// ===========================================================================
// [STITCH]
// ===========================================================================

// Emits triangles given in the tessellator's native order (clockwise with the
// v axis down); Ccw swaps the last two corners.
struct TriangleSink {
    std::vector<uint32_t>* tris;
    bool ccw;
    void operator()(uint32_t a, uint32_t b, uint32_t c) const {
        tris->push_back(a);
        tris->push_back(ccw ? c : b);
        tris->push_back(ccw ? b : c);
    }
};

// The points of one ring edge, addressed 0 .. count-1 from the edge's start.
// The last point of a ring's last edge is the ring's first point.
struct EdgeRow {
    uint32_t base = 0;
    int count = 0;
    bool wraps = false;
    uint32_t wrapTo = 0;
    uint32_t operator[](int k) const {
        assert(k >= 0 && k < count);
        return (wraps && k == count - 1) ? wrapTo : base + static_cast<uint32_t>(k);
    }
};

// Ruler order of the half-edge positions 0..32: step i of a stitch looks at
// position rulerPosition(i); the position exists on a half with h points when
// it is < h. Step 0 is position 0, step 1 the middle (32), then the positions
// of the coarsest levels first (16, 8, 4, ...), interleaved with the finest.
constexpr int rulerPosition(int i) {
    if (i == 0) return 0;
    if (i == 1) return 32;
    if ((i & 1) == 0) return 15 + i / 2;
    int j = (i - 1) / 2;  // 1 .. 15
    int level = 0;
    while ((j & 1) == 0) {
        j >>= 1;
        ++level;
    }
    return (8 >> level) + (j - 1) / 2;
}

// Joins the outer ring's edge to the first interior ring's edge, whose
// factors may differ. Walks both half-edges in ruler order so that each
// point of either row is fanned to the nearest point of the other, then the
// middle, then the second halves in reverse order.
void stitchTransition(const EdgeRow& in, const EdgeRule& inRule, const EdgeRow& out, const EdgeRule& outRule,
                      const TriangleSink& emit) {
    const int inHalf = inRule.halfPoints - (inRule.odd ? 1 : 0);
    const int outHalf = outRule.halfPoints - (outRule.odd ? 1 : 0);
    int i = 0;
    int o = 0;
    auto advanceIn = [&] {
        emit(in[i], out[o], in[i + 1]);
        ++i;
    };
    auto advanceOut = [&] {
        emit(out[o], out[o + 1], in[i]);
        ++o;
    };
    if (outHalf > 0) advanceOut();
    for (int step = 1; step <= 32; ++step) {
        const int pos = rulerPosition(step);
        if (pos < inHalf) advanceIn();
        if (pos < outHalf) advanceOut();
    }
    if (inRule.odd && outRule.odd) {  // a quad in the middle
        emit(in[i], out[o], in[i + 1]);
        emit(in[i + 1], out[o], out[o + 1]);
        ++i;
        ++o;
    } else if (outRule.odd) {  // only the outer row has a middle segment
        emit(in[i], out[o], out[o + 1]);
        ++o;
    } else if (inRule.odd) {  // only the inner row has a middle segment
        emit(in[i], out[o], in[i + 1]);
        ++i;
    }
    for (int step = 32; step >= 1; --step) {
        const int pos = rulerPosition(step);
        if (pos < outHalf) advanceOut();
        if (pos < inHalf) advanceIn();
    }
    if (outHalf > 0) advanceOut();
    assert(i == in.count - 1 && o == out.count - 1);
}

// Joins two interior ring edges (out.count == in.count + 2): a triangle at
// each corner, and quads in between whose diagonals mirror at the middle.
void stitchRegular(const EdgeRow& in, const EdgeRow& out, const TriangleSink& emit) {
    int i = 0;
    int o = 0;
    emit(out[o], out[o + 1], in[i]);
    ++o;
    const int quads = in.count - 1;
    for (int q = 0; q < quads; ++q, ++i, ++o) {
        if (q < in.count / 2) {
            emit(out[o], in[i + 1], in[i]);
            emit(out[o], out[o + 1], in[i + 1]);
        } else {
            emit(in[i], out[o], out[o + 1]);
            emit(in[i], out[o + 1], in[i + 1]);
        }
    }
    emit(out[o], out[o + 1], in[i]);
}

void generateTriangles(const Factors& p, const TriangleSink& emit) {
    const int rings = (p.innerPoints + 1) >> 1;  // the centre point counts as a ring
    int outerPoints[3] = {p.outerPoints[0], p.outerPoints[1], p.outerPoints[2]};
    uint32_t outsideBase = 0;
    uint32_t insideBase = static_cast<uint32_t>(p.outerPoints[0] + p.outerPoints[1] + p.outerPoints[2] - 3);
    for (int ring = 1; ring < rings; ++ring) {
        const int innerEdgePoints = p.innerPoints - 2 * ring;
        const uint32_t outsideRingStart = outsideBase;
        const uint32_t insideRingStart = insideBase;
        for (int e = 0; e < 3; ++e) {
            const bool lastEdge = e == 2;
            const EdgeRow out{outsideBase, outerPoints[e], lastEdge, outsideRingStart};
            const EdgeRow in{insideBase, innerEdgePoints, lastEdge, insideRingStart};
            if (ring == 1)
                stitchTransition(in, p.inner, out, p.outer[e], emit);
            else
                stitchRegular(in, out, emit);
            outsideBase += static_cast<uint32_t>(outerPoints[e] - 1);
            insideBase += static_cast<uint32_t>(innerEdgePoints - 1);
            outerPoints[e] = innerEdgePoints;
        }
    }
    if (p.inner.odd) emit(outsideBase, outsideBase + 1, outsideBase + 2);
}

}  // namespace

// ===========================================================================
// [API]
// ===========================================================================

uint32_t tessFactorToFixed(float f) {
    assert(std::isfinite(f) && f >= 0.0f && f < 32768.0f);
    // f * 2^16 is exact in double; round half to even by hand, so the result
    // does not depend on the floating-point rounding mode.
    const double scaled = static_cast<double>(f) * 65536.0;
    const double whole = std::floor(scaled);
    uint32_t fx = static_cast<uint32_t>(whole);
    const double rest = scaled - whole;
    if (rest > 0.5 || (rest == 0.5 && (fx & 1u))) fx += 1;
    return fx;
}

void tessellateTriangle(const float outer[3], float inner, TessSpacing spacing, TessDomain& out, TessWinding winding) {
    assert(outer != nullptr);
    out.coords.clear();
    out.triangles.clear();
    const Factors p = processFactors(outer, inner, spacing);
    if (p.culled) return;
    const TriangleSink emit{&out.triangles, winding == TessWinding::Ccw};
    if (p.minimal) {
        out.coords.reserve(9);
        out.triangles.reserve(3);
        pushPoint(out, 0, kOne);  // corner y=1
        pushPoint(out, 0, 0);     // corner z=1
        pushPoint(out, kOne, 0);  // corner x=1
        emit(0, 1, 2);
        return;
    }
    const size_t points = countPoints(p);
    const size_t triangles = countTriangles(p);
    assert(points <= kTessMaxPoints && triangles <= kTessMaxTriangles);
    out.coords.reserve(3 * points);
    out.triangles.reserve(3 * triangles);
    generatePoints(p, out);
    generateTriangles(p, emit);
    assert(out.coords.size() == 3 * points);
    assert(out.triangles.size() == 3 * triangles);
}

}  // namespace lt
