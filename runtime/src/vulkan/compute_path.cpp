// DrawPath::Compute (see compute_path.h and vulkan.h's batches).
#include "compute_path.h"

#include "evaluate_pass.h"

#include <algorithm>

namespace lt {
namespace {

constexpr vk::DeviceSize kAlign = 256;  // the largest minStorageBufferOffsetAlignment Vulkan allows
vk::DeviceSize aligned(vk::DeviceSize bytes) { return (bytes + kAlign - 1) / kAlign * kAlign; }

}  // namespace

std::vector<ComputeBatch> planComputeBatches(const DrawPlan& plan, uint32_t vertices, uint32_t indices) {
    std::vector<ComputeBatch> out(1);
    for (const DrawBatch& b : plan.batches) {
        const uint32_t n = b.pattern, points = patternPoints(n), triangles = n * n;
        for (uint32_t r = 0; r < b.recordCount;) {
            ComputeBatch& batch = out.back();
            const uint32_t fit = std::min(
                {b.recordCount - r, (vertices - batch.vertices) / points, (indices - batch.indices) / (3 * triangles)});
            if (fit == 0) {  // full: the record goes in the next batch
                out.emplace_back();
                continue;
            }
            ComputeSegment* last = batch.segments.empty() ? nullptr : &batch.segments.back();
            if (last && last->listOffset == b.listOffset && last->pattern == n &&
                last->first + last->records == b.firstRecord + r)
                last->records += fit;  // the plan's draws of one list, joined again
            else
                batch.segments.push_back({b.listOffset, b.firstRecord + r, fit, n});
            batch.vertices += fit * points;
            batch.indices += 3 * fit * triangles;
            r += fit;
        }
    }
    for (uint32_t t = 0; t < plan.ippTriangles;) {  // IPP triangles: 3 vertices and 3 indices each
        ComputeBatch& batch = out.back();
        const uint32_t fit =
            std::min({plan.ippTriangles - t, (vertices - batch.vertices) / 3, (indices - batch.indices) / 3});
        if (fit == 0) {
            out.emplace_back();
            continue;
        }
        if (batch.corners == 0) batch.firstCorner = 3 * t;
        batch.corners += 3 * fit;
        batch.vertices += 3 * fit;
        batch.indices += 3 * fit;
        t += fit;
    }
    return out;
}

// The buffer, its descriptor sets and PLACE for `frame`'s vertex words and bytes,
// made or remade as they change.
VulkanSurface::Impl::ComputeState& VulkanSurface::Impl::computeFor(const FrameSettings& frame) {
    const uint32_t words = LT_DRAW_WORDS(uint32_t(frame.tangents), uint32_t(frame.attributes));
    const uint32_t bytes = frame.computeBytes ? frame.computeBytes : kDefaultComputeBytes;
    const uint32_t vertices = computeBatchVertices(bytes, words);
    if (vertices < 2 * LT_MAX_RECORD_VERTICES)
        throw Failure(Status::Usage, "FrameSettings::computeBytes " + std::to_string(bytes) + " holds " +
                                         std::to_string(vertices) + " vertices; a batch needs room for at least " +
                                         std::to_string(2 * LT_MAX_RECORD_VERTICES));
    if (compute && compute->bytes == bytes && compute->words == words) return *compute;
    auto state = std::make_unique<ComputeState>();
    ComputeState& c = *state;
    c.bytes = bytes;
    c.words = words;
    c.vertices = vertices;
    const vk::DeviceSize vertexBytes = vk::DeviceSize(vertices) * words * 4,
                         indexBytes = vk::DeviceSize(6) * vertices * 4;
    const vk::DeviceSize range = ctx.properties.limits.maxStorageBufferRange;
    if (vertexBytes > range || indexBytes > range)
        throw Failure(Status::Unsupported, "FrameSettings::computeBytes " + std::to_string(bytes) +
                                               " needs storage buffer ranges beyond the device's " +
                                               std::to_string(range));
    // The indices in a buffer of their own, bound at 0: lavapipe 22.3's indexed
    // indirect draws read an index buffer bound at an offset from its start (seen here).
    c.vertexBuffer = ctx.createBuffer(vertexBytes, vk::BufferUsageFlagBits::eStorageBuffer, MemoryKind::DeviceLocal);
    c.indexBuffer =
        ctx.createBuffer(indexBytes, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eIndexBuffer,
                         MemoryKind::DeviceLocal);
    // PLACE (evaluate.comp) for the largest frame at screen-space factors, then the
    // batch table and commands for as many batches as its largest output needs.
    const SortRegionSize most = sortRegionSize(tables);
    uint64_t largest = uint64_t(most.records) * LT_MAX_RECORD_VERTICES;
    for (const GpuLevelInfo& level : tables.levels)
        largest = std::max<uint64_t>(largest, 3 * uint64_t(level.irregular));
    c.maxBatches = uint32_t(std::min<uint64_t>(largest / (vertices - LT_MAX_RECORD_VERTICES) + 2, UINT32_MAX / 64));
    c.batchTable = 2 + 2 * most.chunks + 4 * most.records;
    c.countsOffset = aligned(
        vk::DeviceSize(c.batchTable + LT_BATCH_WORDS * (c.maxBatches + 1) + LT_BATCH_COMMAND_WORDS * c.maxBatches) * 4);
    c.place = ctx.createBuffer(c.countsOffset + 8,
                               vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc,
                               MemoryKind::DeviceLocal);
    // The commands, copied out of PLACE for the indirect reads: every evaluate.comp
    // dispatch may write PLACE (its binding is writable), so the commands must not
    // stay there while batches are evaluated.
    c.commands = ctx.createBuffer(vk::DeviceSize(LT_BATCH_COMMAND_WORDS) * 4 * c.maxBatches,
                                  vk::BufferUsageFlagBits::eIndirectBuffer | vk::BufferUsageFlagBits::eTransferDst,
                                  MemoryKind::DeviceLocal);

    const Pipelines& pipes = pipelines();
    const vk::DescriptorPoolSize size(vk::DescriptorType::eStorageBuffer, 9);
    c.pool = vk::raii::DescriptorPool(
        ctx.device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 2, size));
    const vk::DescriptorSetLayout layouts[2] = {*pipes.setLayout, *pipes.evaluateSetLayout};
    vk::raii::DescriptorSets sets(ctx.device, vk::DescriptorSetAllocateInfo(*c.pool, layouts));
    c.drawSet = std::move(sets[0]);
    c.outputs = std::move(sets[1]);
    const vk::DescriptorBufferInfo vertexRange(*c.vertexBuffer.buffer, 0, VK_WHOLE_SIZE);
    writeSurfaceSet(*c.drawSet, vertexRange);
    const GpuBuffer& table = ctx.patternTableBuffer();
    const vk::DescriptorBufferInfo infos[5] = {vertexRange,
                                               {*c.indexBuffer.buffer, 0, VK_WHOLE_SIZE},
                                               {*c.place.buffer, c.countsOffset, 8},
                                               {*table.buffer, 0, VK_WHOLE_SIZE},
                                               {*c.place.buffer, 0, VK_WHOLE_SIZE}};
    vk::WriteDescriptorSet writes[5];
    for (uint32_t i = 0; i < 5; ++i)
        writes[i] = {*c.outputs, i, 0, 1, vk::DescriptorType::eStorageBuffer, nullptr, &infos[i]};
    ctx.device.updateDescriptorSets(writes, {});
    compute = std::move(state);
    return *compute;
}

