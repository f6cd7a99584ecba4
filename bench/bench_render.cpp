// bench/bench_render.cpp -- frame time and GPU memory of the adaptive pipeline
// against global refinement, per mesh and tessellation factor (bench/README.md).
//
//   bench_render [--mesh NAME]... [--factor F]... [--frames N] [--size WxH]
//                [--json FILE] [--save DIR] [--corpus DIR] [--global-max-triangles N]
//                [--chunk-triangles N] [--chunked-factor F]...
//
// Adaptive: lt::bake at depth ceil(log2 F), drawn by lt::VulkanSurface at factor F.
// Global refinement: uniform_asset.h's asset at the same depth, drawn by the same
// lt::VulkanSurface (its compute kernels, then one plain triangle draw). When
// that asset does not fit the device (lavapipe's 128 MiB storage buffers), and at
// --chunked-factor, global refinement is also run in chunks of base faces
// (buildUniformChunk), one surface each, and their figures summed. Both paths
// render the same shaded view offscreen. The tables go to stdout, progress to
// stderr. Exit status: 0 when every figure was measured (targets met or not),
// 1 on usage errors, 2 when a mesh cannot be read or baked, 3 without a Vulkan
// device, 5 on a Vulkan error.
#include "render_measure.h"
#include "render_report.h"
#include "uniform_asset.h"

#include "looprender_common.h"  // cameraMatrix, writePngFile

#include "looptess/tools/baker.h"
#include "looptess/tools/file_io.h"
#include "looptess/tools/vulkan_tools.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using ltbench::Clock;
using ltbench::depthOf;
using ltbench::measure;
using ltbench::measureChunks;
using ltbench::msSince;
using ltbench::PathResult;

struct Args {
    std::vector<std::string> meshes;  // empty: spot, bob, duck
    std::vector<float> factors;       // empty: 4, 8, 16, 32
    uint32_t frames = 3, width = 512, height = 512;
    uint64_t globalMaxTriangles = 0;    // 0: no limit
    uint64_t chunkTriangles = 1500000;  // finest triangles per chunk of global refinement, at most
    std::vector<float> chunkedFactors;  // also chunk here when the whole fits (default: never)
    std::string json, save, corpus = LOOPTESS_CORPUS_DIR;
};

const char* const kUsage =
    "usage: bench_render [--mesh NAME]... [--factor F]... [--frames N] [--size WxH] [--json FILE]\n"
    "                    [--save DIR] [--corpus DIR] [--global-max-triangles N]\n"
    "                    [--chunk-triangles N] [--chunked-factor F]...\n"
    "  --mesh NAME     spot, bob or duck; repeat for several (default: all three)\n"
    "  --factor F      tessellation factor >= 1; repeat for several (default: 4 8 16 32)\n"
    "  --frames N      timed frames per figure after the warm-up (until two frames are within 5%);\n"
    "                  medians reported (default 3)\n"
    "  --size WxH      image size (default 512x512)\n"
    "  --json FILE     also write every figure as JSON\n"
    "  --save DIR      also write each path's last frame as DIR/<mesh>-F<F>-<adaptive|global>.png\n"
    "  --corpus DIR    corpus root holding meshes/*.obj and gltf/Duck.glb (default " LOOPTESS_CORPUS_DIR
    ")\n"
    "  --global-max-triangles N  skip global refinement above N triangles (default: no limit)\n"
    "  --chunk-triangles N       global refinement that does not fit runs in chunks of base faces, each\n"
    "                            drawing about N triangles at the largest factor's depth (default 1500000)\n"
    "  --chunked-factor F        also measure chunked global refinement at F when the whole fits, with\n"
    "                            the same chunks, to see what chunking costs (repeatable; default: never)\n";

