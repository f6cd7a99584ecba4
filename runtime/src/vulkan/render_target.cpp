// Offscreen targets and one frame's draws into them (see render_target.h).
#include "render_target.h"

namespace lt {
namespace {

Attachment createAttachment(VulkanContext::Impl& ctx, vk::Format format, vk::ImageUsageFlags usage,
                            vk::ImageAspectFlags aspect, uint32_t width, uint32_t height) {
    Attachment a;
    vk::ImageCreateInfo info({}, vk::ImageType::e2D, format, vk::Extent3D(width, height, 1), 1, 1,
                             vk::SampleCountFlagBits::e1, vk::ImageTiling::eOptimal, usage);
    a.image = vk::raii::Image(ctx.device, info);
    vk::MemoryRequirements req = a.image.getMemoryRequirements();
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < ctx.memory.memoryTypeCount && type == UINT32_MAX; ++i)
        if (req.memoryTypeBits & (1u << i)) type = i;
    for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i)
        if ((req.memoryTypeBits & (1u << i)) &&
            (ctx.memory.memoryTypes[i].propertyFlags & vk::MemoryPropertyFlagBits::eDeviceLocal)) {
            type = i;
            break;
        }
    if (type == UINT32_MAX) throw Failure(Status::Unsupported, "no memory type for an image");
    a.memory = vk::raii::DeviceMemory(ctx.device, {req.size, type});
    a.bytes = req.size;
    a.image.bindMemory(*a.memory, 0);
    a.view = vk::raii::ImageView(ctx.device, vk::ImageViewCreateInfo({}, *a.image, vk::ImageViewType::e2D, format, {},
                                                                     vk::ImageSubresourceRange(aspect, 0, 1, 0, 1)));
    return a;
}

}  // namespace

vk::Format depthFormat(const VulkanContext::Impl& ctx) {
    for (vk::Format f : {vk::Format::eD32Sfloat, vk::Format::eD16Unorm})
        if (ctx.physical.getFormatProperties(f).optimalTilingFeatures &
            vk::FormatFeatureFlagBits::eDepthStencilAttachment)
            return f;
    throw Failure(Status::Unsupported, "no depth attachment format");
}

void transition(const vk::raii::CommandBuffer& cmd, vk::Image image, vk::ImageAspectFlags aspect, vk::ImageLayout from,
                vk::ImageLayout to, vk::PipelineStageFlags srcStage, vk::AccessFlags srcAccess,
                vk::PipelineStageFlags dstStage, vk::AccessFlags dstAccess) {
    vk::ImageMemoryBarrier barrier(srcAccess, dstAccess, from, to, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED,
                                   image, vk::ImageSubresourceRange(aspect, 0, 1, 0, 1));
    cmd.pipelineBarrier(srcStage, dstStage, {}, {}, {}, barrier);
}

RenderTarget::RenderTarget(VulkanContext::Impl& ctx, uint32_t w, uint32_t h)
    : width(w),
      height(h),
      depth(depthFormat(ctx)),
      color(createAttachment(ctx, kColorFormat,
                             vk::ImageUsageFlagBits::eColorAttachment | vk::ImageUsageFlagBits::eTransferSrc,
                             vk::ImageAspectFlagBits::eColor, w, h)),
      zbuffer(createAttachment(ctx, depth, vk::ImageUsageFlagBits::eDepthStencilAttachment,
                               vk::ImageAspectFlagBits::eDepth, w, h)) {}

void RenderTarget::prepare(const vk::raii::CommandBuffer& cmd) const {
    // After any earlier frame drawn into it (DrawPath::Auto's trials reuse a target).
    transition(cmd, *color.image, vk::ImageAspectFlagBits::eColor, vk::ImageLayout::eUndefined,
               vk::ImageLayout::eColorAttachmentOptimal, vk::PipelineStageFlagBits::eColorAttachmentOutput,
               vk::AccessFlagBits::eColorAttachmentWrite, vk::PipelineStageFlagBits::eColorAttachmentOutput,
               vk::AccessFlagBits::eColorAttachmentWrite);
    transition(cmd, *zbuffer.image, vk::ImageAspectFlagBits::eDepth, vk::ImageLayout::eUndefined,
               vk::ImageLayout::eDepthAttachmentOptimal,
               vk::PipelineStageFlagBits::eEarlyFragmentTests | vk::PipelineStageFlagBits::eLateFragmentTests,
               vk::AccessFlagBits::eDepthStencilAttachmentWrite,
               vk::PipelineStageFlagBits::eEarlyFragmentTests | vk::PipelineStageFlagBits::eLateFragmentTests,
               vk::AccessFlagBits::eDepthStencilAttachmentWrite | vk::AccessFlagBits::eDepthStencilAttachmentRead);
}

void recordTargetDraws(VulkanSurface::Impl& s, const vk::raii::CommandBuffer& cmd, const DrawPlan& plan,
                       const FrameSettings& frame, const RenderTarget& target, const float background[4],
                       const SurfacePipelines* app, const EvaluationMark& mark) {
    const bool computed = frame.path == DrawPath::Compute;
    const GraphicsKey key = s.renderKey(kColorFormat, target.depth, frame);
    // Screen-space factors: the pattern path's sort pass, or the compute path's plan
    // (timed with its evaluation).
    if (plan.sorted && !computed) s.recordSort(cmd, plan, frame);
    if (plan.sorted && computed) {
        if (mark) mark(0, false);
        s.recordComputePlan(cmd, plan, frame);
        s.markSorted(plan, frame);
    }
    const uint32_t batches = computed ? s.computeFor(frame).batchCount(plan) : 1;
    const vk::ClearValue clearColor(
        vk::ClearColorValue(std::array<float, 4>{background[0], background[1], background[2], background[3]}));
    const uint32_t w = target.width, h = target.height;
    for (uint32_t k = 0; k < batches; ++k) {
        if (computed) {
            if (mark && (k > 0 || !plan.sorted)) mark(k, false);
            s.recordComputeBatch(cmd, plan, frame, k);
            if (mark) mark(k, true);
        }
        const vk::AttachmentLoadOp load = k == 0 ? vk::AttachmentLoadOp::eClear : vk::AttachmentLoadOp::eLoad;
        vk::RenderingAttachmentInfo colorInfo(*target.color.view, vk::ImageLayout::eColorAttachmentOptimal, {}, {}, {},
                                              load, vk::AttachmentStoreOp::eStore, clearColor);
        vk::RenderingAttachmentInfo depthInfo(
            *target.zbuffer.view, vk::ImageLayout::eDepthAttachmentOptimal, {}, {}, {}, load,
            k + 1 < batches ? vk::AttachmentStoreOp::eStore : vk::AttachmentStoreOp::eDontCare,
            vk::ClearValue(vk::ClearDepthStencilValue(1.0f, 0)));
        cmd.beginRendering(vk::RenderingInfo({}, vk::Rect2D({0, 0}, {w, h}), 1, 0, colorInfo, &depthInfo, nullptr));
        cmd.setViewport(0, vk::Viewport(0, 0, float(w), float(h), 0, 1));
        cmd.setScissor(0, vk::Rect2D({0, 0}, {w, h}));
        s.recordDraws(cmd, plan, key, frame, nullptr, app);
        cmd.endRendering();
    }
}

}  // namespace lt
