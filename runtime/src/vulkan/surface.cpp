// VulkanSurface: upload, per-frame compute and draws (see vulkan.h, surface.h).
#include "surface.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace lt {
namespace {

constexpr vk::BufferUsageFlags kStorage = vk::BufferUsageFlagBits::eStorageBuffer |
                                          vk::BufferUsageFlagBits::eTransferDst | vk::BufferUsageFlagBits::eTransferSrc;

// One thread per item, LT_LOCAL_SIZE a group, split into dispatches of at most
// maxComputeWorkGroupCount[0] groups (push constant `base` is the first item).
void dispatchThreads(const vk::raii::CommandBuffer& cmd, const Pipelines& pipes, PushConstants pc, uint32_t count,
                     uint32_t maxGroups) {
    uint64_t perDispatch = uint64_t(maxGroups) * LT_LOCAL_SIZE;
    for (uint64_t base = 0; base < count; base += perDispatch) {
        uint64_t items = std::min<uint64_t>(perDispatch, count - base);
        pc.base = uint32_t(base);
        pipes.push(cmd, pc);
        cmd.dispatch(uint32_t((items + LT_LOCAL_SIZE - 1) / LT_LOCAL_SIZE), 1, 1);
    }
}

}  // namespace

DrawStats drawStats(const DrawPlan& plan, bool exact) {
    DrawStats s;
    s.tessFactor = plan.tessFactor;
    s.exact = exact;
    s.depth = plan.depth;
    s.drawCalls = uint32_t(plan.sorted ? LT_PATTERN_KEYS : plan.batches.size()) + (plan.ippTriangles > 0 ? 1 : 0);
    s.patches = plan.patches;
    s.points = plan.points;
    s.triangles = plan.triangles();
    s.path = plan.path;
    return s;
}

uint32_t VulkanSurface::Impl::vertexCountUpTo(uint32_t depth) const {
    return depth + 1 < tables.levels.size() ? tables.levels[depth + 1].firstVertex : tables.totalVertices;
}

void VulkanSurface::Impl::checkFactor(float tessFactor) const {
    if (!(tessFactor >= 1.0f) || !std::isfinite(tessFactor))
        throw Failure(Status::Usage, "the tessellation factor must be a finite number >= 1");
}

GraphicsKey VulkanSurface::Impl::renderKey(vk::Format color, vk::Format depth, const FrameSettings& frame) const {
    if (frame.wireframe && !ctx.fillModeNonSolid)
        throw Failure(Status::Unsupported, "wireframe needs the fillModeNonSolid feature");
    return GraphicsKey{color, depth,           frame.spacing,    frame.path,
                       false, frame.wireframe, frame.watertight, displaceKey(frame)};
}

bool VulkanSurface::Impl::displaceKey(const FrameSettings& frame) const {
    return (frame.displace && tables.displaced) || (frame.watertight && tables.smoothCreaseRoots);
}

float VulkanSurface::Impl::factorFor(const FrameSettings& frame) const {
    const Lod& lod = frame.lod;
    if (lod.mode != LodMode::Global) {
        float scale = lodScale(lod);
        if (!(scale > 0.0f) || !std::isfinite(scale) || !std::isfinite(lod.eye[0] + lod.eye[1] + lod.eye[2]))
            throw Failure(Status::Usage,
                          "level of detail needs a finite eye and positive pixelsPerUnit and pixelsPerEdge");
    }
    float f = lodTessFactor(control.data(), faces, maxDepth, flatAtMaxDepth, lod, frame.tessFactor);
    checkFactor(f);
    return f;
}