const std::vector<ComputeBatch>& VulkanSurface::Impl::ComputeState::batchesOf(const DrawPlan& plan) {
    if (plannedFor != plan.tessFactor || plannedDepth != plan.depth || planned.empty()) {
        planned = planComputeBatches(plan, vertices, 6 * vertices);
        plannedFor = plan.tessFactor;
        plannedDepth = plan.depth;
    }
    return planned;
}

uint32_t VulkanSurface::Impl::ComputeState::batchCount(const DrawPlan& plan) {
    if (!plan.sorted) return uint32_t(batchesOf(plan).size());
    // Screen-space factors: enough batches for the bound F's output (evaluate.comp
    // starts a batch every `vertices - LT_MAX_RECORD_VERTICES` vertices).
    const uint64_t bound = plan.points + 3 * uint64_t(plan.ippTriangles);
    return uint32_t(std::min<uint64_t>(bound / (vertices - LT_MAX_RECORD_VERTICES) + 1, maxBatches));
}

vk::DeviceSize VulkanSurface::Impl::ComputeState::commandsInPlace(uint32_t batches) const {
    return vk::DeviceSize(batchTable + LT_BATCH_WORDS * (batches + 1)) * 4;
}

// Screen-space factors: every record's pattern and place (evaluate.comp's KEYS, SCAN,
// PLACE), then the batches that cut the frame (BATCHES) and their commands (ARGS).
void VulkanSurface::Impl::recordComputePlan(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan,
                                            const FrameSettings& frame) {
    ComputeState& c = computeFor(frame);
    EvaluatePass pass(*this, cmd, frame, plan, *c.outputs, LT_LAYOUT_DRAW, frame.tangents, frame.attributes);
    pass.barrier();
    const uint32_t ippCorners = 3 * plan.ippTriangles;
    pass.place(ippCorners, ippCorners);
    const uint32_t batches = c.batchCount(plan);
    pass.pc.base = c.batchTable;
    pass.pc.evaluate[0] = uint32_t(plan.patches);
    pass.pc.evaluate[1] = plan.ippTriangles;
    pass.pc.evaluate[2] = c.vertices - LT_MAX_RECORD_VERTICES;
    pass.pc.evaluate[3] = batches;
    pass.bind(LT_EVALUATE_BATCHES);
    const uint64_t items = std::max<uint64_t>(plan.patches + plan.ippTriangles, 1);
    for (uint64_t first = 0; first < items; first += pass.maxThreads()) {
        pass.pc.level = uint32_t(first);
        pass.push();
        cmd.dispatch(uint32_t((std::min(pass.maxThreads(), items - first) + LT_LOCAL_SIZE - 1) / LT_LOCAL_SIZE), 1, 1);
    }
    pass.barrier();
    pass.bind(LT_EVALUATE_BATCH_ARGS);
    pass.push();
    cmd.dispatch((batches + LT_LOCAL_SIZE - 1) / LT_LOCAL_SIZE, 1, 1);
    memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                  vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer,
                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eTransferRead);
    cmd.copyBuffer(*c.place.buffer, *c.commands.buffer,
                   vk::BufferCopy(c.commandsInPlace(batches), 0, vk::DeviceSize(LT_BATCH_COMMAND_WORDS) * 4 * batches));
    memoryBarrier(cmd, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
                  vk::PipelineStageFlagBits::eDrawIndirect, vk::AccessFlagBits::eIndirectCommandRead);
    c.recorded.reset();
}

