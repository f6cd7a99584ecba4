// Private to looptess_vulkan: VulkanSurface's state and the command recording that
// the public calls and the blocking helpers share.
#pragma once

#include "compute_path.h"
#include "vulkan/context.h"
#include "vulkan/draw_plan.h"
#include "vulkan/gpu_tables.h"
#include "vulkan/pipelines.h"

#include <functional>
#include <optional>

namespace lt {

// Timestamp slots of one frame (PassTimes): subdivision start, subdivision end,
// limit end, draw start, draw end.
enum : uint32_t { kTsStart = 0, kTsSubdivided, kTsLimit, kTsDrawStart, kTsDrawEnd, kTsCount };

// Where a capture draws write: transform feedback buffer 0, the tessellated
// triangles from offset 0, the IPPs after them. Each of the two transform feedback
// sessions may write up to the end of `buffer` (so a wrong plan shows in the
// counters instead of being clipped) and leaves its byte counter in `counters`
// (two uint32 at offsets 0 and 4).
struct CaptureTarget {
    vk::Buffer buffer;
    vk::DeviceSize size = 0;
    vk::Buffer counters;
};

struct VulkanSurface::Impl {
    explicit Impl(VulkanContext::Impl& context);
    ~Impl();

    VulkanContext::Impl& ctx;
    Pipelines& pipelines() { return *ctx.pipelines; }

    GpuTables tables;                         // CPU copy of the level infos and record lists (words freed)
    uint32_t maxDepth = 0;                    // the asset's (runtimeDepth, lodTessFactor)
    bool flatAtMaxDepth = false;              // the asset's (lodTessFactor)
    std::vector<float> control;               // CPU copy of the control points (lodTessFactor)
    std::vector<uint32_t> faces;              // the control mesh's triangles (lodTessFactor)
    bool texcoords = false;                   // the asset has TEXCOORD_0 (FACE_UVS): captures record them
    bool texcoords1 = false, colors = false;  // TEXCOORD_1 (FACE_UV1S), COLOR_0 (FACE_COLORS): likewise
    GpuBuffer tableBuffer, vertexBuffer, limitBuffer, controlUpload;
    GpuBuffer editUpload;  // host-visible edit values (setEditValues); none without edits
    // recordEvaluate's set 1 (the application's buffers), made on first use.
    vk::raii::DescriptorPool evaluatePool{nullptr};
    vk::raii::DescriptorSet evaluateSet{nullptr};
    // A set 1 of evaluate.comp's layout from a pool of its own (made into `pool`).
    vk::raii::DescriptorSet evaluateOutputs(vk::raii::DescriptorPool& pool) const;
    // Writes set 0's bindings (tables, vertices, limit) into `set`, and `draw` as its
    // LT_BINDING_DRAW.
    void writeSurfaceSet(vk::DescriptorSet set, const vk::DescriptorBufferInfo& draw) const;
    // Control points from an application's device buffer (setControlPoints(VkBuffer)):
    // recordCompute copies them instead of controlUpload's.
    vk::Buffer deviceControl;
    vk::DeviceSize deviceControlOffset = 0;
    // Its PLACE at screen-space factors (evaluate.comp): sized for the largest frame,
    // made by the first recordEvaluate there (16 bytes before).
    GpuBuffer placeBuffer;
    vk::raii::DescriptorPool descriptorPool{nullptr};
    vk::raii::DescriptorSet descriptorSet{nullptr};
    std::optional<uint32_t> subdividedDepth;  // depth of the last recordSubdivision
    bool subdividedWatertight = true;         // and its FrameSettings::watertight
    std::optional<DrawPlan> plan;             // of the last draw
    // What the last recordSubdivision sorted patterns for (DrawPlan::sorted):
    // the bound F, the eye and the scale k (lod.h).
    struct SortedFor {
        float tessFactor = 0, eye[3] = {0, 0, 0}, scale = 0;
    };
    std::optional<SortedFor> sortedFor;
    uint32_t sortCommands = 0, sortRecords = 0;  // the sort region's word offsets (gpu_layout.h)