const DrawPlan& VulkanSurface::Impl::planFor(const FrameSettings& frame) {
    float f = factorFor(frame);
    uint32_t maxPoints = frame.maxPointsPerDraw ? frame.maxPointsPerDraw : kDefaultMaxPointsPerDraw;
    if (frame.path == DrawPath::Auto) throw Failure(Status::Internal, "an unresolved DrawPath::Auto frame");
    if (frame.path == DrawPath::Tessellator && !ctx.tessellation)
        throw Failure(Status::Unsupported,
                      "the device has no tessellation shaders enabled: draw with DrawPath::Patterns");
    // DrawPath::Compute evaluates the pattern path's plan (compute_path.h).
    if (drawsPatterns(frame.path) && frame.lod.mode == LodMode::Screen) {
        if (frame.path == DrawPath::Patterns && !ctx.drawIndirectFirstInstance)
            throw Failure(Status::Unsupported,
                          "screen-space factors on the pattern path draw indirect with a first "
                          "instance: they need the drawIndirectFirstInstance feature");
        if (!plan || !plan->sorted || plan->tessFactor != f) plan = planSortedPatternDraws(tables, depthFor(f), f);
        return *plan;
    }
    if (drawsPatterns(frame.path)) {
        if (!plan || plan->path != DrawPath::Patterns || plan->sorted || plan->tessFactor != f ||
            plan->maxPointsPerDraw != maxPoints)
            plan = planPatternDraws(tables, depthFor(f), f, maxPoints);
        return *plan;
    }
    if (!plan || plan->path != frame.path || plan->sorted || plan->tessFactor != f || plan->spacing != frame.spacing ||
        plan->maxPointsPerDraw != maxPoints)
        plan = planDraws(tables, depthFor(f), f, frame.spacing, maxPoints);
    return *plan;
}

void VulkanSurface::Impl::recordCompute(const vk::raii::CommandBuffer& cmd, uint32_t depth, bool watertight,
                                        vk::QueryPool timestamps) {
    const Pipelines& pipes = pipelines();
    sortedFor.reset();  // recordSort follows where the frame needs it
    if (timestamps) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, timestamps, kTsStart);
    // Earlier draws and passes of this surface read what we overwrite: wait for them.
    memoryBarrier(cmd,
                  ctx.drawStages() | vk::PipelineStageFlagBits::eComputeShader |
                      vk::PipelineStageFlagBits::eDrawIndirect | vk::PipelineStageFlagBits::eVertexInput,
                  {}, vk::PipelineStageFlagBits::eTransfer | vk::PipelineStageFlagBits::eComputeShader, {});
    const vk::DeviceSize controlBytes = vk::DeviceSize(tables.controlVertices) * 12;
    if (deviceControl)  // the application's buffer (setControlPoints(VkBuffer))
        cmd.copyBuffer(deviceControl, *vertexBuffer.buffer, vk::BufferCopy(deviceControlOffset, 0, controlBytes));
    else
        cmd.copyBuffer(*controlUpload.buffer, *vertexBuffer.buffer, vk::BufferCopy(0, 0, controlBytes));
    if (tables.editCount)  // the edit values into the tables' EDIT_VALUES words
        cmd.copyBuffer(*editUpload.buffer, *tableBuffer.buffer,
                       vk::BufferCopy(0, vk::DeviceSize(tables.editValues) * 4, vk::DeviceSize(tables.editCount) * 12));
    memoryBarrier(cmd, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
                  vk::PipelineStageFlagBits::eComputeShader | ctx.drawStages(),
                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);

    cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipes.layout, 0, *descriptorSet, {});
    uint32_t maxGroups = ctx.properties.limits.maxComputeWorkGroupCount[0];
    PushConstants pc;
    // Per level (level 0: the copied control points only):
    //   vertex points | edge points --> [edits --> ] level l+1
    // where --> is a compute-to-compute (and vertex-pipeline) barrier.
    for (uint32_t l = 0; l <= depth; ++l) {
        const GpuLevelInfo& level = tables.levels[l];
        pc.level = l;
        if (l > 0) {
            // Vertex and edge points of one level read only the level above: no barrier between.
            cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipes.vertexPoints);
            dispatchThreads(cmd, pipes, pc, level.vertexPoints, maxGroups);
            cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipes.edgePoints);
            dispatchThreads(cmd, pipes, pc, level.edgePoints, maxGroups);
            // The edit pass reads and rewrites points just written.
            vk::AccessFlags next = vk::AccessFlagBits::eShaderRead;
            if (level.editedVertices) next |= vk::AccessFlagBits::eShaderWrite;
            memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                          vk::PipelineStageFlagBits::eComputeShader | ctx.drawStages(), next);
        }
        if (level.editedVertices) {
            cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipes.edits);
            dispatchThreads(cmd, pipes, pc, level.editedVertices, maxGroups);
            memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                          vk::PipelineStageFlagBits::eComputeShader | ctx.drawStages(),
                          vk::AccessFlagBits::eShaderRead);
        }
    }
    if (timestamps) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, timestamps, kTsSubdivided);
    pc.level = depth;
    pc.flags = watertight ? LT_FLAG_WATERTIGHT : 0u;
    if (watertight) {
        // The watertight pass (gpu_layout.h): three kinds of sources, each written to
        // its own floats of the limit buffer, so no barrier between them; the limit
        // pass takes its stencils' shared points from them:
        //   points | normals | roots --> limit --> draws
        cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipes.watertightPoints);
        dispatchThreads(cmd, pipes, pc, tables.levels[depth].watertightPoints, maxGroups);
        cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipes.watertightNormals);
        dispatchThreads(cmd, pipes, pc, tables.levels[depth].watertightNormals, maxGroups);
        cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipes.watertightRoots);
        dispatchThreads(cmd, pipes, pc, tables.levels[depth].watertightRoots, maxGroups);
        memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                      vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderRead);
    }
    cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipes.limit);
    dispatchThreads(cmd, pipes, pc, tables.levels[depth].stencils, maxGroups);
    memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                  ctx.drawStages() | vk::PipelineStageFlagBits::eTransfer,
                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eTransferRead);
    if (timestamps) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, timestamps, kTsLimit);
    subdividedDepth = depth;
    subdividedWatertight = watertight;
}

