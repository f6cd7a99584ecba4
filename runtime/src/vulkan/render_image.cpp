// Blocking offscreen render of a VulkanSurface with per-pass GPU times (vulkan.h).
#include "surface.h"

#include <cstring>

namespace lt {
namespace {

constexpr vk::Format kColorFormat = vk::Format::eR8G8B8A8Unorm;

struct Attachment {
    vk::raii::Image image{nullptr};
    vk::raii::DeviceMemory memory{nullptr};
    vk::raii::ImageView view{nullptr};
};

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
        if ((req.memoryTypeBits & (1u << i)) && (ctx.memory.memoryTypes[i].propertyFlags & vk::MemoryPropertyFlagBits::eDeviceLocal)) {
            type = i;
            break;
        }
    if (type == UINT32_MAX) throw Failure(Status::Unsupported, "no memory type for an image");
    a.memory = vk::raii::DeviceMemory(ctx.device, {req.size, type});
    a.image.bindMemory(*a.memory, 0);
    a.view = vk::raii::ImageView(ctx.device, vk::ImageViewCreateInfo({}, *a.image, vk::ImageViewType::e2D, format, {},
                                                                      vk::ImageSubresourceRange(aspect, 0, 1, 0, 1)));
    return a;
}

vk::Format depthFormat(const VulkanContext::Impl& ctx) {
    for (vk::Format f : {vk::Format::eD32Sfloat, vk::Format::eD16Unorm})
        if (ctx.physical.getFormatProperties(f).optimalTilingFeatures & vk::FormatFeatureFlagBits::eDepthStencilAttachment)
            return f;
    throw Failure(Status::Unsupported, "no depth attachment format");
}

void transition(const vk::raii::CommandBuffer& cmd, vk::Image image, vk::ImageAspectFlags aspect, vk::ImageLayout from, vk::ImageLayout to,
                vk::PipelineStageFlags srcStage, vk::AccessFlags srcAccess, vk::PipelineStageFlags dstStage,
                vk::AccessFlags dstAccess) {
    vk::ImageMemoryBarrier barrier(srcAccess, dstAccess, from, to, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, image,
                                   vk::ImageSubresourceRange(aspect, 0, 1, 0, 1));
    cmd.pipelineBarrier(srcStage, dstStage, {}, {}, {}, barrier);
}

// Timestamps (kTs*, then two per batch of DrawPath::Compute around its evaluation)
// and pipeline statistics of one frame.
class FrameQueries {
public:
    FrameQueries(VulkanContext::Impl& ctx, uint32_t batches) : ctx_(ctx), count_(kTsCount + 2 * batches) {
        if (ctx.timestampBits > 0)
            timestamps_ = vk::raii::QueryPool(ctx.device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, count_));
        if (ctx.pipelineStatistics)
            statistics_ = vk::raii::QueryPool(ctx.device, vk::QueryPoolCreateInfo({}, vk::QueryType::ePipelineStatistics, 1, kStatistics));
    }
    vk::QueryPool timestamps() const { return *timestamps_; }
    void reset(const vk::raii::CommandBuffer& cmd) const {
        if (*timestamps_) cmd.resetQueryPool(*timestamps_, 0, count_);
        if (*statistics_) cmd.resetQueryPool(*statistics_, 0, 1);
    }
    // Around the draws' rendering scope (timestamps inside it undercount on
    // lavapipe). `drawPipeline` is bound first: lavapipe 22.3 crashes in
    // vkCmdBeginQuery when the last bound pipeline is a compute pipeline (measured).
    void beginDraws(const vk::raii::CommandBuffer& cmd, vk::Pipeline drawPipeline) const {
        if (*timestamps_) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *timestamps_, kTsDrawStart);
        if (*statistics_) {
            cmd.bindPipeline(vk::PipelineBindPoint::eGraphics, drawPipeline);
            cmd.beginQuery(*statistics_, 0, {});
        }
    }
    // Around batch k's evaluation (DrawPath::Compute), outside rendering.
    void evaluation(const vk::raii::CommandBuffer& cmd, uint32_t k, bool end) const {
        if (*timestamps_) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *timestamps_, kTsCount + 2 * k + end);
    }
    void endDraws(const vk::raii::CommandBuffer& cmd) const {
        if (*statistics_) cmd.endQuery(*statistics_, 0);
        if (*timestamps_) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *timestamps_, kTsDrawEnd);
    }
    void read(FrameReport& report) const {
        const auto flags = vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait;
        if (*timestamps_) {
            auto [r, results] = timestamps_.getResults<uint64_t>(0, count_, count_ * 8, 8, flags);
            if (r == vk::Result::eSuccess) {
                uint64_t mask = ctx_.timestampBits >= 64 ? ~uint64_t(0) : (uint64_t(1) << ctx_.timestampBits) - 1;
                double ms = double(ctx_.properties.limits.timestampPeriod) * 1e-6;
                const std::vector<uint64_t>& ts = results;  // C++17 lambdas cannot capture a structured binding
                auto span = [&](uint32_t a, uint32_t b) { return double((ts[b] - ts[a]) & mask) * ms; };
                report.subdivideMs = span(kTsStart, kTsSubdivided);
                report.limitMs = span(kTsSubdivided, kTsLimit);
                report.evaluateMs = 0;
                for (uint32_t t = kTsCount; t < count_; t += 2) report.evaluateMs += span(t, t + 1);
                report.drawMs = span(kTsDrawStart, kTsDrawEnd) - report.evaluateMs;
            }
        }
        if (*statistics_) {
            // Results come in the order of the bits: clipping invocations (bit 6), then
            // tessellation evaluation invocations (bit 10).
            auto [r, counts] = statistics_.getResults<uint64_t>(0, 1, 16, 16, flags);
            if (r == vk::Result::eSuccess) {
                report.primitives = int64_t(counts[0]);
                report.tessEvaluations = int64_t(counts[1]);
            }
        }
    }

