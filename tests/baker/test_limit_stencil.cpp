// The baker's smooth limit stencils (baker_refiner.h): their weights against Loop's
// closed-form limit masks, and limitStencil without them (smoothWeights false) against
// the same call with them.
#include "baker_refiner.h"
#include "osd_reference.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lt::test {
namespace {

// Loop's limit position of a smooth vertex of valence n: each neighbour weighs
// 1 / (n + 3 / (8 g)), g = (5/8 - b^2) / n, b = 3/8 + cos(2 pi / n) / 4; its tangents
// weigh the k-th neighbour cos(2 pi k / n) and sin(2 pi k / n), the vertex none
// (Loop 1987; Sdc's masks, scaled here to a largest weight of 1).
TEST(LimitStencil, SmoothWeightsAreLoopsClosedForm) {
    for (int n = 3; n <= 16; ++n) {
        SCOPED_TRACE("valence " + std::to_string(n));
        const SmoothWeights& w = smoothLimitWeights(n);
        ASSERT_EQ(w.position.size(), size_t(n) + 1);
        ASSERT_EQ(w.tangentU.size(), size_t(n) + 1);
        ASSERT_EQ(w.tangentV.size(), size_t(n) + 1);
        const double pi = std::acos(-1.0), b = 0.375 + 0.25 * std::cos(2 * pi / n), g = (0.625 - b * b) / n;
        const double edge = 1 / (n + 3 / (8 * g));
        EXPECT_NEAR(w.position[0], 1 - n * edge, 1e-6);
        double largestU = 0, largestV = 0;
        for (int k = 0; k < n; ++k) {
            largestU = std::max(largestU, std::fabs(std::cos(2 * pi * k / n)));
            largestV = std::max(largestV, std::fabs(std::sin(2 * pi * k / n)));
        }
        EXPECT_NEAR(w.tangentU[0], 0, 1e-6);
        EXPECT_NEAR(w.tangentV[0], 0, 1e-6);
        for (int k = 0; k < n; ++k) {
            EXPECT_NEAR(w.position[size_t(k) + 1], edge, 1e-6) << "neighbour " << k;
            EXPECT_NEAR(w.tangentU[size_t(k) + 1], std::cos(2 * pi * k / n) / largestU, 1e-6) << "neighbour " << k;
            EXPECT_NEAR(w.tangentV[size_t(k) + 1], std::sin(2 * pi * k / n) / largestV, 1e-6) << "neighbour " << k;
        }
    }
}

// Every vertex of OpenSubdiv's Loop shapes (creases, corners, boundaries,
// non-manifold vertices) and two levels of their refinement, at each face: the
// stencil without smooth weights is the stencil with them, its smooth weights left
// out, and withWeights puts back the same bits.
TEST(LimitStencil, WithoutSmoothWeightsIsTheSameStencil) {
    size_t smooth = 0, other = 0;
    for (const std::string& path : corpusShapes()) {
        SCOPED_TRACE(path);
        const InputMesh mesh = loadObj(path);
        if (!checkInput(mesh, path)) continue;  // rejected input: covered by the input tests
        std::unique_ptr<Far::TopologyRefiner> refiner;
        const Status st = buildRefiner(mesh, 2, path, refiner);
        ASSERT_TRUE(st) << st.message;
        for (int l = 0; l <= refiner->GetMaxLevel(); ++l) {
            const Far::TopologyLevel& level = refiner->GetLevel(l);
            for (OsdIndex v = 0; v < level.GetNumVertices(); ++v) {
                for (OsdIndex f : level.GetVertexFaces(v)) {
                    LimitStencil full, lean, scratch;
                    limitStencil(*refiner, l, v, f, full);
                    limitStencil(*refiner, l, v, f, lean, /*smoothWeights=*/false);
                    ASSERT_EQ(lean.smooth, full.smooth) << "level " << l << " vertex " << v;
                    ASSERT_EQ(lean.points, full.points);
                    ASSERT_EQ(lean.sector, full.sector);
                    if (full.smooth) {
                        ++smooth;
                        EXPECT_TRUE(lean.position.empty() && lean.tangentU.empty() && lean.tangentV.empty());
                    } else {
                        ++other;
                    }
                    const LimitStencil& back = withWeights(lean, scratch);
                    ASSERT_EQ(back.points, full.points);
                    // Bitwise: == on doubles, no tolerance.
                    ASSERT_EQ(back.position, full.position) << "level " << l << " vertex " << v;
                    ASSERT_EQ(back.tangentU, full.tangentU) << "level " << l << " vertex " << v;
                    ASSERT_EQ(back.tangentV, full.tangentV) << "level " << l << " vertex " << v;
                }
            }
        }
    }
    EXPECT_GT(smooth, 0u);
    EXPECT_GT(other, 0u);
}

}  // namespace
}  // namespace lt::test
