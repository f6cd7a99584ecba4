// looptess/tools/vulkan_tools.h -- blocking helpers of the Vulkan path (library
// looptess_vulkan) for tools and tests: the emitted vertices captured, the refined
// vertices read back, the surface rendered offscreen. Each one records into a
// command buffer of its own, submits it to the context's queue and waits; an
// engine's frame loop needs none of them (looptess/vulkan.h is its whole API).
//
//   std::unique_ptr<lt::VulkanContext> gpu;
//   lt::Status st = lt::VulkanContext::createHeadless({}, gpu);
//   std::unique_ptr<lt::VulkanSurface> surface;
//   if (st) st = lt::VulkanSurface::create(*gpu, asset, surface);
//   lt::Tessellation soup;
//   if (st) st = lt::capture(*surface, lt::FrameSettings{eval}, soup);  // lt::evaluateCpu's soup
//   lt::RenderSettings render;
//   lt::Image image;
//   if (st) st = lt::renderImage(*surface, render, image);
//
// Errors, threading and lifetime as vulkan.h says: a Status, never an exception; the
// application must not use the context's queue while a helper runs.
#pragma once

#include "looptess/runtime.h"
#include "looptess/vulkan.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace lt {

// Whether `context` can capture: VK_EXT_transform_feedback with its feature enabled
// (createHeadless enables it where the device has it; adopt: VulkanHandles).
bool canCapture(const VulkanContext& context);

// The attachment formats of renderImage (colour RGBA8 UNORM; depth D32 or D16,
// whichever the device has), for pipelines given in RenderSettings::pipelines.
DrawTarget imageFormats(const VulkanContext& context);

// What renderImage measured for one frame.
struct FrameReport {
    DrawStats draw;
    // GPU times of the passes (ms) from timestamp queries written outside the
    // rendering scope; negative when the queue has no timestamps. evaluateMs: the
    // compute path's evaluation into its batches (0 on the other paths, whose
    // evaluation is part of the draw).
    double subdivideMs = -1, limitMs = -1, evaluateMs = -1, drawMs = -1;
    // Pipeline statistics of the draws; negative without pipelineStatisticsQuery.
    // Drivers count evaluation shader calls differently (lavapipe: one per unique
    // domain point of a patch), so compare them only on one driver.
    int64_t tessEvaluations = -1;  // tessellation evaluation shader invocations
    int64_t primitives = -1;       // primitives reaching the clipper
};

struct Image {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;  // row-major from the top, 4 bytes a pixel
};

struct RenderSettings {
    uint32_t width = 512, height = 512;
    FrameSettings frame;
    float background[4] = {1, 1, 1, 1};
    // When set, renderImage draws with these (built for imageFormats(context),
    // surfaceStages(frame.spacing) and specialization(frame)) instead of its own.
    SurfacePipelines pipelines;
};

// Subdivides `surface` to runtimeDepth(asset, tessFactor) and reads the refined
// vertex buffer back: 3 floats per global vertex, zero above that depth (like
// subdivideCpu). `limit` (optional) receives 9 floats per limit stencil of that
// depth: position, unit normal, and the unit direction displacement moves along.
Status readVertices(VulkanSurface& surface, float tessFactor, std::vector<float>& vertices,
                    std::vector<float>* limit = nullptr);

// The largest transform feedback session capture writes by default: lavapipe 22.3
// writes past 2 GiB out of bounds (a crash in its draw thread).
constexpr uint64_t kMaxCaptureSessionBytes = (uint64_t(1) << 31) - 1;

// Subdivides, draws with rasterization off and captures every emitted vertex by
// transform feedback into `out` (replaced), in lt::evaluateCpu's order and format:
// the same soup evaluateCpu makes of the frame's EvalSettings (without
// EvalSettings::attributes, no texture coordinates, tangents or colours either). Needs
// canCapture(context). Of the frame's drawing fields only maxPointsPerDraw and
// computeBytes matter. With LodMode::Screen it first reads the refined vertices back
// to plan the exact factors. A capture over `maxSessionBytes` (84 bytes a vertex) is
// taken in several transform feedback sessions, runs of the frame's draws, each read
// back before the next (a draw is never split: one larger than `maxSessionBytes` is a
// session of its own, up to kMaxCaptureSessionBytes); Unsupported where the frame
// draws in one (DrawPath::Compute, and DrawPath::Patterns at screen-space factors). Host memory: the soup, and a
// session's bytes twice where the device's memory is the host's (lavapipe).
Status capture(VulkanSurface& surface, const FrameSettings& frame, Tessellation& out, DrawStats* stats = nullptr,
               uint64_t maxSessionBytes = kMaxCaptureSessionBytes);
// As above, session by session: each session's soup (the frame's vertices `first` ..
// first + session.vertexCount(), in order) handed to `each` as it is read back, so
// that the host holds one session's, not the frame's (loopcheck's cases in pieces).
// A Status other than ok from `each` ends the capture with it.
using CaptureSessionFn = std::function<Status(const Tessellation& session, size_t first)>;
Status capture(VulkanSurface& surface, const FrameSettings& frame, const CaptureSessionFn& each,
               DrawStats* stats = nullptr, uint64_t maxSessionBytes = kMaxCaptureSessionBytes);

// Subdivides and renders `surface` offscreen (colour RGBA8 + depth) as `settings`
// say; `report` (optional) receives the frame's draw counts and GPU times.
Status renderImage(VulkanSurface& surface, const RenderSettings& settings, Image& out, FrameReport* report = nullptr);

}  // namespace lt
