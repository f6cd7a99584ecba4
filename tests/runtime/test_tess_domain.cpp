// tests/runtime/test_tess_domain.cpp -- the CPU copy of lavapipe's tessellator
// (runtime/internal/tess_domain.h): the project's measured facts, point and triangle
// counts, edge symmetry, coverage and winding, culling and clamping, no
// allocation on reuse, and two digests of a factor sweep that pin the output to
// what was checked against the real thing:
//   kGpuDigest       the triangle-corner stream (x, y, z bits of every corner,
//                    in order) as captured from lavapipe (Mesa 22.3.6) by
//                    transform feedback, on the same sweep;
//   kReferenceDigest points (in order) and triangle indices, as produced by
//                    Microsoft's reference tessellator (CHWTessellator).
// Both captures were made with throwaway programs outside the repository; the
// sweep below must stay in step with them (see sweepCases).
#include "tess_domain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace {

using lt::TessDomain;
using lt::TessSpacing;
using lt::TessWinding;

const TessSpacing kSpacings[] = {TessSpacing::Equal, TessSpacing::FractionalOdd, TessSpacing::FractionalEven};
const TessWinding kWindings[] = {TessWinding::Cw, TessWinding::Ccw};

uint32_t bitsOf(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

TessDomain tess(float o0, float o1, float o2, float inner, TessSpacing s, TessWinding w = TessWinding::Cw) {
    const float outer[3] = {o0, o1, o2};
    TessDomain d;
    lt::tessellateTriangle(outer, inner, s, d, w);
    return d;
}

float cx(const TessDomain& d, size_t i) { return d.coords[3 * i]; }
float cy(const TessDomain& d, size_t i) { return d.coords[3 * i + 1]; }
float cz(const TessDomain& d, size_t i) { return d.coords[3 * i + 2]; }

// The three outer edges as documented in tess_domain.h: the outer ring starts
// at corner y=1 (point 0) and runs x==0 (y falling), y==0 (x rising), z==0
// (x falling) back to point 0. Returns each edge's points, both corners
// included, in walking order. Fails the test if the layout differs.
struct OuterRing {
    std::vector<uint32_t> edge[3];
    bool ok = false;
};

OuterRing outerRing(const TessDomain& d) {
    OuterRing r;
    const uint32_t n = static_cast<uint32_t>(d.pointCount());
    if (n < 3 || cx(d, 0) != 0.0f || cy(d, 0) != 1.0f) {
        ADD_FAILURE() << "point 0 is not corner y=1";
        return r;
    }
    // edge x==0: y falls from 1 to 0 (corner z=1)
    uint32_t i = 0;
    r.edge[0].push_back(i);
    while (cy(d, i) != 0.0f) {
        ++i;
        if (i >= n || cx(d, i) != 0.0f || !(cy(d, i) < cy(d, i - 1))) {
            ADD_FAILURE() << "edge x==0 broken at point " << i;
            return r;
        }
        r.edge[0].push_back(i);
    }
    // edge y==0: x rises from 0 to 1 (corner x=1)
    r.edge[1].push_back(i);
    while (cx(d, i) != 1.0f) {
        ++i;
        if (i >= n || cy(d, i) != 0.0f || !(cx(d, i) > cx(d, i - 1))) {
            ADD_FAILURE() << "edge y==0 broken at point " << i;
            return r;
        }
        r.edge[1].push_back(i);
    }
    // edge z==0: x falls from 1 back to 0 (point 0); its own points have x in
    // (0, 1). The first point after it is an interior one, or there is none.
    r.edge[2].push_back(i);
    for (uint32_t next = i + 1; next < n; ++next) {
        const bool onEdge = cz(d, next) == 0.0f && cx(d, next) > 0.0f && cx(d, next) < cx(d, next - 1);
        if (!onEdge) break;
        r.edge[2].push_back(next);
    }
    r.edge[2].push_back(0);
    r.ok = true;
    return r;
}

// Points an edge gets for factor f (f a multiple of 1/4, inside the range).
int expectedEdgePoints(float f, TessSpacing s) {
    if (s == TessSpacing::FractionalOdd && f > 63.0f) f = 63.0f;
    int seg = static_cast<int>(std::ceil(f));
    if (s == TessSpacing::FractionalOdd && seg % 2 == 0) seg += 1;
    if (s == TessSpacing::FractionalEven && seg % 2 == 1) seg += 1;
    if (s == TessSpacing::FractionalEven && seg < 2) seg = 2;
    return seg + 1;
}

double signedArea(const TessDomain& d, size_t t) {
    const uint32_t a = d.triangles[3 * t], b = d.triangles[3 * t + 1], c = d.triangles[3 * t + 2];
    const double ux = double(cx(d, b)) - cx(d, a), uy = double(cy(d, b)) - cy(d, a);
    const double vx = double(cx(d, c)) - cx(d, a), vy = double(cy(d, c)) - cy(d, a);
    return 0.5 * (ux * vy - uy * vx);
}

// Factors 1 .. 64 in steps of 1/4.
std::vector<float> quarterGrid() {
    std::vector<float> g;
    for (int k = 4; k <= 256; ++k) g.push_back(static_cast<float>(k) * 0.25f);
    return g;
}

// The digest sweep. For each spacing, winding and k = 4 .. 256 (f = k/4): the
// uniform patch (f, f, f; f), then a patch with differing factors taken from
// the same grid by fixed strides.
struct Case {
    float outer[3];
    float inner;
    TessSpacing spacing;
    TessWinding winding;
};

std::vector<Case> sweepCases() {
    std::vector<Case> cases;
    const auto q = [](int j) { return static_cast<float>(j % 253 + 4) * 0.25f; };
    for (TessSpacing s : kSpacings)
        for (TessWinding w : kWindings)
            for (int k = 4; k <= 256; ++k) {
                const float f = static_cast<float>(k) * 0.25f;
                cases.push_back({{f, f, f}, f, s, w});
                cases.push_back({{f, q(k * 37), q(k * 101)}, q(k * 59), s, w});
            }
    return cases;
}

struct Fnv64 {
    uint64_t h = 1469598103934665603ull;
    void word(uint32_t v) {
        for (int i = 0; i < 4; ++i) {
            h ^= (v >> (8 * i)) & 0xffu;
            h *= 1099511628211ull;
        }
    }
};

// Digests of sweepCases() computed by the throwaway programs from lavapipe's
// transform-feedback records alone, and from CHWTessellator alone (run with
// denormals flushed, as in llvmpipe's threads). See the file comment.
constexpr uint64_t kGpuDigest = 0x8cb0d6e24f8549a7ull;
constexpr uint64_t kReferenceDigest = 0x940bce73d069193bull;

// ---------------------------------------------------------------------------
// Facts measured on lavapipe (shared/docs/facts.md)

TEST(TessDomain, SixEqualSegmentsGiveTheFixedPointSixth) {
    const TessDomain d = tess(6, 6, 6, 6, TessSpacing::Equal);
    const OuterRing r = outerRing(d);
    ASSERT_EQ(r.edge[1].size(), 7u);
    const float second = cx(d, r.edge[1][1]);
    EXPECT_EQ(second, 0.166671753f);
    EXPECT_EQ(second, 10923.0f / 65536.0f);
    EXPECT_NE(second, 1.0f / 6.0f);
    // The mirror point is exactly 1 - t.
    EXPECT_EQ(cx(d, r.edge[1][5]), 1.0f - second);
}

TEST(TessDomain, PointCountsOfTheFacts) {
    EXPECT_EQ(outerRing(tess(5.3f, 1, 1, 1, TessSpacing::Equal)).edge[0].size(), 7u);
    EXPECT_EQ(outerRing(tess(2.0f, 1, 1, 1, TessSpacing::FractionalOdd)).edge[0].size(), 4u);
    EXPECT_EQ(outerRing(tess(1.0f, 2, 2, 2, TessSpacing::FractionalEven)).edge[0].size(), 3u);
}

TEST(TessDomain, LevelOneIsOneTriangle) {
    for (TessSpacing s : {TessSpacing::Equal, TessSpacing::FractionalOdd}) {
        const TessDomain cw = tess(1, 1, 1, 1, s, TessWinding::Cw);
        ASSERT_EQ(cw.pointCount(), 3u);
        ASSERT_EQ(cw.triangleCount(), 1u);
        const float corners[9] = {0, 1, 0, 0, 0, 1, 1, 0, 0};  // y=1, z=1, x=1
        for (int i = 0; i < 9; ++i) EXPECT_EQ(cw.coords[i], corners[i]);
        EXPECT_EQ(cw.triangles, (std::vector<uint32_t>{0, 1, 2}));
        EXPECT_EQ(tess(1, 1, 1, 1, s, TessWinding::Ccw).triangles, (std::vector<uint32_t>{0, 2, 1}));
    }
    // Factors below 1 clamp to 1; fractional_even's minimum is 2.
    EXPECT_EQ(tess(0.5f, 0.25f, 1, 0.1f, TessSpacing::Equal).triangleCount(), 1u);
    EXPECT_EQ(tess(1, 1, 1, 1, TessSpacing::FractionalEven).triangleCount(), 6u);
}

// ---------------------------------------------------------------------------
// Counts

TEST(TessDomain, UniformIntegerLevelCounts) {
    for (int n = 1; n <= 64; ++n) {
        const float f = static_cast<float>(n);
        const TessDomain d = tess(f, f, f, f, TessSpacing::Equal);
        const size_t m = static_cast<size_t>(n / 2);
        const size_t points = (n % 2) ? 3 * (m + 1) * (m + 1) : 3 * m * (m + 1) + 1;
        const size_t triangles = (n % 2) ? 6 * m * (m + 1) + 1 : 6 * m * m;
        EXPECT_EQ(d.pointCount(), points) << "level " << n;
        EXPECT_EQ(d.triangleCount(), triangles) << "level " << n;
    }
    // Level 64 is the largest patch there is.
    const TessDomain d = tess(64, 64, 64, 64, TessSpacing::Equal);
    EXPECT_EQ(d.pointCount(), lt::kTessMaxPoints);
    EXPECT_EQ(d.triangleCount(), lt::kTessMaxTriangles);
}

TEST(TessDomain, EachOuterFactorSetsItsOwnEdge) {
    const TessDomain d = tess(2, 5, 9, 3, TessSpacing::Equal);
    const OuterRing r = outerRing(d);
    EXPECT_EQ(r.edge[0].size(), 3u);
    EXPECT_EQ(r.edge[1].size(), 6u);
    EXPECT_EQ(r.edge[2].size(), 10u);
    for (TessSpacing s : kSpacings)
        for (float a : {1.0f, 2.5f, 7.0f, 12.75f, 33.0f, 64.0f})
            for (float b : {1.0f, 4.25f, 18.0f}) {
                const TessDomain e = tess(a, b, 3.5f, 6.0f, s);
                const OuterRing re = outerRing(e);
                EXPECT_EQ(re.edge[0].size(), size_t(expectedEdgePoints(a, s))) << a;
                EXPECT_EQ(re.edge[1].size(), size_t(expectedEdgePoints(b, s))) << b;
                EXPECT_EQ(re.edge[2].size(), size_t(expectedEdgePoints(3.5f, s)));
            }
}

TEST(TessDomain, NeverLargerThanTheDocumentedMaximum) {
    TessDomain d;
    for (TessSpacing s : kSpacings)
        for (float f : quarterGrid())
            for (float g : {1.0f, 17.5f, 64.0f}) {
                const float outer[3] = {g, f, 64.0f};
                lt::tessellateTriangle(outer, f, s, d);
                EXPECT_LE(d.pointCount(), lt::kTessMaxPoints);
                EXPECT_LE(d.triangleCount(), lt::kTessMaxTriangles);
            }
}

// ---------------------------------------------------------------------------
// Geometry

TEST(TessDomain, CoordsAreBarycentricAndExact) {
    TessDomain d;
    for (TessSpacing s : kSpacings)
        for (float f : quarterGrid()) {
            const float outer[3] = {f, 64.0f - f + 1.0f, 0.5f * f + 1.0f};
            lt::tessellateTriangle(outer, f, s, d);
            for (size_t i = 0; i < d.pointCount(); ++i) {
                const float x = cx(d, i), y = cy(d, i), z = cz(d, i);
                ASSERT_TRUE(x >= 0.0f && x <= 1.0f && y >= 0.0f && y <= 1.0f && z >= 0.0f && z <= 1.0f);
                EXPECT_NEAR(double(x) + y + z, 1.0, 1e-6);
                // x and y are 16.16 values; z is (1 - x) - y in float, as on the GPU.
                EXPECT_EQ(x * 65536.0f, std::floor(x * 65536.0f));
                EXPECT_EQ(y * 65536.0f, std::floor(y * 65536.0f));
                EXPECT_EQ(bitsOf(z), bitsOf((1.0f - x) - y));
            }
        }
}

TEST(TessDomain, EdgePointsAreSymmetric) {
    TessDomain d;
    for (TessSpacing s : kSpacings)
        for (float f : quarterGrid()) {
            const float outer[3] = {f, 65.0f - f, std::fmod(f * 7.0f, 63.0f) + 1.0f};
            lt::tessellateTriangle(outer, 5.0f, s, d);
            const OuterRing r = outerRing(d);
            ASSERT_TRUE(r.ok) << f;
            for (int e = 0; e < 3; ++e) {
                // Parameter along the edge: y on x==0, x on y==0 and z==0.
                std::set<uint32_t> params;
                std::vector<float> ts;
                for (uint32_t i : r.edge[e]) {
                    const float t = (e == 0) ? cy(d, i) : cx(d, i);
                    ts.push_back(t);
                    params.insert(bitsOf(t));
                }
                EXPECT_EQ(r.edge[e].size(), size_t(expectedEdgePoints(outer[e], s)));
                for (float t : ts)
                    EXPECT_TRUE(params.count(bitsOf(1.0f - t))) << "edge " << e << " factor " << outer[e] << " t " << t;
            }
        }
}

// Every triangle turns the documented way, the triangles tile the domain
// (areas sum to 1/2) and form a closed strip structure: each directed edge is
// used once, and an inner edge is matched by its reverse.
TEST(TessDomain, TrianglesTileTheDomainWithConsistentWinding) {
    TessDomain d;
    const std::vector<float> grid = quarterGrid();
    for (TessSpacing s : kSpacings)
        for (TessWinding w : kWindings)
            for (size_t k = 0; k < grid.size(); k += 3) {
                const float f = grid[k];
                const float outer[3] = {f, grid[(k * 37) % grid.size()], grid[(k * 101) % grid.size()]};
                lt::tessellateTriangle(outer, grid[(k * 59) % grid.size()], s, d, w);
                const double sign = (w == TessWinding::Cw) ? 1.0 : -1.0;
                double area = 0.0;
                std::map<std::pair<uint32_t, uint32_t>, int> directed;
                for (size_t t = 0; t < d.triangleCount(); ++t) {
                    const double a = sign * signedArea(d, t);
                    EXPECT_GE(a, 0.0) << "triangle " << t << " factor " << f;
                    area += a;
                    for (int c = 0; c < 3; ++c) ++directed[{d.triangles[3 * t + c], d.triangles[3 * t + (c + 1) % 3]}];
                }
                EXPECT_NEAR(area, 0.5, 1e-6) << "factor " << f;
                // The boundary: consecutive outer ring points, walked in the
                // ring's direction for Cw, against it for Ccw.
                const OuterRing r = outerRing(d);
                std::set<std::pair<uint32_t, uint32_t>> boundary;
                for (int e = 0; e < 3; ++e)
                    for (size_t i = 0; i + 1 < r.edge[e].size(); ++i) {
                        const uint32_t a = r.edge[e][i], b = r.edge[e][i + 1];
                        boundary.insert(w == TessWinding::Cw ? std::make_pair(a, b) : std::make_pair(b, a));
                    }
                for (const auto& kv : directed) {
                    EXPECT_EQ(kv.second, 1);
                    const bool onBoundary = boundary.count(kv.first) != 0;
                    const bool matched = directed.count({kv.first.second, kv.first.first}) != 0;
                    EXPECT_NE(onBoundary, matched) << kv.first.first << "-" << kv.first.second;
                }
                for (const auto& b : boundary) EXPECT_TRUE(directed.count(b));
            }
}

// ---------------------------------------------------------------------------
// Factor handling

TEST(TessDomain, CulledPatchesAreEmpty) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const float denormal = std::numeric_limits<float>::denorm_min() * 1000.0f;
    TessDomain d = tess(4, 4, 4, 4, TessSpacing::Equal);
    for (TessSpacing s : kSpacings)
        for (float bad : {0.0f, -0.0f, -1.0f, -inf, nan, denormal})
            for (int slot = 0; slot < 3; ++slot) {
                float outer[3] = {4, 4, 4};
                outer[slot] = bad;
                lt::tessellateTriangle(outer, 4, s, d);
                EXPECT_TRUE(d.empty() && d.triangles.empty()) << bad << " in slot " << slot;
            }
    // The inner factor never culls: NaN and values below the range clamp to the minimum.
    for (TessSpacing s : kSpacings) {
        const TessDomain lowest = tess(4, 4, 4, s == TessSpacing::FractionalEven ? 2.0f : 1.0f, s);
        for (float in : {nan, 0.0f, -5.0f, -inf, denormal}) {
            const TessDomain d2 = tess(4, 4, 4, in, s);
            EXPECT_FALSE(d2.empty());
            EXPECT_EQ(d2.coords, lowest.coords) << in;
            EXPECT_EQ(d2.triangles, lowest.triangles) << in;
        }
    }
}