bool parseArgs(int argc, char** argv, Args& a) {
    const bool parsed =
        ltbench::parseOptions(argc, argv, "bench_render", kUsage, [&](const std::string& o, const std::string& v) {
            char* end = nullptr;
            if (ltbench::sharedOption(o, v, a.meshes, a.frames, a.width, a.height, a.corpus)) {
            } else if (o == "--factor" && std::strtof(v.c_str(), &end) >= 1.0f && *end == 0) {
                a.factors.push_back(std::strtof(v.c_str(), nullptr));
            } else if (o == "--global-max-triangles" &&
                       (a.globalMaxTriangles = std::strtoull(v.c_str(), &end, 10), *end == 0)) {
            } else if (o == "--chunk-triangles" && (a.chunkTriangles = std::strtoull(v.c_str(), &end, 10), *end == 0) &&
                       a.chunkTriangles > 0) {
            } else if (o == "--chunked-factor" && std::strtof(v.c_str(), &end) >= 0.0f && *end == 0) {
                if (std::strtof(v.c_str(), nullptr) > 0) a.chunkedFactors.push_back(std::strtof(v.c_str(), nullptr));
            } else if (o == "--json") {
                a.json = v;
            } else if (o == "--save") {
                a.save = v;
            } else {
                return false;
            }
            return true;
        });
    if (!parsed) return false;
    if (a.meshes.empty()) a.meshes = {"spot", "bob", "duck"};
    if (a.factors.empty()) a.factors = {4, 8, 16, 32};

    return true;
}

// Chunked global refinement of one row, in `parts` (shared by the mesh's rows);
// a chunk that does not fit doubles the chunk count (and keeps it for later rows).
lt::Status measureChunkedRow(lt::VulkanContext& gpu, const Args& a, const lt::InputMesh& mesh,
                             std::vector<std::vector<uint32_t>>& parts, const lt::RenderSettings& rs,
                             const std::string& stem, ltbench::RenderRow& row) {
    int depth = depthOf(row.factor);
    for (;;) {
        std::fprintf(stderr, "bench_render: %s F %g: global refinement in %zu chunks...\n", row.mesh.c_str(),
                     double(row.factor), parts.size());
        lt::Status st = measureChunks(gpu, mesh, depth, parts, rs, a.frames, stem, row.chunked);
        if (st.code != lt::Status::Unsupported) return st;
        if (parts.size() >= 256 || parts.size() >= mesh.faceCount()) {
            row.chunked = PathResult{};
            row.chunked.note = st.message;
            return lt::Status::ok();
        }
        parts = ltbench::partitionFaces(mesh, uint32_t(2 * parts.size()));
    }
}

