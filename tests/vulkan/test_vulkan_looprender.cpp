// tests/vulkan/test_vulkan_looprender.cpp -- looprender's Vulkan mode (the default without
// --cpu) as a command: the same capture as --cpu, the same indexed mesh (--mesh,
// recordEvaluate), as surface_compare.h compares them (on lavapipe the same bytes),
// a PNG of the requested size, a JSON report with per-pass GPU times and device
// memory, and its exit codes.
#include "test_vulkan_support.h"
#include "test_paths.h"
#include "tool_run.h"

#include "looptess/tools/file_io.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include <unistd.h>

namespace lt::test {
namespace {

namespace fs = std::filesystem;

class Looprender : public VulkanTest {
protected:
    void SetUp() override {
        VulkanTest::SetUp();
        scratch = fs::temp_directory_path() / ("looptess_looprender_" + std::to_string(::getpid()));
        fs::create_directories(scratch);
        const Baked* b = baked(corpusMesh("spot.obj"), 3);
        ASSERT_NE(b, nullptr);
        std::vector<uint8_t> glb;
        ASSERT_TRUE(writeAssetGlb(b->asset, glb));
        asset = (scratch / "spot.glb").string();
        ASSERT_TRUE(writeFileAtomic(asset, glb.data(), glb.size()));
    }
    void TearDown() override {
        fs::remove_all(scratch);
        VulkanTest::TearDown();
    }
    RunResult run(std::vector<std::string> args) { return runTool(looprenderExe(), args, scratch); }
    std::string path(const char* name) const { return (scratch / name).string(); }
    // The device's file gpu.ply against the CPU's cpu.ply, drawn on `drawPath`.
    void expectSameFiles(DrawPath drawPath) const {
        bool gpuOk = false, cpuOk = false;
        const Tessellation device = readPly(readText(path("gpu.ply")), gpuOk),
                           cpu = readPly(readText(path("cpu.ply")), cpuOk);
        ASSERT_TRUE(gpuOk && cpuOk) << "unreadable PLY files";
        ASSERT_GT(device.triangleCount(), 10u);
        expectSameSurface(device, cpu, drawPath);
    }

    fs::path scratch;
    std::string asset;
};

TEST_F(Looprender, CaptureIsTheCpuPaths) {
    for (const char* f : {"1", "4", "5.5"}) {
        for (const char* spacing : {"equal", "fractional_odd"}) {
            SCOPED_TRACE(std::string("F ") + f + " " + spacing);
            RunResult gpuRun =
                run({asset, "--tess", f, "--spacing", spacing, "--capture", path("gpu.ply"), "--validation"});
            ASSERT_EQ(gpuRun.exitCode, 0) << gpuRun.err;
            RunResult cpuRun = run({"--cpu", asset, "--tess", f, "--spacing", spacing, "--capture", path("cpu.ply")});
            ASSERT_EQ(cpuRun.exitCode, 0) << cpuRun.err;
            expectSameFiles(DrawPath::Tessellator);
        }
    }
}

// Level of detail (paper 3.5): the default camera framing the bounding box, and an
// explicit one; the same capture with and without --cpu, and a PNG.
TEST_F(Looprender, LodCaptureIsTheCpuPaths) {
    for (const char* mode : {"screen", "distance"}) {
        for (bool camera : {false, true}) {
            SCOPED_TRACE(std::string(mode) + (camera ? " --camera" : " default camera"));
            std::vector<std::string> args = {asset, "--lod", mode, "--pixels-per-edge", "6", "--size", "200x160"};
            if (camera) args.insert(args.end(), {"--camera", "0.3,0.3,0.9,0,0,0,40"});
            std::vector<std::string> gpuArgs = args, cpuArgs = args;
            gpuArgs.insert(gpuArgs.end(), {"--capture", path("gpu.ply"), "--png", path("lod.png"), "--validation"});
            cpuArgs.insert(cpuArgs.end(), {"--cpu", "--capture", path("cpu.ply"), "--json", path("cpu.json")});
            RunResult gpuRun = run(gpuArgs);
            ASSERT_EQ(gpuRun.exitCode, 0) << gpuRun.err;
            RunResult cpuRun = run(cpuArgs);
            ASSERT_EQ(cpuRun.exitCode, 0) << cpuRun.err;
            expectSameFiles(DrawPath::Tessellator);
            EXPECT_GT(fs::file_size(path("lod.png")), 1000u);
            nlohmann::json report = nlohmann::json::parse(readText(path("cpu.json")));
            EXPECT_EQ(report["lod"], mode);
            EXPECT_LE(report["tessFactor"].get<double>(), std::ldexp(1.0, report["depth"].get<int>()));
        }
    }
    EXPECT_EQ(run({asset, "--lod", "nearest"}).exitCode, 1);
    EXPECT_EQ(run({asset, "--lod", "screen", "--pixels-per-edge", "0"}).exitCode, 1);
}

// The vertex count, face count and floats per vertex of a --mesh file's header, and
// where its vertices start.
struct MeshHeader {
    size_t vertices = 0, faces = 0, floats = 0, body = 0;
};
MeshHeader meshHeader(const std::string& ply) {
    MeshHeader h;
    h.body = ply.find("end_header\n") + 11;
    std::istringstream in(ply.substr(0, h.body));
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("element vertex ", 0) == 0) h.vertices = std::stoul(line.substr(15));
        if (line.rfind("element face ", 0) == 0) h.faces = std::stoul(line.substr(13));
        if (line.rfind("property float ", 0) == 0) ++h.floats;
    }
    return h;
}

