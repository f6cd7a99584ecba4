// VulkanSurface::evaluateSizes and recordEvaluate: one frame of the pattern path into
// an application's buffers (vulkan.h; shaders/evaluate.comp has the layout).
#include "surface.h"

#include "lod.h"

#include <algorithm>

namespace lt {
namespace {

uint32_t patternPoints(uint32_t n) { return (n + 1) * (n + 2) / 2; }

// Exact for global and distance factors; at screen-space factors (a sorted plan,
// the uniform factors of the bound F) the most any frame writes: every edge factor
// is at most F's, and a pattern has no more points and triangles than one with
// larger factors (tests/test_patterns.cpp checks that of the pattern library).
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
    if (frame.path != DrawPath::Patterns)
        throw Failure(Status::Usage, "the surface goes into buffers on the pattern path only: set FrameSettings::path "
                                     "to DrawPath::Patterns");
    const DrawPlan& plan = s.planFor(frame);
    // evaluate.comp addresses the output's floats and indices with 32 bits.
    const VulkanSurface::EvaluateSizes sizes = sizesOf(plan);
    if (sizes.vertices * kEvaluateVertexFloats > UINT32_MAX || sizes.indices > UINT32_MAX)
        throw Failure(Status::Unsupported, "the frame needs " + std::to_string(sizes.vertices) + " vertices and " +
                                               std::to_string(sizes.indices) + " indices; at most " +
                                               std::to_string(UINT32_MAX / kEvaluateVertexFloats) + " and " +
                                               std::to_string(UINT32_MAX) + " go into buffers");
    return plan;
}

} // namespace

Status VulkanSurface::evaluateSizes(const FrameSettings& frame, EvaluateSizes& out) {
    return guarded("evaluateSizes", [&]() -> Status {
        out = sizesOf(patternPlan(*impl_, frame));
        return Status::ok();
    });
}

