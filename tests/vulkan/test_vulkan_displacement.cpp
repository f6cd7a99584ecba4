// tests/vulkan/test_vulkan_displacement.cpp -- shaders/displacement.glsl against the CPU
// sampler (runtime/internal/displacement.h), bit for bit, on the Vulkan device: the
// displacement block uploaded by buildGpuTables (gpu_layout.h's LT_D_*) and a
// test-only compute shader (tests/vulkan/displacement_probe.comp) that samples a list of
// (face, u, v): every corner, points on every face edge at dyadic parameters (the
// bitwise-critical ones), every grid point and pseudo-random interior points.
#include "test_vulkan_support.h"

#include "compute_probe.h"
#include "displacement.h"
#include "displacement_map.h"
#include "vulkan/gpu_tables.h"

#include <cstdint>
#include <cstring>
#include <tuple>

#include "displacement_probe_spv.h"

namespace lt::test {
namespace {

// `b`'s asset with the procedural pattern baked in at resolution R.
Asset displaced(const Baked& b, uint32_t R) {
    GrayImage image;
    image.width = image.height = 128;
    for (uint32_t y = 0; y < 128; ++y)
        for (uint32_t x = 0; x < 128; ++x) image.texels.push_back(patternTexel(x, y, 128, 128));
    Asset a = b.asset;
    DisplacementSettings ds;
    ds.scale = 0.0625f;
    ds.bias = -0.03125f;
    ds.resolution = R;
    const Status st = bakeDisplacement(image, ds, a, b.name);
    EXPECT_TRUE(st) << st.message;
    return a;
}

struct Query {
    uint32_t face;
    float u, v;
};

std::vector<Query> queries(const Asset& a) {
    const uint32_t R = a.displacement.resolution;
    std::vector<Query> q;
    uint32_t state = 99;
    auto next = [&]() { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1 << 24); };
    for (uint32_t f = 0; f < a.faceCount(); ++f) {
        for (uint32_t j = 0; j <= R; ++j)  // grid points, the corners among them
            for (uint32_t i = 0; i + j <= R; ++i) q.push_back({f, float(i) / float(R), float(j) / float(R)});
        for (int m = 1; m < 64; m += 3) {  // on the three edges, dyadic
            const float t = std::ldexp(float(m), -6) + std::ldexp(float(m), -16);
            q.push_back({f, t, 0.0f});
            q.push_back({f, 0.0f, t});
            q.push_back({f, 1.0f - t, t});
        }
        for (int n = 0; n < 16; ++n) {  // inside
            float u = next(), v = next();
            if (u + v >= 1.0f) u = 1.0f - u, v = 1.0f - v;
            q.push_back({f, u, v});
        }
    }
    return q;
}

// Runs the probe shader on `qs` over `a`'s GPU tables; returns one float per query.
std::vector<float> sampleOnGpu(VulkanContext& context, const Asset& a, const std::vector<Query>& qs) {
    GpuTables tables;
    const Status st = buildGpuTables(a, tables);
    EXPECT_TRUE(st) << st.message;
    const uint32_t base = uint32_t(tables.words.size());
    tables.words.push_back(uint32_t(qs.size()));
    for (const Query& q : qs) tables.words.insert(tables.words.end(), {q.face, floatBits(q.u), floatBits(q.v)});
    return runComputeProbe(context, lt_spv_displacement_probe, sizeof lt_spv_displacement_probe, tables.words, base,
                           qs.size());
}

void expectGpuMatchesCpu(VulkanContext& gpu, const Asset& a, const std::string& name) {
    SCOPED_TRACE(name + " at resolution " + std::to_string(a.displacement.resolution));
    const std::vector<Query> qs = queries(a);
    const std::vector<float> onGpu = sampleOnGpu(gpu, a, qs);
    ASSERT_EQ(onGpu.size(), qs.size());
    size_t mismatches = 0, first = SIZE_MAX;
    for (size_t i = 0; i < qs.size(); ++i)
        if (floatBits(onGpu[i]) != floatBits(sampleDisplacement(a, qs[i].face, qs[i].u, qs[i].v)) && mismatches++ == 0)
            first = i;
    EXPECT_EQ(mismatches, 0u) << mismatches << " of " << qs.size() << " differ; first: face " << qs[first].face << " ("
                              << qs[first].u << ", " << qs[first].v << "): GPU " << onGpu[first] << ", CPU "
                              << sampleDisplacement(a, qs[first].face, qs[first].u, qs[first].v);
}

using VulkanDisplacement = VulkanTest;

TEST_F(VulkanDisplacement, GlslSamplerMatchesCpuBitForBit) {
    const Baked* spot = baked(corpusMesh("spot.obj"), 1);
    ASSERT_NE(spot, nullptr);
    for (uint32_t R : {1u, 4u, 16u}) expectGpuMatchesCpu(*gpu, displaced(*spot, R), "spot");
    const Baked* cube = baked(corpusShape("loop_cube.obj"), 1);  // UVs with seams
    ASSERT_NE(cube, nullptr);
    expectGpuMatchesCpu(*gpu, displaced(*cube, 64), "loop_cube");
}

TEST_F(VulkanDisplacement, TablesWithoutAMapSayNone) {
    const Baked* spot = baked(corpusMesh("spot.obj"), 1);
    ASSERT_NE(spot, nullptr);
    GpuTables tables;
    ASSERT_TRUE(buildGpuTables(spot->asset, tables));
    EXPECT_EQ(tables.words[LT_H_DISPLACEMENT], LT_NONE);
    const Asset a = displaced(*spot, 4);
    ASSERT_TRUE(buildGpuTables(a, tables));
    const uint32_t block = tables.words[LT_H_DISPLACEMENT];
    ASSERT_NE(block, LT_NONE);
    EXPECT_EQ(tables.words[block + LT_D_RESOLUTION], 4u);
    EXPECT_EQ(tables.words[block + LT_D_VERTICES], a.controlVertexCount());
    EXPECT_EQ(tables.words[block + LT_D_EDGE_BASE], a.controlVertexCount() + a.faceCount() * 3u);
    const uint32_t samples = tables.words[block + LT_D_SAMPLES];
    for (size_t k = 0; k < a.displacement.values.size(); k += 97)
        EXPECT_EQ((tables.words[samples + k / 2] >> (16 * (k & 1))) & 0xffffu, a.displacement.values[k]) << k;
}

// The displaced surface: GPU capture equals the CPU evaluator (surface_compare.h; a
// displaced position moves along a unit normal, so within 1e-6 of the diagonal, bit
// for bit on lavapipe), and --no-displacement (FrameSettings::displace) gives the
// undisplaced surface back.
TEST_F(VulkanDisplacement, DisplacedCaptureEqualsCpu) {
    const Baked* spot = baked(corpusMesh("spot.obj"), 3);
    ASSERT_NE(spot, nullptr);
    const Asset a = displaced(*spot, 8);
    std::unique_ptr<VulkanSurface> surface;
    ASSERT_TRUE(VulkanSurface::create(*gpu, a, surface));
    size_t vertices = 0;
    double worst = 0;
    const std::tuple<float, Spacing, DrawPath> cases[] = {{4.0f, Spacing::Equal, DrawPath::Tessellator},
                                                          {5.5f, Spacing::FractionalOdd, DrawPath::Tessellator},
                                                          {4.0f, Spacing::Equal, DrawPath::Compute}};
    for (auto [factor, spacing, path] : cases) {
        for (bool displace : {true, false}) {
            SCOPED_TRACE("F " + std::to_string(factor) + (displace ? " displaced" : " undisplaced") +
                         (path == DrawPath::Compute ? " compute" : ""));
            FrameSettings frame;
            frame.tessFactor = factor;
            frame.spacing = spacing;
            frame.displace = displace;
            frame.path = path;
            Tessellation onGpu, onCpu, flat;
            ASSERT_TRUE(capture(*surface, frame, onGpu));
            EvalSettings es;
            es.tessFactor = factor;
            es.spacing = spacing;
            es.displace = displace;
            es.path = path;
            evaluateCpu(a, a.positions.data(), es, onCpu);
            evaluateCpu(spot->asset, spot->asset.positions.data(), es, flat);
            const SurfaceDiff diff = expectSameSurface(onGpu, onCpu, path, displace ? 1e-6 * spot->diagonal : 0.0);
            EXPECT_EQ(onCpu.positions == flat.positions, !displace);
            vertices += onGpu.vertexCount();
            worst = std::max(worst, diff.worstPosition / spot->diagonal);
        }
    }
    std::printf(
        "[ figures  ] displaced spot: %zu captured vertices equal the CPU's; positions at most %.3g of the "
        "diagonal apart\n",
        vertices, worst);
}

}  // namespace
}  // namespace lt::test