    // DrawPath::Compute (compute_path.h): the batch buffer, its descriptor sets, PLACE
    // and the batch table, made for a vertex size and FrameSettings::computeBytes.
    struct ComputeState {
        uint32_t bytes = 0, words = 0;        // FrameSettings::computeBytes, LT_DRAW_WORDS
        uint32_t vertices = 0;                // a batch's room (and 6 times as many indices)
        GpuBuffer vertexBuffer, indexBuffer;  // the batch's vertices and indices
        GpuBuffer place;                      // PLACE, batch table, commands (words), counts
        GpuBuffer commands;                   // the commands, copied for the indirect reads
        uint32_t batchTable = 0, maxBatches = 0;
        vk::DeviceSize countsOffset = 0;  // evaluate.comp's counts (unread), after the rest
        vk::raii::DescriptorPool pool{nullptr};
        vk::raii::DescriptorSet drawSet{nullptr};  // set 0 with the vertices at LT_BINDING_DRAW
        vk::raii::DescriptorSet outputs{nullptr};  // evaluate.comp's set 1: the batch
        std::vector<ComputeBatch> planned;         // batchesOf's, for plannedFor and plannedDepth
        float plannedFor = 0;
        uint32_t plannedDepth = 0;
        std::optional<uint32_t> recorded;  // the last recordBatch's batch since recordSubdivision
        // The batches of a uniform-factor plan (cached), and any plan's count.
        const std::vector<ComputeBatch>& batchesOf(const DrawPlan& plan);
        uint32_t batchCount(const DrawPlan& plan);
        // Byte offset of a frame of `batches` batches' commands in `place`, and of
        // batch k's in `commands`.
        vk::DeviceSize commandsInPlace(uint32_t batches) const;
        static vk::DeviceSize commandBytes(uint32_t k) { return vk::DeviceSize(LT_BATCH_COMMAND_WORDS) * 4 * k; }
    };
    std::unique_ptr<ComputeState> compute;
    ComputeState& computeFor(const FrameSettings& frame);
    // compute_path.cpp: at screen-space factors the batches' plan (in recordSubdivision);
    // batch k's evaluation (recordBatch); the draw of the last one (`pc` its constants).
    void recordComputePlan(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan, const FrameSettings& frame);
    void recordComputeBatch(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan, const FrameSettings& frame,
                            uint32_t k);
    void recordComputeDraw(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan, const GraphicsKey& key,
                           const FrameSettings& frame, const PushConstants& pc, const CaptureTarget* capture,
                           const SurfacePipelines* app);
    // DrawPath::Auto (auto_path.cpp): `frame` with Auto replaced by the path it
    // draws; the finished trials' times read (never waiting) and decisions made; a
    // trial of `frame` recorded after its subdivision while its range is undecided.
    struct AutoState;
    std::unique_ptr<AutoState> autoState;
    FrameSettings resolved(const FrameSettings& frame) const;
    void collectTrials();
    void recordTrial(const vk::raii::CommandBuffer& cmd, const FrameSettings& frame);
    uint64_t trialMemory() const;  // the trial image

    uint32_t depthFor(float tessFactor) const { return runtimeDepth(maxDepth, tessFactor); }
    uint32_t vertexCountUpTo(uint32_t depth) const;
    // F of `frame` (lodTessFactor on the current control points); Usage if invalid.
    float factorFor(const FrameSettings& frame) const;
    // The plan of factorFor(frame), uniform factors: exact for Global and Distance,
    // the bound of Screen (draw_plan.h); frame.path's. Cached. Unsupported for
    // patterns at screen-space factors without drawIndirectFirstInstance.
    const DrawPlan& planFor(const FrameSettings& frame);
    // A sorted plan's pass (pattern_sort.comp) after recordCompute computed its depth,
    // with its barriers; sets sortedFor.
    void recordSort(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan, const FrameSettings& frame);
    // Sets sortedFor: the frame's patterns are picked (the compute path picks its own).
    void markSorted(const DrawPlan& plan, const FrameSettings& frame);
    // A sorted plan's chunk dispatches (pattern_sort.comp's COUNT and SCATTER,
    // evaluate.comp's SORTED_KEYS and SORTED_PLACE): per drawn list, pc.base its offset,
    // pc.evaluate[0] its records, [1] its first chunk's index, [2] the records of
    // the lists before it, then push() and a work group per chunk. Returns the chunks.
    uint32_t dispatchChunks(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan, PushConstants& pc,
                            const std::function<void()>& push) const;

    // Control point and edit value copies, subdivision, edit and limit passes for
    // `depth`, barriers included.
    // With `timestamps`, writes kTsStart, kTsSubdivided, kTsLimit.
    // `watertight`: the limit pass applies watertight.h's rules and the watertight pass
    // evaluates the sources for the draws (FrameSettings::watertight).
    void recordCompute(const vk::raii::CommandBuffer& cmd, uint32_t depth, bool watertight,
                       vk::QueryPool timestamps = {});
    // The draws of `plan` inside a rendering scope (DrawPath::Compute: of the last
    // recorded batch); `capture`: with transform feedback. `app`: the application's
    // pipelines instead of the key's.
    void recordDraws(const vk::raii::CommandBuffer& cmd, const DrawPlan& plan, const GraphicsKey& key,
                     const FrameSettings& frame, const CaptureTarget* capture = nullptr,
                     const SurfacePipelines* app = nullptr);
    // The push constants of the draws of `frame`.
    PushConstants drawConstants(const DrawPlan& plan, const GraphicsKey& key, const FrameSettings& frame) const;
    void checkFactor(float tessFactor) const;
    // Usage unless `app` has a layout, the patches pipeline and, where `plan` draws
    // IPPs on a path other than DrawPath::Compute, the ipps pipeline.
    static Status checkPipelines(const SurfacePipelines& app, const DrawPlan& plan, DrawPath path);
    // The statistics of `frame` (resolved) drawn with `plan`.
    DrawStats frameStats(const DrawPlan& plan, const FrameSettings& frame);
    // The render pipeline key of `frame` for these attachment formats (Unsupported
    // for a wireframe without fillModeNonSolid).
    GraphicsKey renderKey(vk::Format color, vk::Format depth, const FrameSettings& frame) const;
    // GraphicsKey::displace of `frame`: it displaces, or watertight draws of this asset
    // need watertight.glsl's two-evaluation path (GpuTables::smoothCreaseRoots).
    bool displaceKey(const FrameSettings& frame) const;
};

// Usage unless recordSubdivision computed plan.depth with frame.watertight and, for a
// sorted plan, sorted for frame's factor and eye (surface.cpp).
Status subdividedFor(const VulkanSurface::Impl& s, const DrawPlan& plan, const FrameSettings& frame);

// Statistics of a plan; `exact` false: the plan is a screen-space LOD frame's bound.
DrawStats drawStats(const DrawPlan& plan, bool exact);

}  // namespace lt
