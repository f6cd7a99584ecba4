// The baked refinement tables, run by the CPU evaluator, reproduce OpenSubdiv's
// PrimvarRefiner on the same adaptive refinement, level by level: the baker's own
// refiner (baker_refiner.h), whose vertices BakeTrace names.
#include "bake_trace.h"  // bakeTraced
#include "baker_refiner.h"
#include "looptess/tools/baker.h"
#include "looptess/runtime.h"
#include "osd_reference.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <gtest/gtest.h>

#include <cmath>

namespace lt::test {
namespace {

using Point = OsdPoint;

// OpenSubdiv's vertices of every level of the baker's adaptive refinement of `mesh`
// to `maxDepth`, in double: levels[l][v] (fails the calling test when the baker's
// refiner cannot be built).
std::vector<std::vector<Point>> osdRefinement(const InputMesh& mesh, int maxDepth) {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    const Status st = buildRefiner(mesh, maxDepth, "osd", refiner);
    EXPECT_TRUE(st) << st.message;
    if (!st) return {};
    std::vector<std::vector<Point>> levels(1, std::vector<Point>(mesh.vertexCount()));
    for (size_t v = 0; v < levels[0].size(); ++v)
        for (int k = 0; k < 3; ++k) levels[0][v].p[k] = mesh.positions[3 * v + size_t(k)];
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    for (int l = 1; l <= refiner->GetMaxLevel(); ++l) {
        levels.emplace_back(size_t(refiner->GetLevel(l).GetNumVertices()));
        const Point* src = levels[size_t(l) - 1].data();
        Point* dst = levels[size_t(l)].data();
        primvar.Interpolate(l, src, dst);
    }
    return levels;
}

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
    const std::vector<std::vector<Point>> osd = osdRefinement(mesh, depth);
    ASSERT_FALSE(osd.empty());
    double tolerance = 1e-6 * bboxDiagonal(mesh);
    ASSERT_EQ(trace.osdLevel.size(), size_t(asset.totalVertexCount()));
    size_t bad = 0;
    double worst = 0;
    for (size_t i = 0; i < trace.osdLevel.size(); ++i) {
        const double* ref = osd[trace.osdLevel[i]][trace.osdVertex[i]].p;
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

}  // namespace
}  // namespace lt::test
