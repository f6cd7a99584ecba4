// bench/render_measure.cpp -- frame measurements shared by bench_render and bench_lod
// (render_measure.h).
#include "render_measure.h"

#include "uniform_asset.h"

#include "looprender_common.h"  // writePngFile

#include "looptess/tools/file_io.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace ltbench {

// A frame's GPU time: every pass.
double frameTime(const lt::FrameReport& r) { return r.subdivideMs + r.limitMs + r.evaluateMs + r.drawMs; }

lt::Status measure(lt::VulkanContext& gpu, const lt::Asset& asset, const std::vector<Path>& paths, uint32_t frames,
                   const std::string& png) {
    struct Times {
        std::vector<double> sub, lim, eval, draw, frame, wall;
    };
    std::vector<Times> times(paths.size());
    std::unique_ptr<lt::VulkanSurface> surface;
    lt::Status st = lt::VulkanSurface::create(gpu, asset, surface);
    if (!st) return st;
    lt::Image image, last;
    lt::FrameReport report;
    // Warm-up until steady: each path renders until two frames in a row are within 5%
    // of each other (at least 2, at most kMaxWarmup frames). A GPU raises its clocks
    // and fills caches over several frames: one warm-up frame left global refinement
    // 10x slower than it is on an H200.
    constexpr uint32_t kMaxWarmup = 12;
    for (size_t k = 0; k < paths.size(); ++k) {
        double previous = -1;
        uint32_t n = 0;
        for (bool steady = false; !steady && n < kMaxWarmup; ++n) {
            st = lt::renderImage(*surface, paths[k].settings, image, &report);
            if (!st) return st;
            const double ms = frameTime(report);
            steady = n >= 1 && std::fabs(ms - previous) <= 0.05 * std::max(ms, previous);
            previous = ms;
        }
        paths[k].out->warmup = n;
    }
    for (uint32_t i = 0; i < frames; ++i)
        for (size_t k = 0; k < paths.size(); ++k) {
            const Path& path = paths[k];
            Times& t = times[k];
            auto t0 = Clock::now();
            st = lt::renderImage(*surface, path.settings, image, &report);
            if (!st) return st;
            if (k == 0) std::swap(image, last);
            PathResult& out = *path.out;
            out.depth = report.draw.depth;
            // Drawn: pipeline statistics where the device counts them (exact at screen-
            // space factors too), else the plan's count.
            out.triangles = report.primitives >= 0 ? uint64_t(report.primitives) : report.draw.triangles;
            out.drawCalls = report.draw.drawCalls;
            t.wall.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
            t.sub.push_back(report.subdivideMs);
            t.lim.push_back(report.limitMs);
            t.eval.push_back(report.evaluateMs);
            t.draw.push_back(report.drawMs);
            t.frame.push_back(frameTime(report));
        }
    for (size_t k = 0; k < paths.size(); ++k) {
        PathResult& out = *paths[k].out;
        const Times& t = times[k];
        out.measured = true;
        out.subdivideMs = median(t.sub);
        out.limitMs = median(t.lim);
        out.evaluateMs = median(t.eval);
        out.drawMs = median(t.draw);
        out.frameMs = median(t.frame);
        out.wallMs = median(t.wall);
        out.frames = t.frame;
        // The path's own memory: the compute path's batch buffer is not the other paths'.
        out.memory = surface->deviceMemory();
        if (paths[k].settings.frame.path != lt::DrawPath::Compute) out.memory.compute = 0;
        out.memory.trials = 0;
    }
    return png.empty() ? lt::Status::ok() : looprender::writePngFile(png, last.width, last.height, last.rgba);
}

std::string deviceDescription(lt::VulkanContext& gpu) {
    const lt::VulkanHandles h = gpu.handles();
    VkPhysicalDeviceDriverProperties driver{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, nullptr, {}, {}, {}, {}};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver, {}};
    vkGetPhysicalDeviceProperties2(h.physicalDevice, &props);
    const uint32_t v = props.properties.driverVersion;
    return gpu.deviceName() + ", driver " + driver.driverName + " " + driver.driverInfo + " (version " +
           std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v)) + ", Vulkan " +
           std::to_string(VK_API_VERSION_MAJOR(props.properties.apiVersion)) + "." +
           std::to_string(VK_API_VERSION_MINOR(props.properties.apiVersion)) + ")";
}

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