TEST(TessDomain, FactorsClampToTheSpacingsRange) {
    const float inf = std::numeric_limits<float>::infinity();
    struct Range {
        TessSpacing s;
        float top;
    };
    const Range ranges[] = {
        {TessSpacing::Equal, 64.0f}, {TessSpacing::FractionalOdd, 63.0f}, {TessSpacing::FractionalEven, 64.0f}};
    for (const auto& r : ranges) {
        const TessDomain top = tess(r.top, r.top, r.top, r.top, r.s);
        for (float big : {64.5f, 100.0f, 1e30f, inf}) {
            const TessDomain d = tess(big, big, big, big, r.s);
            EXPECT_EQ(d.coords, top.coords) << big;
            EXPECT_EQ(d.triangles, top.triangles) << big;
        }
    }
    // Equal rounds each factor up: 5.3 and 6 give the same patch.
    EXPECT_EQ(tess(5.3f, 2.1f, 3, 4.2f, TessSpacing::Equal).coords, tess(6, 3, 3, 5, TessSpacing::Equal).coords);
}

TEST(TessDomain, FractionalOddKeepsAnInnerRing) {
    // Outer factors above 1 force the inner factor above 1: points exist
    // beyond the outer ring even when inner is 1.
    const TessDomain d = tess(3, 1, 1, 1, TessSpacing::FractionalOdd);
    const OuterRing r = outerRing(d);
    const size_t ring = r.edge[0].size() + r.edge[1].size() + r.edge[2].size() - 3;
    EXPECT_EQ(d.pointCount(), ring + 3);
}

