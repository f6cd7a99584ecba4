// Refinement patterns (see patterns.h).
#include "patterns.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace lt {

uint32_t patternFactor(float f) {
    uint32_t e = 1;
    while (e < kMaxPatternFactor && float(e) < f) e *= 2;  // NaN compares false: 1
    return e;
}

void wholePatchPatternFactors(const PatchFactors& f, uint8_t splitMask, uint32_t e[3]) {
    static const int kPatchEdge[3] = {2, 0, 1};  // tessellator edge k -> patch edge
    for (int k = 0; k < 3; ++k) {
        const int edge = kPatchEdge[k];
        e[k] = (splitMask >> edge) & 1 ? std::min(2 * patternFactor(f.half[edge][0]), kMaxPatternFactor)
                                       : patternFactor(f.edge[edge]);
    }
}

namespace {

// Grid units: point (i, j) is (x, y) = (i / n, j / n).
struct Builder {
    uint32_t n;
    TessDomain& out;
    uint32_t add(uint32_t i, uint32_t j) {
        const float x = float(i) / float(n), y = float(j) / float(n);  // exact: n is a power of two
        out.coords.insert(out.coords.end(), {x, y, (1.0f - x) - y});
        return uint32_t(out.coords.size() / 3 - 1);
    }
    void triangle(uint32_t a, uint32_t b, uint32_t c) { out.triangles.insert(out.triangles.end(), {a, b, c}); }
    // Stitches a side: `outer` and `inner`, points along two parallel lines, both
    // walked the same way with the interior on the left. Any merge of two ordered
    // point rows on parallel lines gives counter-clockwise triangles tiling the strip;
    // this one advances by the fraction of each row walked.
    void stitch(const std::vector<uint32_t>& outer, const std::vector<uint32_t>& inner) {
        size_t a = 0, b = 0;
        const size_t no = outer.size() - 1, ni = inner.size() - 1;
        while (a < no || b < ni) {
            // Advance the outer row when its next point comes first (a+1)/no <= (b+1)/ni.
            const bool outerNext = b == ni || (a < no && (a + 1) * ni <= (b + 1) * no);
            if (outerNext) {
                triangle(outer[a], outer[a + 1], inner[b]);
                ++a;
            } else {
                triangle(outer[a], inner[b + 1], inner[b]);
                ++b;
            }
        }
    }
};

}  // namespace

void makePattern(const uint32_t e[3], TessDomain& out) {
    for (int k = 0; k < 3; ++k) assert(e[k] >= 1 && e[k] <= kMaxPatternFactor && (e[k] & (e[k] - 1)) == 0);
    const uint32_t n = std::max(e[0], std::max(e[1], e[2]));
    out.coords.clear();
    out.triangles.clear();
    Builder b{n, out};
    if (e[0] == n && e[1] == n && e[2] == n) {  // the uniform grid, row by row
        std::vector<uint32_t> row((n + 1) * (n + 1));
        for (uint32_t j = 0; j <= n; ++j)
            for (uint32_t i = 0; i + j <= n; ++i) row[j * (n + 1) + i] = b.add(i, j);
        auto at = [&](uint32_t i, uint32_t j) { return row[j * (n + 1) + i]; };
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i + j < n; ++i) {
                b.triangle(at(i, j), at(i + 1, j), at(i, j + 1));
                if (i + j + 2 <= n) b.triangle(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            }
        return;
    }
    // The outer ring: edge y = 0 from (0,0) to (n,0), z = 0 from (n,0) to (0,n), x = 0
    // from (0,n) to (0,0), each with its own e_k segments (corners shared).
    const uint32_t c0 = b.add(0, 0), c1 = b.add(n, 0), c2 = b.add(0, n);
    std::vector<uint32_t> side[3];  // y = 0, z = 0, x = 0, each from its first corner to its last
    side[0] = {c0};
    for (uint32_t k = 1; k < e[1]; ++k) side[0].push_back(b.add(k * (n / e[1]), 0));
    side[0].push_back(c1);
    side[1] = {c1};
    for (uint32_t k = 1; k < e[2]; ++k) side[1].push_back(b.add(n - k * (n / e[2]), k * (n / e[2])));
    side[1].push_back(c2);
    side[2] = {c2};
    for (uint32_t k = 1; k < e[0]; ++k) side[2].push_back(b.add(0, n - k * (n / e[0])));
    side[2].push_back(c0);
    if (n == 2) {  // no inner point: fan from the midpoints (or the corner) as sub_patches.h splits
        // One or two of the edges have a midpoint. Fan from a midpoint: its edge's two
        // halves to every other boundary point in ring order.
        std::vector<uint32_t> ring;
        for (int k = 0; k < 3; ++k) ring.insert(ring.end(), side[k].begin(), side[k].end() - 1);
        size_t m = 0;
        while (m < ring.size() && (ring[m] == c0 || ring[m] == c1 || ring[m] == c2)) ++m;
        for (size_t k = 1; k + 1 < ring.size(); ++k)
            b.triangle(ring[m], ring[(m + k) % ring.size()], ring[(m + k + 1) % ring.size()]);
        return;
    }
    // The inner grid: points with i, j >= 1 and i + j <= n - 1 (a triangle of n - 3
    // segments a side), its cells, then the three strips between it and the ring.
    const uint32_t inner = n - 3;
    std::vector<uint32_t> grid((inner + 1) * (inner + 1));
    for (uint32_t j = 0; j <= inner; ++j)
        for (uint32_t i = 0; i + j <= inner; ++i) grid[j * (inner + 1) + i] = b.add(i + 1, j + 1);
    auto at = [&](uint32_t i, uint32_t j) { return grid[j * (inner + 1) + i]; };
    for (uint32_t j = 0; j < inner; ++j)
        for (uint32_t i = 0; i + j < inner; ++i) {
            b.triangle(at(i, j), at(i + 1, j), at(i, j + 1));
            if (i + j + 2 <= inner) b.triangle(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
    std::vector<uint32_t> row[3];
    for (uint32_t k = 0; k <= inner; ++k) {
        row[0].push_back(at(k, 0));          // y = 1, from (1,1) to (n-2,1)
        row[1].push_back(at(inner - k, k));  // i + j = n - 1, from (n-2,1) to (1,n-2)
        row[2].push_back(at(0, inner - k));  // x = 1, from (1,n-2) to (1,1)
    }
    for (int k = 0; k < 3; ++k) b.stitch(side[k], row[k]);
}

}  // namespace lt
