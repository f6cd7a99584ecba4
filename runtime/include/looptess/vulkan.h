// looptess/vulkan.h -- the Vulkan path of the runtime (library looptess_vulkan):
// uploads a baked asset once, then every frame subdivides it with compute passes
// and draws its exact Loop limit surface by one of runtime.h's DrawPaths. It
// computes what lt::evaluateCpu computes, in the same operation order
// (docs/devices.md: what is the same bits on every device). The paths and when each
// is fastest: docs/how-it-works.md; the frame loop: docs/engine-integration.md.
//
// In an engine (its own Vulkan 1.3 device, see "Device requirements"):
//
//   lt::VulkanHandles h;                      // instance, physicalDevice, device,
//   h.instance = instance; ...                // queue, queueFamily (not owned)
//   std::unique_ptr<lt::VulkanContext> gpu;
//   lt::Status st = lt::VulkanContext::adopt(h, gpu);
//   std::unique_ptr<lt::VulkanSurface> surface;
//   if (st) st = lt::VulkanSurface::create(*gpu, asset, surface);  // tables uploaded once
//   // every frame, into the engine's command buffer `cmd`:
//   surface->setControlPoints(skinnedPositions);        // optional (animation)
//   surface->recordSubdivision(cmd, frame);             // compute, outside rendering
//   uint32_t batches = 1;
//   surface->drawBatches(frame, batches);               // 1 but for a large compute-path frame
//   for (uint32_t b = 0; b < batches; ++b) {
//       surface->recordBatch(cmd, frame, b);            // compute path: evaluates batch b
//       vkCmdBeginRendering(cmd, ...);                  // attachments as DrawTarget says;
//                                                       // after batch 0 load, not clear
//       vkCmdSetViewport(...); vkCmdSetScissor(...);    // dynamic state
//       surface->recordDraw(cmd, target, frame);        // draws batch b
//       vkCmdEndRendering(cmd);
//   }
//
// Into the engine's own buffers (DrawPath::Patterns; ray tracing, physics, export),
// outside any rendering scope:
//
//   frame.path = lt::DrawPath::Patterns;
//   surface->evaluateSizes(frame, sizes);               // vertices, indices (at most)
//   surface->recordSubdivision(cmd, frame);
//   surface->recordEvaluate(cmd, frame, vertexBuffer, 0, indexBuffer, 0,
//                           countBuffer, 0);            // the counts written
//   // the engine's barrier: compute-shader writes -> its reads
//
// Tools and tests add looptess/tools/vulkan_tools.h: blocking capture of the emitted
// vertices, read-back of the refined vertices, and offscreen images.
//
// Errors come back as lt::Status (asset.h), never as exceptions or exit():
//   Unsupported  no Vulkan loader or device, a missing feature or extension, an
//                asset beyond the device's limits
//   Usage        a call against this header's contract (e.g. recordDraw for a depth
//                that recordSubdivision did not compute)
//   Internal     a Vulkan call failed (out of memory, device lost, ...); the message
//                names the call and the VkResult
// Inside, the library uses Vulkan-Hpp's RAII classes (vulkan_raii.hpp) with C++
// exceptions enabled; every function of this header catches them and returns a
// Status. After a device-lost Status the surface and context should be destroyed.
//
// Threading: objects are not thread-safe; calls on one context and its surfaces
// must be serialized, and the blocking calls (VulkanSurface::create, the helpers of
// vulkan_tools.h) use the context's queue (the application must not use that queue
// concurrently, as Vulkan requires).
// Lifetime: destroy surfaces before their context; adopted handles must outlive the
// context, which never destroys them.
#pragma once