void VulkanSurface::Impl::recordComputeBatch(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan,
                                             const FrameSettings& frame, uint32_t k) {
    ComputeState& c = computeFor(frame);
    const uint32_t batches = c.batchCount(plan);
    if (k >= batches)
        throw Failure(Status::Usage,
                      "batch " + std::to_string(k) + " of a frame of " + std::to_string(batches) + " (drawBatches)");
    // The draw before read the buffer (vertices in the vertex stage, indices in vertex
    // input): this batch overwrites it after that; and it reads what the subdivision
    // and limit passes wrote.
    memoryBarrier(
        cmd, ctx.drawStages() | vk::PipelineStageFlagBits::eVertexInput | vk::PipelineStageFlagBits::eComputeShader,
        vk::AccessFlagBits::eShaderWrite, vk::PipelineStageFlagBits::eComputeShader,
        vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
    EvaluatePass pass(*this, cmd, frame, plan, *c.outputs, LT_LAYOUT_DRAW, frame.tangents, frame.attributes);
    if (plan.sorted) {  // indirect, as BATCH_ARGS wrote
        pass.pc.base = c.batchTable;
        pass.pc.evaluate[0] = uint32_t(plan.patches);
        pass.pc.evaluate[1] = plan.ippTriangles;
        pass.pc.evaluate[2] = k;
        pass.pc.evaluate[3] = batches;
        pass.pc.level = plan.ippLevel;
        pass.bind(LT_EVALUATE_BATCH_POINTS);
        pass.push();
        cmd.dispatchIndirect(*c.commands.buffer, c.commandBytes(k));
        pass.bind(LT_EVALUATE_BATCH_INDICES);
        cmd.dispatchIndirect(*c.commands.buffer, c.commandBytes(k) + 12);
    } else {
        const ComputeBatch& batch = c.batchesOf(plan)[k];
        uint64_t vertex = 0, index = 0;
        for (const ComputeSegment& seg : batch.segments) {
            pass.patternRecords(seg.listOffset, seg.first, seg.records, seg.pattern, vertex, index);
            vertex += uint64_t(seg.records) * patternPoints(seg.pattern);
            index += 3 * uint64_t(seg.records) * seg.pattern * seg.pattern;
        }
        pass.ippCorners(batch.firstCorner, batch.corners, vertex, index);
    }
    memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                  vk::PipelineStageFlagBits::eVertexShader | vk::PipelineStageFlagBits::eVertexInput,
                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eIndexRead);
    c.recorded = k;
}

