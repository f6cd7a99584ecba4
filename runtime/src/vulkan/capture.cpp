// Blocking read-backs of a VulkanSurface: refined vertices and the transform
// feedback capture (vulkan_tools.h).
#include "surface.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace lt {
namespace {

// `out` replaced by `vertices` vertices' arrays. `texcoords`: the records' s t are
// the asset's TEXCOORD_0 and tx ty tz tw its TANGENT (surface_out.glsl computes
// them as runtime.h's faceTexcoord and faceTangent), else (0, 0) and (0, 0, 0, 1)
// and left out. `uv1s`, `colors`: the records' s1 t1 and r g b a are the asset's
// TEXCOORD_1 and COLOR_0, else left out.
void sizeCapture(size_t vertices, bool texcoords, bool uv1s, bool colors, Tessellation& out) {
    out = Tessellation{};
    out.positions.resize(vertices * 3);
    out.normals.resize(vertices * 3);
    out.face.resize(vertices);
    out.uv.resize(vertices * 2);
    out.texcoords.resize(texcoords ? vertices * 2 : 0);
    out.tangents.resize(texcoords ? vertices * 4 : 0);
    out.texcoords1.resize(uv1s ? vertices * 2 : 0);
    out.colors.resize(colors ? vertices * 4 : 0);
}

// `count` captured records into `out`'s vertices from `first` on (sizeCapture).
void unpackCapture(const uint8_t* bytes, size_t first, size_t count, Tessellation& out) {
    const bool texcoords = !out.texcoords.empty(), uv1s = !out.texcoords1.empty(), colors = !out.colors.empty();
    for (size_t k = 0; k < count; ++k) {
        // x y z nx ny nz face u v s t tx ty tz tw s1 t1 r g b a
        const uint8_t* v = bytes + k * LT_CAPTURE_STRIDE;
        const size_t i = first + k;
        std::memcpy(&out.positions[i * 3], v, 12);
        std::memcpy(&out.normals[i * 3], v + 12, 12);
        std::memcpy(&out.face[i], v + 24, 4);
        std::memcpy(&out.uv[i * 2], v + 28, 8);
        if (texcoords) {
            std::memcpy(&out.texcoords[i * 2], v + 36, 8);
            std::memcpy(&out.tangents[i * 4], v + 44, 16);
        }
        if (uv1s) std::memcpy(&out.texcoords1[i * 2], v + 60, 8);
        if (colors) std::memcpy(&out.colors[i * 4], v + 68, 16);
    }
}

// A sorted plan's captured patches (pattern_sort.comp's order: by pattern key, then
// record) back in record order, the CPU evaluator's: `keys` are the records' keys in
// record order, each record's vertices 3 per triangle of its pattern.
std::vector<uint8_t> recordOrder(const uint8_t* sorted, const std::vector<uint16_t>& keys) {
    const PatternLibrary& library = patternLibrary();
    const size_t stride = LT_CAPTURE_STRIDE;
    std::vector<uint64_t> start(LT_PATTERN_KEYS + 1, 0);  // first captured vertex of each key
    for (uint16_t k : keys) start[k + 1] += library.count[k];
    for (uint32_t k = 0; k < LT_PATTERN_KEYS; ++k) start[k + 1] += start[k];
    std::vector<uint8_t> out(size_t(start[LT_PATTERN_KEYS]) * stride);
    size_t at = 0;
    for (uint16_t k : keys) {
        const size_t bytes = size_t(library.count[k]) * stride;
        std::memcpy(out.data() + at, sorted + size_t(start[k]) * stride, bytes);
        start[k] += library.count[k];
        at += bytes;
    }
    return out;
}

}  // namespace