uint32_t VulkanSurface::Impl::dispatchChunks(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan,
                                             PushConstants& pc, const std::function<void()>& push) const {
    uint32_t chunk = 0, records = 0;
    for (uint32_t l = 0; l <= plan.depth; ++l) {
        const RecordList& list = drawnList(tables, l, plan.depth);
        const uint32_t n = uint32_t(list.records.size()), groups = (n + LT_SORT_CHUNK - 1) / LT_SORT_CHUNK;
        if (groups == 0) continue;
        pc.base = list.offset;
        pc.evaluate[0] = n;
        pc.evaluate[1] = chunk;
        pc.evaluate[2] = records;
        push();
        cmd.dispatch(groups, 1, 1);
        chunk += groups;
        records += n;
    }
    return chunk;
}

void VulkanSurface::Impl::recordSort(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan,
                                     const FrameSettings& frame) {
    const Pipelines& pipes = pipelines();
    auto computeBarrier = [&] {
        memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                      vk::PipelineStageFlagBits::eComputeShader,
                      vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
    };
    computeBarrier();  // the passes before read the tables this one writes (the sort region)
    PushConstants pc;
    pc.tessFactor = plan.tessFactor;
    pc.flags = LT_FLAG_LOD_SCREEN;
    std::copy(frame.lod.eye, frame.lod.eye + 3, pc.lod);
    pc.lod[3] = lodScale(frame.lod);
    cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipes.patternSort);
    cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipes.layout, 0, *descriptorSet, {});
    // COUNT and SCATTER: a work group per chunk of each drawn list (pattern_sort.comp).
    auto chunks = [&](uint32_t pass) {
        pc.level = pass;
        return dispatchChunks(cmd, plan, pc, [&] { pipes.push(cmd, pc); });
    };
    const uint32_t total = chunks(LT_SORT_COUNT);
    computeBarrier();
    pc.level = LT_SORT_SCAN;
    pc.evaluate[3] = total;
    pipes.push(cmd, pc);
    cmd.dispatch(1, 1, 1);
    computeBarrier();
    chunks(LT_SORT_SCATTER);
    memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                  vk::PipelineStageFlagBits::eDrawIndirect | ctx.drawStages(),
                  vk::AccessFlagBits::eIndirectCommandRead | vk::AccessFlagBits::eShaderRead);
    markSorted(plan, frame);
}

