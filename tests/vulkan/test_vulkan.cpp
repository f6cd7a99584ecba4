// tests/vulkan/test_vulkan.cpp -- the Vulkan path's infrastructure and compute subdivision
// (paper 3.1) against the CPU runtime: a headless lavapipe device with the
// validation layers on, errors as values, the draw plan's exact counts, and every
// refined vertex of the GPU's edge-point and vertex-point passes against
// lt::subdivideCpu (which is itself checked against OpenSubdiv in test_refine).
// Captures (paper 3.2-3.3) are in test_vulkan_capture.cpp.
#include "test_vulkan_support.h"

#include "vulkan/draw_plan.h"
#include "vulkan/gpu_tables.h"

#include <cmath>
#include <cstdio>

namespace lt::test {
namespace {

constexpr int kCorpusDepth = 4;  // corpus shapes: small, so deep
constexpr int kMeshDepth = 3;    // spot, bob, the Duck

int depthOf(const std::string& path) {
    return path.find("opensubdiv-loop") != std::string::npos ? kCorpusDepth : kMeshDepth;
}

using VulkanDevice = VulkanTest;

TEST_F(VulkanDevice, HeadlessLavapipeWithValidationAndTransformFeedback) {
    EXPECT_FALSE(gpu->deviceName().empty());
    EXPECT_TRUE(canCapture(*gpu)) << gpu->deviceName() << " has no transform feedback";
}

TEST_F(VulkanDevice, ErrorsComeBackAsValues) {
    std::unique_ptr<VulkanContext> other;
    Status st = VulkanContext::adopt(VulkanHandles{}, other);
    EXPECT_EQ(st.code, Status::Usage) << st.message;
    EXPECT_EQ(other, nullptr);

    HeadlessOptions options;
    options.deviceName = "no device is called this";
    st = VulkanContext::createHeadless(options, other);
    EXPECT_EQ(st.code, Status::Unsupported) << st.message;
    EXPECT_NE(st.message.find("no suitable Vulkan device"), std::string::npos) << st.message;

    const Baked* b = baked(corpusMesh("spot.obj"), kMeshDepth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    std::vector<float> v;
    EXPECT_EQ(readVertices(*surface, 0.5f, v).code, Status::Usage);
    EXPECT_EQ(readVertices(*surface, NAN, v).code, Status::Usage);
    EXPECT_EQ(surface->setControlPoints(nullptr).code, Status::Usage);
    // Drawing a depth the compute passes did not produce is a contract violation.
    FrameSettings frame;
    frame.tessFactor = 8;
    EXPECT_EQ(surface->recordDraw(VK_NULL_HANDLE, DrawTarget{}, frame).code, Status::Usage);
}

// A second context adopting the first one's handles shares its device and
// destroys nothing of it.
TEST_F(VulkanDevice, AdoptedHandlesAreBorrowed) {
    const Baked* b = baked(corpusShape("loop_cube_creases0.obj"), 2);
    ASSERT_NE(b, nullptr);
    std::vector<float> before, after;
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    ASSERT_TRUE(readVertices(*surface, 4, before));
    {
        VulkanHandles h = gpu->handles();
        std::unique_ptr<VulkanContext> adopted;
        Status st = VulkanContext::adopt(h, adopted);
        ASSERT_TRUE(st) << st.message;
        std::unique_ptr<VulkanSurface> s2;
        ASSERT_TRUE(VulkanSurface::create(*adopted, b->asset, s2));
        std::vector<float> v;
        ASSERT_TRUE(readVertices(*s2, 4, v));
        EXPECT_EQ(v, before);
    }
    ASSERT_TRUE(readVertices(*surface, 4, after));  // the device still works
    EXPECT_EQ(after, before);
}

// The plan's exact triangle counts (from the tessellator's own rules) are what the
// CPU evaluator emits, for both spacings; batches respect their point budget.
TEST(VulkanDrawPlan, CountsMatchTheCpuEvaluator) {
    for (const std::string& path :
         {corpusShape("loop_xord_boundary.obj"), corpusShape("loop_cubes_semisharp.obj"), corpusMesh("spot.obj")}) {
        const Baked* b = baked(path, kMeshDepth);
        ASSERT_NE(b, nullptr);
        GpuTables tables;
        ASSERT_TRUE(buildGpuTables(b->asset, tables));
        for (Spacing spacing : {Spacing::Equal, Spacing::FractionalOdd}) {
            for (float f : {1.0f, 3.3f, 5.5f, 8.0f}) {
                SCOPED_TRACE(b->name + " F " + std::to_string(f));
                EvalSettings es;
                es.tessFactor = f;
                es.spacing = spacing;
                Tessellation soup;
                evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
                DrawPlan plan = planDraws(tables, runtimeDepth(b->asset, f), f, spacing, 5000);
                EXPECT_EQ(plan.triangles(), soup.triangleCount());
                for (const DrawBatch& batch : plan.batches)
                    EXPECT_TRUE(batch.points <= 5000 || batch.recordCount == 1) << batch.points;
            }
        }
    }
}

// A capture too large for one transform feedback session is split into runs of the
// plan's batches: in order, every batch once, each run within the session's bytes
// (with a triangle's slack), the IPPs in the last; a sorted plan is not split.
TEST(VulkanDrawPlan, CaptureSessionsAreRunsOfTheBatchesInOrder) {
    const Baked* b = baked(corpusMesh("spot.obj"), kMeshDepth);
    ASSERT_NE(b, nullptr);
    GpuTables tables;
    ASSERT_TRUE(buildGpuTables(b->asset, tables));
    const uint32_t stride = 84;
    const uint64_t maxBytes = uint64_t(1) << 25;  // 32 MiB: 133,152 triangles, two batches and more
    const uint32_t depth = runtimeDepth(b->asset, 8.0f);
    for (const DrawPlan& plan :
         {planDraws(tables, depth, 8.0f, Spacing::Equal), planDraws(tables, depth, 7.5f, Spacing::FractionalOdd),
          planPatternDraws(tables, depth, 8.0f)}) {
        uint64_t batchTriangles = 0;
        for (const DrawBatch& batch : plan.batches) batchTriangles += batch.triangles;
        EXPECT_EQ(batchTriangles, plan.tessTriangles);
        const std::vector<DrawPlan> sessions = captureSessions(plan, maxBytes, stride);
        ASSERT_GT(sessions.size(), size_t(plan.triangles() * 3 * stride / maxBytes));
        std::vector<DrawBatch> drawn;
        uint64_t triangles = 0;
        for (const DrawPlan& session : sessions) {
            EXPECT_LE(session.triangles() * 3 * stride + 3 * stride, maxBytes);
            EXPECT_EQ(session.ippTriangles, &session == &sessions.back() ? plan.ippTriangles : 0u);
            EXPECT_EQ(session.depth, plan.depth);
            drawn.insert(drawn.end(), session.batches.begin(), session.batches.end());
            triangles += session.triangles();
        }
        EXPECT_EQ(triangles, plan.triangles());
        ASSERT_EQ(drawn.size(), plan.batches.size());
        for (size_t k = 0; k < drawn.size(); ++k)
            EXPECT_TRUE(drawn[k].listOffset == plan.batches[k].listOffset &&
                        drawn[k].firstRecord == plan.batches[k].firstRecord &&
                        drawn[k].recordCount == plan.batches[k].recordCount)
                << "batch " << k;
        EXPECT_EQ(captureSessions(plan, plan.triangles() * 3 * stride + 3 * stride, stride).size(), 1u);
        EXPECT_TRUE(captureSessions(plan, 6 * stride, stride).empty()) << "a batch larger than a session";
    }
    EXPECT_TRUE(captureSessions(planSortedPatternDraws(tables, depth, 8.0f), maxBytes, stride).empty());
}

// Every refined vertex of every level from the GPU's compute passes equals the CPU's
// within 1e-6 of the bounding-box diagonal; the bitwise-equal share is reported.
TEST_F(VulkanDevice, SubdivisionMatchesCpuOnEveryMesh) {
    size_t floats = 0, bitwise = 0, meshes = 0;
    for (const std::string& path : allTestMeshes()) {
        const Baked* b = baked(path, depthOf(path), true);
        if (!b) continue;  // rejected input (covered by test_input)
        ++meshes;
        SCOPED_TRACE(b->name);
        auto surface = upload(*b);
        ASSERT_NE(surface, nullptr);
        uint32_t depth = b->asset.maxDepth();
        std::vector<float> gpuVertices, cpuVertices;
        Status st = readVertices(*surface, std::ldexp(1.0f, int(depth)), gpuVertices);
        ASSERT_TRUE(st) << st.message;
        subdivideCpu(b->asset, b->asset.positions.data(), depth, cpuVertices);
        ASSERT_EQ(gpuVertices.size(), cpuVertices.size());
        double tolerance = 1e-6 * b->diagonal;
        Agreement a = compareFloats(gpuVertices, cpuVertices, tolerance);
        EXPECT_EQ(a.outside, 0u) << a.summary(tolerance);
        if (a.bitwise != a.count) std::printf("[ figures  ] %s: %s\n", b->name.c_str(), a.summary(tolerance).c_str());
        floats += a.count;
        bitwise += a.bitwise;
    }
    std::printf("[ figures  ] subdivision, %zu meshes: %zu floats, %zu bitwise equal (%.4f%%)\n", meshes, floats,
                bitwise, 100.0 * double(bitwise) / double(floats));
}

// Each depth runs exactly levels 1..depth; the limit pass evaluates that depth's
// stencils.
TEST_F(VulkanDevice, SubdivisionStopsAtTheRuntimeDepth) {
    const Baked* b = baked(corpusShape("loop_icos_semisharp.obj"), kCorpusDepth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    for (float f : {1.0f, 1.5f, 2.0f, 3.0f, 7.9f, 16.0f, 64.0f}) {
        uint32_t depth = runtimeDepth(b->asset, f);
        std::vector<float> gpuVertices, cpuVertices, limit;
        ASSERT_TRUE(readVertices(*surface, f, gpuVertices, &limit));
        subdivideCpu(b->asset, b->asset.positions.data(), depth, cpuVertices);
        Agreement a = compareFloats(gpuVertices, cpuVertices, 1e-6 * b->diagonal);
        EXPECT_EQ(a.outside, 0u) << "F " << f << ": " << a.summary(1e-6 * b->diagonal);
        EXPECT_EQ(limit.size(), size_t(b->asset.levels[depth].limit.count()) * 9);
    }
}

// Animation: new control points every frame reuse every table; only the compute
// passes run again, and they follow the new points.
TEST_F(VulkanDevice, UpdatedControlPointsAreSubdividedAgain) {
    const Baked* b = baked(corpusMesh("spot.obj"), kMeshDepth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    VulkanSurface::Memory memory = surface->deviceMemory();
    for (int frame = 1; frame <= 3; ++frame) {
        std::vector<float> moved = b->asset.positions;
        for (size_t i = 0; i < moved.size(); i += 3) moved[i + 1] += 0.05f * float(frame) * std::sin(3.0f * moved[i]);
        ASSERT_TRUE(surface->setControlPoints(moved.data()));
        std::vector<float> gpuVertices, cpuVertices;
        ASSERT_TRUE(readVertices(*surface, 8, gpuVertices));
        subdivideCpu(b->asset, moved.data(), runtimeDepth(b->asset, 8), cpuVertices);
        Agreement a = compareFloats(gpuVertices, cpuVertices, 1e-6 * b->diagonal);
        EXPECT_EQ(a.outside, 0u) << "frame " << frame << ": " << a.summary(1e-6 * b->diagonal);
    }
    EXPECT_EQ(surface->deviceMemory().total(), memory.total());
    std::printf(
        "[ figures  ] spot at depth %u: device memory %llu bytes (tables %llu, vertices %llu, limit %llu, upload "
        "%llu)\n",
        b->asset.maxDepth(), static_cast<unsigned long long>(memory.total()),
        static_cast<unsigned long long>(memory.tables), static_cast<unsigned long long>(memory.vertices),
        static_cast<unsigned long long>(memory.limit), static_cast<unsigned long long>(memory.upload));
}

}  // namespace
}  // namespace lt::test