Status readVertices(VulkanSurface& surface, float tessFactor, std::vector<float>& vertices, std::vector<float>* limit) {
    return guarded("readVertices", [&]() -> Status {
        VulkanSurface::Impl& s = VulkanAccess::surface(surface);
        s.checkFactor(tessFactor);
        uint32_t depth = s.depthFor(tessFactor);
        vk::DeviceSize vertexBytes = vk::DeviceSize(s.vertexCountUpTo(depth)) * 12;
        vk::DeviceSize limitBytes = vk::DeviceSize(s.tables.levels[depth].stencils) * 4 * LT_LIMIT_FLOATS;
        GpuBuffer readback = s.ctx.createBuffer(vertexBytes + limitBytes, vk::BufferUsageFlagBits::eTransferDst,
                                                MemoryKind::HostVisible);
        s.ctx.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
            s.recordCompute(cmd, depth, true);
            if (vertexBytes)
                cmd.copyBuffer(*s.vertexBuffer.buffer, *readback.buffer, vk::BufferCopy(0, 0, vertexBytes));
            if (limitBytes)
                cmd.copyBuffer(*s.limitBuffer.buffer, *readback.buffer, vk::BufferCopy(0, vertexBytes, limitBytes));
            memoryBarrier(cmd, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
                          vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
        });
        const float* data = static_cast<const float*>(readback.mapped);
        vertices.assign(size_t(s.tables.totalVertices) * 3, 0.0f);
        std::memcpy(vertices.data(), data, size_t(vertexBytes));
        if (limit) limit->assign(data + vertexBytes / 4, data + (vertexBytes + limitBytes) / 4);
        return Status::ok();
    });
}