void VulkanSurface::Impl::markSorted(const DrawPlan& plan, const FrameSettings& frame) {
    SortedFor sorted;
    sorted.tessFactor = plan.tessFactor;
    std::copy(frame.lod.eye, frame.lod.eye + 3, sorted.eye);
    sorted.scale = lodScale(frame.lod);
    sortedFor = sorted;
}

PushConstants VulkanSurface::Impl::drawConstants(const DrawPlan& plan, const GraphicsKey& key,
                                                 const FrameSettings& frame) const {
    PushConstants pc;
    std::copy(frame.mvp, frame.mvp + 16, pc.mvp);
    std::copy(frame.light, frame.light + 3, pc.light);
    pc.tessFactor = plan.tessFactor;
    pc.flags = frame.coloring == Coloring::Levels      ? LT_FLAG_COLOR_LEVELS
               : frame.coloring == Coloring::Texcoords ? LT_FLAG_COLOR_TEXCOORDS
                                                       : 0u;
    if (frame.watertight) pc.flags |= LT_FLAG_WATERTIGHT;
    if (frame.displace) pc.flags |= LT_FLAG_DISPLACE;
    if (frame.displace && tables.displaced) pc.flags |= LT_FLAG_FACETED;
    if (key.spacing == Spacing::FractionalOdd) pc.flags |= LT_FLAG_FRACTIONAL_ODD;
    if (frame.lod.mode == LodMode::Screen) {
        pc.flags |= LT_FLAG_LOD_SCREEN;
        std::copy(frame.lod.eye, frame.lod.eye + 3, pc.lod);
        pc.lod[3] = lodScale(frame.lod);
    }
    return pc;
}

