// evaluate.comp's dispatches (see evaluate_pass.h).
#include "evaluate_pass.h"

#include "lod.h"

#include <algorithm>

namespace lt {

EvaluatePass::EvaluatePass(VulkanSurface::Impl& surface, const vk::raii::CommandBuffer& c, const FrameSettings& frame,
                           const DrawPlan& plan, vk::DescriptorSet outputs, uint32_t layout, bool tangent,
                           bool attributes)
    : cmd(c),
      s_(surface),
      plan_(plan),
      layout_(*surface.pipelines().evaluateLayout),
      vertexLayout_(layout),
      watertight_(frame.watertight),
      displace_(surface.displaceKey(frame)),
      tangent_(tangent),
      attributes_(attributes) {
    cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, layout_, 0, {*s_.descriptorSet, outputs}, {});
    pc.tessFactor = plan.tessFactor;
    pc.flags = (frame.watertight ? LT_FLAG_WATERTIGHT : 0u) | (frame.displace ? LT_FLAG_DISPLACE : 0u);
    if (plan.sorted) {  // the records' patterns as pattern_sort.comp picks them
        pc.flags |= LT_FLAG_LOD_SCREEN;
        std::copy(frame.lod.eye, frame.lod.eye + 3, pc.lod);
        pc.lod[3] = lodScale(frame.lod);
    }
}

void EvaluatePass::barrier() const {
    memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                  vk::PipelineStageFlagBits::eComputeShader,
                  vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
}

void EvaluatePass::bind(uint32_t kind) {
    cmd.bindPipeline(vk::PipelineBindPoint::eCompute,
                     s_.pipelines().evaluate(kind, watertight_, displace_, vertexLayout_, tangent_, attributes_));
}

void EvaluatePass::push() { cmd.pushConstants<PushConstants>(layout_, kAllStages, 0, pc); }

uint64_t EvaluatePass::maxThreads() const {
    return uint64_t(s_.ctx.properties.limits.maxComputeWorkGroupCount[0]) * LT_LOCAL_SIZE;
}

void EvaluatePass::dispatch(uint32_t kind, uint64_t threads) {
    bind(kind);
    pc.evaluate[3] = uint32_t(threads);
    push();
    cmd.dispatch(uint32_t((threads + LT_LOCAL_SIZE - 1) / LT_LOCAL_SIZE), 1, 1);
}

void EvaluatePass::place(uint32_t extraVertices, uint32_t extraIndices) {
    auto pushNow = [&] { push(); };
    if (plan_.sorted) {  // each record's key and the chunks' sizes
        bind(LT_EVALUATE_SORTED_KEYS);
        s_.dispatchChunks(cmd, plan_, pc, pushNow);
        barrier();
    }
    pc.evaluate[0] = extraVertices;  // the chunks' first outputs and the counts
    pc.evaluate[1] = extraIndices;
    pc.evaluate[3] = plan_.sorted ? plan_.sortChunks : 0;
    bind(LT_EVALUATE_SORTED_SCAN);
    push();
    cmd.dispatch(1, 1, 1);
    if (!plan_.sorted) return;
    barrier();  // where each record's output starts
    bind(LT_EVALUATE_SORTED_PLACE);
    s_.dispatchChunks(cmd, plan_, pc, pushNow);
    barrier();
}

void EvaluatePass::sortedRecords() {
    bind(LT_EVALUATE_SORTED_RECORDS);
    const uint32_t most = s_.ctx.properties.limits.maxComputeWorkGroupCount[0];
    for (uint64_t first = 0; first < plan_.patches; first += most) {
        pc.evaluate[2] = uint32_t(first);
        push();
        cmd.dispatch(uint32_t(std::min<uint64_t>(most, plan_.patches - first)), 1, 1);
    }
}

void EvaluatePass::patternRecords(uint32_t listOffset, uint32_t first, uint32_t records, uint32_t n, uint64_t vertex,
                                  uint64_t index) {
    const uint32_t points = patternPoints(n);
    pc.base = listOffset;
    pc.level = n;
    // Whole records per dispatch, as many as keep both kinds within maxThreads.
    const uint64_t perDispatch = std::max<uint64_t>(maxThreads() / std::max(points, n * n), 1);
    for (uint32_t r = 0; r < records; r += uint32_t(perDispatch)) {
        const uint32_t count = uint32_t(std::min<uint64_t>(perDispatch, records - r));
        pc.evaluate[0] = uint32_t(vertex);
        pc.evaluate[1] = uint32_t(index);
        pc.evaluate[2] = first + r;
        dispatch(LT_EVALUATE_PATTERN_POINTS, uint64_t(count) * points);
        dispatch(LT_EVALUATE_PATTERN_INDICES, uint64_t(count) * n * n);
        vertex += uint64_t(count) * points;
        index += 3 * uint64_t(count) * n * n;
    }
}

void EvaluatePass::ippCorners(uint32_t first, uint32_t count, uint64_t vertex, uint64_t index) {
    pc.level = plan_.ippLevel;
    for (uint64_t corner = 0; corner < count; corner += maxThreads()) {
        pc.evaluate[0] = uint32_t(vertex + corner);  // corner c's vertex and index are both first + c
        pc.evaluate[1] = uint32_t(index + corner);
        pc.evaluate[2] = uint32_t(first + corner);  // the dispatch's first IPP corner
        dispatch(LT_EVALUATE_IPPS, std::min<uint64_t>(maxThreads(), count - corner));
    }
}

}  // namespace lt