TEST(TessDomain, FactorToFixedRoundsHalfToEven) {
    EXPECT_EQ(lt::tessFactorToFixed(1.0f), 0x10000u);
    EXPECT_EQ(lt::tessFactorToFixed(64.0f), 0x400000u);
    EXPECT_EQ(lt::tessFactorToFixed(5.3f), 347341u);                      // 347340.81...
    EXPECT_EQ(lt::tessFactorToFixed(1.0f + 1.0f / 131072.0f), 0x10000u);  // .5 -> even
    EXPECT_EQ(lt::tessFactorToFixed(1.0f + 3.0f / 131072.0f), 0x10002u);  // 1.5 -> even
}

// ---------------------------------------------------------------------------
// Reuse

TEST(TessDomain, ReusedOutputDoesNotReallocate) {
    TessDomain d;
    const float big[3] = {64, 64, 64};
    lt::tessellateTriangle(big, 64, TessSpacing::Equal, d);
    const float* coords = d.coords.data();
    const uint32_t* tris = d.triangles.data();
    const TessDomain reference = d;
    for (float f : quarterGrid()) {
        const float outer[3] = {f, 2.0f, 64.0f - f + 1.0f};
        for (TessSpacing s : kSpacings) lt::tessellateTriangle(outer, f, s, d);
    }
    lt::tessellateTriangle(big, 64, TessSpacing::Equal, d);
    EXPECT_EQ(d.coords.data(), coords);
    EXPECT_EQ(d.triangles.data(), tris);
    EXPECT_EQ(d.coords, reference.coords);
    EXPECT_EQ(d.triangles, reference.triangles);
}