Status VulkanSurface::recordEvaluate(VkCommandBuffer cmd, const FrameSettings& frame, VkBuffer vertices,
                                     VkDeviceSize vertexOffset, VkBuffer indices, VkDeviceSize indexOffset, VkBuffer counts,
                                     VkDeviceSize countsOffset, const EvaluateSizes* roomGiven) {
    return guarded("recordEvaluate", [&]() -> Status {
        Impl& s = *impl_;
        VulkanContext::Impl& ctx = s.ctx;
        const DrawPlan& plan = patternPlan(s, frame);
        if (Status st = subdividedFor(s, plan, frame); !st) return st;
        if (!cmd || !vertices || !indices) return Status::error(Status::Usage, "recordEvaluate: a null command buffer or buffer");
        if (plan.sorted && !counts)
            return Status::error(Status::Usage, "recordEvaluate: at screen-space factors the counts are known only on the "
                                                "GPU: pass a `counts` buffer");
        const VkDeviceSize align = ctx.properties.limits.minStorageBufferOffsetAlignment;
        if (vertexOffset % align || indexOffset % align || countsOffset % align)
            return Status::error(Status::Usage, "recordEvaluate: offsets must be multiples of minStorageBufferOffsetAlignment (" +
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
            return Status::error(Status::Usage, "recordEvaluate: room for " + std::to_string(room.vertices) + " vertices and " +
                                                    std::to_string(room.indices) + " indices; the frame has " +
                                                    std::to_string(sizes.vertices) + " and " + std::to_string(sizes.indices));
        if (room.vertexBytes() > range || room.indexBytes() > range)
            return Status::error(Status::Unsupported, "recordEvaluate: room for " + std::to_string(room.vertexBytes()) +
                                                          " vertex and " + std::to_string(room.indexBytes()) +
                                                          " index bytes; the device binds at most " + std::to_string(range) +
                                                          (plan.sorted ? " (give less room: the counts tell what fits)" : ""));
        Pipelines& pipes = s.pipelines();
        if (!*s.evaluateSet) {
            vk::DescriptorPoolSize size(vk::DescriptorType::eStorageBuffer, 5);
            s.evaluatePool = vk::raii::DescriptorPool(
                ctx.device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, size));
            vk::raii::DescriptorSets sets(ctx.device, vk::DescriptorSetAllocateInfo(*s.evaluatePool, *pipes.evaluateSetLayout));
            s.evaluateSet = std::move(sets[0]);
        }
        // PLACE (evaluate.comp): 16 bytes until a frame at screen-space factors needs
        // it (2 words, 2 a chunk, 4 a record). Bindings 2 and 4 name it where the
        // dispatches write no counts or PLACE: a buffer that no binding reads.
        const SortRegionSize most = sortRegionSize(s.tables);
        const vk::DeviceSize place = plan.sorted ? 8 + 8 * vk::DeviceSize(most.chunks) + 16 * vk::DeviceSize(most.records) : 0;
        if (s.placeBuffer.size < std::max<vk::DeviceSize>(place, 16))
            s.placeBuffer = ctx.createBuffer(std::max<vk::DeviceSize>(place, 16), vk::BufferUsageFlagBits::eStorageBuffer,
                                             MemoryKind::DeviceLocal);
        // An empty frame still binds valid ranges (at least 4 bytes).
        const GpuBuffer& table = ctx.patternTableBuffer();
        const vk::DescriptorBufferInfo unused(*s.placeBuffer.buffer, 0, 16);
        vk::DescriptorBufferInfo infos[5] = {
            {vertices, vertexOffset, std::max<VkDeviceSize>(room.vertexBytes(), 4)},   // evaluate.comp writes within
            {indices, indexOffset, std::max<VkDeviceSize>(room.indexBytes(), 4)},     // these ranges (.length())
            counts ? vk::DescriptorBufferInfo(counts, countsOffset, 8) : unused,
            {*table.buffer, 0, VK_WHOLE_SIZE},
            {*s.placeBuffer.buffer, 0, VK_WHOLE_SIZE}};
        vk::WriteDescriptorSet writes[5];
        for (uint32_t i = 0; i < 5; ++i) writes[i] = {*s.evaluateSet, i, 0, 1, vk::DescriptorType::eStorageBuffer, nullptr, &infos[i]};
        ctx.device.updateDescriptorSets(writes, {});

        BorrowedCommandBuffer borrowed(ctx.device, cmd);
        const vk::raii::CommandBuffer& c = *borrowed;
        // The subdivision's results, then each pass's, are read and (PLACE) rewritten
        // next.
        auto computeBarrier = [&] {
            memoryBarrier(c, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                          vk::PipelineStageFlagBits::eComputeShader,
                          vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
        };
        computeBarrier();
        const vk::PipelineLayout layout = *pipes.evaluateLayout;
        c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, layout, 0, {*s.descriptorSet, *s.evaluateSet}, {});
        PushConstants pc;
        pc.tessFactor = plan.tessFactor;
        pc.flags = (frame.watertight ? LT_FLAG_WATERTIGHT : 0u) | (frame.displace ? LT_FLAG_DISPLACE : 0u);
        if (plan.sorted) {   // the records' patterns as pattern_sort.comp picked them
            pc.flags |= LT_FLAG_LOD_SCREEN;
            std::copy(frame.lod.eye, frame.lod.eye + 3, pc.lod);
            pc.lod[3] = lodScale(frame.lod);
        }
        const bool displace = s.displaceKey(frame);
        auto bind = [&](uint32_t kind) { c.bindPipeline(vk::PipelineBindPoint::eCompute, pipes.evaluate(kind, frame.watertight, displace)); };
        auto push = [&] { c.pushConstants<PushConstants>(layout, kAllStages, 0, pc); };
        const uint64_t maxThreads = uint64_t(ctx.properties.limits.maxComputeWorkGroupCount[0]) * LT_LOCAL_SIZE;
        auto dispatch = [&](uint32_t kind, uint64_t threads) {   // threads <= maxThreads
            bind(kind);
            pc.evaluate[3] = uint32_t(threads);
            push();
            c.dispatch(uint32_t((threads + LT_LOCAL_SIZE - 1) / LT_LOCAL_SIZE), 1, 1);
        };
        const uint32_t ippCorners = 3 * plan.ippTriangles;
        if (plan.sorted) {   // each record's key and the chunks' sizes (evaluate.comp)
            bind(LT_EVALUATE_SORTED_KEYS);
            s.dispatchChunks(c, plan, pc, push);
            computeBarrier();
        }
        if (plan.sorted || counts) {   // the chunks' first outputs and the counts
            pc.evaluate[0] = plan.sorted ? ippCorners : uint32_t(sizes.vertices);
            pc.evaluate[1] = plan.sorted ? ippCorners : uint32_t(sizes.indices);
            pc.evaluate[3] = plan.sorted ? plan.sortChunks : 0;
            bind(LT_EVALUATE_SORTED_SCAN);
            push();
            c.dispatch(1, 1, 1);
        }
        uint64_t vertex = 0, index = 0;   // outputs so far (at screen-space factors, after the patterns')
        if (plan.sorted) {   // where each record's output starts, then a work group per record
            computeBarrier();
            bind(LT_EVALUATE_SORTED_PLACE);
            s.dispatchChunks(c, plan, pc, push);
            computeBarrier();
            bind(LT_EVALUATE_SORTED_RECORDS);
            const uint32_t most = ctx.properties.limits.maxComputeWorkGroupCount[0];
            for (uint64_t first = 0; first < plan.patches; first += most) {
                pc.evaluate[2] = uint32_t(first);
                push();
                c.dispatch(uint32_t(std::min<uint64_t>(most, plan.patches - first)), 1, 1);
            }
        }
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
        for (uint64_t corner = 0; corner < ippCorners; corner += maxThreads) {
            pc.evaluate[0] = uint32_t(vertex + corner);   // corner c's vertex and index are both first + c
            pc.evaluate[1] = uint32_t(index + corner);
            pc.evaluate[2] = uint32_t(corner);            // the dispatch's first IPP corner
            dispatch(LT_EVALUATE_IPPS, std::min(maxThreads, ippCorners - corner));
        }
        return Status::ok();
    });
}

} // namespace lt