// One mesh at one factor: both paths. Returns a failing Status only for errors
// that should stop the bench (Vulkan errors, unreadable meshes).
lt::Status measureRow(lt::VulkanContext& gpu, const Args& a, const lt::InputMesh& mesh,
                      std::vector<std::vector<uint32_t>>& parts, ltbench::RenderRow& row) {
    int depth = depthOf(row.factor);
    std::string stem = a.save.empty() ? "" : a.save + "/" + row.mesh + "-F" + std::to_string(int(row.factor)) + "-";

    lt::BakeSettings bs;
    bs.maxDepth = depth;
    lt::Asset adaptive;
    auto t0 = Clock::now();
    lt::Status st = lt::bake(mesh, bs, adaptive);
    row.adaptive.buildMs = msSince(t0);
    if (!st) return st;
    looprender::Options view;  // looprender's default framing of the bounding box
    view.width = a.width;
    view.height = a.height;
    lt::RenderSettings rs;
    rs.width = a.width;
    rs.height = a.height;
    rs.frame.tessFactor = row.factor;
    looprender::cameraMatrix(view, adaptive, rs.frame.mvp, rs.frame.light);
    lt::RenderSettings plain = rs;  // the cost of watertight evaluation (paper 4.6)
    plain.frame.watertight = false;
    lt::RenderSettings patterns = rs;  // the draw path without the tessellator
    patterns.frame.path = lt::DrawPath::Patterns;
    lt::RenderSettings computed = rs;  // evaluated in compute passes, drawn as plain triangles
    computed.frame.path = lt::DrawPath::Compute;
    std::fprintf(stderr,
                 "bench_render: %s F %g: adaptive (depth %d), with and without watertight rules, as patterns and "
                 "in compute...\n",
                 row.mesh.c_str(), double(row.factor), depth);
    st = measure(gpu, adaptive,
                 {{rs, &row.adaptive}, {plain, &row.plain}, {patterns, &row.patterns}, {computed, &row.compute}},
                 a.frames, stem.empty() ? "" : stem + "adaptive.png");
    if (!st) return st;

    lt::Asset uniform;
    t0 = Clock::now();
    st = ltbench::buildUniformAsset(mesh, depth, uniform);
    row.global.buildMs = msSince(t0);
    if (!st) return st;
    ltbench::UniformCounts counts = ltbench::uniformCounts(uniform);
    row.leanGlobalBytes = ltbench::leanBytes(counts);
    if (a.globalMaxTriangles && counts.faces > a.globalMaxTriangles) {
        row.global.note = "skipped: " + std::to_string(counts.faces) + " triangles > --global-max-triangles";
        return lt::Status::ok();
    }
    std::fprintf(stderr, "bench_render: %s F %g: global refinement (%llu triangles)...\n", row.mesh.c_str(),
                 double(row.factor), static_cast<unsigned long long>(counts.faces));
    st = measure(gpu, uniform, {{rs, &row.global}}, a.frames, stem.empty() ? "" : stem + "global.png");
    uniform = lt::Asset{};  // free it before the chunks
    if (st.code == lt::Status::Unsupported) {
        // The device cannot hold it (lavapipe: a storage buffer holds at most 128 MiB).
        row.global = PathResult{};
        row.global.note = st.message;
    } else if (!st) {
        return st;
    }
    bool asked = std::find(a.chunkedFactors.begin(), a.chunkedFactors.end(), row.factor) != a.chunkedFactors.end();
    return row.global.measured && !asked ? lt::Status::ok() : measureChunkedRow(gpu, a, mesh, parts, rs, stem, row);
}

std::string machine() {
    std::ifstream in("/proc/cpuinfo");
    std::string line, model = "unknown CPU";
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " CPUs";
}

int exitCode(const lt::Status& st) { return ltbench::exitCode("bench_render", st); }

}  // namespace

int main(int argc, char** argv) {
    Args args;
    if (!parseArgs(argc, argv, args)) return 1;
    std::unique_ptr<lt::VulkanContext> gpu;
    lt::Status st = lt::VulkanContext::createHeadless({}, gpu);
    if (!st) return exitCode(st);

    ltbench::RenderReport report;
    report.device = ltbench::deviceDescription(*gpu);
    report.machine = machine();
    report.width = args.width;
    report.height = args.height;
    report.frames = args.frames;
    for (const std::string& name : args.meshes) {
        lt::InputMesh mesh;
        st = ltbench::loadMesh(args.corpus, name, mesh);
        if (!st) return exitCode(st);
        // Chunks of global refinement sized for the largest factor's depth, used at
        // every factor that needs or asks for them (so --chunked-factor compares
        // the same chunks).
        float maxFactor = *std::max_element(args.factors.begin(), args.factors.end());
        double finest = double(mesh.faceCount()) * std::pow(4.0, depthOf(maxFactor));
        double chunks = std::min(double(mesh.faceCount()), std::ceil(finest / double(args.chunkTriangles)));
        std::vector<std::vector<uint32_t>> parts = ltbench::partitionFaces(mesh, uint32_t(chunks));
        for (float factor : args.factors) {
            ltbench::RenderRow row;
            row.mesh = name;
            row.controlVertices = mesh.vertexCount();
            row.controlTriangles = mesh.faceCount();
            row.factor = factor;
            st = measureRow(*gpu, args, mesh, parts, row);
            if (!st) return exitCode(st);
            report.rows.push_back(row);
        }
    }
    std::fputs(ltbench::formatTables(report).c_str(), stdout);
    if (!args.json.empty()) {
        std::string text = ltbench::formatJson(report);
        st = lt::writeFileAtomic(args.json, reinterpret_cast<const uint8_t*>(text.data()), text.size());
        if (!st) return exitCode(st);
    }
    return 0;
}
