// Private to looptess_vulkan: an offscreen colour and depth target, and one frame's
// draws into it outside any rendering scope (renderImage; DrawPath::Auto's trials).
#pragma once

#include "surface.h"

#include <functional>

namespace lt {

constexpr vk::Format kColorFormat = vk::Format::eR8G8B8A8Unorm;

// D32 or D16, whichever the device has (Unsupported if neither).
vk::Format depthFormat(const VulkanContext::Impl& ctx);

void transition(const vk::raii::CommandBuffer& cmd, vk::Image image, vk::ImageAspectFlags aspect, vk::ImageLayout from,
                vk::ImageLayout to, vk::PipelineStageFlags srcStage, vk::AccessFlags srcAccess,
                vk::PipelineStageFlags dstStage, vk::AccessFlags dstAccess);

struct Attachment {
    vk::raii::Image image{nullptr};
    vk::raii::DeviceMemory memory{nullptr};
    vk::raii::ImageView view{nullptr};
    vk::DeviceSize bytes = 0;
};

// A width x height RGBA8 colour (TRANSFER_SRC too) and depth target.
struct RenderTarget {
    RenderTarget(VulkanContext::Impl& ctx, uint32_t width, uint32_t height);
    uint32_t width, height;
    vk::Format depth;
    Attachment color, zbuffer;
    // Both into attachment layouts, contents undefined (before the first frame).
    void prepare(const vk::raii::CommandBuffer& cmd) const;
};

// Called around batch k's evaluation on the compute path (`end` false before, true
// after), outside rendering: renderImage's timestamps.
using EvaluationMark = std::function<void(uint32_t k, bool end)>;

// `frame`'s draws (resolved, subdivided: after recordCompute) into `target`, which
// prepare() has made ready: the screen-space sort or plan, then per batch (one but on
// the compute path) its evaluation and a rendering scope, cleared to `background`
// first and loaded after, with its draws. `app`: the application's pipelines.
void recordTargetDraws(VulkanSurface::Impl& s, const vk::raii::CommandBuffer& cmd, const DrawPlan& plan,
                       const FrameSettings& frame, const RenderTarget& target, const float background[4],
                       const SurfacePipelines* app, const EvaluationMark& mark = {});

}  // namespace lt
