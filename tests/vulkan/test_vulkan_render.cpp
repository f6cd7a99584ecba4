// tests/vulkan/test_vulkan_render.cpp -- offscreen rendering of the Vulkan path: the image
// covers the model, split and single draws give the same pixels, the pipeline
// statistics count what the draw plan predicts, level colouring and wireframe work.
#include "test_vulkan_support.h"

#include <cstring>

namespace lt::test {
namespace {

using VulkanRender = VulkanTest;

// A camera looking down -z at the control mesh's bounding box (Vulkan clip space).
void frameBox(const Asset& asset, FrameSettings& frame) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (size_t i = 0; i < asset.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], asset.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], asset.positions[i]);
    }
    float scale = 0;
    for (int k = 0; k < 3; ++k) scale = std::max(scale, hi[k] - lo[k]);
    float s = 1.8f / scale;  // orthographic: x, y to [-0.9, 0.9], z to [0.05, 0.95]
    float m[16] = {s, 0, 0, 0, 0, -s, 0, 0, 0, 0, -0.9f / scale, 0, 0, 0, 0, 1};
    for (int k = 0; k < 2; ++k) m[12 + k] = -(lo[k] + hi[k]) * 0.5f * m[k * 5];
    m[14] = 0.5f + (lo[2] + hi[2]) * 0.5f * 0.9f / scale;
    std::memcpy(frame.mvp, m, sizeof m);
}

size_t coveredPixels(const Image& image) {
    size_t n = 0;
    for (size_t i = 0; i < image.rgba.size(); i += 4)
        if (image.rgba[i] != 255 || image.rgba[i + 1] != 255 || image.rgba[i + 2] != 255) ++n;
    return n;
}

TEST_F(VulkanRender, SpotCoversTheImageAndCountsMatchThePlan) {
    const Baked* b = baked(corpusMesh("spot.obj"), 3);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    RenderSettings rs;
    rs.width = rs.height = 128;
    rs.frame.tessFactor = 6;
    frameBox(b->asset, rs.frame);
    Image image;
    FrameReport report;
    Status st = renderImage(*surface, rs, image, &report);
    ASSERT_TRUE(st) << st.message;
    ASSERT_EQ(image.rgba.size(), 128u * 128u * 4u);
    size_t covered = coveredPixels(image);
    EXPECT_GT(covered, 128u * 128u / 5) << "the cow covers a good part of the frame";
    EXPECT_LT(covered, 128u * 128u * 9 / 10);
    EXPECT_GT(report.subdivideMs, 0.0);
    EXPECT_GT(report.limitMs, 0.0);
    EXPECT_GT(report.drawMs, 0.0);
    // lavapipe counts one evaluation per unique domain point of a patch, which is
    // what the plan counts; other drivers may differ (facts.md).
    if (gpu->deviceName().find("llvmpipe") != std::string::npos) {
        EXPECT_EQ(report.primitives, int64_t(report.draw.triangles));
        EXPECT_EQ(report.tessEvaluations, int64_t(report.draw.points));
    }
    std::printf("[ figures  ] spot F 6: %llu triangles in %u draws; GPU ms subdivide %.3f, limit %.3f, draw %.3f\n",
                static_cast<unsigned long long>(report.draw.triangles), report.draw.drawCalls, report.subdivideMs,
                report.limitMs, report.drawMs);
}

// Batches of a few hundred domain points give the pixels of one draw per list on
// a case below lavapipe's ~65k points per draw.
TEST_F(VulkanRender, SplitDrawsGiveTheSameImage) {
    const Baked* b = baked(corpusShape("loop_icos_semisharp.obj"), 4);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    RenderSettings rs;
    rs.width = rs.height = 160;
    rs.frame.tessFactor = 16;
    frameBox(b->asset, rs.frame);
    Image single, split;
    FrameReport a, c;
    rs.frame.maxPointsPerDraw = 60000;
    ASSERT_TRUE(renderImage(*surface, rs, single, &a));
    rs.frame.maxPointsPerDraw = 300;
    ASSERT_TRUE(renderImage(*surface, rs, split, &c));
    ASSERT_LT(a.draw.points, 60000u);
    EXPECT_GE(c.draw.drawCalls, 10 * a.draw.drawCalls);
    EXPECT_TRUE(single.rgba == split.rgba) << "split and single draws render different pixels";
    EXPECT_GT(coveredPixels(single), 160u * 160u / 10);
}

TEST_F(VulkanRender, LevelColoursAndWireframe) {
    const Baked* b = baked(corpusShape("loop_icosahedron.obj"), 3);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    RenderSettings rs;
    rs.width = rs.height = 96;
    rs.frame.tessFactor = 8;
    frameBox(b->asset, rs.frame);
    Image shaded, levels, wire;
    ASSERT_TRUE(renderImage(*surface, rs, shaded));
    rs.frame.coloring = Coloring::Levels;
    ASSERT_TRUE(renderImage(*surface, rs, levels));
    EXPECT_FALSE(shaded.rgba == levels.rgba);
    // Shaded is grey; levels have saturated pixels.
    size_t coloured = 0;
    for (size_t i = 0; i < levels.rgba.size(); i += 4)
        if (std::abs(int(levels.rgba[i]) - int(levels.rgba[i + 2])) > 40) ++coloured;
    EXPECT_GT(coloured, 100u);
    rs.frame.wireframe = true;
    Status st = renderImage(*surface, rs, wire);
    if (gpu->handles().fillModeNonSolid) {
        ASSERT_TRUE(st) << st.message;
        EXPECT_GT(coveredPixels(wire), 50u);
        EXPECT_LT(coveredPixels(wire), coveredPixels(levels));
    } else {
        EXPECT_EQ(st.code, Status::Unsupported);
    }
}

}  // namespace
}  // namespace lt::test
