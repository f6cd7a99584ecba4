// Private to looptess_vulkan: the dispatches of shaders/evaluate.comp, which
// evaluate the pattern path's points in compute passes into an output bound as its
// descriptor set 1 (outputs, counts, the pattern table, PLACE): recordEvaluate's (the
// application's buffers, evaluate.cpp) and DrawPath::Compute's (the surface's batch
// buffer, compute_path.cpp). evaluate.comp's header says what each kind does.
#pragma once

#include "surface.h"

namespace lt {

class EvaluatePass {
public:
    // Binds set 0 (the surface's) and `outputs` (set 1) to the evaluation layout and
    // sets the push constants of `frame` (factor, flags, eye); `layout`, `tangent`,
    // `attributes`: the vertex the outputs take (gpu_layout.h's LT_LAYOUT_*).
    EvaluatePass(VulkanSurface::Impl& surface, const vk::raii::CommandBuffer& cmd, const FrameSettings& frame,
                 const DrawPlan& plan, vk::DescriptorSet outputs, uint32_t layout, bool tangent, bool attributes);

    // Compute writes before, compute reads and writes after.
    void barrier() const;

    // At screen-space factors (a sorted plan): each record's pattern key (KEYS), the
    // chunks' first outputs and the frame's counts (SCAN; `extra` vertices and indices
    // besides the patterns'), each record's first outputs (PLACE) in PLACE; barriers
    // between and after. With a plan of global factors only SCAN's counts, of
    // `extra` (the whole frame's sizes then).
    void place(uint32_t extraVertices, uint32_t extraIndices);
    // Global factors: `records` records of the list at `listOffset` from `first`, each
    // an instance of the uniform pattern of n segments a side, their points from
    // output vertex `vertex`, their triangles from output index `index`.
    void patternRecords(uint32_t listOffset, uint32_t first, uint32_t records, uint32_t n, uint64_t vertex,
                        uint64_t index);
    // IPP corners [first, first + count) of the frame's depth, from output vertex and
    // index `vertex` and `index` (at screen-space factors after PLACE's totals).
    void ippCorners(uint32_t first, uint32_t count, uint64_t vertex, uint64_t index);
    // Screen-space factors, after place(): every record, where PLACE says.
    void sortedRecords();

    // evaluate.comp's push constants, for kinds the surface's own code dispatches.
    PushConstants pc;
    void bind(uint32_t kind);
    void push();
    // A dispatch of `threads` threads of `kind` (at most maxThreads()).
    void dispatch(uint32_t kind, uint64_t threads);
    uint64_t maxThreads() const;
    const vk::raii::CommandBuffer& cmd;

private:
    VulkanSurface::Impl& s_;
    const DrawPlan& plan_;
    vk::PipelineLayout layout_;
    uint32_t vertexLayout_;
    bool watertight_, displace_, tangent_, attributes_;
};

}  // namespace lt