// --mesh: recordEvaluate's indexed triangles (on the device) and the CPU evaluator's
// indexed ones (--cpu) are the same, at a global factor and at screen-space
// factors; every index names a vertex, and with vertices welded only where their
// positions are equal bit for bit, every edge of the closed spot has two triangles.
TEST_F(Looprender, MeshIsTheCpuPaths) {
    const std::vector<std::vector<std::string>> views = {
        {"--tess", "4"}, {"--lod", "screen", "--pixels-per-edge", "6", "--size", "200x160"}};
    for (const std::vector<std::string>& view : views) {
        SCOPED_TRACE(view[1]);
        std::vector<std::string> gpuArgs = {asset,    "--mesh",         path("gpu.ply"),
                                            "--json", path("gpu.json"), "--validation"};
        std::vector<std::string> cpuArgs = {"--cpu", asset, "--mesh", path("cpu.ply")};
        gpuArgs.insert(gpuArgs.end(), view.begin(), view.end());
        cpuArgs.insert(cpuArgs.end(), view.begin(), view.end());
        RunResult gpuRun = run(gpuArgs);
        ASSERT_EQ(gpuRun.exitCode, 0) << gpuRun.err;
        RunResult cpuRun = run(cpuArgs);
        ASSERT_EQ(cpuRun.exitCode, 0) << cpuRun.err;
        expectSameFiles(DrawPath::Patterns);
        const std::string ply = readText(path("gpu.ply"));

        const MeshHeader h = meshHeader(ply);
        ASSERT_EQ(h.floats, 12u);  // spot has TEXCOORD_0: tangents and s t too
        ASSERT_EQ(ply.size(), h.body + h.vertices * h.floats * 4 + h.faces * 13);
        nlohmann::json report = nlohmann::json::parse(readText(path("gpu.json")));
        EXPECT_EQ(report["mesh"]["vertices"], h.vertices);
        EXPECT_EQ(report["mesh"]["triangles"], h.faces);
        // The frame's path and the mesh's are each named (screen-space factors draw
        // through the tessellator; the mesh is always the patterns').
        EXPECT_EQ(report["drawPath"], view[0] == "--lod" ? "tessellator" : "patterns");
        EXPECT_EQ(report["mesh"]["drawPath"], "patterns");
        ASSERT_GT(h.faces, 5856u);                         // more than the base faces
        std::map<std::array<uint32_t, 3>, uint32_t> weld;  // position bits -> welded vertex
        std::vector<uint32_t> welded(h.vertices);
        for (size_t v = 0; v < h.vertices; ++v) {
            std::array<uint32_t, 3> bits;
            std::memcpy(bits.data(), ply.data() + h.body + v * h.floats * 4, 12);
            welded[v] = weld.emplace(bits, uint32_t(weld.size())).first->second;
        }
        std::map<std::pair<uint32_t, uint32_t>, int> edges;  // welded edge -> triangles
        size_t outOfRange = 0;
        for (size_t t = 0; t < h.faces; ++t) {
            const char* face = ply.data() + h.body + h.vertices * h.floats * 4 + t * 13;
            ASSERT_EQ(face[0], 3);
            uint32_t i[3];
            std::memcpy(i, face + 1, 12);
            for (int k = 0; k < 3; ++k) outOfRange += i[k] >= h.vertices;
            if (outOfRange) break;
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = welded[i[k]], b = welded[i[(k + 1) % 3]];
                ++edges[{std::min(a, b), std::max(a, b)}];
            }
        }
        ASSERT_EQ(outOfRange, 0u);
        size_t open = 0;
        for (const auto& e : edges) open += e.second != 2;
        EXPECT_EQ(open, 0u) << "of " << edges.size() << " welded edges";
    }
    EXPECT_EQ(run({asset, "--mesh", path("m.ply"), "--path", "tessellator"}).exitCode, 1);
    EXPECT_EQ(run({asset, "--mesh", path("m.ply"), "--spacing", "fractional_odd"}).exitCode, 1);
}