namespace {

// capture's work: into `out` whole, or (out null) each session into a soup of its own
// handed to `each`.
Status captureInto(VulkanSurface& surface, const FrameSettings& requested, Tessellation* out,
                   const CaptureSessionFn* each, DrawStats* stats, uint64_t maxSessionBytes) {
    return guarded("capture", [&]() -> Status {
        VulkanSurface::Impl& s = VulkanAccess::surface(surface);
        if (!s.ctx.transformFeedback)
            return Status::error(Status::Unsupported,
                                 "capture needs VK_EXT_transform_feedback, which the device lacks");
        FrameSettings frame = s.resolved(requested);
        const bool computed = frame.path == DrawPath::Compute;
        if (computed) frame.tangents = frame.attributes = true;  // every output of a captured vertex
        // Screen-space LOD: plan exactly from the refined vertices the draws will read
        // (the compute path draws its own plan, of the bound F, and is sized by this one).
        const DrawPlan& bound = s.planFor(frame);
        const DrawPlan* planned = &bound;
        std::optional<DrawPlan> exact;
        std::vector<uint16_t> keys;  // a sorted plan's pattern per record
        if (frame.lod.mode == LodMode::Screen) {
            std::vector<float> vertices;
            Status st = readVertices(surface, planned->tessFactor, vertices);
            if (!st) return st;
            ScreenFactorInput screen;
            screen.vertices = vertices.data();
            std::copy(frame.lod.eye, frame.lod.eye + 3, screen.eye);
            screen.scale = lodScale(frame.lod);
            exact = planned->sorted
                        ? planSortedPatternDraws(s.tables, planned->depth, planned->tessFactor, &screen, &keys)
                        : planDraws(s.tables, planned->depth, planned->tessFactor, frame.spacing,
                                    planned->maxPointsPerDraw, &screen);
            planned = &*exact;
        }
        const DrawPlan& plan = *planned;  // what the capture holds; `bound` is what the compute path draws
        const vk::DeviceSize stride = LT_CAPTURE_STRIDE;
        const vk::DeviceSize slack = 3 * stride;  // room for one unplanned triangle: detected, not clipped
        // One transform feedback session, or runs of the plan's batches, each read back
        // before the next (the sorted and compute paths draw in one).
        std::vector<DrawPlan> runs;
        std::vector<const DrawPlan*> sessions{&plan};
        if (plan.triangles() * 3 * stride + slack > maxSessionBytes) {
            // A draw is never split: one larger than a session is a session of its own.
            uint64_t draw = plan.ippTriangles;
            for (const DrawBatch& b : plan.batches) draw = std::max<uint64_t>(draw, b.triangles);
            const uint64_t bytes =
                std::max(maxSessionBytes, std::min(kMaxCaptureSessionBytes, draw * 3 * stride + slack));
            if (!computed) runs = captureSessions(plan, bytes, LT_CAPTURE_STRIDE);
            if (runs.empty())
                return Status::error(Status::Unsupported,
                                     "a capture of " + std::to_string(plan.triangles()) + " triangles needs " +
                                         std::to_string(plan.triangles() * 3 * stride + slack) +
                                         " bytes of transform feedback, more than a session's " +
                                         std::to_string(maxSessionBytes) + ", and " +
                                         (computed      ? "this path (compute) draws in one session"
                                          : plan.sorted ? "this path (sorted patterns: screen-space factors) draws in "
                                                          "one session"
                                                        : "one of its draws (or its flat triangles) alone needs more "
                                                          "than the largest session") +
                                         "; capture at a lower factor");
            sessions.clear();
            for (const DrawPlan& run : runs) sessions.push_back(&run);
        }
        vk::DeviceSize largest = 0;
        for (const DrawPlan* session : sessions) largest = std::max(largest, session->triangles() * 3 * stride);
        GpuBuffer feedback = s.ctx.createBuffer(
            largest + slack,
            vk::BufferUsageFlagBits::eTransformFeedbackBufferEXT | vk::BufferUsageFlagBits::eTransferSrc,
            MemoryKind::DeviceLocal);
        GpuBuffer counters = s.ctx.createBuffer(
            8, vk::BufferUsageFlagBits::eTransformFeedbackCounterBufferEXT | vk::BufferUsageFlagBits::eTransferSrc,
            MemoryKind::DeviceLocal);
        GpuBuffer readback =
            s.ctx.createBuffer(largest + 8, vk::BufferUsageFlagBits::eTransferDst, MemoryKind::HostVisible);
        CaptureTarget target{*feedback.buffer, largest + slack, *counters.buffer};
        GraphicsKey key{vk::Format::eUndefined, vk::Format::eUndefined, frame.spacing, frame.path, true, false,
                        frame.watertight,       s.displaceKey(frame),   s.texcoords};
        // No attachments: the capture pipelines discard rasterization.
        auto draw = [&](const vk::raii::CommandBuffer& cmd, const DrawPlan& drawn) {
            cmd.beginRendering(vk::RenderingInfo({}, vk::Rect2D({0, 0}, {1, 1}), 1, 0, {}, nullptr, nullptr));
            cmd.setViewport(0, vk::Viewport(0, 0, 1, 1, 0, 1));
            cmd.setScissor(0, vk::Rect2D({0, 0}, {1, 1}));
            s.recordDraws(cmd, drawn, key, frame, &target);
            cmd.endRendering();
        };

        // Without EvalSettings::attributes, as evaluateCpu: no texture coordinates,
        // tangents or colours (FrameSettings::attributes is the compute path's own).
        const bool attributes = static_cast<const EvalSettings&>(requested).attributes;
        auto size = [&](size_t vertices, Tessellation& soup) {
            sizeCapture(vertices, s.texcoords && attributes, s.texcoords1 && attributes, s.colors && attributes, soup);
        };
        if (out) size(plan.triangles() * 3, *out);
        Tessellation piece;  // a session's, handed to `each`
        size_t at = 0;       // the next session's first vertex in the frame's soup
        for (const DrawPlan* session : sessions) {
            const vk::DeviceSize tessBytes = session->tessTriangles * 3 * stride;
            const vk::DeviceSize bytes = session->triangles() * 3 * stride;
            s.ctx.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
                if (session == sessions.front()) {  // the refined vertices stay for the next sessions
                    s.recordCompute(cmd, plan.depth, frame.watertight);
                    if (s.compute) s.compute->recorded.reset();
                }
                if (computed) {  // batch after batch, each resuming transform feedback at the last one's counter
                    if (bound.sorted) s.recordComputePlan(cmd, bound, frame);
                    const uint32_t batches = s.computeFor(frame).batchCount(bound);
                    for (uint32_t k = 0; k < batches; ++k) {
                        s.recordComputeBatch(cmd, bound, frame, k);
                        draw(cmd, bound);
                        memoryBarrier(cmd, vk::PipelineStageFlagBits::eTransformFeedbackEXT,
                                      vk::AccessFlagBits::eTransformFeedbackCounterWriteEXT,
                                      vk::PipelineStageFlagBits::eDrawIndirect,
                                      vk::AccessFlagBits::eTransformFeedbackCounterReadEXT);
                    }
                } else {
                    if (plan.sorted) s.recordSort(cmd, plan, frame);
                    draw(cmd, *session);
                }
                memoryBarrier(cmd, vk::PipelineStageFlagBits::eTransformFeedbackEXT,
                              vk::AccessFlagBits::eTransformFeedbackWriteEXT |
                                  vk::AccessFlagBits::eTransformFeedbackCounterWriteEXT,
                              vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferRead);
                if (bytes) cmd.copyBuffer(*feedback.buffer, *readback.buffer, vk::BufferCopy(0, 0, bytes));
                cmd.copyBuffer(*counters.buffer, *readback.buffer, vk::BufferCopy(0, bytes, 8));
                memoryBarrier(cmd, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
                              vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
            });
            // Each session's counter says where it stopped: exactly where the plan says,
            // or the plan is wrong. lavapipe counts from the session's bound offset; the
            // absolute position is accepted too.
            const uint8_t* data = static_cast<const uint8_t*>(readback.mapped);
            uint32_t written[2];
            std::memcpy(written, data + bytes, 8);
            if (computed && written[0] != bytes)
                return Status::error(Status::Internal, "transform feedback of the compute path ended at byte " +
                                                           std::to_string(written[0]) + "; the plan expected " +
                                                           std::to_string(bytes));
            if (!computed && (written[0] != tessBytes || (written[1] != bytes - tessBytes && written[1] != bytes)))
                return Status::error(Status::Internal,
                                     "transform feedback ended at bytes " + std::to_string(written[0]) + " and " +
                                         std::to_string(written[1]) + "; the draw plan expected " +
                                         std::to_string(tessBytes) + " and " + std::to_string(bytes - tessBytes));
            std::vector<uint8_t> reordered;
            if (plan.sorted && !computed) {  // the compute path writes in record order already
                reordered = recordOrder(data, keys);
                reordered.insert(reordered.end(), data + tessBytes, data + bytes);  // the IPPs as they are
                data = reordered.data();
            }
            const size_t vertices = size_t(session->triangles()) * 3;
            if (out) {
                unpackCapture(data, at, vertices, *out);
            } else {
                size(vertices, piece);
                unpackCapture(data, 0, vertices, piece);
                if (Status st = (*each)(piece, at); !st) return st;
            }
            at += vertices;
        }
        if (stats) {
            *stats = drawStats(plan, true);
            stats->path = frame.path;
            if (computed) stats->batches = stats->drawCalls = s.computeFor(frame).batchCount(bound);
        }
        return Status::ok();
    });
}

}  // namespace

Status capture(VulkanSurface& surface, const FrameSettings& frame, Tessellation& out, DrawStats* stats,
               uint64_t maxSessionBytes) {
    return captureInto(surface, frame, &out, nullptr, stats, maxSessionBytes);
}

Status capture(VulkanSurface& surface, const FrameSettings& frame, const CaptureSessionFn& each, DrawStats* stats,
               uint64_t maxSessionBytes) {
    return captureInto(surface, frame, nullptr, &each, stats, maxSessionBytes);
}

}  // namespace lt