int depthOf(float factor) { return std::max(1, int(std::ceil(std::log2(double(factor)) - 1e-9))); }

// Adds one chunk's figures to the sum over chunks.
static void accumulate(const PathResult& part, PathResult& sum) {
    sum.depth = part.depth;
    sum.triangles += part.triangles;
    sum.drawCalls += part.drawCalls;
    sum.subdivideMs += part.subdivideMs;
    sum.limitMs += part.limitMs;
    sum.evaluateMs += part.evaluateMs;
    sum.drawMs += part.drawMs;
    sum.frameMs += part.frameMs;
    sum.wallMs += part.wallMs;
    sum.buildMs += part.buildMs;
    sum.memory.tables += part.memory.tables;
    sum.memory.vertices += part.memory.vertices;
    sum.memory.limit += part.memory.limit;
    sum.memory.upload += part.memory.upload;
    sum.memory.watertight += part.memory.watertight;
    sum.memory.compute += part.memory.compute;
}

lt::Status measureChunks(lt::VulkanContext& gpu, const lt::InputMesh& mesh, int depth,
                         const std::vector<std::vector<uint32_t>>& parts, const lt::RenderSettings& rs, uint32_t frames,
                         const std::string& stem, PathResult& out) {
    out = PathResult{};
    for (size_t i = 0; i < parts.size(); ++i) {
        lt::Asset chunk;
        auto t0 = Clock::now();
        lt::Status st = ltbench::buildUniformChunk(mesh, depth, parts[i], chunk);
        double buildMs = msSince(t0);
        if (!st) return st;
        PathResult part;
        st = measure(gpu, chunk, {{rs, &part}}, frames,
                     stem.empty() ? "" : stem + "global-chunk" + std::to_string(i) + ".png");
        if (!st) return st;
        part.buildMs = buildMs;
        accumulate(part, out);
    }
    out.measured = true;
    out.chunks = uint32_t(parts.size());
    return lt::Status::ok();
}

bool parseOptions(int argc, char** argv, const char* tool, const char* usage,
                  const std::function<bool(const std::string& option, const std::string& value)>& option) {
    for (int i = 1; i < argc; i += 2) {
        const std::string o = argv[i];
        if (o == "--help" || o == "-h") {
            std::fputs(usage, stdout);
            std::exit(0);
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "%s: option %s needs a value\n\n%s", tool, o.c_str(), usage);
            return false;
        }
        if (!option(o, argv[i + 1])) {
            std::fprintf(stderr, "%s: bad option %s %s\n\n%s", tool, o.c_str(), argv[i + 1], usage);
            return false;
        }
    }
    return true;
}

int exitCode(const char* tool, const lt::Status& st) {
    std::fprintf(stderr, "%s: error: %s\n", tool, st.message.c_str());
    return st.code == lt::Status::Unsupported ? 3 : st.code == lt::Status::Internal ? 5 : 2;
}

bool sharedOption(const std::string& option, const std::string& value, std::vector<std::string>& meshes,
                  uint32_t& frames, uint32_t& width, uint32_t& height, std::string& corpus) {
    char* end = nullptr;
    if (option == "--mesh" && (value == "spot" || value == "bob" || value == "duck")) {
        meshes.push_back(value);
    } else if (option == "--frames" && std::strtoul(value.c_str(), &end, 10) >= 1 && *end == 0) {
        frames = uint32_t(std::strtoul(value.c_str(), nullptr, 10));
    } else if (option == "--size" && std::sscanf(value.c_str(), "%ux%u", &width, &height) == 2 && width && height) {
    } else if (option == "--corpus") {
        corpus = value;
    } else {
        return false;
    }
    return true;
}

}  // namespace ltbench