void VulkanSurface::Impl::recordDraws(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan, const GraphicsKey& key,
                                      const FrameSettings& frame, const CaptureTarget* capture,
                                      const SurfacePipelines* app) {
    PushConstants pc = drawConstants(plan, key, frame);
    if (frame.path == DrawPath::Compute) return recordComputeDraw(cmd, plan, key, frame, pc, capture, app);
    Pipelines& pipes = pipelines();
    const vk::PipelineLayout layout = app ? vk::PipelineLayout(app->layout) : *pipes.layout;
    auto push = [&](const PushConstants& pc) { cmd.pushConstants<PushConstants>(layout, kAllStages, 0, pc); };
    vk::DeviceSize tessBytes = plan.tessTriangles * 3 * LT_CAPTURE_STRIDE;

    cmd.bindPipeline(vk::PipelineBindPoint::eGraphics, app ? vk::Pipeline(app->patches) : pipes.patches(key));
    cmd.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, layout, 0, *descriptorSet, {});
    if (capture) {
        cmd.bindTransformFeedbackBuffersEXT(0, capture->buffer, vk::DeviceSize(0), capture->size);
        cmd.beginTransformFeedbackEXT(0, {}, {});
    }
    const PatternLibrary& library = patternLibrary();
    if (plan.path == DrawPath::Patterns)
        cmd.bindIndexBuffer(*ctx.patternIndices.buffer, 0, vk::IndexType::eUint16);  // made by create()
    if (plan.sorted) {  // one indirect draw per pattern of the sort region (gpu_layout.h)
        pc.base = sortRecords;
        push(pc);
        const vk::DeviceSize stride = LT_SORT_COMMAND_WORDS * 4, commands = vk::DeviceSize(sortCommands) * 4;
        if (ctx.multiDrawIndirect)
            cmd.drawIndexedIndirect(*tableBuffer.buffer, commands, LT_PATTERN_KEYS, uint32_t(stride));
        else
            for (uint32_t k = 0; k < LT_PATTERN_KEYS; ++k)
                cmd.drawIndexedIndirect(*tableBuffer.buffer, commands + k * stride, 1, uint32_t(stride));
    }
    uint32_t pushedBase = LT_NONE;
    for (const DrawBatch& batch : plan.batches) {
        if (batch.listOffset != pushedBase) {
            pc.base = pushedBase = batch.listOffset;
            push(pc);
        }
        if (batch.pattern) {  // instances of pattern N: records [first, first + count) of the list
            const uint32_t e[3] = {batch.pattern, batch.pattern, batch.pattern}, k = patternKey(e);
            cmd.drawIndexed(library.count[k], batch.recordCount, library.first[k], 0, batch.firstRecord);
        } else {
            cmd.draw(12 * batch.recordCount, 1, 12 * batch.firstRecord, 0);
        }
    }
    if (capture) cmd.endTransformFeedbackEXT(0, capture->counters, vk::DeviceSize(0));
    if (plan.ippTriangles == 0 && !capture) return;

    cmd.bindPipeline(vk::PipelineBindPoint::eGraphics, app ? vk::Pipeline(app->ipps) : pipes.ipps(key));
    pc.level = plan.ippLevel;
    push(pc);
    if (capture) {
        cmd.bindTransformFeedbackBuffersEXT(0, capture->buffer, tessBytes, capture->size - tessBytes);
        cmd.beginTransformFeedbackEXT(0, {}, {});
    }
    if (plan.ippTriangles > 0) cmd.draw(3 * plan.ippTriangles, 1, 0, 0);
    if (capture) cmd.endTransformFeedbackEXT(0, capture->counters, vk::DeviceSize(4));
}

