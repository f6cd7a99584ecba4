// tests/vulkan/test_vulkan_capture.cpp -- the Vulkan path's tessellated output (paper
// 3.2-3.3), captured by transform feedback, against lt::evaluateCpu (itself checked
// against OpenSubdiv's limit surface in test_limit): every corpus shape, spot, bob
// and the Duck at several factors and both spacings; split against single draws;
// a capture in several transform feedback sessions against one; animated control
// points.
#include "test_vulkan_support.h"

#include "lod_sweep.h"  // weldFindings
#include "vulkan/gpu_tables.h"
#include "watertight.h"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace lt::test {
namespace {

constexpr int kDepth = 3;  // F = 8 reaches it

struct Totals {
    size_t vertices = 0, normalsBitwise = 0, welded = 0;
    void add(const SurfaceDiff& d) {
        vertices += d.vertices;
        normalsBitwise += d.normalsBitwise;
    }
    void print(const char* what) const {
        std::printf(
            "[ figures  ] %s: %zu vertices, positions bitwise equal; normals %.4f%% bitwise equal; %zu captures "
            "welded by themselves\n",
            what, vertices, 100.0 * double(normalsBitwise) / double(std::max<size_t>(vertices, 1)), welded);
    }
};

// GPU capture of `frame` against the CPU evaluator on `positions`, as
// surface_compare.h says (the tessellator's triangles in any order; positions, base
// faces, (u,v) and texture coordinates bit for bit; normals and tangents within their
// bounds). With watertight evaluation the capture also welds by itself, bit for bit,
// as the CPU's does (without a crack, but on shapes made to have them): the device's
// own shared edges agree, whatever its rounding.
void compareCapture(VulkanSurface& surface, const Baked& b, const FrameSettings& frame, const float* positions,
                    Totals* totals = nullptr) {
    SCOPED_TRACE(b.name + " F " + std::to_string(frame.tessFactor) +
                 (frame.path == DrawPath::Patterns  ? " patterns"
                  : frame.path == DrawPath::Compute ? " compute"
                  : frame.spacing == Spacing::Equal ? " equal"
                                                    : " fractional_odd"));
    Tessellation gpuSoup, cpuSoup;
    Status st = capture(surface, frame, gpuSoup);
    ASSERT_TRUE(st) << st.message;
    evaluateCpu(b.asset, positions, frame, cpuSoup);  // the frame's EvalSettings
    const SurfaceDiff diff = expectSameSurface(gpuSoup, cpuSoup, frame.path);
    if (frame.watertight) {  // "" on a well-formed mesh; the same cracks where the CPU's has them
        const ControlTopology topology = analyzeControlMesh(b.asset);
        EXPECT_EQ(weldFindings(topology, gpuSoup), weldFindings(topology, cpuSoup)) << "the device's own output";
    }
    if (totals) {
        totals->add(diff);
        totals->welded += frame.watertight;
    }
}

using VulkanCapture = VulkanTest;

TEST_F(VulkanCapture, EveryMeshMatchesCpuAtEachFactor) {
    Totals all;
    size_t meshes = 0;
    for (const std::string& path : allTestMeshes()) {
        const Baked* b = baked(path, kDepth, true);
        if (!b) continue;  // rejected input (covered by test_input)
        auto surface = upload(*b);
        ASSERT_NE(surface, nullptr);
        ++meshes;
        Totals mesh;
        for (float f : {1.0f, 4.0f, 8.0f, 5.5f}) {
            FrameSettings frame;
            frame.tessFactor = f;
            compareCapture(*surface, *b, frame, b->asset.positions.data(), &mesh);
        }
        FrameSettings odd;
        odd.tessFactor = 5.5f;
        odd.spacing = Spacing::FractionalOdd;
        compareCapture(*surface, *b, odd, b->asset.positions.data(), &mesh);
        for (float f : {1.0f, 3.0f, 8.0f}) {  // refinement patterns (pattern.vert), no tessellator
            FrameSettings patterns;
            patterns.tessFactor = f;
            patterns.path = DrawPath::Patterns;
            compareCapture(*surface, *b, patterns, b->asset.positions.data(), &mesh);
        }
        for (float f : {1.0f, 8.0f}) {  // the same points evaluated in compute (evaluate.comp, compute.vert)
            FrameSettings computed;
            computed.tessFactor = f;
            computed.path = DrawPath::Compute;
            compareCapture(*surface, *b, computed, b->asset.positions.data(), &mesh);
        }
        if (mesh.normalsBitwise != mesh.vertices) mesh.print(b->name.c_str());
        all.vertices += mesh.vertices;
        all.normalsBitwise += mesh.normalsBitwise;
        all.welded += mesh.welded;
    }
    std::printf(
        "[ figures  ] %zu meshes at F = 1, 4, 8, 5.5 equal, 5.5 fractional_odd, 1, 3, 8 patterns and 1, 8 "
        "compute\n",
        meshes);
    all.print("capture, all meshes");
}

// TEXCOORD_1 and COLOR_0 from the draw, against the CPU evaluator: the Duck with a
// second set of texture coordinates and colours made up per corner.
TEST_F(VulkanCapture, SecondTexcoordsAndColoursMatchCpu) {
    const Baked* duck = baked(duckPath(), kDepth);
    ASSERT_NE(duck, nullptr);
    Baked b = *duck;
    const size_t corners = b.asset.faces.size();
    for (size_t c = 0; c < corners; ++c) {
        const float* p = &b.asset.positions[3 * size_t(b.asset.faces[c])];
        b.asset.faceUV1s.insert(b.asset.faceUV1s.end(), {p[0] * 0.01f + 0.1f * float(c % 3), p[1] * 0.01f});
        b.asset.faceColors.insert(b.asset.faceColors.end(), {0.3f + 0.2f * float(c % 3), p[2] * 0.003f, 0.7f, 0.5f});
    }
    auto surface = upload(b);
    ASSERT_NE(surface, nullptr);
    for (float f : {1.0f, 5.5f, 8.0f}) {
        FrameSettings frame;
        frame.tessFactor = f;
        frame.spacing = f == 5.5f ? Spacing::FractionalOdd : Spacing::Equal;
        compareCapture(*surface, b, frame, b.asset.positions.data());
    }
}

// Batches of at most a few hundred domain points against one draw per record list,
// on a case small enough for a single draw to be right on lavapipe (< 65k points).
TEST_F(VulkanCapture, SplitDrawsEqualSingleDraws) {
    const Baked* b = baked(corpusShape("loop_icos_semisharp.obj"), kDepth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    for (float f : {7.0f, 16.0f}) {
        FrameSettings single, split;
        single.tessFactor = split.tessFactor = f;
        single.maxPointsPerDraw = 60000;
        split.maxPointsPerDraw = 300;
        Tessellation a, c;
        DrawStats sa, sc;
        ASSERT_TRUE(capture(*surface, single, a, &sa));
        ASSERT_TRUE(capture(*surface, split, c, &sc));
        ASSERT_LT(sa.points, 60000u);
        EXPECT_LE(sa.drawCalls, sa.depth + 2) << "one draw per level and one for the IPPs";
        EXPECT_GE(sc.drawCalls, 3 * sa.drawCalls);
        std::printf("[ figures  ] F %g: %u draws vs %u draws, %llu domain points, %llu triangles\n", double(f),
                    sa.drawCalls, sc.drawCalls, static_cast<unsigned long long>(sa.points),
                    static_cast<unsigned long long>(sa.triangles));
        // One device: the same bits, in any order (the tessellator's).
        const SurfaceDiff diff = compareSurfaces(c, a, SurfaceMatch{Order::Any, 0, 0, 0});
        EXPECT_TRUE(diff.ok()) << diff.summary();
    }
}

// A capture over its session's bytes is taken in several transform feedback
// sessions: the same soup, bit for bit and in order, as one session; a frame drawn in
// one session (the compute path; sorted patterns at screen-space factors) is
// refused with Unsupported instead.
TEST_F(VulkanCapture, ACaptureOverASessionIsTakenInSeveral) {
    const Baked* b = baked(corpusMesh("spot.obj"), kDepth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    const uint64_t session = uint64_t(1) << 25;  // 32 MiB: spot at F = 8 needs about 94 MB
    for (DrawPath path : {DrawPath::Tessellator, DrawPath::Patterns}) {
        FrameSettings frame;
        frame.tessFactor = 8;
        frame.path = path;
        Tessellation one, several;
        ASSERT_TRUE(capture(*surface, frame, one));
        Status st = capture(*surface, frame, several, nullptr, session);
        ASSERT_TRUE(st) << st.message;
        ASSERT_GT(one.vertexCount() * 84, 2 * session);
        EXPECT_TRUE(one.positions == several.positions && one.normals == several.normals && one.face == several.face &&
                    one.uv == several.uv && one.texcoords == several.texcoords && one.tangents == several.tangents)
            << (path == DrawPath::Patterns ? "patterns" : "tessellator");
        // Session by session (loopcheck's cases in pieces): each session is the next
        // vertices of the same soup.
        Tessellation joined;
        size_t sessions = 0;
        st = capture(
            *surface, frame,
            [&](const Tessellation& part, size_t first) {
                EXPECT_EQ(first, joined.vertexCount());
                joined.positions.insert(joined.positions.end(), part.positions.begin(), part.positions.end());
                joined.normals.insert(joined.normals.end(), part.normals.begin(), part.normals.end());
                joined.face.insert(joined.face.end(), part.face.begin(), part.face.end());
                ++sessions;
                return Status::ok();
            },
            nullptr, session);
        ASSERT_TRUE(st) << st.message;
        EXPECT_GE(sessions, 3u);
        EXPECT_TRUE(joined.positions == one.positions && joined.normals == one.normals && joined.face == one.face);
        // Without attributes, as evaluateCpu: the same surface, no texture coordinates.
        frame.EvalSettings::attributes = false;
        Tessellation plain;
        ASSERT_TRUE(capture(*surface, frame, plain, nullptr, session));
        EXPECT_TRUE(plain.texcoords.empty() && plain.tangents.empty() && !one.texcoords.empty());
        EXPECT_TRUE(plain.positions == one.positions && plain.normals == one.normals && plain.uv == one.uv);
    }
    const uint64_t tiny = uint64_t(1) << 20;  // under spot's base faces' capture
    FrameSettings computed;
    computed.tessFactor = 8;
    computed.path = DrawPath::Compute;
    Tessellation soup;
    EXPECT_EQ(capture(*surface, computed, soup, nullptr, tiny).code, Status::Unsupported);
    FrameSettings screen;
    const float eye[3] = {0, 0, 4};
    screen.lod = cameraLod(LodMode::Screen, eye, 45, 1024, 8);
    screen.tessFactor = 8;
    screen.path = DrawPath::Patterns;
    EXPECT_EQ(capture(*surface, screen, soup, nullptr, tiny).code, Status::Unsupported);
}

// Animation: moved control points, captured again, against the CPU on the moved
// points (also on the compute path without the watertight rules).
TEST_F(VulkanCapture, MovedControlPointsMatchCpu) {
    const Baked* b = baked(corpusMesh("spot.obj"), kDepth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    std::vector<float> moved = b->asset.positions;
    for (size_t i = 0; i < moved.size(); i += 3) {
        moved[i] += 0.03f * std::sin(5.0f * moved[i + 1]);
        moved[i + 2] *= 1.2f;
    }
    ASSERT_TRUE(surface->setControlPoints(moved.data()));
    FrameSettings frame;
    frame.tessFactor = 6;
    compareCapture(*surface, *b, frame, moved.data());
    frame.path = DrawPath::Compute;  // and each patch alone (no watertight rules) on the compute path
    frame.watertight = false;
    compareCapture(*surface, *b, frame, moved.data());
}

// A boundary or sharp patch edge whose root edge is smooth (GpuTables::smoothCreaseRoots):
// our baker never makes one, so mark a rooted edge of spot's refined patches sharp. Its
// draws keep the second box-spline evaluation (the displacement specialization) and
// must still equal the CPU bit for bit.
TEST_F(VulkanCapture, SharpEdgeOnASmoothRootMatchesCpu) {
    const Baked* b = baked(corpusMesh("spot.obj"), kDepth);
    ASSERT_NE(b, nullptr);
    Baked edited = *b;
    WatertightPlan plan;
    buildWatertightPlan(edited.asset, plan);
    size_t marked = 0;
    for (size_t l = 1; l < edited.asset.levels.size() && marked < 40; ++l) {
        std::vector<RegularPatch>& regular = edited.asset.levels[l].regular;
        for (size_t k = 0; k < regular.size() && marked < 40; ++k) {
            RegularPatch& patch = regular[k];
            for (int i = 0; i < 3; ++i) {
                uint32_t r = plan.levels[l].regularEdge[3 * k + i];
                if (r == kNoSource || patch.boundaryMask != 0) continue;
                const EdgeRoot& root = plan.roots[r];
                if (edited.asset.levels[root.level].regular[root.patch].boundaryMask >> root.edge & 1u) continue;
                patch.boundaryMask = uint8_t(1u << i);
                ++marked;
            }
        }
    }
    ASSERT_GT(marked, 0u);
    GpuTables tables;
    ASSERT_TRUE(buildGpuTables(edited.asset, tables));
    EXPECT_TRUE(tables.smoothCreaseRoots);
    auto surface = upload(edited);
    ASSERT_NE(surface, nullptr);
    for (float f : {3.0f, 8.0f}) {
        FrameSettings frame;
        frame.tessFactor = f;
        compareCapture(*surface, edited, frame, edited.asset.positions.data());
    }
    if (!HasFailure())
        std::printf("[ figures  ] spot with %zu sharp edges on smooth roots: GPU = CPU at F = 3, 8\n", marked);
}

}  // namespace
}  // namespace lt::test
