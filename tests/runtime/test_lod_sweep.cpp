// tests/runtime/test_lod_sweep.cpp -- screen-space level of detail is watertight on every
// mesh: the corpus shapes, spot, bob, fandisk and a generated mesh of
// random valences, seen from three cameras (one inside the bounding box), at pixel
// sizes 1..16 and both spacings, weld bit for bit with no crack and no fold (check's
// weldTessellation, as loopcheck's W1-W3). The GPU's captures are the CPU's bit for
// bit (test_vulkan_lod.cpp runs part of this sweep there).
#include "generated_meshes.h"
#include "lod_sweep.h"
#include "osd_reference.h"  // loadObj, corpusShapes, corpusMesh
#include "sanitizer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <memory>

namespace lt::test {
namespace {

struct Baked {
    std::string name;
    Asset asset;
    ControlTopology topology;
};

// Bakes an OBJ at `depth`, cached for the run; null when the input is rejected
// (some corpus shapes are invalid input on purpose).
const Baked* bakedAt(const std::string& path, int depth) {
    static std::map<std::pair<std::string, int>, std::unique_ptr<Baked>> cache;
    auto& slot = cache[{path, depth}];
    if (slot) return slot.get();
    InputMesh mesh = loadObj(path);
    if (!checkInput(mesh, path)) return nullptr;
    auto b = std::make_unique<Baked>();
    b->name = path.substr(path.find_last_of('/') + 1);
    BakeSettings settings;
    settings.maxDepth = depth;
    Status st = bake(mesh, settings, b->asset);
    EXPECT_TRUE(st) << path << ": " << st.message;
    if (!st) return nullptr;
    b->topology = analyzeControlMesh(b->asset);
    slot = std::move(b);
    return slot.get();
}

struct Totals {
    size_t cases = 0, triangles = 0;
};

void sweep(const Baked& b, const std::vector<float>& pixels, Totals& totals) {
    for (const SweepView& view : sweepViews(pixels)) {
        SCOPED_TRACE(b.name + ", " + view.name());
        const EvalSettings es = sweepSettings(b.asset, view);
        Tessellation soup;
        evaluateCpu(b.asset, b.asset.positions.data(), es, soup);
        EXPECT_EQ(weldFindings(b.topology, soup), "");
        totals.triangles += soup.triangleCount();
        ++totals.cases;
    }
}

TEST(LodSweep, CorpusShapesWeldAtEveryView) {
    Totals totals;
    size_t shapes = 0;
    for (const std::string& path : asanSample(corpusShapes(), 2)) {  // ASan: half the shapes
        // Two back-to-back sheets are one surface seen from both sides: a weld by
        // position merges them at every factor, global ones too (test_loopcheck_corpus).
        if (path.find("loop_val2_interior") != std::string::npos) continue;
        const Baked* b = bakedAt(path, 3);
        if (!b) continue;
#ifdef LOOPTESS_ASAN
        sweep(*b, {2, 8}, totals);  // a third of the views: 70 s under ASan with all six
#else
        sweep(*b, {1, 2, 3, 5, 8, 16}, totals);
#endif
        ++shapes;
    }
    EXPECT_GT(shapes, kAsan ? 12u : 25u);
    std::printf("[ figures  ] screen LOD sweep: %zu corpus shapes, %zu views, %zu triangles, all welded\n", shapes,
                totals.cases, totals.triangles);
}

TEST(LodSweep, MeshesWeldAtEveryView) {
#ifdef LOOPTESS_ASAN
    GTEST_SKIP() << "4 minutes under ASan on 2 cores; the release test run covers it (the corpus shapes above run)";
#endif
    Totals totals;
    for (const std::string& path :
         {corpusMesh("spot.obj"), corpusMesh("bob.obj"), corpusMesh("fandisk.obj"), randomDiagonalTorusFile(40, 3)}) {
        const Baked* b = bakedAt(path, 3);
        ASSERT_NE(b, nullptr) << path;
        // Two pixel sizes keep this under a minute; the corpus shapes above take 1..16.
        sweep(*b, {4, 11}, totals);
    }
    std::printf("[ figures  ] screen LOD sweep: 4 meshes, %zu views, %zu triangles, all welded\n", totals.cases,
                totals.triangles);
}

// Fractional-odd factors a little above an odd integer (sub_patches.h's
// snapOddFactor): before the snap, fandisk folded at F = 1.0001 and 3.0001 (edges
// used by four triangles, where a sub-triangle's innermost ring, 1e-5 of its edge
// wide, welded in part).
TEST(LodSweep, OddFactorsJustAboveAnOddIntegerWeld) {
    size_t cases = 0;
    // Under ASan fandisk and spot at every other factor (34 s there with all 28 cases).
    for (const std::string& path : asanSample<std::string>(
             {corpusMesh("fandisk.obj"), corpusMesh("spot.obj"), corpusMesh("bob.obj"), randomDiagonalTorusFile(40, 3)},
             2)) {
        const Baked* b = bakedAt(path, 2);
        ASSERT_NE(b, nullptr) << path;
        for (float f :
             asanSample(std::vector<float>{1.00003f, 1.0001f, 1.0003f, 1.001f, 3.0001f, 3.0003f, 3.001f}, 2)) {
            SCOPED_TRACE(b->name + " at F = " + std::to_string(f));
            EvalSettings es;
            es.tessFactor = f;
            es.spacing = Spacing::FractionalOdd;
            Tessellation soup;
            evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
            EXPECT_EQ(weldFindings(b->topology, soup), "");
            ++cases;
        }
    }
    EXPECT_EQ(cases, kAsan ? 8u : 28u);
}

}  // namespace
}  // namespace lt::test
