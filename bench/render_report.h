// bench/render_report.h -- bench_render's figures, its targets and its two outputs
// (text tables for stdout, JSON for --json). Pure formatting: no measuring here.
#pragma once

#include "bench_common.h"

#include "looptess/tools/vulkan_tools.h"

#include <cstdint>
#include <string>
#include <vector>

namespace ltbench {

// Targets at F = kTargetFactor (bench/README.md): the adaptive pipeline's
// GPU memory at most kMaxMemoryRatio of global refinement's, its frame time at
// least kMinSpeedup times shorter.
constexpr float kTargetFactor = 32.0f;
constexpr double kMaxMemoryRatio = 0.10;
constexpr double kMinSpeedup = 2.0;
// Target (paper 4.6 pays +80%): watertight evaluation costs at most
// kMaxWatertightCost more frame time than --no-watertight, at every factor.
constexpr double kMaxWatertightCost = 0.25;
// Targets of the compute path on a hardware GPU (bench/README.md): at F = 8 and 32 at
// least kMinComputeRate of global refinement's frame rate, and at F = 32 its memory
// at most kMaxMemoryRatio of global refinement's.
constexpr double kMinComputeRate = 0.9;
// The paper's Table 2 (GTX 570, Direct3D 11, F = 32, depth 5), in ms.
constexpr double kPaperDuckMs = 12.66;

// One pipeline (adaptive or global refinement) at one factor. Times are medians
// over the timed frames, in ms; GPU times come from the runtime's timestamp
// queries (lt::FrameReport), the frame time is their sum.
struct PathResult {
    bool measured = false;
    std::string note;  // why it was not measured, or empty
    uint32_t depth = 0;
    uint64_t triangles = 0;  // drawn per frame
    uint32_t drawCalls = 0;
    double subdivideMs = 0, limitMs = 0, evaluateMs = 0, drawMs = 0, frameMs = 0;
    uint32_t warmup = 0;         // frames rendered until the frame time was steady
    double wallMs = 0;           // lt::renderImage, wall clock (info)
    double buildMs = 0;          // lt::bake or buildUniformAsset, wall clock (info)
    std::vector<double> frames;  // each timed frame's GPU time, in the order rendered
    lt::VulkanSurface::Memory memory;
    // 0: one asset. n > 0: global refinement in n chunks (uniform_asset.h's
    // buildUniformChunk), one surface each, measured one after the other; every
    // figure above is the sum over the chunks of each chunk's own figure (times:
    // the sum of the per-chunk medians).
    uint32_t chunks = 0;
};

struct RenderRow {
    std::string mesh;
    uint32_t controlVertices = 0, controlTriangles = 0;
    float factor = 1;
    PathResult adaptive, global;
    PathResult chunked;            // global refinement in chunks (when global does not fit, or asked for)
    PathResult plain;              // adaptive with FrameSettings::watertight = false
    PathResult patterns;           // adaptive with DrawPath::Patterns (no tessellator)
    PathResult compute;            // adaptive with DrawPath::Compute (evaluated in compute, plain draws)
    uint64_t leanGlobalBytes = 0;  // leanBytes(): vertex-only global refinement (computed)

    // The baseline the targets compare against: global refinement in one asset when
    // it was measured, else in chunks.
    const PathResult& baseline() const { return global.measured ? global : chunked; }
    double speedup() const { return adaptive.frameMs > 0 ? baseline().frameMs / adaptive.frameMs : 0; }
    double memoryRatio() const { return ratio(adaptive.memory.total(), baseline().memory.total()); }
    // Chunked over whole global refinement, minus 1 (both measured).
    double chunkingTimeCost() const { return global.frameMs > 0 ? chunked.frameMs / global.frameMs - 1 : 0; }
    double chunkingMemoryCost() const {
        return global.memory.total() ? double(chunked.memory.total()) / double(global.memory.total()) - 1 : 0;
    }
    double leanMemoryRatio() const { return ratio(adaptive.memory.total(), leanGlobalBytes); }
    // Watertight evaluation's extra frame time and memory, relative to plain. Time:
    // the median over rounds of the two paths' frame-time ratio (bench_render renders
    // them in turn, so each ratio compares frames under the same machine load).
    double watertightTimeCost() const;
    double watertightMemoryCost() const {
        uint64_t w = adaptive.memory.watertight, t = adaptive.memory.total();
        return t > w ? double(w) / double(t - w) : 0;
    }
    static double ratio(uint64_t a, uint64_t b) { return b ? double(a) / double(b) : 0; }
};

struct RenderReport {
    std::string device, machine;  // Vulkan device name and driver; CPU model and count
    uint32_t width = 0, height = 0, frames = 0;
    std::vector<RenderRow> rows;
};

// The comparison table (one row per mesh and factor), the targets at F = 32 with
// PASS/MISS, then the Table-2-style table of the adaptive pipeline.
std::string formatTables(const RenderReport& report);

// Every figure as JSON (times in ms, sizes in bytes).
std::string formatJson(const RenderReport& report);

}  // namespace ltbench
