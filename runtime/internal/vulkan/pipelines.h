// Private to looptess_vulkan: the descriptor set layout, pipeline layout and
// pipelines, built from the embedded SPIR-V (shaders/). One set per context, shared
// by its surfaces; graphics pipelines are built on first use per attachment formats.
#pragma once

#include "context.h"
#include "gpu_layout.h"

#include <cstddef>
#include <map>
#include <tuple>

namespace lt {

// The push constant block of every shader (shaders/common.glsl).
struct PushConstants {
    float mvp[16] = {};
    float light[4] = {};
    float tessFactor = 1.0f;
    uint32_t level = 0;
    uint32_t base = 0;
    uint32_t flags = 0;
    float lod[4] = {};
    uint32_t evaluate[4] = {};  // evaluate.comp (recordEvaluate)
};
static_assert(sizeof(PushConstants) == LT_PUSH_CONSTANT_SIZE, "push constants as in common.glsl");
static_assert(offsetof(PushConstants, tessFactor) == 80 && offsetof(PushConstants, base) == 88, "std430 offsets");

constexpr vk::ShaderStageFlags kAllStages = vk::ShaderStageFlagBits::eAllGraphics | vk::ShaderStageFlagBits::eCompute;

// Which graphics pipeline: attachment formats (eUndefined: none), spacing, whether
// it captures by transform feedback (then rasterization is off), polygon mode, and
// which features the shaders keep (the rest is compiled out).
struct GraphicsKey {
    vk::Format color = vk::Format::eUndefined;
    vk::Format depth = vk::Format::eUndefined;
    Spacing spacing = Spacing::Equal;
    DrawPath path = DrawPath::Tessellator;  // of the patches pipeline (IPPs: always Tessellator)
    bool capture = false;
    bool wireframe = false;
    bool watertight = true;  // specialization constants (common.glsl's kSpec*)
    bool displace = true;
    bool tangent = false;
    // kSpecAttributes: DrawPath::Compute's vertex layout (FrameSettings::attributes);
    // off elsewhere (captures write those outputs anyway).
    bool attributes = false;
    bool operator<(const GraphicsKey& o) const {
        return std::tie(color, depth, spacing, path, capture, wireframe, watertight, displace, tangent, attributes) <
               std::tie(o.color, o.depth, o.spacing, o.path, o.capture, o.wireframe, o.watertight, o.displace,
                        o.tangent, o.attributes);
    }
};

class Pipelines {
public:
    explicit Pipelines(VulkanContext::Impl& context);

    vk::raii::DescriptorSetLayout setLayout{nullptr};
    vk::raii::PipelineLayout layout{nullptr};
    vk::raii::Pipeline vertexPoints{nullptr}, edgePoints{nullptr}, edits{nullptr}, limit{nullptr};
    // The watertight pass (gpu_layout.h): point sources, normal sources.
    vk::raii::Pipeline watertightPoints{nullptr}, watertightNormals{nullptr}, watertightRoots{nullptr};
    vk::raii::Pipeline patternSort{nullptr};  // pattern_sort.comp

    // Regular patches (through the tessellator, as patterns, or DrawPath::Compute's
    // evaluated vertices: key.path), and IPP triangles.
    vk::Pipeline patches(const GraphicsKey& key);
    vk::Pipeline ipps(const GraphicsKey& key);

    void push(const vk::raii::CommandBuffer& cmd, const PushConstants& pc) const;

    // evaluate.comp (recordEvaluate, DrawPath::Compute): set 1 holds the output
    // vertex, index and count buffers, the context's pattern table and a PLACE;
    // `kind` an LT_EVALUATE_*, `layout` an LT_LAYOUT_* (with `tangent` and
    // `attributes`, the vertex it writes); built on first use.
    vk::raii::DescriptorSetLayout evaluateSetLayout{nullptr};
    vk::raii::PipelineLayout evaluateLayout{nullptr};
    vk::Pipeline evaluate(uint32_t kind, bool watertight, bool displace, uint32_t layout = LT_LAYOUT_APPLICATION,
                          bool tangent = true, bool attributes = false);

private:
    vk::raii::Pipeline compute(const uint32_t* code, size_t bytes);
    // `stage`: the patches' path, or nothing (IPPs).
    vk::raii::Pipeline graphics(const GraphicsKey& key, bool patches);

    VulkanContext::Impl& context_;
    std::map<GraphicsKey, vk::raii::Pipeline> patches_, ipps_;
    std::map<std::tuple<uint32_t, bool, bool, uint32_t, bool, bool>, vk::raii::Pipeline> evaluate_;
};

}  // namespace lt