void VulkanSurface::Impl::recordComputeDraw(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan,
                                            const GraphicsKey& key, const FrameSettings& frame, const PushConstants& pc,
                                            const CaptureTarget* capture, const SurfacePipelines* app) {
    ComputeState& c = computeFor(frame);
    if (!c.recorded)
        throw Failure(Status::Usage,
                      "DrawPath::Compute draws the batch of the last recordBatch: none since recordSubdivision");
    const uint32_t k = *c.recorded;
    const vk::PipelineLayout layout = app ? vk::PipelineLayout(app->layout) : *pipelines().layout;
    GraphicsKey computeKey = key;
    computeKey.path = DrawPath::Compute;
    computeKey.tangent = frame.tangents;
    computeKey.attributes = frame.attributes;
    cmd.bindPipeline(vk::PipelineBindPoint::eGraphics,
                     app ? vk::Pipeline(app->patches) : pipelines().patches(computeKey));
    cmd.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 0, *c.drawSet, {});
    cmd.pushConstants<PushConstants>(layout, kAllStages, 0, pc);
    cmd.bindIndexBuffer(*c.indexBuffer.buffer, 0, vk::IndexType::eUint32);
    if (capture) {  // batch after batch into one transform feedback buffer, resumed at its counter
        cmd.bindTransformFeedbackBuffersEXT(0, capture->buffer, vk::DeviceSize(0), capture->size);
        if (k == 0)
            cmd.beginTransformFeedbackEXT(0, {}, {});
        else
            cmd.beginTransformFeedbackEXT(0, capture->counters, vk::DeviceSize(0));
    }
    if (plan.sorted)
        cmd.drawIndexedIndirect(*c.commands.buffer, c.commandBytes(k) + 24, 1, LT_BATCH_COMMAND_WORDS * 4);
    else if (const uint32_t indices = c.batchesOf(plan)[k].indices; indices > 0)
        cmd.drawIndexed(indices, 1, 0, 0, 0);
    if (capture) cmd.endTransformFeedbackEXT(0, capture->counters, vk::DeviceSize(0));
}

Status VulkanSurface::drawBatches(const FrameSettings& frame, uint32_t& count) {
    return guarded("drawBatches", [&]() -> Status {
        const FrameSettings f = impl_->resolved(frame);
        const DrawPlan& plan = impl_->planFor(f);
        count = f.path == DrawPath::Compute ? impl_->computeFor(f).batchCount(plan) : 1;
        return Status::ok();
    });
}

Status VulkanSurface::recordBatch(VkCommandBuffer cmd, const FrameSettings& frame, uint32_t batch) {
    return guarded("recordBatch", [&]() -> Status {
        const FrameSettings f = impl_->resolved(frame);
        const DrawPlan& plan = impl_->planFor(f);
        if (Status st = subdividedFor(*impl_, plan, f); !st) return st;
        if (!cmd) return Status::error(Status::Usage, "null command buffer");
        if (f.path != DrawPath::Compute) {
            if (batch != 0) return Status::error(Status::Usage, "batch " + std::to_string(batch) + " of a frame of 1");
            return Status::ok();
        }
        BorrowedCommandBuffer borrowed(impl_->ctx.device, cmd);
        impl_->recordComputeBatch(*borrowed, plan, f, batch);
        return Status::ok();
    });
}

}  // namespace lt