private:
    static constexpr vk::QueryPipelineStatisticFlags kStatistics =
        vk::QueryPipelineStatisticFlagBits::eClippingInvocations |
        vk::QueryPipelineStatisticFlagBits::eTessellationEvaluationShaderInvocations;
    VulkanContext::Impl& ctx_;
    uint32_t count_;
    vk::raii::QueryPool timestamps_{nullptr}, statistics_{nullptr};
};

} // namespace

DrawTarget VulkanContext::imageFormats() const {
    DrawTarget t;
    t.color = VkFormat(kColorFormat);
    try {
        t.depth = VkFormat(depthFormat(*impl_));
    } catch (const Failure&) {   // renderImage says Unsupported then
    }
    return t;
}

Status VulkanSurface::renderImage(const RenderSettings& settings, Image& out, FrameReport* report) {
    return guarded("renderImage", [&]() -> Status {
        Impl& s = *impl_;
        VulkanContext::Impl& ctx = s.ctx;
        uint32_t w = settings.width, h = settings.height;
        const auto& limits = ctx.properties.limits;
        if (w == 0 || h == 0 || w > limits.maxImageDimension2D || h > limits.maxImageDimension2D)
            return Status::error(Status::Usage, "image size " + std::to_string(w) + "x" + std::to_string(h) +
                                                    " outside 1.." + std::to_string(limits.maxImageDimension2D));
        const FrameSettings frame = s.resolved(settings.frame);
        const DrawPlan& plan = s.planFor(frame);
        const SurfacePipelines& p = settings.pipelines;
        if (p.patches || p.ipps || p.layout)
            if (Status st = Impl::checkPipelines(p, plan, frame.path); !st) return st;
        vk::Format depth = depthFormat(ctx);
        Attachment color = createAttachment(ctx, kColorFormat, vk::ImageUsageFlagBits::eColorAttachment | vk::ImageUsageFlagBits::eTransferSrc,
                                            vk::ImageAspectFlagBits::eColor, w, h);
        Attachment zbuffer = createAttachment(ctx, depth, vk::ImageUsageFlagBits::eDepthStencilAttachment,
                                              vk::ImageAspectFlagBits::eDepth, w, h);
        GpuBuffer readback = ctx.createBuffer(vk::DeviceSize(w) * h * 4, vk::BufferUsageFlagBits::eTransferDst, MemoryKind::HostVisible);
        const bool computed = frame.path == DrawPath::Compute;
        const uint32_t batches = computed ? s.computeFor(frame).batchCount(plan) : 1;
        FrameQueries queries(ctx, computed ? batches : 0);
        GraphicsKey key = s.renderKey(kColorFormat, depth, frame);

        ctx.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            queries.reset(cmd);
            s.recordCompute(cmd, plan.depth, frame.watertight, queries.timestamps());
            if (s.compute) s.compute->recorded.reset();
            transition(cmd, *color.image, vk::ImageAspectFlagBits::eColor, vk::ImageLayout::eUndefined,
                       vk::ImageLayout::eColorAttachmentOptimal, vk::PipelineStageFlagBits::eTopOfPipe, {},
                       vk::PipelineStageFlagBits::eColorAttachmentOutput, vk::AccessFlagBits::eColorAttachmentWrite);
            transition(cmd, *zbuffer.image, vk::ImageAspectFlagBits::eDepth, vk::ImageLayout::eUndefined,
                       vk::ImageLayout::eDepthAttachmentOptimal, vk::PipelineStageFlagBits::eTopOfPipe, {},
                       vk::PipelineStageFlagBits::eEarlyFragmentTests | vk::PipelineStageFlagBits::eLateFragmentTests,
                       vk::AccessFlagBits::eDepthStencilAttachmentWrite | vk::AccessFlagBits::eDepthStencilAttachmentRead);
            const SurfacePipelines* app = settings.pipelines.patches ? &settings.pipelines : nullptr;
            GraphicsKey statisticsKey = key;
            if (computed) statisticsKey.tangent = frame.tangents, statisticsKey.attributes = frame.attributes;
            queries.beginDraws(cmd, app ? vk::Pipeline(app->patches) : s.pipelines().patches(statisticsKey));
            // Screen-space factors: the pattern path's sort pass, timed with the draws;
            // the compute path's plan, timed with its evaluation.
            if (plan.sorted && !computed) s.recordSort(cmd, plan, frame);
            if (plan.sorted && computed) {
                queries.evaluation(cmd, 0, false);
                s.recordComputePlan(cmd, plan, frame);
                s.markSorted(plan, frame);
            }
            vk::ClearValue clearColor(vk::ClearColorValue(std::array<float, 4>{settings.background[0], settings.background[1],
                                                                               settings.background[2], settings.background[3]}));
            for (uint32_t k = 0; k < batches; ++k) {   // one batch but on the compute path
                if (computed) {
                    if (k > 0 || !plan.sorted) queries.evaluation(cmd, k, false);
                    s.recordComputeBatch(cmd, plan, frame, k);
                    queries.evaluation(cmd, k, true);
                }
                const vk::AttachmentLoadOp load = k == 0 ? vk::AttachmentLoadOp::eClear : vk::AttachmentLoadOp::eLoad;
                vk::RenderingAttachmentInfo colorInfo(*color.view, vk::ImageLayout::eColorAttachmentOptimal, {}, {}, {}, load,
                                                      vk::AttachmentStoreOp::eStore, clearColor);
                vk::RenderingAttachmentInfo depthInfo(*zbuffer.view, vk::ImageLayout::eDepthAttachmentOptimal, {}, {}, {}, load,
                                                      k + 1 < batches ? vk::AttachmentStoreOp::eStore : vk::AttachmentStoreOp::eDontCare,
                                                      vk::ClearValue(vk::ClearDepthStencilValue(1.0f, 0)));
                cmd.beginRendering(vk::RenderingInfo({}, vk::Rect2D({0, 0}, {w, h}), 1, 0, colorInfo, &depthInfo, nullptr));
                cmd.setViewport(0, vk::Viewport(0, 0, float(w), float(h), 0, 1));
                cmd.setScissor(0, vk::Rect2D({0, 0}, {w, h}));
                s.recordDraws(cmd, plan, key, frame, nullptr, app);
                cmd.endRendering();
            }
            queries.endDraws(cmd);
            transition(cmd, *color.image, vk::ImageAspectFlagBits::eColor, vk::ImageLayout::eColorAttachmentOptimal,
                       vk::ImageLayout::eTransferSrcOptimal, vk::PipelineStageFlagBits::eColorAttachmentOutput,
                       vk::AccessFlagBits::eColorAttachmentWrite, vk::PipelineStageFlagBits::eTransfer,
                       vk::AccessFlagBits::eTransferRead);
            vk::BufferImageCopy region(0, 0, 0, vk::ImageSubresourceLayers(vk::ImageAspectFlagBits::eColor, 0, 0, 1), {0, 0, 0},
                                       {w, h, 1});
            cmd.copyImageToBuffer(*color.image, vk::ImageLayout::eTransferSrcOptimal, *readback.buffer, region);
            memoryBarrier(cmd, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
                          vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
        });

        out.width = w;
        out.height = h;
        out.rgba.resize(size_t(w) * h * 4);
        std::memcpy(out.rgba.data(), readback.mapped, out.rgba.size());
        if (report) {
            *report = FrameReport{};
            report->draw = s.frameStats(plan, frame);
            queries.read(*report);
        }
        return Status::ok();
    });
}

} // namespace lt
