// bench/render_measure.h -- frame measurements shared by bench_render and bench_lod:
// a bench model's control mesh, an asset's frames through lt::VulkanSurface, global
// refinement in chunks. Figures go into render_report.h's PathResult.
#pragma once

#include "bench_common.h"

#include "render_report.h"

#include "looptess/tools/baker.h"
#include "looptess/tools/vulkan_tools.h"

#include <chrono>
#include <functional>
#include <cstdint>
#include <string>
#include <vector>

namespace ltbench {

using Clock = std::chrono::steady_clock;

// One way to render an asset, and its figures.
struct Path {
    lt::RenderSettings settings;
    PathResult* out;
};

// Uploads `asset` once and renders each path until its frame time is steady (two
// frames in a row within 5%), then `frames` rounds of one timed frame of each path in
// turn (so that all paths see the same machine load: on lavapipe frame times drift
// by 10-30% between runs); fills each path's `out` (medians) and saves the first
// path's last image to `png` when non-empty.
lt::Status measure(lt::VulkanContext& gpu, const lt::Asset& asset, const std::vector<Path>& paths, uint32_t frames,
                   const std::string& png);

// Global refinement of `mesh` at `depth` in the chunks `parts`, one surface at a
// time (each built, measured and freed before the next); `out` is the sum.
// Unsupported when a chunk does not fit the device either.
lt::Status measureChunks(lt::VulkanContext& gpu, const lt::InputMesh& mesh, int depth,
                         const std::vector<std::vector<uint32_t>>& parts, const lt::RenderSettings& rs, uint32_t frames,
                         const std::string& stem, PathResult& out);

double msSince(Clock::time_point t0);

// Command lines of bench_render and bench_lod: `--name value` pairs, each handed to
// `option`, which stores a valid one and returns true. --help prints `usage` and
// exits 0; a missing value or an option `option` refuses prints an error naming
// `tool` and the usage, and gives false.
bool parseOptions(int argc, char** argv, const char* tool, const char* usage,
                  const std::function<bool(const std::string& option, const std::string& value)>& option);
// Prints "TOOL: error: ..." and gives the render benchmarks' exit status of `st`: 3
// Unsupported (no device, or it cannot run the figure), 5 Internal (a Vulkan error),
// 2 otherwise (a mesh that cannot be read or baked).
int exitCode(const char* tool, const lt::Status& st);

// The options both share (--mesh spot|bob|duck, --frames N >= 1, --size WxH,
// --corpus DIR): true when `option` is one with a valid `value`, stored.
bool sharedOption(const std::string& option, const std::string& value, std::vector<std::string>& meshes,
                  uint32_t& frames, uint32_t& width, uint32_t& height, std::string& corpus);

// "NAME, driver VERSION (DRIVER NAME INFO)" of the context's device.
std::string deviceDescription(lt::VulkanContext& gpu);

// Subdivision depth of factor F: ceil(log2 F), at least 1.
int depthOf(float factor);

}  // namespace ltbench
