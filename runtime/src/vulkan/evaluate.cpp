// VulkanSurface::evaluateSizes and recordEvaluate: one frame of the pattern path into
// an application's buffers (vulkan.h; shaders/evaluate.comp has the layout).
#include "evaluate_pass.h"

#include <algorithm>

namespace lt {
namespace {

// Exact for global and distance factors; at screen-space factors (a sorted plan,
// the uniform factors of the bound F) the most any frame writes: every edge factor
// is at most F's, and a pattern has no more points and triangles than one with
// larger factors (tests/runtime/test_patterns.cpp checks that of the pattern library).
VulkanSurface::EvaluateSizes sizesOf(const DrawPlan& plan) {
    VulkanSurface::EvaluateSizes s;
    if (plan.sorted) {
        s.vertices = plan.points;
        s.indices = 3 * plan.tessTriangles;
    }
    for (const DrawBatch& b : plan.batches) {
        s.vertices += uint64_t(b.recordCount) * patternPoints(b.pattern);
        s.indices += 3 * uint64_t(b.recordCount) * b.pattern * b.pattern;
    }
    s.vertices += 3 * uint64_t(plan.ippTriangles);
    s.indices += 3 * uint64_t(plan.ippTriangles);
    return s;
}

const DrawPlan& patternPlan(VulkanSurface::Impl& s, const FrameSettings& frame) {
    if (!drawsPatterns(frame.path))
        throw Failure(Status::Usage,
                      "the surface goes into buffers with the pattern path's points: set "
                      "FrameSettings::path to DrawPath::Patterns or Compute");
    FrameSettings patterns = frame;
    patterns.path = DrawPath::Patterns;
    const DrawPlan& plan = s.planFor(patterns);
    // evaluate.comp addresses the output's floats and indices with 32 bits.
    const VulkanSurface::EvaluateSizes sizes = sizesOf(plan);
    if (sizes.vertices * kEvaluateVertexFloats > UINT32_MAX || sizes.indices > UINT32_MAX)
        throw Failure(Status::Unsupported, "the frame needs " + std::to_string(sizes.vertices) + " vertices and " +
                                               std::to_string(sizes.indices) + " indices; at most " +
                                               std::to_string(UINT32_MAX / kEvaluateVertexFloats) + " and " +
                                               std::to_string(UINT32_MAX) + " go into buffers");
    return plan;
}

}  // namespace

Status VulkanSurface::evaluateSizes(const FrameSettings& frame, EvaluateSizes& out) {
    return guarded("evaluateSizes", [&]() -> Status {
        out = sizesOf(patternPlan(*impl_, frame));
        return Status::ok();
    });
}

Status VulkanSurface::recordEvaluate(VkCommandBuffer cmd, const FrameSettings& frame, VkBuffer vertices,
                                     VkDeviceSize vertexOffset, VkBuffer indices, VkDeviceSize indexOffset,
                                     VkBuffer counts, VkDeviceSize countsOffset, const EvaluateSizes* roomGiven) {
    return guarded("recordEvaluate", [&]() -> Status {
        Impl& s = *impl_;
        VulkanContext::Impl& ctx = s.ctx;
        const DrawPlan& plan = patternPlan(s, frame);
        if (Status st = subdividedFor(s, plan, frame); !st) return st;
        if (!cmd || !vertices || !indices)
            return Status::error(Status::Usage, "recordEvaluate: a null command buffer or buffer");
        if (plan.sorted && !counts)
            return Status::error(Status::Usage,
                                 "recordEvaluate: at screen-space factors the counts are known only on the "
                                 "GPU: pass a `counts` buffer");
        const VkDeviceSize align = ctx.properties.limits.minStorageBufferOffsetAlignment;
        if (vertexOffset % align || indexOffset % align || countsOffset % align)
            return Status::error(Status::Usage,
                                 "recordEvaluate: offsets must be multiples of minStorageBufferOffsetAlignment (" +
                                     std::to_string(align) + ")");
        const EvaluateSizes sizes = sizesOf(plan);
        const VkDeviceSize range = ctx.properties.limits.maxStorageBufferRange;
        // The room bound (never more than the frame's sizes: nothing is written past
        // them); the shader writes within it (evaluate.comp, .length()).
        EvaluateSizes room = sizes;
        if (roomGiven) {
            room.vertices = std::min(room.vertices, roomGiven->vertices);
            room.indices = std::min(room.indices, roomGiven->indices);
        }
        if ((room.vertices == 0 && sizes.vertices > 0) || (room.indices == 0 && sizes.indices > 0))
            return Status::error(Status::Usage, "recordEvaluate: room for no vertices or no indices");
        if (!plan.sorted && (room.vertices < sizes.vertices || room.indices < sizes.indices))
            return Status::error(Status::Usage, "recordEvaluate: room for " + std::to_string(room.vertices) +
                                                    " vertices and " + std::to_string(room.indices) +
                                                    " indices; the frame has " + std::to_string(sizes.vertices) +
                                                    " and " + std::to_string(sizes.indices));
        if (room.vertexBytes() > range || room.indexBytes() > range)
            return Status::error(Status::Unsupported,
                                 "recordEvaluate: room for " + std::to_string(room.vertexBytes()) + " vertex and " +
                                     std::to_string(room.indexBytes()) + " index bytes; the device binds at most " +
                                     std::to_string(range) +
                                     (plan.sorted ? " (give less room: the counts tell what fits)" : ""));
        if (!*s.evaluateSet) s.evaluateSet = s.evaluateOutputs(s.evaluatePool);
        // PLACE (evaluate.comp): 16 bytes until a frame at screen-space factors needs
        // it (2 words, 2 a chunk, 4 a record). Bindings 2 and 4 name it where the
        // dispatches write no counts or PLACE: a buffer that no binding reads.
        const SortRegionSize most = sortRegionSize(s.tables);
        const vk::DeviceSize place =
            plan.sorted ? 8 + 8 * vk::DeviceSize(most.chunks) + 16 * vk::DeviceSize(most.records) : 0;
        if (s.placeBuffer.size < std::max<vk::DeviceSize>(place, 16))
            s.placeBuffer = ctx.createBuffer(std::max<vk::DeviceSize>(place, 16),
                                             vk::BufferUsageFlagBits::eStorageBuffer, MemoryKind::DeviceLocal);
        // An empty frame still binds valid ranges (at least 4 bytes).
        const GpuBuffer& table = ctx.patternTableBuffer();
        const vk::DescriptorBufferInfo unused(*s.placeBuffer.buffer, 0, 16);
        vk::DescriptorBufferInfo infos[5] = {
            {vertices, vertexOffset, std::max<VkDeviceSize>(room.vertexBytes(), 4)},  // evaluate.comp writes within
            {indices, indexOffset, std::max<VkDeviceSize>(room.indexBytes(), 4)},     // these ranges (.length())
            counts ? vk::DescriptorBufferInfo(counts, countsOffset, 8) : unused,
            {*table.buffer, 0, VK_WHOLE_SIZE},
            {*s.placeBuffer.buffer, 0, VK_WHOLE_SIZE}};
        vk::WriteDescriptorSet writes[5];
        for (uint32_t i = 0; i < 5; ++i)
            writes[i] = {*s.evaluateSet, i, 0, 1, vk::DescriptorType::eStorageBuffer, nullptr, &infos[i]};
        ctx.device.updateDescriptorSets(writes, {});

        BorrowedCommandBuffer borrowed(ctx.device, cmd);
        EvaluatePass pass(s, *borrowed, frame, plan, *s.evaluateSet, LT_LAYOUT_APPLICATION, true, false);
        pass.barrier();  // the subdivision's results, then each pass's, are read and (PLACE) rewritten next
        const uint32_t ippCorners = 3 * plan.ippTriangles;
        if (plan.sorted || counts)
            pass.place(plan.sorted ? ippCorners : uint32_t(sizes.vertices),
                       plan.sorted ? ippCorners : uint32_t(sizes.indices));
        if (plan.sorted) pass.sortedRecords();  // the IPPs then follow PLACE's totals
        uint64_t vertex = 0, index = 0;
        for (const DrawBatch& b : plan.batches) {
            pass.patternRecords(b.listOffset, b.firstRecord, b.recordCount, b.pattern, vertex, index);
            vertex += uint64_t(b.recordCount) * patternPoints(b.pattern);
            index += 3 * uint64_t(b.recordCount) * b.pattern * b.pattern;
        }
        pass.ippCorners(0, ippCorners, vertex, index);
        return Status::ok();
    });
}

}  // namespace lt