VulkanSurface::VulkanSurface(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
VulkanSurface::~VulkanSurface() = default;

Status VulkanSurface::create(VulkanContext& context, const Asset& asset, std::unique_ptr<VulkanSurface>& out) {
    return guarded("Vulkan upload", [&]() -> Status {
        VulkanContext::Impl& ctx = VulkanAccess::context(context);
        auto impl = std::make_unique<Impl>(ctx);
        Status st = buildGpuTables(asset, impl->tables);
        if (!st) return st;
        impl->maxDepth = asset.maxDepth();
        impl->flatAtMaxDepth = lt::flatAtMaxDepth(asset);
        impl->control = asset.positions;
        impl->faces = asset.faces;
        impl->texcoords = !asset.faceUVs.empty();
        impl->texcoords1 = !asset.faceUV1s.empty();
        impl->colors = !asset.faceColors.empty();

        GpuTables& t = impl->tables;
        vk::DeviceSize tableBytes = vk::DeviceSize(t.words.size()) * 4;
        vk::DeviceSize vertexBytes = vk::DeviceSize(t.totalVertices) * 12;
        vk::DeviceSize limitBytes = (vk::DeviceSize(t.maxStencils) * LT_LIMIT_FLOATS + t.watertightResultFloats) * 4;
        vk::DeviceSize range = ctx.properties.limits.maxStorageBufferRange;
        if (std::max({tableBytes, vertexBytes, limitBytes}) > range)
            return Status::error(Status::Unsupported,
                                 "the asset needs a storage buffer of " +
                                     std::to_string(std::max({tableBytes, vertexBytes, limitBytes})) +
                                     " bytes; the device allows " + std::to_string(range));
        impl->tableBuffer =
            ctx.createBuffer(tableBytes, kStorage | vk::BufferUsageFlagBits::eIndirectBuffer, MemoryKind::DeviceLocal);
        impl->vertexBuffer = ctx.createBuffer(vertexBytes, kStorage, MemoryKind::DeviceLocal);
        impl->limitBuffer = ctx.createBuffer(limitBytes, kStorage, MemoryKind::DeviceLocal);
        impl->controlUpload = ctx.createBuffer(vk::DeviceSize(t.controlVertices) * 12,
                                               vk::BufferUsageFlagBits::eTransferSrc, MemoryKind::HostVisible);
        ctx.upload(impl->tableBuffer, t.words.data(), tableBytes);
        ctx.patternIndexBuffer();  // the context's, on its first surface: no upload while recording a frame
        ctx.patternTableBuffer();
        impl->sortCommands = t.words[LT_H_SORT];
        impl->sortRecords = t.words[LT_H_SORT_RECORDS];
        t.words = {};  // the GPU has them; keep only level infos and record lists
        std::memcpy(impl->controlUpload.mapped, asset.positions.data(), asset.positions.size() * sizeof(float));
        if (t.editCount) {
            impl->editUpload = ctx.createBuffer(vk::DeviceSize(t.editCount) * 12, vk::BufferUsageFlagBits::eTransferSrc,
                                                MemoryKind::HostVisible);
            std::vector<float> values = bakedEditValues(asset);
            std::memcpy(impl->editUpload.mapped, values.data(), values.size() * sizeof(float));
        }

        vk::DescriptorPoolSize size(vk::DescriptorType::eStorageBuffer, 4);
        impl->descriptorPool = vk::raii::DescriptorPool(
            ctx.device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, size));
        vk::DescriptorSetLayout layout = *ctx.pipelines->setLayout;
        vk::raii::DescriptorSets sets(ctx.device, vk::DescriptorSetAllocateInfo(*impl->descriptorPool, layout));
        impl->descriptorSet = std::move(sets[0]);
        // LT_BINDING_DRAW is DrawPath::Compute's (its own set 0): a placeholder here.
        impl->writeSurfaceSet(*impl->descriptorSet,
                              vk::DescriptorBufferInfo(*impl->limitBuffer.buffer, 0, VK_WHOLE_SIZE));
        out.reset(new VulkanSurface(std::move(impl)));
        return Status::ok();
    });
}

Status VulkanSurface::setControlPoints(const float* positions) {
    return guarded("setControlPoints", [&]() -> Status {
        if (!positions) return Status::error(Status::Usage, "null positions");
        std::memcpy(impl_->controlUpload.mapped, positions, size_t(impl_->tables.controlVertices) * 12);
        std::copy(positions, positions + size_t(impl_->tables.controlVertices) * 3, impl_->control.begin());
        impl_->deviceControl = vk::Buffer();
        return Status::ok();
    });
}

Status VulkanSurface::setControlPoints(VkBuffer buffer, VkDeviceSize offset, const float* lodPositions) {
    return guarded("setControlPoints", [&]() -> Status {
        if (!buffer) return Status::error(Status::Usage, "null control point buffer");
        impl_->deviceControl = vk::Buffer(buffer);
        impl_->deviceControlOffset = offset;
        if (lodPositions)
            std::copy(lodPositions, lodPositions + size_t(impl_->tables.controlVertices) * 3, impl_->control.begin());
        return Status::ok();
    });
}

vk::raii::DescriptorSet VulkanSurface::Impl::evaluateOutputs(vk::raii::DescriptorPool& pool) const {
    vk::DescriptorPoolSize size(vk::DescriptorType::eStorageBuffer, 5);
    pool = vk::raii::DescriptorPool(
        ctx.device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, size));
    const vk::DescriptorSetLayout layout = *ctx.pipelines->evaluateSetLayout;
    vk::raii::DescriptorSets sets(ctx.device, vk::DescriptorSetAllocateInfo(*pool, layout));
    return std::move(sets[0]);
}