// ---------------------------------------------------------------------------
// Digests checked against lavapipe and the reference tessellator

TEST(TessDomain, SweepMatchesLavapipeCapture) {
    Fnv64 h;
    TessDomain d;
    for (const Case& c : sweepCases()) {
        lt::tessellateTriangle(c.outer, c.inner, c.spacing, d, c.winding);
        h.word(static_cast<uint32_t>(d.triangleCount()));
        for (uint32_t i : d.triangles)
            for (int k = 0; k < 3; ++k) h.word(bitsOf(d.coords[3 * i + k]));
    }
    EXPECT_EQ(h.h, kGpuDigest) << std::hex << h.h;
}

TEST(TessDomain, SweepMatchesReferenceTessellator) {
    Fnv64 h;
    TessDomain d;
    for (const Case& c : sweepCases()) {
        lt::tessellateTriangle(c.outer, c.inner, c.spacing, d, c.winding);
        h.word(static_cast<uint32_t>(d.pointCount()));
        for (float v : d.coords) h.word(bitsOf(v));
        h.word(static_cast<uint32_t>(d.triangleCount()));
        for (uint32_t i : d.triangles) h.word(i);
    }
    EXPECT_EQ(h.h, kReferenceDigest) << std::hex << h.h;
}

}  // namespace
