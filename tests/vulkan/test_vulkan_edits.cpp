// tests/vulkan/test_vulkan_edits.cpp -- hierarchical edits on the Vulkan path:
// the edit pass (shaders/apply_edits.comp) after each level's points, and
// VulkanSurface::setEditValues, against the CPU path (test_edits_runtime.cpp checks
// that one) bit for bit: refined vertices (readVertices) and captures, with edits on
// levels 0..3 of hand-edited corpus bakes (hand_edits.h).
#include "hand_edits.h"
#include "test_vulkan_support.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace lt::test {
namespace {

constexpr int kDepth = 3;

// `path` baked at kDepth with editsOnEveryLevel.
Baked edited(const std::string& path) {
    Baked e;
    const Baked* b = baked(path, kDepth);
    if (!b) return e;
    e = *b;
    setEdits(e.asset, editsOnEveryLevel(e.asset, float(e.diagonal)));
    EXPECT_TRUE(validateAsset(e.asset, e.name)) << e.name;
    return e;
}

// GPU against CPU for `values` (3 per edit; null: the baked ones): every level's
// vertices at each depth 0..3, bit for bit, and captures at the factors `captures`
// (1, 2, 4, 8 reach depths 0..3), as surface_compare.h says.
void compareWithCpu(VulkanSurface& surface, const Baked& b, const float* values, std::vector<float> captures) {
    for (float factor : {1.0f, 2.0f, 4.0f, 8.0f}) {
        SCOPED_TRACE(b.name + " F " + std::to_string(factor));
        std::vector<float> gpu, cpu;
        Status st = readVertices(surface, factor, gpu);
        ASSERT_TRUE(st) << st.message;
        subdivideCpu(b.asset, b.asset.positions.data(), runtimeDepth(b.asset, factor), cpu, values);
        Agreement v = compareFloats(gpu, cpu, 0.0);
        EXPECT_EQ(v.bitwise, cpu.size()) << "vertices: " << v.summary(0.0);
        EXPECT_EQ(gpu.size(), cpu.size());
        if (std::find(captures.begin(), captures.end(), factor) == captures.end()) continue;

        for (DrawPath path : {DrawPath::Tessellator, DrawPath::Compute}) {
            FrameSettings frame;
            frame.tessFactor = factor;
            frame.path = path;
            Tessellation gpuSoup, cpuSoup;
            st = capture(surface, frame, gpuSoup);
            ASSERT_TRUE(st) << st.message;
            EvalSettings es;
            es.tessFactor = factor;
            es.editValues = values;
            es.path = path;
            evaluateCpu(b.asset, b.asset.positions.data(), es, cpuSoup);
            expectSameSurface(gpuSoup, cpuSoup, frame.path);
        }
    }
}

using VulkanEdits = VulkanTest;

TEST_F(VulkanEdits, EditsOnEveryLevelMatchCpuBitForBit) {
    for (const std::string& path : {corpusMesh("spot.obj"), corpusShape("loop_xord_boundary.obj")}) {
        Baked b = edited(path);
        ASSERT_GT(b.asset.editCount(), 0u) << path;
        for (uint32_t l = 0; l <= b.asset.maxDepth(); ++l)
            EXPECT_GT(b.asset.levels[l].edits.count(), 0u) << "level " << l;
        auto surface = upload(b);
        ASSERT_NE(surface, nullptr);
        compareWithCpu(*surface, b, nullptr, {1.0f, 2.0f, 4.0f, 8.0f});
        // The edits show: the unedited bake differs.
        std::vector<float> withEdits, without;
        subdivideCpu(b.asset, b.asset.positions.data(), kDepth, withEdits);
        subdivideCpu(baked(path, kDepth)->asset, b.asset.positions.data(), kDepth, without);
        EXPECT_NE(withEdits, without);
        std::printf("[ figures  ] %s: %u edits on levels 0..%u, GPU = CPU bit for bit\n", b.name.c_str(),
                    b.asset.editCount(), b.asset.maxDepth());
    }
}

// Paper 4.3: new values at runtime, no re-bake; then back to the baked ones.
TEST_F(VulkanEdits, SetEditValuesMatchesCpuEditValues) {
    Baked b = edited(corpusMesh("spot.obj"));
    auto surface = upload(b);
    ASSERT_NE(surface, nullptr);
    std::vector<float> values = bakedEditValues(b.asset);
    for (float scale : {0.0f, -2.5f, 3.0f}) {
        SCOPED_TRACE("scale " + std::to_string(scale));
        std::vector<float> scaled = values;
        for (float& x : scaled) x = x * scale;
        Status st = surface->setEditValues(scaled.data(), scaled.size());
        ASSERT_TRUE(st) << st.message;
        compareWithCpu(*surface, b, scaled.data(), {4.0f});
    }
    ASSERT_TRUE(surface->setEditValues(values.data(), values.size()));
    compareWithCpu(*surface, b, nullptr, {8.0f});
}

TEST_F(VulkanEdits, WrongValueCountIsUsage) {
    Baked b = edited(corpusShape("loop_cube.obj"));
    auto surface = upload(b);
    ASSERT_NE(surface, nullptr);
    std::vector<float> values = bakedEditValues(b.asset);
    values.push_back(0);
    values.push_back(0);
    values.push_back(0);
    for (size_t count : {values.size() - 6, values.size(), size_t(0)})
        EXPECT_EQ(surface->setEditValues(values.data(), count).code, Status::Usage) << count;
    EXPECT_EQ(surface->setEditValues(nullptr, values.size() - 3).code, Status::Usage);
    EXPECT_TRUE(surface->setEditValues(values.data(), values.size() - 3));

    // Without edits: only an empty set of values.
    auto plain = upload(*baked(corpusShape("loop_cube.obj"), kDepth));
    ASSERT_NE(plain, nullptr);
    EXPECT_TRUE(plain->setEditValues(nullptr, 0));
    EXPECT_EQ(plain->setEditValues(values.data(), 3).code, Status::Usage);
}

}  // namespace
}  // namespace lt::test