void VulkanSurface::Impl::writeSurfaceSet(vk::DescriptorSet set, const vk::DescriptorBufferInfo& draw) const {
    const vk::DescriptorBufferInfo infos[4] = {{*tableBuffer.buffer, 0, VK_WHOLE_SIZE},
                                               {*vertexBuffer.buffer, 0, VK_WHOLE_SIZE},
                                               {*limitBuffer.buffer, 0, VK_WHOLE_SIZE},
                                               draw};
    const uint32_t bindings[4] = {LT_BINDING_TABLES, LT_BINDING_VERTICES, LT_BINDING_LIMIT, LT_BINDING_DRAW};
    vk::WriteDescriptorSet writes[4];
    for (int i = 0; i < 4; ++i)
        writes[i] =
            vk::WriteDescriptorSet(set, bindings[i], 0, 1, vk::DescriptorType::eStorageBuffer, nullptr, &infos[i]);
    ctx.device.updateDescriptorSets(writes, {});
}

Status VulkanSurface::setEditValues(const float* values, size_t count) {
    return guarded("setEditValues", [&]() -> Status {
        size_t expected = size_t(impl_->tables.editCount) * 3;
        if (count != expected)
            return Status::error(Status::Usage, std::to_string(count) + " edit values; the asset has " +
                                                    std::to_string(impl_->tables.editCount) + " edits, 3 values each");
        if (!values && count) return Status::error(Status::Usage, "null edit values");
        if (count) std::memcpy(impl_->editUpload.mapped, values, count * sizeof(float));
        return Status::ok();
    });
}

Status VulkanSurface::recordSubdivision(VkCommandBuffer cmd, float tessFactor) {
    FrameSettings frame;
    frame.tessFactor = tessFactor;
    return recordSubdivision(cmd, frame);
}

Status VulkanSurface::recordSubdivision(VkCommandBuffer cmd, const FrameSettings& frame) {
    return guarded("recordSubdivision", [&]() -> Status {
        Impl& s = *impl_;
        s.collectTrials();
        const FrameSettings resolved = s.resolved(frame);
        float f = s.factorFor(resolved);
        if (!cmd) return Status::error(Status::Usage, "null command buffer");
        BorrowedCommandBuffer borrowed(s.ctx.device, cmd);
        s.recordCompute(*borrowed, s.depthFor(f), resolved.watertight);
        s.recordTrial(*borrowed, frame);  // DrawPath::Auto, undecided: every path timed
        if (s.compute) s.compute->recorded.reset();
        if (drawsPatterns(resolved.path) && resolved.lod.mode == LodMode::Screen) {
            const DrawPlan& plan = s.planFor(resolved);
            if (resolved.path == DrawPath::Compute) {
                s.recordComputePlan(*borrowed, plan, resolved);
                s.markSorted(plan, resolved);
            } else {
                s.recordSort(*borrowed, plan, resolved);
            }
        }
        return Status::ok();
    });
}

Status VulkanSurface::Impl::checkPipelines(const SurfacePipelines& app, const DrawPlan& plan, DrawPath path) {
    if (app.patches && app.layout && (plan.ippTriangles == 0 || app.ipps || path == DrawPath::Compute))
        return Status::ok();
    return Status::error(Status::Usage,
                         "the application's pipelines need a layout and the patches pipeline, and the "
                         "ipps pipeline (this frame draws " +
                             std::to_string(plan.ippTriangles) + " IPP triangles)");
}