TEST_F(Looprender, PngAndJsonReport) {
    RunResult r = run({asset, "--tess", "6", "--png", path("spot.png"), "--size", "96x64", "--frames", "2", "--json",
                       path("report.json"), "--validation"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string png = readText(path("spot.png"));
    ASSERT_GT(png.size(), 24u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
    auto be32 = [&](size_t at) {
        return uint32_t(uint8_t(png[at])) << 24 | uint32_t(uint8_t(png[at + 1])) << 16 |
               uint32_t(uint8_t(png[at + 2])) << 8 | uint32_t(uint8_t(png[at + 3]));
    };
    EXPECT_EQ(be32(16), 96u);  // IHDR width, height
    EXPECT_EQ(be32(20), 64u);

    nlohmann::json report = nlohmann::json::parse(readText(path("report.json")));
    EXPECT_EQ(report["path"], "vulkan");
    EXPECT_EQ(report["depth"], 3);
    EXPECT_GT(report["gpuMemoryBytes"]["total"].get<uint64_t>(), 0u);
    EXPECT_EQ(report["gpuTimesMs"]["frames"], 2);
    for (const char* pass : {"subdivide", "limit", "draw"})
        EXPECT_GT(report["gpuTimesMs"]["mean"][pass].get<double>(), 0.0) << pass;
    EXPECT_GT(report["triangles"].get<uint64_t>(), 5856u * 36u);
}

// --path compute draws the pattern path's pixels and captures the same file as the
// CPU; --path auto measures every path over the frames and says what it kept.
TEST_F(Looprender, ComputeAndAutoPaths) {
    for (const char* p : {"patterns", "compute"}) {
        RunResult r = run({asset, "--tess", "6", "--path", p, "--png", path((std::string(p) + ".png").c_str()),
                           "--size", "96x64", "--json", path((std::string(p) + ".json").c_str()), "--validation"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    EXPECT_TRUE(readText(path("patterns.png")) == readText(path("compute.png")))
        << "the compute path draws other pixels";
    nlohmann::json computed = nlohmann::json::parse(readText(path("compute.json")));
    EXPECT_EQ(computed["drawPath"], "compute");
    EXPECT_GE(computed["batches"].get<int>(), 1);
    EXPECT_GT(computed["gpuMemoryBytes"]["compute"].get<uint64_t>(), 0u);
    EXPECT_GT(computed["gpuTimesMs"]["mean"]["evaluate"].get<double>(), 0.0);

    RunResult gpuRun = run({asset, "--tess", "5", "--path", "compute", "--capture", path("gpu.ply"), "--validation"});
    ASSERT_EQ(gpuRun.exitCode, 0) << gpuRun.err;
    RunResult cpuRun = run({"--cpu", asset, "--tess", "5", "--path", "compute", "--capture", path("cpu.ply")});
    ASSERT_EQ(cpuRun.exitCode, 0) << cpuRun.err;
    expectSameFiles(DrawPath::Compute);

    RunResult autoRun = run({asset, "--tess", "6", "--png", path("auto.png"), "--size", "96x64", "--frames", "5", "-v",
                             "--json", path("auto.json"), "--validation"});
    ASSERT_EQ(autoRun.exitCode, 0) << autoRun.err;
    nlohmann::json report = nlohmann::json::parse(readText(path("auto.json")));
    ASSERT_EQ(report["autoPath"].size(), 1u) << report.dump();
    const nlohmann::json& choice = report["autoPath"][0];
    EXPECT_TRUE(choice["decided"].get<bool>());
    EXPECT_EQ(choice["depth"], 3);
    EXPECT_EQ(report["drawPath"], choice["kept"]) << "the last frame draws with the path kept";
    for (const char* p : {"tessellator", "patterns", "compute"})
        EXPECT_GT(choice["medianMs"][p].get<double>(), 0.0) << p;
    EXPECT_TRUE(contains(autoRun.err, "auto path at depth 3: kept")) << autoRun.err;
}

// --threads changes how the CPU evaluation is split, never a byte of its output.
TEST_F(Looprender, CpuThreadsWriteTheSameFiles) {
    for (const char* output : {"--capture", "--mesh"}) {
        SCOPED_TRACE(output);
        std::string files[3];
        const char* counts[3] = {"1", "3", "0"};
        for (int k = 0; k < 3; ++k) {
            const std::string file = path((std::string("threads") + counts[k] + ".ply").c_str());
            RunResult r = run({"--cpu", asset, "--tess", "6", "--threads", counts[k], output, file});
            ASSERT_EQ(r.exitCode, 0) << r.err;
            files[k] = readText(file);
        }
        ASSERT_GT(files[0].size(), 1000u);
        EXPECT_TRUE(files[0] == files[1] && files[0] == files[2]);
    }
    EXPECT_EQ(run({"--cpu", asset, "--threads", "-1"}).exitCode, 1);
    EXPECT_EQ(run({"--cpu", asset, "--threads", "many"}).exitCode, 1);
}

TEST_F(Looprender, ExitCodes) {
    EXPECT_EQ(run({asset, "--device", "no device is called this"}).exitCode, 3);
    // No Vulkan driver at all (the loader finds no ICD): unsupported too.
    ::setenv("VK_ICD_FILENAMES", (scratch / "no_driver.json").c_str(), 1);
    RunResult noDriver = run({asset, "--tess", "2"});
    ::unsetenv("VK_ICD_FILENAMES");
    EXPECT_EQ(noDriver.exitCode, 3) << noDriver.err;
    EXPECT_EQ(run({"--cpu", asset, "--png", path("x.png")}).exitCode, 1);
    EXPECT_EQ(run({asset, "--size", "0x10"}).exitCode, 1);
    EXPECT_EQ(run({asset, "--camera", "1,2,3"}).exitCode, 1);
    // A camera with no direction, or not finite, is a usage error (before: exit 0; on a
    // 12-triangle box the eye on the target gave 60,312 triangles, nan 12).
    for (const char* camera : {"0,0,0,0,0,0", "nan,0,0,0,0,0", "inf,0,0,1,1,1", "0,0,1,0,0,-inf"})
        EXPECT_EQ(run({"--cpu", asset, "--lod", "screen", "--camera", camera, "--mesh", path("c.ply")}).exitCode, 1)
            << camera;
    EXPECT_EQ(run({path("missing.glb")}).exitCode, 2);
    EXPECT_EQ(run({asset, "--png", (scratch / "no" / "such" / "dir.png").string()}).exitCode, 4);
}

}  // namespace
}  // namespace lt::test