#include "looptess/asset.h"
#include "looptess/runtime.h"

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lt {

// An application's Vulkan objects, borrowed (not owned).
//
// Device requirements: Vulkan 1.3; feature dynamicRendering enabled; `queue` from
// family `queueFamily` supports graphics and compute. The tessellator path
// (DrawPath::Tessellator, the default) also needs tessellationShader enabled (say so
// in `tessellationShader`); without it frames draw with DrawPath::Patterns.
// vulkan_tools.h's capture also needs VK_EXT_transform_feedback with its
// transformFeedback feature enabled (say so in `transformFeedback`). Screen-space
// level of detail on DrawPath::Patterns draws indirect with a first instance: it
// needs drawIndirectFirstInstance enabled (say so in `drawIndirectFirstInstance`),
// and draws once per pattern instead of 343 times where multiDrawIndirect is enabled
// too. DrawPath::Compute needs nothing more, at any level of detail (its indirect
// draws start at instance 0). Nothing else is assumed: storage buffers are read-only
// in vertex-pipeline stages, and 4 storage buffers are bound per stage (the
// guaranteed minimum).
struct VulkanHandles {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;  // null: the Vulkan loader's
    bool transformFeedback = false;
    bool fillModeNonSolid = false;           // feature enabled: FrameSettings::wireframe works
    bool pipelineStatisticsQuery = false;    // feature enabled: vulkan_tools.h's FrameReport counts work
    bool tessellationShader = true;          // feature enabled: DrawPath::Tessellator works
    bool drawIndirectFirstInstance = false;  // feature enabled: screen-space LOD on DrawPath::Patterns works
    bool multiDrawIndirect = false;          // feature enabled: ... with one draw call
};

struct HeadlessOptions {
    // Enables VK_LAYER_KHRONOS_validation and records its warnings and errors (see
    // VulkanContext::messages); fails with Unsupported if the layer is missing.
    bool validation = false;
    // Also enables the layer's synchronization validation (needs `validation`).
    bool synchronizationValidation = false;
    // Substring of the device name to use; empty: the first suitable device,
    // discrete GPUs before integrated, virtual and CPU devices.
    std::string deviceName;
};

// A device the Vulkan path runs on, owned (createHeadless) or borrowed (adopt).
class VulkanContext {
public:
    // A Vulkan 1.3 instance without surface extensions and a device with the
    // requirements above (tessellation shaders and transform feedback when the
    // device has them).
    static Status createHeadless(const HeadlessOptions& options, std::unique_ptr<VulkanContext>& out);
    // Wraps an application's device; checks what it can check (API version,
    // tessellation support, queue family flags).
    static Status adopt(const VulkanHandles& handles, std::unique_ptr<VulkanContext>& out);
    ~VulkanContext();

    // The device's name, as VkPhysicalDeviceProperties::deviceName says.
    std::string deviceName() const;
    // The raw handles (for recording with one's own command buffers, or adopting
    // them elsewhere); owned by this context unless it adopted them.
    VulkanHandles handles() const;
    // For an application's own pipelines (SurfaceStages below): descriptor set 0
    // every surface binds (owned by this context), and the push constant range the
    // draws push (the application's pipeline layout has exactly this range).
    VkDescriptorSetLayout surfaceSetLayout() const;
    VkPushConstantRange surfacePushConstants() const;
    // Validation messages (warnings and errors) recorded so far, oldest first:
    // "<severity> <message id>: <text>". Always empty without validation.
    std::vector<std::string> messages() const;

    struct Impl;  // opaque: the library's own

private:
    friend struct VulkanAccess;  // the library's way to its Impl
    explicit VulkanContext(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// Attachment formats of the rendering scope recordDraw is called in
// (VK_FORMAT_UNDEFINED: no such attachment). One pipeline is built per target.
struct DrawTarget {
    VkFormat color = VK_FORMAT_UNDEFINED;
    VkFormat depth = VK_FORMAT_UNDEFINED;
};

// How recordDraw colours the surface: shaded grey, by subdivision level and patch
// class (paper Fig. 7 and 9: a hue per level, non-plain sub-patches paler, IPPs
// dark blue), or by TEXCOORD_0 (a checker of 8 x 8 squares per unit of texture
// space; grey-blue where the asset has no texture coordinates).
enum class Coloring : uint8_t { Shaded, Levels, Texcoords };

// One frame: an evaluation (EvalSettings, runtime.h; the same values give the CPU's
// surface) and what only the GPU's draw needs.
//
//   lt::FrameSettings frame{eval};   // from an lt::EvalSettings; the rest defaulted
//
// On the GPU the evaluation's fields say more:
//   path        DrawPath::Patterns with LodMode::Screen needs drawIndirectFirstInstance
//               (VulkanHandles), and recordSubdivision must be given the frame: it
//               sorts the patches by pattern on the GPU (a compute pass after the
//               limit pass), which recordDraw then draws indirect.
//   lod         Distance and Screen compute F from the camera and the surface's
//               current control points (tessFactor unused); Screen also gives every
//               patch edge its own factor (in the tessellation control shader, or in
//               the patterns' sort pass).
//   watertight  recordSubdivision and recordDraw of one frame must agree on it.
//   indexed     not read: recordEvaluate always writes indexed triangles, and
//               vulkan_tools.h's capture the soup.
//   editValues  not read: a surface keeps its own (VulkanSurface::setEditValues).
struct FrameSettings : EvalSettings {
    Coloring coloring = Coloring::Shaded;
    bool wireframe = false;                                            // polygon mode line (needs fillModeNonSolid)
    float mvp[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major, object to clip
    float light[3] = {0, 0, 1};                                        // unit direction towards the light, object space
    // Tessellated domain points per vkCmdDraw at most: lavapipe renders a draw of
    // more than about 65k tessellated vertices wrongly and far slower. 0: the
    // default, 32768.
    uint32_t maxPointsPerDraw = 0;
    // DrawPath::Compute: the bytes of the surface's buffer that one batch of the
    // frame is evaluated into (its vertices and indices); a frame that does not fit
    // is evaluated and drawn in batches (drawBatches). 0: kDefaultComputeBytes. A
    // change takes a new buffer: no command buffer with this surface's earlier draws
    // may still be pending then.
    uint32_t computeBytes = 0;
    // DrawPath::Compute evaluates before any pipeline sees the vertices, so the frame
    // says what the draws' fragment shaders read beyond position, normal, style and
    // TEXCOORD_0: TANGENT, and base face, (u,v), TEXCOORD_1 and COLOR_0. Its
    // pipelines are built with kSpecTangent and kSpecAttributes equal to these
    // (specialization(frame)). On the other paths each pipeline's own constants decide.
    bool tangents = false;
    bool attributes = false;
};

// DrawPath::Compute's batch buffer when FrameSettings::computeBytes is 0: a batch
// holds about 250 thousand vertices (36 bytes each, and room for 6 indices).
inline constexpr uint32_t kDefaultComputeBytes = 16u << 20;

// What one frame drew.
struct DrawStats {
    float tessFactor = 0;  // F (lodTessFactor of the frame)
    // false for frames with LodMode::Screen: the factors live on the GPU, so
    // patches/points/triangles are the bound the draws were batched for (the
    // global factor F's); vulkan_tools.h's capture reports exact counts.
    bool exact = true;
    uint32_t depth = 0;
    uint32_t drawCalls = 0;                 // vkCmdDraw calls (tessellated batches + IPPs)
    uint64_t patches = 0;                   // 12-point patches (sub-triangles of NPPs count each)
    uint64_t points = 0;                    // tessellated domain points
    uint64_t triangles = 0;                 // tessellated triangles + IPP triangles
    DrawPath path = DrawPath::Tessellator;  // the path drawn (DrawPath::Auto's choice)
    uint32_t batches = 1;                   // DrawPath::Compute: batches of evaluation and draw
};

// ---- An application's own pipelines --------------------------------------------
// The stages before the fragment shader, as SPIR-V (Vulkan 1.3), for an application
// that builds its own graphics pipelines around the surface: its fragment shader
// and descriptor sets 1 and up (materials), blending, depth, multisampling, its
// render pass or dynamic rendering.
//
//   patches  patchVertex + patchControl + patchEvaluation; topology PATCH_LIST,
//            12 control points a patch; no vertex input (they read storage buffers)
//   patterns patternVertex; topology TRIANGLE_LIST; no vertex input (the index
//            buffer is looptess's, bound by recordDraw): frames with
//            DrawPath::Patterns, SurfacePipelines::patches
//   ipps     ippVertex; topology TRIANGLE_LIST; no vertex input
//   compute  computeVertex; topology TRIANGLE_LIST; no vertex input (the index buffer
//            is the surface's, bound by recordDraw): frames with DrawPath::Compute,
//            SurfacePipelines::patches (they have no IPP draw)
//
// Pipeline layout: set 0 = VulkanContext::surfaceSetLayout(), push constants =
// VulkanContext::surfacePushConstants(). Specialization constants (VkBool32) of
// every stage: id kSpecWatertight and kSpecDisplace, with the values
// VulkanSurface::specialization(frame) gives, and the application's choices:
// kSpecTangent, VK_TRUE for a pipeline whose fragment shader reads the tangent (it
// costs the evaluation one more box-spline evaluation at shared points), and
// kSpecAttributes, VK_TRUE for one that reads base face, (u,v), TEXCOORD_1 or COLOR_0
// (5-8% of a draw on lavapipe even when unread); what a constant leaves off is
// undefined. Viewport and scissor are dynamic in
// looptess's own pipelines; yours may choose. What the last stage writes, for any
// fragment shader to read:
//
//   location 0  vec3 position        object space, displaced
//   location 1  vec3 normal          object space, unit
//   location 2  flat uint face       the base face (input face order)      kSpecAttributes
//   location 3  vec2 uv              (u, v) on the base face: corners      kSpecAttributes
//                                    (0,0), (1,0), (0,1)
//   location 4  flat uint style      subdivision level | patch class << 8
//                                    (class 0 regular, 1 non-plain sub-patch, 2 IPP)
//   location 5  vec2 texcoord        TEXCOORD_0, (0, 0) where the asset has none
//   location 6  vec4 tangent         TANGENT (runtime.h's Tessellation::tangents:   kSpecTangent
//                                    xyz unit, w handedness) where the asset has
//                                    TEXCOORD_0
//   location 7  vec2 texcoord1       TEXCOORD_1, (0, 0) where the asset has none    kSpecAttributes
//   location 8  vec4 color           COLOR_0 (linear RGBA), (1, 1, 1, 1) where none kSpecAttributes
//   gl_Position                      FrameSettings::mvp * position
//
// Fragment shaders may also read the push constants, laid out (std430) as
//
//   layout(push_constant) uniform PushConstants {
//       mat4 mvp;  vec4 light;  float tessFactor;  uint level;  uint base;  uint flags;
//       vec4 lod;  uvec4 evaluate;
//   };
//
// mvp and light.xyz as FrameSettings says; the rest is the library's.
struct SpirvModule {
    const uint32_t* code = nullptr;
    size_t bytes = 0;
};
struct SurfaceStages {
    SpirvModule patchVertex, patchControl, patchEvaluation, ippVertex;
    SpirvModule patternVertex;  // DrawPath::Patterns (no tessellation stages)
    SpirvModule computeVertex;  // DrawPath::Compute (reads what its compute passes wrote)
};
// The stages for `spacing` (the evaluation stage differs per spacing).
SurfaceStages surfaceStages(Spacing spacing);
inline constexpr uint32_t kSpecWatertight = 0, kSpecDisplace = 1, kSpecTangent = 2, kSpecAttributes = 3;
// Floats per vertex of VulkanSurface::recordEvaluate.
inline constexpr uint32_t kEvaluateVertexFloats = 12;

// An application's pipelines built from surfaceStages with `layout` (see above).
// `patches` draws the regular patches of the frame's path: the tessellation stages
// for DrawPath::Tessellator, patternVertex for DrawPath::Patterns, computeVertex for
// DrawPath::Compute (then the whole surface: `ipps` is not used).
struct SurfacePipelines {
    VkPipeline patches = VK_NULL_HANDLE;
    VkPipeline ipps = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
};

// A baked asset on the GPU: its tables, the refined vertex buffer, the limit points
// of the current depth, and the pipelines' descriptor set.
class VulkanSurface {
public:
    // Validates nothing about the asset itself: it must have passed
    // lt::validateAsset (readAssetGlb does that). Uploads the tables and the
    // asset's control points. Blocks until the upload is done.
    static Status create(VulkanContext& context, const Asset& asset, std::unique_ptr<VulkanSurface>& out);
    ~VulkanSurface();

    // Replaces the control points (3 floats per control vertex) used by the next
    // recordSubdivision. Writes host-visible memory at once: no command buffer that
    // recorded this surface's recordSubdivision may still be pending.
    Status setControlPoints(const float* positions);
    // Control points from the application's device buffer instead: 3 floats per
    // control vertex from byte `offset` of `buffer` (TRANSFER_SRC usage), e.g. skinned
    // or morphed by the application's own compute pass. Every recordSubdivision copies
    // them on the device, until the next setControlPoints; the application records the
    // barrier from its writes to transfer reads before it, and keeps the buffer alive.
    // Level of detail other than Global computes F on the host: from `lodPositions` (3
    // floats per control vertex, e.g. a CPU pose or bounding positions) when not null,
    // else from the last host control points.
    Status setControlPoints(VkBuffer buffer, VkDeviceSize offset, const float* lodPositions = nullptr);

    // Replaces the hierarchical edit values (paper 4.3; asset.h's VertexEdits) used
    // by the next recordSubdivision: `count` = 3 * asset.editCount() floats in the
    // flat edit order (lt::bakedEditValues gives the baked ones to start from), as
    // EvalSettings::editValues on the CPU path, which gives the same bits. Where the
    // edits are and their ops stay as baked. Usage if `count` is wrong (also for an
    // asset without edits, unless count is 0) or `values` is null. Writes
    // host-visible memory at once, as setControlPoints: no command buffer that
    // recorded this surface's recordSubdivision may still be pending. Until the
    // first call the asset's baked values are used.
    Status setEditValues(const float* values, size_t count);

    // Records, outside any rendering scope: the control point and edit value
    // copies, per level 1..depth a vertex-point and an edge-point dispatch, per level
    // 0..depth with hierarchical edits an edit dispatch after the level's points,
    // and the limit dispatch of level depth = runtimeDepth(asset, tessFactor);
    // barriers included (waits for earlier vertex-pipeline and compute reads of this
    // surface, makes the results visible to vertex-pipeline stages).
    Status recordSubdivision(VkCommandBuffer cmd, float tessFactor);
    // The same for the factor F of `frame` (its level of detail on the control
    // points of the last setControlPoints; runtime.h's lodTessFactor). At screen-space
    // factors it also picks every patch's pattern (DrawPath::Patterns and Compute)
    // and cuts the frame into batches (Compute). With DrawPath::Auto it fixes the
    // frame's path (DrawStats::path), and while trials run it also draws the paths it
    // measures, into an image of its own (pathChoices).
    Status recordSubdivision(VkCommandBuffer cmd, const FrameSettings& frame);

    // ---- Batches -------------------------------------------------------------------
    // DrawPath::Compute evaluates the surface in compute passes into a buffer of the
    // surface's (FrameSettings::computeBytes) and draws it from there as plain indexed
    // triangles; a frame larger than the buffer goes in batches, each evaluated
    // outside a rendering scope (recordBatch), then drawn inside one (recordDraw). The
    // other paths have one batch and recordBatch records nothing for them, so one loop
    // drives every path (the example at the top of this header).
    //
    // The batches of `frame` (its factor on the current control points): exact at
    // global and distance factors; at screen-space factors, where only the GPU knows
    // the frame's size, enough for the bound F's output, and the batches past the
    // frame's own are empty (their dispatches and draw are indirect, of zero size).
    Status drawBatches(const FrameSettings& frame, uint32_t& count);
    // Records batch `batch` < drawBatches of `frame`, after recordSubdivision(cmd,
    // frame) and outside any rendering scope: its compute evaluation into the
    // surface's buffer, between barriers (after the previous batch's draw has read
    // the buffer; before this batch's draw reads it). recordDraw then draws it.
    Status recordBatch(VkCommandBuffer cmd, const FrameSettings& frame, uint32_t batch);

    // Records the draws inside the application's rendering scope (formats of
    // `target`, viewport and scissor set by the caller). frame.tessFactor must give
    // the depth of the last recordSubdivision (else Usage; with a level of detail, call
    // recordSubdivision(cmd, frame) with the same frame). DrawPath::Compute draws the
    // batch of the last recordBatch (Usage if there is none since recordSubdivision).
    // `stats` is optional. Leaves this library's pipeline, descriptor set 0 and push
    // constants bound.
    Status recordDraw(VkCommandBuffer cmd, const DrawTarget& target, const FrameSettings& frame,
                      DrawStats* stats = nullptr);
    // The same with the application's pipelines (see "An application's own
    // pipelines"): binds `pipelines.patches`, then `pipelines.ipps` where the frame
    // has IPPs, with descriptor set 0 and the push constants on `pipelines.layout`;
    // the application's own sets 1 and up stay as it bound them. Usage when a
    // needed pipeline or the layout is null.
    Status recordDraw(VkCommandBuffer cmd, const SurfacePipelines& pipelines, const FrameSettings& frame,
                      DrawStats* stats = nullptr);
    // The specialization constant values (ids kSpecWatertight, kSpecDisplace) that
    // pipelines drawing `frame` of this surface must be built with, and `tangent` and
    // `attributes` (ids kSpecTangent, kSpecAttributes): the frame's tangents and
    // attributes, which DrawPath::Compute's pipelines must have and the other paths'
    // may choose. The fields are laid out for a VkSpecializationInfo's data, one
    // VkBool32 each in id order.
    struct Specialization {
        VkBool32 watertight = VK_TRUE, displace = VK_TRUE, tangent = VK_FALSE, attributes = VK_FALSE;
    };
    Specialization specialization(const FrameSettings& frame) const;

    // DrawPath::Auto: per level-of-detail mode and depth (a range of factors), the
    // paths tried, each one's median GPU time over its trial frames (ms; negative: not
    // measured, e.g. the device lacks tessellation shaders), and the path kept once
    // `decided` (until then frames draw with DrawPath::Patterns).
    struct PathChoice {
        LodMode mode = LodMode::Global;
        uint32_t depth = 0;
        bool decided = false;
        DrawPath kept = DrawPath::Patterns;
        double ms[3] = {-1, -1, -1};  // Tessellator, Patterns, Compute
        uint32_t trials = 0;          // trial frames measured
    };
    std::vector<PathChoice> pathChoices() const;
    // The path `frame` draws with: frame.path, or with DrawPath::Auto the one kept for
    // its level-of-detail mode and depth (Patterns while undecided). Decisions are
    // made only at recordSubdivision and vulkan_tools.h's renderImage, so from
    // recordSubdivision to the frame's last recordDraw this stays: an application
    // with its own pipelines picks them by it (SurfaceStages of that path).
    DrawPath drawnPath(const FrameSettings& frame) const;

    // ---- The surface into buffers ---------------------------------------------------
    // One frame as indexed triangles in the application's buffers, for ray-tracing
    // acceleration structures, physics, shadow passes or export: the pattern path's
    // vertices (frame.path must not be DrawPath::Tessellator, else Usage), each pattern point
    // once per patch, bit for bit what its draw emits and what the CPU evaluator gives
    // with EvalSettings::indexed (the same order too). Per vertex kEvaluateVertexFloats
    // floats: position xyz, unit normal xyz, TANGENT xyzw ((0, 0, 0, 1) without
    // TEXCOORD_0), TEXCOORD_0 s t ((0, 0) without); uint32 indices, 3 a triangle,
    // counter-clockwise seen from the normals' side, as the draw. Any level of detail:
    // at screen-space factors each patch's pattern is picked on the GPU, so the sizes
    // are bounds and the counts come back in a buffer (the device needs
    // drawIndirectFirstInstance there, as the pattern path's draws).
    struct EvaluateSizes {
        uint64_t vertices = 0, indices = 0;
        uint64_t vertexBytes() const { return vertices * 48; }
        uint64_t indexBytes() const { return indices * 4; }
    };
    // The sizes `frame` needs (its factor on the current control points): exact at
    // global and distance factors, at screen-space factors the most any eye needs
    // (the frame's bound F; recordEvaluate may be given less room, below).
    // Unsupported past 2^32 / kEvaluateVertexFloats vertices or 2^32 indices.
    Status evaluateSizes(const FrameSettings& frame, EvaluateSizes& out);
    // What recordEvaluate writes into `counts`: the vertices and indices of the frame
    // (at screen-space factors also where they exceed the room given).
    struct EvaluateCounts {
        uint32_t vertices = 0, indices = 0;
    };
    // Records, outside any rendering scope and after recordSubdivision(cmd, frame),
    // compute dispatches that write the frame into `vertices` at `vertexOffset` and
    // `indices` at `indexOffset`, and its EvaluateCounts into `counts` at
    // `countsOffset` (bytes; buffers with STORAGE_BUFFER usage, offsets multiples of
    // minStorageBufferOffsetAlignment, room for `room` and for the 8 bytes of
    // EvaluateCounts). `counts` may be null except at screen-space factors
    // (LodMode::Screen), where only the GPU knows them (Usage).
    //
    // `room`: the vertices and indices the buffers hold from their offsets (at least
    // one of each; more than evaluateSizes' counts as evaluateSizes'); null means
    // evaluateSizes', which global and distance factors need (less is Usage). At
    // screen-space factors the bound is often far above what a view needs, so `room`
    // may be less (e.g. last frame's counts with a margin). When the counts come back
    // above the room, the buffers hold an incomplete frame (the records that fit,
    // whole, and part of the IPPs): make room for the counts and record again.
    // Unsupported where the room's bytes exceed maxStorageBufferRange.
    //
    // Reads what recordSubdivision wrote (its barrier included); the application
    // records the barrier from these compute-shader writes to its own reads (of the
    // counts too). Rewrites the surface's output descriptor set: no command buffer
    // with an earlier recordEvaluate of this surface may still be pending.
    Status recordEvaluate(VkCommandBuffer cmd, const FrameSettings& frame, VkBuffer vertices, VkDeviceSize vertexOffset,
                          VkBuffer indices, VkDeviceSize indexOffset, VkBuffer counts = VK_NULL_HANDLE,
                          VkDeviceSize countsOffset = 0, const EvaluateSizes* room = nullptr);

    // Device memory the asset keeps (what every frame needs; not the buffers of
    // vulkan_tools.h's blocking helpers), in bytes as allocated.
    struct Memory {
        uint64_t tables = 0;    // every baked table, uploaded once (edit values: every frame)
        uint64_t vertices = 0;  // refined vertices of all levels
        uint64_t limit = 0;     // limit points of the current depth
        uint64_t upload = 0;    // host-visible control point and edit value staging
        // The part of `tables` and `limit` only watertight evaluation uses (its records
        // and the watertight pass's results).
        uint64_t watertight = 0;
        // DrawPath::Compute's batch buffer and plan, once a frame has used it.
        uint64_t compute = 0;
        // DrawPath::Auto's trial image and queries, while trials run.
        uint64_t trials = 0;
        uint64_t total() const { return tables + vertices + limit + upload + compute + trials; }
    };
    Memory deviceMemory() const;

    struct Impl;  // opaque: the library's own

private:
    friend struct VulkanAccess;  // the library's way to its Impl
    explicit VulkanSurface(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace lt