// Usage unless the last recordSubdivision computed what `plan` draws.
Status subdividedFor(const VulkanSurface::Impl& s, const DrawPlan& plan, const FrameSettings& frame) {
    if (!s.subdividedDepth || *s.subdividedDepth != plan.depth)
        return Status::error(Status::Usage, "factor " + std::to_string(plan.tessFactor) + " needs depth " +
                                                std::to_string(plan.depth) +
                                                ", which recordSubdivision did not compute");
    if (s.subdividedWatertight != frame.watertight)
        return Status::error(Status::Usage, std::string("recordSubdivision ran with watertight = ") +
                                                (s.subdividedWatertight ? "true" : "false") +
                                                ", the draw has the opposite");
    if (plan.sorted) {
        const auto& sorted = s.sortedFor;
        if (!sorted || sorted->tessFactor != plan.tessFactor || sorted->scale != lodScale(frame.lod) ||
            !std::equal(frame.lod.eye, frame.lod.eye + 3, sorted->eye))
            return Status::error(Status::Usage,
                                 "screen-space factors on the pattern path: recordSubdivision did not sort "
                                 "the patterns for this frame's factor, eye and scale (pass it the same "
                                 "FrameSettings)");
    }
    return Status::ok();
}

DrawStats VulkanSurface::Impl::frameStats(const DrawPlan& plan, const FrameSettings& frame) {
    DrawStats stats = drawStats(plan, frame.lod.mode != LodMode::Screen);
    stats.path = frame.path;
    if (frame.path == DrawPath::Compute) {
        stats.batches = computeFor(frame).batchCount(plan);
        stats.drawCalls = stats.batches;
    }
    return stats;
}

Status VulkanSurface::recordDraw(VkCommandBuffer cmd, const DrawTarget& target, const FrameSettings& frame,
                                 DrawStats* stats) {
    return guarded("recordDraw", [&]() -> Status {
        const FrameSettings f = impl_->resolved(frame);
        const DrawPlan& plan = impl_->planFor(f);
        if (Status st = subdividedFor(*impl_, plan, f); !st) return st;
        GraphicsKey key = impl_->renderKey(vk::Format(target.color), vk::Format(target.depth), f);
        if (!cmd) return Status::error(Status::Usage, "null command buffer");
        BorrowedCommandBuffer borrowed(impl_->ctx.device, cmd);
        impl_->recordDraws(*borrowed, plan, key, f);
        if (stats) *stats = impl_->frameStats(plan, f);
        return Status::ok();
    });
}

Status VulkanSurface::recordDraw(VkCommandBuffer cmd, const SurfacePipelines& pipelines, const FrameSettings& frame,
                                 DrawStats* stats) {
    return guarded("recordDraw", [&]() -> Status {
        const FrameSettings f = impl_->resolved(frame);
        const DrawPlan& plan = impl_->planFor(f);
        if (Status st = subdividedFor(*impl_, plan, f); !st) return st;
        if (!cmd) return Status::error(Status::Usage, "null command buffer");
        if (Status st = Impl::checkPipelines(pipelines, plan, f.path); !st) return st;
        const GraphicsKey key{vk::Format::eUndefined, vk::Format::eUndefined, f.spacing, f.path, false, false,
                              f.watertight,           impl_->displaceKey(f)};  // the application's polygon mode
        BorrowedCommandBuffer borrowed(impl_->ctx.device, cmd);
        impl_->recordDraws(*borrowed, plan, key, f, nullptr, &pipelines);
        if (stats) *stats = impl_->frameStats(plan, f);
        return Status::ok();
    });
}

VulkanSurface::Specialization VulkanSurface::specialization(const FrameSettings& frame) const {
    return Specialization{frame.watertight, impl_->displaceKey(frame), frame.tangents, frame.attributes};
}

VulkanSurface::Memory VulkanSurface::deviceMemory() const {
    Memory m;
    m.tables = impl_->tableBuffer.allocated;
    m.vertices = impl_->vertexBuffer.allocated;
    m.limit = impl_->limitBuffer.allocated;
    m.upload = impl_->controlUpload.allocated + impl_->editUpload.allocated;
    m.watertight = (uint64_t(impl_->tables.watertightWords) + impl_->tables.watertightResultFloats) * 4;
    if (const auto& c = impl_->compute)
        m.compute = c->vertexBuffer.allocated + c->indexBuffer.allocated + c->place.allocated + c->commands.allocated;
    m.trials = impl_->trialMemory();
    return m;
}

}  // namespace lt
