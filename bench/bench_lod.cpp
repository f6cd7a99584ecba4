// bench/bench_lod.cpp -- equal quality: screen-space level of
// detail at P pixels per edge, drawn by the tessellator path and by the pattern
// path, against global refinement at the shallowest depth whose every projected
// edge is under P pixels, from looprender's default view (bench/README.md).
//
//   bench_lod [--mesh NAME]... [--pixels P]... [--frames N] [--size WxH]
//             [--corpus DIR] [--chunk-triangles N] [--max-global-triangles N]
//
// Global refinement's depth: the longest on-screen edge of uniform refinement (the
// limit points its frame draws, from the CPU evaluator) is measured at depths 1..3;
// the depth is the first at or below 3 under P, else depth 3's longest edge halved
// per level by the ratio measured between depths 2 and 3 (Loop refinement halves
// edges in the limit) until under P. Deeper than the device holds in one surface,
// global refinement runs in chunks of base faces (render_measure.h), as in
// bench_render; past --max-global-triangles it is measured at the deepest depth
// within that many triangles and its frame time and triangles scaled by 4 per
// level beyond (marked "est."; its draw is linear in triangles, bench/README.md).
// The adaptive asset is baked to depth 6 (F <= 64). The table goes to
// stdout, progress to stderr. Exit status: 0 when every figure was measured, 1 on
// usage errors, 2 when a mesh cannot be read or baked, 3 without a Vulkan device, 5
// on a Vulkan error.
#include "render_measure.h"
#include "uniform_asset.h"

#include "looprender_common.h"  // cameraMatrix, lodSettings

#include "looptess/runtime.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr int kAdaptiveDepth = 6;

struct Args {
    std::vector<std::string> meshes;  // empty: spot, bob, duck
    std::vector<float> pixels;        // empty: 1, 2, 4
    uint32_t frames = 2, width = 1024, height = 1024;
    uint64_t chunkTriangles = 1500000;
    uint64_t maxGlobalTriangles = 25000000;
    std::string corpus = LOOPTESS_CORPUS_DIR;
};

const char* const kUsage =
    "usage: bench_lod [--mesh NAME]... [--pixels P]... [--frames N] [--size WxH] [--corpus DIR]\n"
    "                 [--chunk-triangles N] [--max-global-triangles N]\n"
    "  --mesh NAME         spot, bob or duck; repeat for several (default: all three)\n"
    "  --pixels P          target edge length in pixels; repeat for several (default: 1 2 4)\n"
    "  --frames N          timed frames per figure after a steady warm-up; medians (default 2)\n"
    "  --size WxH          image size (default 1024x1024)\n"
    "  --corpus DIR        corpus root (default " LOOPTESS_CORPUS_DIR
    ")\n"
    "  --chunk-triangles N global refinement that does not fit the device runs in chunks of about N\n"
    "                      triangles (default 1500000)\n"
    "  --max-global-triangles N  deeper global refinement is estimated from the deepest depth within N\n"
    "                      triangles, 4x per level (default 25000000)\n";

bool parseArgs(int argc, char** argv, Args& a) {
    const bool parsed =
        ltbench::parseOptions(argc, argv, "bench_lod", kUsage, [&](const std::string& o, const std::string& v) {
            char* end = nullptr;
            if (ltbench::sharedOption(o, v, a.meshes, a.frames, a.width, a.height, a.corpus)) {
            } else if (o == "--pixels" && std::strtof(v.c_str(), &end) > 0.0f && *end == 0) {
                a.pixels.push_back(std::strtof(v.c_str(), nullptr));
            } else if (o == "--chunk-triangles" && (a.chunkTriangles = std::strtoull(v.c_str(), &end, 10), *end == 0) &&
                       a.chunkTriangles > 0) {
            } else if (o == "--max-global-triangles" &&
                       (a.maxGlobalTriangles = std::strtoull(v.c_str(), &end, 10), *end == 0) &&
                       a.maxGlobalTriangles > 0) {
            } else {
                return false;
            }
            return true;
        });
    if (!parsed) return false;
    if (a.meshes.empty()) a.meshes = {"spot", "bob", "duck"};
    if (a.pixels.empty()) a.pixels = {1, 2, 4};
    return true;
}

