// VulkanSurface::evaluateSizes and recordEvaluate: one frame of the pattern path into
// an application's buffers (vulkan.h; shaders/evaluate.comp has the layout).
#include "surface.h"

#include <algorithm>

namespace lt {
namespace {

uint32_t patternPoints(uint32_t n) { return (n + 1) * (n + 2) / 2; }

VulkanSurface::EvaluateSizes sizesOf(const DrawPlan& plan) {
    VulkanSurface::EvaluateSizes s;
    for (const DrawBatch& b : plan.batches) {
        s.vertices += uint64_t(b.recordCount) * patternPoints(b.pattern);
        s.indices += 3 * uint64_t(b.recordCount) * b.pattern * b.pattern;
    }
    s.vertices += 3 * uint64_t(plan.ippTriangles);
    s.indices += 3 * uint64_t(plan.ippTriangles);
    return s;
}

const DrawPlan& patternPlan(VulkanSurface::Impl& s, const FrameSettings& frame) {
    if (frame.path != DrawPath::Patterns)
        throw Failure(Status::Usage, "the surface goes into buffers on the pattern path only: set FrameSettings::path "
                                     "to DrawPath::Patterns");
    if (frame.lod.mode == LodMode::Screen)
        throw Failure(Status::Usage, "the surface goes into buffers at global and distance factors; screen-space "
                                     "factors are sorted on the GPU, and their sizes known only there");
    return s.planFor(frame);
}

} // namespace

Status VulkanSurface::evaluateSizes(const FrameSettings& frame, EvaluateSizes& out) {
    return guarded("evaluateSizes", [&]() -> Status {
        out = sizesOf(patternPlan(*impl_, frame));
        return Status::ok();
    });
}

Status VulkanSurface::recordEvaluate(VkCommandBuffer cmd, const FrameSettings& frame, VkBuffer vertices,
                                     VkDeviceSize vertexOffset, VkBuffer indices, VkDeviceSize indexOffset) {
    return guarded("recordEvaluate", [&]() -> Status {
        Impl& s = *impl_;
        VulkanContext::Impl& ctx = s.ctx;
        const DrawPlan& plan = patternPlan(s, frame);
        if (Status st = subdividedFor(s, plan, frame); !st) return st;
        if (!cmd || !vertices || !indices) return Status::error(Status::Usage, "recordEvaluate: a null command buffer or buffer");
        const VkDeviceSize align = ctx.properties.limits.minStorageBufferOffsetAlignment;
        if (vertexOffset % align || indexOffset % align)
            return Status::error(Status::Usage, "recordEvaluate: offsets must be multiples of minStorageBufferOffsetAlignment (" +
                                                    std::to_string(align) + ")");
        const EvaluateSizes sizes = sizesOf(plan);
        Pipelines& pipes = s.pipelines();
        if (!*s.evaluateSet) {
            vk::DescriptorPoolSize size(vk::DescriptorType::eStorageBuffer, 2);
            s.evaluatePool = vk::raii::DescriptorPool(
                ctx.device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, size));
            vk::raii::DescriptorSets sets(ctx.device, vk::DescriptorSetAllocateInfo(*s.evaluatePool, *pipes.evaluateSetLayout));
            s.evaluateSet = std::move(sets[0]);
        }
        // An empty frame still binds valid ranges (at least 4 bytes).
        vk::DescriptorBufferInfo infos[2] = {{vertices, vertexOffset, std::max<VkDeviceSize>(sizes.vertexBytes(), 4)},
                                             {indices, indexOffset, std::max<VkDeviceSize>(sizes.indexBytes(), 4)}};
        vk::WriteDescriptorSet writes[2] = {
            {*s.evaluateSet, 0, 0, 1, vk::DescriptorType::eStorageBuffer, nullptr, &infos[0]},
            {*s.evaluateSet, 1, 0, 1, vk::DescriptorType::eStorageBuffer, nullptr, &infos[1]}};
        ctx.device.updateDescriptorSets(writes, {});

        BorrowedCommandBuffer borrowed(ctx.device, cmd);
        const vk::raii::CommandBuffer& c = *borrowed;
        // The subdivision's results (compute writes, made visible to draws) are read here.
        memoryBarrier(c, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                      vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderRead);
        const vk::PipelineLayout layout = *pipes.evaluateLayout;
        c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, layout, 0, {*s.descriptorSet, *s.evaluateSet}, {});
        PushConstants pc;
        pc.tessFactor = plan.tessFactor;
        pc.flags = (frame.watertight ? LT_FLAG_WATERTIGHT : 0u) | (frame.displace ? LT_FLAG_DISPLACE : 0u);
        const bool displace = s.displaceKey(frame);
        const uint64_t maxThreads = uint64_t(ctx.properties.limits.maxComputeWorkGroupCount[0]) * LT_LOCAL_SIZE;
        auto dispatch = [&](uint32_t kind, uint64_t threads) {   // threads <= maxThreads
            c.bindPipeline(vk::PipelineBindPoint::eCompute, pipes.evaluate(kind, frame.watertight, displace));
            pc.evaluate[3] = uint32_t(threads);
            c.pushConstants<PushConstants>(layout, kAllStages, 0, pc);
            c.dispatch(uint32_t((threads + LT_LOCAL_SIZE - 1) / LT_LOCAL_SIZE), 1, 1);
        };
        uint64_t vertex = 0, index = 0;   // outputs so far
        for (const DrawBatch& b : plan.batches) {
            const uint32_t n = b.pattern, points = patternPoints(n);
            pc.base = b.listOffset;
            pc.level = n;
            // Whole records per dispatch, as many as keep both kinds within maxThreads.
            const uint64_t perDispatch = std::max<uint64_t>(maxThreads / std::max(points, n * n), 1);
            for (uint32_t r = 0; r < b.recordCount; r += uint32_t(perDispatch)) {
                const uint32_t records = uint32_t(std::min<uint64_t>(perDispatch, b.recordCount - r));
                pc.evaluate[0] = uint32_t(vertex);
                pc.evaluate[1] = uint32_t(index);
                pc.evaluate[2] = b.firstRecord + r;
                dispatch(LT_EVALUATE_PATTERN_POINTS, uint64_t(records) * points);
                dispatch(LT_EVALUATE_PATTERN_INDICES, uint64_t(records) * n * n);
                vertex += uint64_t(records) * points;
                index += 3 * uint64_t(records) * n * n;
            }
        }
        pc.level = plan.ippLevel;
        for (uint64_t corner = 0; corner < 3 * uint64_t(plan.ippTriangles); corner += maxThreads) {
            pc.evaluate[0] = uint32_t(vertex + corner);   // corner c's vertex and index are both first + c
            pc.evaluate[1] = uint32_t(index + corner);
            pc.evaluate[2] = uint32_t(corner);            // the dispatch's first IPP corner
            dispatch(LT_EVALUATE_IPPS, std::min(maxThreads, 3 * uint64_t(plan.ippTriangles) - corner));
        }
        return Status::ok();
    });
}

} // namespace lt
