// tests/runtime/test_lod.cpp -- view-dependent level of detail (paper 3.5) on the CPU path:
// screen-space factors leave no T-junctions on closed meshes, the weld check that
// says so catches a deliberately mismatched tessellation, and the adaptive depth
// keeps F <= 2^depth with IPPs only at that depth. The GPU's agreement with these
// captures is checked in test_vulkan_lod.cpp.
#include "lod_check.h"
#include "osd_reference.h"  // loadObj, corpusMesh, bboxDiagonal
#include "sanitizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>

namespace lt::test {
namespace {

constexpr int kDepth = 3;

struct Baked {
    std::string name;
    Asset asset;
    double diagonal = 0;
};

// Bakes an OBJ at kDepth, cached for the run.
const Baked* bakedForLod(const std::string& path) {
    static std::map<std::string, std::unique_ptr<Baked>> cache;
    auto& slot = cache[path];
    if (slot) return slot.get();
    auto b = std::make_unique<Baked>();
    b->name = path.substr(path.find_last_of('/') + 1);
    InputMesh mesh = loadObj(path);
    Status st = checkInput(mesh, path);
    BakeSettings settings;
    settings.maxDepth = kDepth;
    if (st) st = bake(mesh, settings, b->asset);
    EXPECT_TRUE(st) << st.message;
    if (!st) return nullptr;
    b->diagonal = bboxDiagonal(mesh);
    slot = std::move(b);
    return slot.get();
}

std::string corpusShape(const char* name) { return std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/" + name; }

TEST(Lod, ScreenSpaceLeavesNoTJunctionsOnClosedMeshes) {
    size_t meshes = 0, edges = 0, triangles = 0, slivers = 0;
    for (const std::string& path : closedLodMeshes()) {
        const Baked* b = bakedForLod(path);
        ASSERT_NE(b, nullptr) << path;
        ASSERT_TRUE(controlMeshIsClosed(b->asset)) << b->name;
        for (int cam = 0; cam < 2; ++cam) {
            for (Spacing spacing : {Spacing::Equal, Spacing::FractionalOdd}) {
                if (kAsan && (cam == 0) != (spacing == Spacing::Equal)) continue;  // ASan: half (27 s with all)
                EvalSettings es = lodForFactor(b->asset, LodMode::Screen, cam, 7.0f);
                es.spacing = spacing;
                SCOPED_TRACE(b->name + " camera " + std::to_string(cam) +
                             (spacing == Spacing::Equal ? " equal" : " odd"));
                Tessellation soup;
                evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
                WeldReport w = weldAndCountEdges(soup, b->diagonal);
                EXPECT_EQ(w.unmatchedEdges, 0u) << w.summary();
                edges += w.edges;
                slivers += w.sliverEdges;
                triangles += soup.triangleCount();
            }
        }
        ++meshes;
    }
    std::printf(
        "[ figures  ] screen LOD, %zu closed meshes x 2 cameras x 2 spacings: %zu triangles, %zu welded edges, "
        "every one shared by exactly two triangles but %zu fractional_odd slivers under 1e-6 of the diagonal\n",
        meshes, triangles, edges, slivers);
}

// Baseline: the global factor (one factor per level, paper 3.3) at a factor that is
// not a power of two, where an unsplit edge towards a finer level would show.
TEST(Lod, GlobalFactorLeavesNoTJunctionsOnClosedMeshes) {
    for (const std::string& path : closedLodMeshes()) {
        const Baked* b = bakedForLod(path);
        ASSERT_NE(b, nullptr) << path;
        // Under ASan the odd spacing alone (31 s with both).
        for (Spacing spacing : kAsan ? std::vector<Spacing>{Spacing::FractionalOdd}
                                     : std::vector<Spacing>{Spacing::Equal, Spacing::FractionalOdd}) {
            EvalSettings es;
            es.tessFactor = 5.5f;
            es.spacing = spacing;
            SCOPED_TRACE(b->name + (spacing == Spacing::Equal ? " equal" : " odd"));
            Tessellation soup;
            evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
            WeldReport w = weldAndCountEdges(soup, b->diagonal);
            EXPECT_EQ(w.unmatchedEdges, 0u) << w.summary();
        }
    }
}

// The check can fail: base faces tessellated at two different factors (as two
// patches would be if each chose its shared edge's factor from its own data).
TEST(Lod, WeldCheckCatchesMismatchedEdgeFactors) {
    const Baked* b = bakedForLod(corpusMesh("spot.obj"));
    ASSERT_NE(b, nullptr);
    EvalSettings a, c;
    a.tessFactor = 4;
    c.tessFactor = 5;
    Tessellation sa, sc, mixed;
    evaluateCpu(b->asset, b->asset.positions.data(), a, sa);
    evaluateCpu(b->asset, b->asset.positions.data(), c, sc);
    // Even base faces from F = 4, odd ones from F = 5.
    for (const Tessellation* s : {&sa, &sc})
        for (size_t v = 0; v < s->vertexCount(); ++v) {
            if ((s->face[v] & 1) != (s == &sc ? 1u : 0u)) continue;
            for (int k = 0; k < 3; ++k) mixed.positions.push_back(s->positions[3 * v + k]);
            for (int k = 0; k < 3; ++k) mixed.normals.push_back(s->normals[3 * v + k]);
            mixed.face.push_back(s->face[v]);
            mixed.uv.push_back(s->uv[2 * v]);
            mixed.uv.push_back(s->uv[2 * v + 1]);
        }
    WeldReport good = weldAndCountEdges(sa, b->diagonal), bad = weldAndCountEdges(mixed, b->diagonal);
    EXPECT_EQ(good.unmatchedEdges, 0u) << good.summary();
    EXPECT_GT(bad.unmatchedEdges, 1000u) << bad.summary();
    std::printf(
        "[ figures  ] weld check: uniform F 4 %zu unmatched edges; faces at F 4 and 5 mixed: %zu of %zu unmatched\n",
        good.unmatchedEdges, bad.unmatchedEdges, bad.edges);
}

// Default settings are unchanged: Global LOD is the plain factor.
TEST(Lod, GlobalModeIsTheTessFactor) {
    const Baked* b = bakedForLod(corpusShape("loop_icos_semisharp.obj"));
    ASSERT_NE(b, nullptr);
    EvalSettings es;
    es.tessFactor = 5.5f;
    EXPECT_EQ(lodTessFactor(b->asset, b->asset.positions.data(), es), 5.5f);
    // The same screen camera seen from further away needs a smaller factor.
    EvalSettings close = lodForFactor(b->asset, LodMode::Distance, 0, 4.0f);
    EvalSettings far = lodSettings(b->asset, LodMode::Distance, 1, close.lod.pixelsPerEdge);
    EXPECT_NEAR(lodTessFactor(b->asset, b->asset.positions.data(), close), 4.0f, 1e-3f);
    EXPECT_LT(lodTessFactor(b->asset, b->asset.positions.data(), far), 2.0f);
}

// Adaptive depth: F <= 2^depth (F is clamped to 2^maxDepth), depth minimal, and
// the IPPs drawn are exactly the irregular faces of that depth: a soup triangle
// spanning an irregular face's whole domain appears only for level == depth.
TEST(Lod, AdaptiveDepthKeepsFactorWithinTwoToTheDepth) {
    size_t checked = 0;
    for (const std::string& path : closedLodMeshes()) {
        const Baked* b = bakedForLod(path);
        ASSERT_NE(b, nullptr);
        std::map<std::array<float, 7>, uint32_t> ippLevel;  // face, 3 uv corners -> level
        for (uint32_t l = 0; l <= b->asset.maxDepth(); ++l)
            for (const IrregularFace& f : b->asset.levels[l].irregular) ippLevel[ippKey(f.param)] = l;
        for (LodMode mode : {LodMode::Distance, LodMode::Screen})
            for (int cam = 0; cam < 2; ++cam)
                for (float target : asanSample(std::vector<float>{1.5f, 6.0f, 3.0f}, 2)) {  // ASan: 1.5, 3
                    EvalSettings es = lodForFactor(b->asset, mode, cam, target);
                    float f = lodTessFactor(b->asset, b->asset.positions.data(), es);
                    uint32_t depth = runtimeDepth(b->asset, f);
                    SCOPED_TRACE(b->name + " F " + std::to_string(f) + " depth " + std::to_string(depth));
                    EXPECT_LE(f, std::ldexp(1.0f, int(depth)));
                    if (depth > 0) { EXPECT_GT(f, std::ldexp(1.0f, int(depth) - 1)); }
                    Tessellation soup;
                    evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
                    std::map<uint32_t, size_t> ippsByLevel;
                    for (size_t t = 0; t < soup.triangleCount(); ++t) {
                        auto it = ippLevel.find(triangleKey(soup, t));
                        if (it != ippLevel.end()) ++ippsByLevel[it->second];
                    }
                    for (const auto& [level, count] : ippsByLevel)
                        EXPECT_EQ(level, depth) << count << " IPP-shaped triangles of level " << level;
                    EXPECT_EQ(ippsByLevel[depth], b->asset.levels[depth].irregular.size());
                    ++checked;
                }
    }
    std::printf("[ figures  ] adaptive depth: %zu (mesh, mode, camera, target) cases\n", checked);
}

}  // namespace
}  // namespace lt::test