// The longest edge, in pixels, of the triangles `soup` draws through `mvp` (column-
// major, Vulkan clip space) into width x height, over the edges in front of the
// eye with an end inside the image.
double longestEdgePixels(const lt::Tessellation& soup, const float mvp[16], uint32_t width, uint32_t height) {
    auto project = [&](size_t v, double out[2]) {
        const float* p = &soup.positions[3 * v];
        double c[4];
        for (int r = 0; r < 4; ++r) c[r] = mvp[r] * p[0] + mvp[4 + r] * p[1] + mvp[8 + r] * p[2] + mvp[12 + r];
        if (c[3] <= 0) return false;
        out[0] = (c[0] / c[3] * 0.5 + 0.5) * width;
        out[1] = (c[1] / c[3] * 0.5 + 0.5) * height;
        return true;
    };
    auto inside = [&](const double q[2]) { return q[0] >= 0 && q[0] <= width && q[1] >= 0 && q[1] <= height; };
    double longest = 0;
    for (size_t t = 0; t < soup.triangleCount(); ++t)
        for (int e = 0; e < 3; ++e) {
            double a[2], b[2];
            if (!project(3 * t + e, a) || !project(3 * t + (e + 1) % 3, b) || !(inside(a) || inside(b))) continue;
            longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1]));
        }
    return longest;
}

struct GlobalDepth {
    int depth = 0;
    double longest[4] = {0, 0, 0, 0};  // measured at depths 1..3
    double expected = 0;               // the longest edge at `depth` (extrapolated past 3)
};

// Global refinement's depth for edges under `pixels` (see the top of the file).
lt::Status globalDepth(const lt::InputMesh& mesh, const float mvp[16], const Args& a, float pixels, GlobalDepth& out) {
    for (int d = 1; d <= 3; ++d) {
        lt::Asset uniform;
        lt::Status st = ltbench::buildUniformAsset(mesh, d, uniform);
        if (!st) return st;
        lt::EvalSettings es;
        es.tessFactor = float(1 << d);
        lt::Tessellation soup;
        lt::evaluateCpu(uniform, uniform.positions.data(), es, soup);
        out.longest[d] = longestEdgePixels(soup, mvp, a.width, a.height);
        if (out.longest[d] < pixels) {
            out.depth = d;
            out.expected = out.longest[d];
            return lt::Status::ok();
        }
    }
    const double ratio = std::clamp(out.longest[3] / out.longest[2], 0.3, 0.9);
    out.depth = 3;
    out.expected = out.longest[3];
    while (out.expected >= pixels) {
        out.expected *= ratio;
        ++out.depth;
    }
    return lt::Status::ok();
}

struct Row {
    std::string mesh;
    float pixels = 0;
    GlobalDepth global;
    ltbench::PathResult tessellator, patterns, compute;
    ltbench::PathResult uniform;  // at global.depth, or scaled from measuredDepth
    int measuredDepth = 0;
};

// Global refinement of one mesh, measured once per depth.
struct GlobalRuns {
    std::vector<ltbench::PathResult> byDepth = std::vector<ltbench::PathResult>(16);
};

// Global refinement of `mesh` at `depth` through `rs`'s camera: whole where it fits
// one surface of the device (chunks would cost it their fixed costs and cut points),
// else in chunks of about --chunk-triangles.
lt::Status measureGlobal(lt::VulkanContext& gpu, const Args& a, const lt::InputMesh& mesh, int depth,
                         lt::RenderSettings rs, ltbench::PathResult& out) {
    const double faces = double(mesh.faceCount()) * std::pow(4.0, depth);
    std::fprintf(stderr, "bench_lod: global refinement at depth %d (%.0f triangles)...\n", depth, faces);
    rs.frame.tessFactor = float(1 << depth);
    lt::Asset uniform;
    lt::Status st = ltbench::buildUniformAsset(mesh, depth, uniform);
    if (!st) return st;
    st = ltbench::measure(gpu, uniform, {{rs, &out}}, a.frames, "");
    if (st.code != lt::Status::Unsupported) return st;
    const uint32_t parts = uint32_t(std::min(double(mesh.faceCount()), std::ceil(faces / double(a.chunkTriangles))));
    std::fprintf(stderr, "bench_lod: ... does not fit the device: in %u chunks\n", std::max(parts, 2u));
    out = ltbench::PathResult{};
    return ltbench::measureChunks(gpu, mesh, depth, ltbench::partitionFaces(mesh, std::max(parts, 2u)), rs, a.frames,
                                  "", out);
}

