// looprender without --cpu: the Vulkan path on a headless device (see looprender.cpp).
#include "looprender_common.h"

#include "looptess/vulkan.h"

#include <algorithm>
#include <cstdio>
#include <memory>

namespace looprender {
namespace {

// Mean and minimum of the per-pass GPU times over the rendered frames.
struct TimeStats {
    double sum[3] = {0, 0, 0}, min[3] = {1e300, 1e300, 1e300};
    uint32_t frames = 0;
    void add(const lt::FrameReport& t) {
        const double v[3] = {t.subdivideMs, t.limitMs, t.drawMs};
        for (int i = 0; i < 3; ++i) {
            sum[i] += v[i];
            min[i] = std::min(min[i], v[i]);
        }
        ++frames;
    }
    nlohmann::json json() const {
        static const char* names[3] = {"subdivide", "limit", "draw"};
        nlohmann::json mean, best;
        double total = 0, totalMin = 0;
        for (int i = 0; i < 3; ++i) {
            mean[names[i]] = sum[i] / frames;
            best[names[i]] = min[i];
            total += sum[i] / frames;
            totalMin += min[i];
        }
        mean["total"] = total;
        best["total"] = totalMin;
        return {{"frames", frames}, {"mean", mean}, {"min", best}};
    }
};

} // namespace

int runGpu(const Options& o, const lt::Asset& asset) {
    lt::HeadlessOptions ho;
    ho.validation = o.validation;
    ho.deviceName = o.device;
    std::unique_ptr<lt::VulkanContext> gpu;
    lt::Status st = lt::VulkanContext::createHeadless(ho, gpu);
    std::unique_ptr<lt::VulkanSurface> surface;
    if (st) st = lt::VulkanSurface::create(*gpu, asset, surface);
    std::vector<float> edits = scaledEditValues(o, asset);
    if (st) st = surface->setEditValues(edits.data(), edits.size());
    if (!st) return fail(st);

    lt::FrameSettings frame;
    frame.tessFactor = o.tess;
    frame.spacing = o.spacing;
    VkPhysicalDeviceProperties device;
    vkGetPhysicalDeviceProperties(gpu->handles().physicalDevice, &device);
    const lt::VulkanHandles handles = gpu->handles();
    frame.path = choosePath(o, device.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU, handles.tessellationShader,
                            handles.drawIndirectFirstInstance);
    frame.watertight = o.watertight;
    frame.displace = o.displace;
    frame.coloring = o.color == "levels"      ? lt::Coloring::Levels
                     : o.color == "texcoords" ? lt::Coloring::Texcoords
                                              : lt::Coloring::Shaded;
    frame.wireframe = o.wireframe;
    cameraMatrix(o, asset, frame.mvp, frame.light);
    frame.lod = lodSettings(o, asset);
    lt::DrawStats stats;
    lt::FrameReport last;
    if (!o.capture.empty()) {
        lt::Tessellation soup;
        st = surface->capture(frame, soup, &stats);
        if (st) st = writePlyFile(o.capture, soup);
        if (!st) return fail(st);
    }
    // Rendered frames give the GPU times; a capture alone renders nothing.
    TimeStats times;
    if (!o.png.empty() || !o.json.empty() || o.capture.empty()) {
        lt::RenderSettings rs;
        rs.width = o.width;
        rs.height = o.height;
        rs.frame = frame;
        lt::Image image;
        for (uint32_t i = 0; i < o.frames; ++i) {
            st = surface->renderImage(rs, image, &last);
            if (!st) return fail(st);
            times.add(last);
            stats = last.draw;
        }
        if (!o.png.empty()) {
            st = writePngFile(o.png, image.width, image.height, image.rgba);
            if (!st) return fail(st);
        }
    }
    std::vector<std::string> messages = gpu->messages();
    for (const std::string& m : messages) std::fprintf(stderr, "looprender: validation: %s\n", m.c_str());
    if (!messages.empty())
        return fail(lt::Status::error(lt::Status::Internal, std::to_string(messages.size()) + " validation messages"));

    std::printf("%s: %u base faces, depth %u of %u, factor %g: %s%llu triangles (%s)\n", o.input.c_str(), asset.faceCount(),
                stats.depth, asset.maxDepth(), double(stats.tessFactor), stats.exact ? "" : "at most ",
                static_cast<unsigned long long>(stats.triangles),
                gpu->deviceName().c_str());
    if (o.verbose) {
        std::fprintf(stderr, "looprender: %s path, %u draws, %llu patches, %llu domain points%s, %llu bytes of device memory\n",
                     frame.path == lt::DrawPath::Patterns ? "patterns" : "tessellator", stats.drawCalls, static_cast<unsigned long long>(stats.patches),
                     static_cast<unsigned long long>(stats.points), stats.exact ? "" : " (at most: screen LOD)",
                     static_cast<unsigned long long>(surface->deviceMemory().total()));
        if (times.frames)
            std::fprintf(stderr, "looprender: GPU ms per frame (mean of %u): subdivide %.3f, limit %.3f, draw %.3f\n",
                         times.frames, times.sum[0] / times.frames, times.sum[1] / times.frames, times.sum[2] / times.frames);
    }
    if (!o.json.empty()) {
        nlohmann::json report = baseReport(o, asset, stats.tessFactor, stats.depth, stats.triangles, frame.path);
        report["countsExact"] = stats.exact;
        report["device"] = gpu->deviceName();
        report["drawCalls"] = stats.drawCalls;
        report["patches"] = stats.patches;
        report["domainPoints"] = stats.points;
        lt::VulkanSurface::Memory memory = surface->deviceMemory();
        report["gpuMemoryBytes"] = {{"total", memory.total()},
                                    {"tables", memory.tables},
                                    {"vertices", memory.vertices},
                                    {"limit", memory.limit},
                                    {"upload", memory.upload},
                                    {"watertight", memory.watertight}};
        if (times.frames) {
            report["gpuTimesMs"] = times.json();
            report["size"] = {o.width, o.height};
            if (last.tessEvaluations >= 0)
                report["pipelineStatistics"] = {{"tessEvaluationInvocations", last.tessEvaluations},
                                                {"clippingPrimitives", last.primitives}};
        }
        st = writeJsonFile(o.json, report);
        if (!st) return fail(st);
    }
    return 0;
}

} // namespace looprender
