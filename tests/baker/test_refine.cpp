// The baked refinement tables, run by the CPU evaluator, reproduce OpenSubdiv's
// PrimvarRefiner on the same adaptive refinement, level by level.
#include "bake_trace.h"   // bakeTraced (looptess_baker_test_seam)
#include "looptess/baker.h"
#include "looptess/runtime.h"
#include "osd_reference.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lt::test {
namespace {

// Bakes `path` at `depth`, subdivides on the CPU and compares every stored vertex.
void checkRefinement(const std::string& path, int depth) {
    SCOPED_TRACE(path);
    InputMesh mesh = loadObj(path);
    if (!checkInput(mesh, path)) return;  // rejected input: covered by the input tests
    Asset asset;
    BakeTrace trace;
    BakeSettings settings;
    settings.maxDepth = depth;
    Status st = bakeTraced(mesh, settings, asset, nullptr, &trace);
    ASSERT_TRUE(st) << st.message;
    ASSERT_TRUE(validateAsset(asset, path)) << validateAsset(asset, path).message;
    std::vector<float> vertices;
    subdivideCpu(asset, asset.positions.data(), asset.maxDepth(), vertices);
    OsdRefinement osd(mesh, depth);
    double tolerance = 1e-6 * bboxDiagonal(mesh);
    ASSERT_EQ(trace.osdLevel.size(), size_t(asset.totalVertexCount()));
    size_t bad = 0;
    double worst = 0;
    for (size_t i = 0; i < trace.osdLevel.size(); ++i) {
        const double* ref = osd.vertex(int(trace.osdLevel[i]), int(trace.osdVertex[i]));
        double err = 0;
        for (int k = 0; k < 3; ++k) err = std::max(err, std::fabs(ref[k] - double(vertices[i * 3 + k])));
        worst = std::max(worst, err);
        if (err > tolerance && bad++ < 5)
            ADD_FAILURE() << "vertex " << i << " (level " << trace.osdLevel[i] << ", OpenSubdiv vertex "
                          << trace.osdVertex[i] << ") off by " << err;
    }
    EXPECT_EQ(bad, 0u) << "worst error " << worst << " of tolerance " << tolerance;
}

TEST(Refine, CorpusShapesMatchPrimvarRefiner) {
    for (const std::string& shape : corpusShapes()) checkRefinement(shape, 4);
}

TEST(Refine, RealMeshesMatchPrimvarRefiner) {
    for (const char* name : {"spot.obj", "bob.obj", "fandisk.obj"}) checkRefinement(corpusMesh(name), 3);
}

// Paper Table 3: once features are isolated, each level adds about as many
// patches as the one before (linear, not exponential, growth with depth).
TEST(Refine, PatchCountsGrowLinearlyOnSpot) {
    InputMesh mesh = loadObj(corpusMesh("spot.obj"));
    Asset asset;
    BakeStats stats;
    BakeSettings settings;
    settings.maxDepth = 6;
    ASSERT_TRUE(bake(mesh, settings, asset, &stats));
    std::vector<uint32_t> regular;
    for (const LevelStats& s : stats.levels) regular.push_back(s.rpp + s.npp);
    for (int l = 3; l <= 6; ++l) {
        EXPECT_EQ(stats.levels[l].ipp, stats.levels[2].ipp) << "level " << l;
        EXPECT_EQ(regular[l], regular[2]) << "level " << l;
    }
}

} // namespace
} // namespace lt::test
