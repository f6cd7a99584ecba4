// Blocking offscreen render of a VulkanSurface with per-pass GPU times (vulkan_tools.h).
#include "render_target.h"

#include <cstring>

namespace lt {
namespace {

// Timestamps (kTs*, then two per batch of DrawPath::Compute around its evaluation)
// and pipeline statistics of one frame.
class FrameQueries {
public:
    FrameQueries(VulkanContext::Impl& ctx, uint32_t batches) : ctx_(ctx), count_(kTsCount + 2 * batches) {
        if (ctx.timestampBits > 0)
            timestamps_ =
                vk::raii::QueryPool(ctx.device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, count_));
        if (ctx.pipelineStatistics)
            statistics_ = vk::raii::QueryPool(
                ctx.device, vk::QueryPoolCreateInfo({}, vk::QueryType::ePipelineStatistics, 1, kStatistics));
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
        if (*timestamps_)
            cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *timestamps_, kTsCount + 2 * k + end);
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

}  // namespace

DrawTarget imageFormats(const VulkanContext& context) {
    DrawTarget t;
    t.color = VkFormat(kColorFormat);
    try {
        t.depth = VkFormat(depthFormat(VulkanAccess::context(context)));
    } catch (const Failure&) {  // renderImage says Unsupported then
    }
    return t;
}

Status renderImage(VulkanSurface& surface, const RenderSettings& settings, Image& out, FrameReport* report) {
    return guarded("renderImage", [&]() -> Status {
        VulkanSurface::Impl& s = VulkanAccess::surface(surface);
        VulkanContext::Impl& ctx = s.ctx;
        uint32_t w = settings.width, h = settings.height;
        const auto& limits = ctx.properties.limits;
        if (w == 0 || h == 0 || w > limits.maxImageDimension2D || h > limits.maxImageDimension2D)
            return Status::error(Status::Usage, "image size " + std::to_string(w) + "x" + std::to_string(h) +
                                                    " outside 1.." + std::to_string(limits.maxImageDimension2D));
        s.collectTrials();
        const FrameSettings frame = s.resolved(settings.frame);
        const DrawPlan& plan = s.planFor(frame);
        const SurfacePipelines& p = settings.pipelines;
        if (p.patches || p.ipps || p.layout)
            if (Status st = VulkanSurface::Impl::checkPipelines(p, plan, frame.path); !st) return st;
        RenderTarget target(ctx, w, h);
        GpuBuffer readback =
            ctx.createBuffer(vk::DeviceSize(w) * h * 4, vk::BufferUsageFlagBits::eTransferDst, MemoryKind::HostVisible);
        const bool computed = frame.path == DrawPath::Compute;
        FrameQueries queries(ctx, computed ? s.computeFor(frame).batchCount(plan) : 0);
        GraphicsKey key = s.renderKey(kColorFormat, target.depth, frame);
        if (computed) key.path = DrawPath::Compute, key.tangent = frame.tangents, key.attributes = frame.attributes;

        ctx.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            queries.reset(cmd);
            s.recordCompute(cmd, plan.depth, frame.watertight, queries.timestamps());
            s.recordTrial(cmd, settings.frame);  // DrawPath::Auto, undecided: every path timed
            if (s.compute) s.compute->recorded.reset();
            target.prepare(cmd);
            const SurfacePipelines* app = settings.pipelines.patches ? &settings.pipelines : nullptr;
            queries.beginDraws(cmd, app ? vk::Pipeline(app->patches) : s.pipelines().patches(key));
            recordTargetDraws(s, cmd, plan, frame, target, settings.background, app,
                              [&](uint32_t k, bool end) { queries.evaluation(cmd, k, end); });
            queries.endDraws(cmd);
            transition(cmd, *target.color.image, vk::ImageAspectFlagBits::eColor,
                       vk::ImageLayout::eColorAttachmentOptimal, vk::ImageLayout::eTransferSrcOptimal,
                       vk::PipelineStageFlagBits::eColorAttachmentOutput, vk::AccessFlagBits::eColorAttachmentWrite,
                       vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferRead);
            vk::BufferImageCopy region(0, 0, 0, vk::ImageSubresourceLayers(vk::ImageAspectFlagBits::eColor, 0, 0, 1),
                                       {0, 0, 0}, {w, h, 1});
            cmd.copyImageToBuffer(*target.color.image, vk::ImageLayout::eTransferSrcOptimal, *readback.buffer, region);
            memoryBarrier(cmd, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
                          vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
        });

        s.collectTrials();  // this frame's trial is done
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

}  // namespace lt