// One mesh at one edge length: the adaptive asset's two paths and global refinement.
lt::Status measureRow(lt::VulkanContext& gpu, const Args& a, const lt::InputMesh& mesh, const lt::Asset& adaptive,
                      GlobalRuns& runs, Row& row) {
    looprender::Options view;
    view.width = a.width;
    view.height = a.height;
    view.lod = lt::LodMode::Screen;
    view.pixelsPerEdge = row.pixels;
    lt::RenderSettings rs;
    rs.width = a.width;
    rs.height = a.height;
    looprender::cameraMatrix(view, adaptive, rs.frame.mvp, rs.frame.light);
    lt::RenderSettings screen = rs;
    screen.frame.lod = looprender::lodSettings(view, adaptive);
    screen.frame.tessFactor = 64;
    lt::RenderSettings patterns = screen, computed = screen;
    patterns.frame.path = lt::DrawPath::Patterns;
    computed.frame.path = lt::DrawPath::Compute;
    std::fprintf(stderr, "bench_lod: %s, %g px: screen-space LOD, tessellator, patterns and compute...\n",
                 row.mesh.c_str(), double(row.pixels));
    lt::Status st = ltbench::measure(
        gpu, adaptive, {{screen, &row.tessellator}, {patterns, &row.patterns}, {computed, &row.compute}}, a.frames, "");
    if (!st) return st;

    st = globalDepth(mesh, rs.frame.mvp, a, row.pixels, row.global);
    if (!st) return st;
    int depth = row.global.depth;
    while (depth > 1 && double(mesh.faceCount()) * std::pow(4.0, depth) > double(a.maxGlobalTriangles)) --depth;
    row.measuredDepth = depth;
    ltbench::PathResult& measured = runs.byDepth[size_t(depth)];
    if (!measured.measured) st = measureGlobal(gpu, a, mesh, depth, rs, measured);
    if (!st) return st;
    row.uniform = measured;
    const double scale = std::pow(4.0, row.global.depth - depth);
    row.uniform.frameMs *= scale;
    row.uniform.triangles = uint64_t(double(row.uniform.triangles) * scale);
    return lt::Status::ok();
}

void printRows(const std::vector<Row>& rows, const Args& a) {
    std::printf(
        "equal quality at %ux%u: screen-space LOD (bound F <= 64) against global refinement at the depth whose\n"
        "longest on-screen edge is under the same length (GPU ms per frame, medians; Mtri: triangles drawn)\n",
        a.width, a.height);
    std::printf(
        "  model   px  depth  longest         glob Mtri    glob ms   tess Mtri    tess ms   pat Mtri     pat ms"
        "   cmp Mtri     cmp ms   tess x   pat x   cmp x\n");
    for (const Row& r : rows) {
        const auto mtri = [](const ltbench::PathResult& p) { return double(p.triangles) / 1e6; };
        const auto speedup = [&](const ltbench::PathResult& p) {
            return p.frameMs > 0 ? r.uniform.frameMs / p.frameMs : 0.0;
        };
        const char* est = r.measuredDepth < r.global.depth ? "est." : "    ";
        std::printf(
            "  %-6s %3g  %5d  %7.2f  %s %9.1f %10.1f  %10.3f %10.1f %10.3f %10.1f %10.3f %10.1f  %6.2fx %6.2fx "
            "%6.2fx%s\n",
            r.mesh.c_str(), double(r.pixels), r.global.depth, r.global.expected, est, mtri(r.uniform),
            r.uniform.frameMs, mtri(r.tessellator), r.tessellator.frameMs, mtri(r.patterns), r.patterns.frameMs,
            mtri(r.compute), r.compute.frameMs, speedup(r.tessellator), speedup(r.patterns), speedup(r.compute),
            r.uniform.chunks ? " (global in chunks)" : "");
    }
    std::printf(
        "longest: global refinement's longest on-screen edge at its depth, in pixels (measured to depth 3, then\n"
        "extrapolated); est.: measured at a shallower depth, triangles and time x 4 per level; tess x, pat x,\n"
        "cmp x: global refinement's frame time over the path's (target on a hardware GPU: compute >= 2.5x)\n");
}

int exitCode(const lt::Status& st) { return ltbench::exitCode("bench_lod", st); }

}  // namespace

int main(int argc, char** argv) {
    Args args;
    if (!parseArgs(argc, argv, args)) return 1;
    std::unique_ptr<lt::VulkanContext> gpu;
    lt::Status st = lt::VulkanContext::createHeadless({}, gpu);
    if (!st) return exitCode(st);
    const std::string device = ltbench::deviceDescription(*gpu);
    std::fprintf(stderr, "bench_lod: %s\n", device.c_str());
    std::printf("bench_lod: device %s\n", device.c_str());
    std::vector<Row> rows;
    for (const std::string& name : args.meshes) {
        lt::InputMesh mesh;
        st = ltbench::loadMesh(args.corpus, name, mesh);
        if (!st) return exitCode(st);
        lt::BakeSettings bs;
        bs.maxDepth = kAdaptiveDepth;
        lt::Asset adaptive;
        st = lt::bake(mesh, bs, adaptive);
        if (!st) return exitCode(st);
        GlobalRuns runs;
        for (float pixels : args.pixels) {
            Row row;
            row.mesh = name;
            row.pixels = pixels;
            st = measureRow(*gpu, args, mesh, adaptive, runs, row);
            if (!st) return exitCode(st);
            rows.push_back(row);
        }
    }
    printRows(rows, args);
    return 0;
}
