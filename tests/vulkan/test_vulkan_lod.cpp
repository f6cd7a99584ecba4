// tests/vulkan/test_vulkan_lod.cpp -- level of detail (paper 3.5) on the Vulkan path: the
// tessellation control shader's screen-space factors, and on the pattern path the
// sort pass's (pattern_sort.comp), against the CPU evaluator's: the factors bit for
// bit on any device (exact_math.glsl), so the same domain points and, through the
// whole capture, positions bit for bit (surface_compare.h); test_lod.cpp's crack
// check on the CPU capture holds for the GPU's too; distance LOD; frames drawn with
// the bound plan.
#include "generated_meshes.h"
#include "lod_check.h"
#include "lod_sweep.h"
#include "test_vulkan_support.h"

#include <cstdio>
#include <cstring>

namespace lt::test {
namespace {

constexpr int kDepth = 3;

// GPU capture of `es` against evaluateCpu, as surface_compare.h says (positions bit
// for bit). `gpuOut` (optional) receives the GPU's capture.
void expectSameCapture(VulkanSurface& surface, const Baked& b, const EvalSettings& es, DrawStats* stats = nullptr,
                       Tessellation* gpuOut = nullptr) {
    Tessellation local, cpuSoup;
    Tessellation& gpuSoup = gpuOut ? *gpuOut : local;
    Status st = capture(surface, FrameSettings{es}, gpuSoup, stats);
    ASSERT_TRUE(st) << st.message;
    evaluateCpu(b.asset, b.asset.positions.data(), es, cpuSoup);
    expectSameSurface(gpuSoup, cpuSoup, es.path);
}

using VulkanLod = VulkanTest;

TEST_F(VulkanLod, ScreenSpaceCaptureEqualsCpu) {
    size_t cases = 0;
    uint64_t triangles = 0;
    for (const std::string& path : {corpusMesh("spot.obj"), corpusShape("loop_icos_semisharp.obj"),
                                    corpusShape("loop_cubes_semisharp.obj"), corpusMesh("fandisk.obj")}) {
        const Baked* b = baked(path, kDepth);
        ASSERT_NE(b, nullptr);
        auto surface = upload(*b);
        ASSERT_NE(surface, nullptr);
        for (int cam = 0; cam < 2; ++cam)
            for (int mode = 0; mode < 4; ++mode) {  // tessellator equal, fractional odd; patterns; compute
                EvalSettings es = lodForFactor(b->asset, LodMode::Screen, cam, cam == 0 ? 7.0f : 3.3f);
                es.spacing = mode == 1 ? Spacing::FractionalOdd : Spacing::Equal;
                es.path = mode == 2 ? DrawPath::Patterns : mode == 3 ? DrawPath::Compute : DrawPath::Tessellator;
                SCOPED_TRACE(b->name + " camera " + std::to_string(cam) +
                             (mode == 0   ? " equal"
                              : mode == 1 ? " odd"
                              : mode == 2 ? " patterns"
                                          : " compute"));
                DrawStats stats;
                expectSameCapture(*surface, *b, es, &stats);
                EXPECT_TRUE(stats.exact);
                triangles += stats.triangles;
                ++cases;
            }
    }
    std::printf(
        "[ figures  ] screen LOD: %zu GPU captures (4 meshes x 2 cameras x (2 spacings, patterns, compute)), %llu "
        "triangles, "
        "all equal to the CPU's\n",
        cases, static_cast<unsigned long long>(triangles));
}

// Part of test_lod_sweep.cpp's sweep on the GPU: every capture the CPU's bit for bit,
// and welded without a crack or a fold (the CPU test sweeps more views). Each view
// (camera x pixels per edge) draws one of the tessellator path at equal spacing, at
// fractional-odd spacing and the pattern path, in a Latin square: each of the three
// sees every camera and every edge length once a mesh.
TEST_F(VulkanLod, ScreenSpaceSweepWeldsOnTheGpu) {
    size_t cases = 0;
    uint64_t triangles = 0;
    for (const std::string& path : {corpusMesh("spot.obj"), corpusShape("loop_cubes_semisharp.obj"),
                                    corpusShape("loop_xord_boundary.obj"), randomDiagonalTorusFile(40, 3)}) {
        const Baked* b = baked(path, kDepth);
        ASSERT_NE(b, nullptr);
        auto surface = upload(*b);
        ASSERT_NE(surface, nullptr);
        const ControlTopology topology = analyzeControlMesh(b->asset);
        const float pixels[3] = {1, 4, 16};
        for (int camera = 0; camera < kSweepCameras; ++camera)
            for (int p = 0; p < 3; ++p) {
                const int kind = (camera + p) % 3;  // 0 equal, 1 fractional-odd, 2 patterns
                const SweepView view{camera, pixels[p], kind == 1 ? Spacing::FractionalOdd : Spacing::Equal};
                const DrawPath path = kind == 2 ? DrawPath::Patterns : DrawPath::Tessellator;
                SCOPED_TRACE(b->name + ", " + view.name() + (path == DrawPath::Patterns ? ", patterns" : ""));
                EvalSettings es = sweepSettings(b->asset, view);
                es.path = path;
                Tessellation gpuSoup;
                DrawStats stats;
                expectSameCapture(*surface, *b, es, &stats, &gpuSoup);
                EXPECT_EQ(weldFindings(topology, gpuSoup), "");
                triangles += stats.triangles;
                ++cases;
            }
    }
    std::printf(
        "[ figures  ] screen LOD sweep on the GPU: %zu captures, %llu triangles, all welded and equal "
        "to the CPU's\n",
        cases, static_cast<unsigned long long>(triangles));
}

TEST_F(VulkanLod, DistanceCaptureEqualsCpu) {
    const Baked* b = baked(corpusMesh("spot.obj"), kDepth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    EvalSettings es = lodForFactor(b->asset, LodMode::Distance, 0, 5.5f);
    DrawStats stats;
    expectSameCapture(*surface, *b, es, &stats);
    EXPECT_NEAR(stats.tessFactor, 5.5f, 1e-3f);
    EXPECT_EQ(stats.depth, 3u);
}

// Frames: drawn with the plan of the bound F (draw_plan.h), whose counts are upper
// bounds of the exact ones; a moved camera re-plans; the engine entry points work.
TEST_F(VulkanLod, ScreenSpaceFramesDrawWithinTheBound) {
    const Baked* b = baked(corpusMesh("spot.obj"), kDepth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    for (DrawPath path : {DrawPath::Tessellator, DrawPath::Patterns}) {
        SCOPED_TRACE(path == DrawPath::Patterns ? "patterns" : "tessellator");
        EvalSettings es = lodForFactor(b->asset, LodMode::Screen, 0, 6.0f);
        es.path = path;
        DrawStats exact;
        Tessellation soup;
        ASSERT_TRUE(capture(*surface, FrameSettings{es}, soup, &exact));
        RenderSettings rs;
        rs.width = rs.height = 128;
        rs.frame = FrameSettings{es};
        Image image;
        FrameReport report;
        Status st = renderImage(*surface, rs, image, &report);
        ASSERT_TRUE(st) << st.message;
        EXPECT_FALSE(report.draw.exact);
        EXPECT_EQ(report.draw.depth, exact.depth);
        EXPECT_GE(report.draw.points, exact.points);
        EXPECT_GE(report.draw.triangles, exact.triangles);
        if (report.primitives >= 0) {  // the frame draws exactly what the capture planned (and the sort sorted)
            EXPECT_EQ(uint64_t(report.primitives), exact.triangles) << "pipeline statistics";
        }
        size_t drawn = 0;
        for (size_t i = 0; i < image.rgba.size(); i += 4) drawn += image.rgba[i] != 255 || image.rgba[i + 1] != 255;
        EXPECT_GT(drawn, 1000u);
        std::printf(
            "[ figures  ] spot, screen LOD F %.2f depth %u, %s: %llu triangles exact, frame planned for %llu "
            "(%u draws)\n",
            double(exact.tessFactor), exact.depth, path == DrawPath::Patterns ? "patterns" : "tessellator",
            static_cast<unsigned long long>(exact.triangles), static_cast<unsigned long long>(report.draw.triangles),
            report.draw.drawCalls);

        FrameSettings bad{es};
        bad.lod.pixelsPerEdge = 0;
        EXPECT_EQ(capture(*surface, bad, soup).code, Status::Usage);
    }
}

}  // namespace
}  // namespace lt::test
