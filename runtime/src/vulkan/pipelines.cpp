// Pipelines of the Vulkan path (see pipelines.h).
#include "vulkan/pipelines.h"

#include "looptess_spirv.h"

#include <array>
#include <vector>

namespace lt {
namespace {

struct Spirv {
    const uint32_t* code;
    size_t bytes;
};
#define LT_SPIRV(name) \
    Spirv { lt_spv_##name, sizeof(lt_spv_##name) }

vk::raii::ShaderModule shaderModule(const vk::raii::Device& device, Spirv s) {
    return vk::raii::ShaderModule(device, vk::ShaderModuleCreateInfo({}, s.bytes, s.code));
}

Spirv evaluationShader(const GraphicsKey& key) {
    bool odd = key.spacing == Spacing::FractionalOdd;
    if (key.capture) return odd ? LT_SPIRV(patch_tese_odd_capture) : LT_SPIRV(patch_tese_equal_capture);
    return odd ? LT_SPIRV(patch_tese_odd) : LT_SPIRV(patch_tese_equal);
}

}  // namespace

SurfaceStages surfaceStages(Spacing spacing) {
    auto module = [](Spirv s) { return SpirvModule{s.code, s.bytes}; };
    SurfaceStages out;
    out.patchVertex = module(LT_SPIRV(patch_vert));
    out.patchControl = module(LT_SPIRV(patch_tesc));
    GraphicsKey key;
    key.spacing = spacing;
    out.patchEvaluation = module(evaluationShader(key));
    out.ippVertex = module(LT_SPIRV(ipp_vert));
    out.patternVertex = module(LT_SPIRV(pattern_vert));
    out.computeVertex = module(LT_SPIRV(compute_vert));
    return out;
}

Pipelines::Pipelines(VulkanContext::Impl& context) : context_(context) {
    const vk::raii::Device& device = context.device;
    std::array<vk::DescriptorSetLayoutBinding, 4> bindings;
    const uint32_t numbers[4] = {LT_BINDING_TABLES, LT_BINDING_VERTICES, LT_BINDING_LIMIT, LT_BINDING_DRAW};
    for (int i = 0; i < 4; ++i) bindings[i] = {numbers[i], vk::DescriptorType::eStorageBuffer, 1, kAllStages};
    setLayout = vk::raii::DescriptorSetLayout(device, vk::DescriptorSetLayoutCreateInfo({}, bindings));
    vk::PushConstantRange range(kAllStages, 0, sizeof(PushConstants));
    layout = vk::raii::PipelineLayout(device, vk::PipelineLayoutCreateInfo({}, *setLayout, range));
    vertexPoints = compute(lt_spv_subdivide_vertices, sizeof lt_spv_subdivide_vertices);
    edgePoints = compute(lt_spv_subdivide_edges, sizeof lt_spv_subdivide_edges);
    edits = compute(lt_spv_apply_edits, sizeof lt_spv_apply_edits);
    limit = compute(lt_spv_limit, sizeof lt_spv_limit);
    watertightPoints = compute(lt_spv_watertight_points, sizeof lt_spv_watertight_points);
    watertightNormals = compute(lt_spv_watertight_normals, sizeof lt_spv_watertight_normals);
    watertightRoots = compute(lt_spv_watertight_roots, sizeof lt_spv_watertight_roots);
    patternSort = compute(lt_spv_pattern_sort, sizeof lt_spv_pattern_sort);
    std::array<vk::DescriptorSetLayoutBinding, 5> outputs;  // evaluate.comp's set 1
    for (uint32_t i = 0; i < 5; ++i)
        outputs[i] =
            vk::DescriptorSetLayoutBinding{i, vk::DescriptorType::eStorageBuffer, 1, vk::ShaderStageFlagBits::eCompute};
    evaluateSetLayout = vk::raii::DescriptorSetLayout(device, vk::DescriptorSetLayoutCreateInfo({}, outputs));
    const std::array<vk::DescriptorSetLayout, 2> sets = {*setLayout, *evaluateSetLayout};
    evaluateLayout = vk::raii::PipelineLayout(device, vk::PipelineLayoutCreateInfo({}, sets, range));
}

vk::Pipeline Pipelines::evaluate(uint32_t kind, bool watertight, bool displace, uint32_t layout, bool tangent,
                                 bool attributes) {
    auto key = std::make_tuple(kind, watertight, displace, layout, tangent, attributes);
    auto it = evaluate_.find(key);
    if (it != evaluate_.end()) return *it->second;
    const uint32_t values[6] = {watertight, displace, tangent, attributes, kind, layout};
    std::array<vk::SpecializationMapEntry, 6> entries;
    const uint32_t ids[6] = {LT_SPEC_WATERTIGHT, LT_SPEC_DISPLACE,      LT_SPEC_TANGENT,
                             LT_SPEC_ATTRIBUTES, LT_SPEC_EVALUATE_KIND, LT_SPEC_EVALUATE_LAYOUT};
    for (uint32_t i = 0; i < 6; ++i) entries[i] = vk::SpecializationMapEntry(ids[i], 4 * i, 4);
    vk::SpecializationInfo specialization(entries, vk::ArrayProxyNoTemporaries<const uint32_t>(values));
    vk::raii::ShaderModule module = shaderModule(context_.device, LT_SPIRV(evaluate));
    vk::ComputePipelineCreateInfo info({}, {{}, vk::ShaderStageFlagBits::eCompute, *module, "main", &specialization},
                                       *evaluateLayout);
    return *evaluate_.emplace(key, vk::raii::Pipeline(context_.device, nullptr, info)).first->second;
}

vk::raii::Pipeline Pipelines::compute(const uint32_t* code, size_t bytes) {
    vk::raii::ShaderModule module = shaderModule(context_.device, {code, bytes});
    vk::ComputePipelineCreateInfo info({}, {{}, vk::ShaderStageFlagBits::eCompute, *module, "main"}, *layout);
    return vk::raii::Pipeline(context_.device, nullptr, info);
}

vk::Pipeline Pipelines::patches(const GraphicsKey& key) {
    auto it = patches_.find(key);
    if (it == patches_.end()) it = patches_.emplace(key, graphics(key, true)).first;
    return *it->second;
}

vk::Pipeline Pipelines::ipps(const GraphicsKey& key) {
    GraphicsKey k = key;
    k.spacing = Spacing::Equal;  // no tessellator
    k.path = DrawPath::Tessellator;
    auto it = ipps_.find(k);
    if (it == ipps_.end()) it = ipps_.emplace(k, graphics(k, false)).first;
    return *it->second;
}

vk::raii::Pipeline Pipelines::graphics(const GraphicsKey& key, bool patches) {
    const bool tessellated = patches && key.path == DrawPath::Tessellator;
    const vk::raii::Device& device = context_.device;
    std::vector<vk::raii::ShaderModule> modules;
    std::vector<vk::PipelineShaderStageCreateInfo> stages;
    const VkBool32 features[4] = {key.watertight, key.displace, key.tangent, key.attributes};
    const std::array<vk::SpecializationMapEntry, 4> entries = {
        vk::SpecializationMapEntry(LT_SPEC_WATERTIGHT, 0, sizeof(VkBool32)),
        vk::SpecializationMapEntry(LT_SPEC_DISPLACE, sizeof(VkBool32), sizeof(VkBool32)),
        vk::SpecializationMapEntry(LT_SPEC_TANGENT, 2 * sizeof(VkBool32), sizeof(VkBool32)),
        vk::SpecializationMapEntry(LT_SPEC_ATTRIBUTES, 3 * sizeof(VkBool32), sizeof(VkBool32))};
    vk::SpecializationInfo specialization(entries, vk::ArrayProxyNoTemporaries<const VkBool32>(features));
    auto stage = [&](vk::ShaderStageFlagBits s, Spirv code) {
        modules.push_back(shaderModule(device, code));
        stages.push_back({{}, s, *modules.back(), "main", &specialization});
    };
    if (tessellated) {
        stage(vk::ShaderStageFlagBits::eVertex, LT_SPIRV(patch_vert));
        stage(vk::ShaderStageFlagBits::eTessellationControl, LT_SPIRV(patch_tesc));
        stage(vk::ShaderStageFlagBits::eTessellationEvaluation, evaluationShader(key));
    } else if (patches && key.path == DrawPath::Compute) {
        stage(vk::ShaderStageFlagBits::eVertex, key.capture ? LT_SPIRV(compute_vert_capture) : LT_SPIRV(compute_vert));
    } else if (patches) {
        stage(vk::ShaderStageFlagBits::eVertex, key.capture ? LT_SPIRV(pattern_vert_capture) : LT_SPIRV(pattern_vert));
    } else {
        stage(vk::ShaderStageFlagBits::eVertex, key.capture ? LT_SPIRV(ipp_vert_capture) : LT_SPIRV(ipp_vert));
    }
    if (!key.capture) stage(vk::ShaderStageFlagBits::eFragment, LT_SPIRV(shade_frag));

    vk::PipelineVertexInputStateCreateInfo vertexInput;  // shaders pull from storage buffers
    vk::PipelineInputAssemblyStateCreateInfo assembly(
        {}, tessellated ? vk::PrimitiveTopology::ePatchList : vk::PrimitiveTopology::eTriangleList);
    // 12 control points a patch; Vulkan's default upper-left domain origin (patch.tese).
    vk::PipelineTessellationStateCreateInfo tessellation({}, 12);
    vk::PipelineViewportStateCreateInfo viewport({}, 1, nullptr, 1, nullptr);
    vk::PipelineRasterizationStateCreateInfo raster(
        {}, VK_FALSE, key.capture ? VK_TRUE : VK_FALSE, key.wireframe ? vk::PolygonMode::eLine : vk::PolygonMode::eFill,
        vk::CullModeFlagBits::eNone, vk::FrontFace::eCounterClockwise, VK_FALSE, 0, 0, 0, 1.0f);
    vk::PipelineMultisampleStateCreateInfo multisample({}, vk::SampleCountFlagBits::e1);
    bool depth = key.depth != vk::Format::eUndefined;
    vk::PipelineDepthStencilStateCreateInfo depthStencil({}, depth, depth, vk::CompareOp::eLess);
    vk::PipelineColorBlendAttachmentState blend;
    blend.colorWriteMask = vk::ColorComponentFlagBits::eR | vk::ColorComponentFlagBits::eG |
                           vk::ColorComponentFlagBits::eB | vk::ColorComponentFlagBits::eA;
    bool color = key.color != vk::Format::eUndefined;
    vk::PipelineColorBlendStateCreateInfo blendState({}, VK_FALSE, vk::LogicOp::eCopy, color ? 1 : 0, &blend);
    std::array<vk::DynamicState, 2> dynamic = {vk::DynamicState::eViewport, vk::DynamicState::eScissor};
    vk::PipelineDynamicStateCreateInfo dynamicState({}, dynamic);
    vk::PipelineRenderingCreateInfo rendering(0, color ? 1 : 0, &key.color, key.depth, vk::Format::eUndefined);

    vk::GraphicsPipelineCreateInfo info({}, stages, &vertexInput, &assembly, tessellated ? &tessellation : nullptr,
                                        &viewport, &raster, &multisample, &depthStencil, &blendState, &dynamicState,
                                        *layout, nullptr, 0, nullptr, -1, &rendering);
    return vk::raii::Pipeline(device, nullptr, info);
}

void Pipelines::push(const vk::raii::CommandBuffer& cmd, const PushConstants& pc) const {
    cmd.pushConstants<PushConstants>(*layout, kAllStages, 0, pc);
}

}  // namespace lt
