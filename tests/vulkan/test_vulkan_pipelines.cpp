// tests/vulkan/test_vulkan_pipelines.cpp -- an application's own pipelines around the
// surface (looptess/vulkan.h, "An application's own pipelines"): its fragment shader
// (tests/vulkan/shaders/texcoord_color.frag: colour = TEXCOORD_0), its pipeline layout and
// pipelines built from surfaceStages, drawn by renderImage through them. The image
// covers the pixels of looptess's own pipelines, and its colours are texture
// coordinates: blue 0, red and green over many levels. (That the draw's TEXCOORD_0
// is the CPU evaluator's, bit for bit, test_vulkan_capture.cpp checks.)
#include "test_vulkan_support.h"

#include "tangent_color_frag.h"   // generated: lt_test_spv_tangent_color_frag
#include "texcoord_color_frag.h"  // generated: lt_test_spv_texcoord_color_frag

#include <vulkan/vulkan.h>

#include <array>
#include <cmath>
#include <set>
#include <vector>

namespace lt::test {
namespace {

struct AppPipelines {
    VkDevice device = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::vector<VkShaderModule> modules;
    VkPipeline patches = VK_NULL_HANDLE, ipps = VK_NULL_HANDLE;
    ~AppPipelines() { reset(); }
    void reset() {
        if (!device) return;
        vkDestroyPipeline(device, patches, nullptr);
        vkDestroyPipeline(device, ipps, nullptr);
        for (VkShaderModule m : modules) vkDestroyShaderModule(device, m, nullptr);
        vkDestroyPipelineLayout(device, layout, nullptr);
        modules.clear();
        patches = ipps = VK_NULL_HANDLE;
        layout = VK_NULL_HANDLE;
    }
};

VkShaderModule module(AppPipelines& p, const uint32_t* code, size_t bytes) {
    auto info = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule m = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateShaderModule(p.device, &info, nullptr, &m), VK_SUCCESS);
    p.modules.push_back(m);
    return m;
}

// What an engine does once per material: a layout with set 0 and the push constants
// of looptess, and the two pipelines with its fragment shader `code` (SPIR-V);
// `tangent`: the shader reads the tangent and the base face (kSpecTangent,
// kSpecAttributes).
template <size_t N>
void build(VulkanContext& gpu, const VulkanSurface& surface, const FrameSettings& frame, const uint32_t (&code)[N],
           bool tangent, AppPipelines& p) {
    const bool patterns = frame.path == DrawPath::Patterns;  // patternVertex, no tessellation stages
    const bool computed = frame.path == DrawPath::Compute;   // computeVertex, no IPP pipeline
    p.device = gpu.handles().device;
    const VkDescriptorSetLayout set0 = gpu.surfaceSetLayout();
    const VkPushConstantRange range = gpu.surfacePushConstants();
    auto layoutInfo = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &set0;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    VK_OK(vkCreatePipelineLayout(p.device, &layoutInfo, nullptr, &p.layout));

    const SurfaceStages stages = surfaceStages(frame.spacing);
    VulkanSurface::Specialization values = surface.specialization(frame);
    values.tangent = values.attributes = tangent;
    const std::array<VkSpecializationMapEntry, 4> entries = {
        VkSpecializationMapEntry{kSpecWatertight, offsetof(VulkanSurface::Specialization, watertight),
                                 sizeof(VkBool32)},
        VkSpecializationMapEntry{kSpecDisplace, offsetof(VulkanSurface::Specialization, displace), sizeof(VkBool32)},
        VkSpecializationMapEntry{kSpecTangent, offsetof(VulkanSurface::Specialization, tangent), sizeof(VkBool32)},
        VkSpecializationMapEntry{kSpecAttributes, offsetof(VulkanSurface::Specialization, attributes),
                                 sizeof(VkBool32)}};
    const VkSpecializationInfo specialization{4, entries.data(), sizeof values, &values};
    const VkShaderModule fragment = module(p, code, sizeof code);
    auto stage = [&](VkShaderStageFlagBits s, VkShaderModule m) {
        auto info = vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
        info.stage = s;
        info.module = m;
        info.pName = "main";
        info.pSpecializationInfo = &specialization;
        return info;
    };
    const DrawTarget formats = imageFormats(gpu);
    for (bool tessellated : {true, false}) {
        if (computed && !tessellated) break;
        std::vector<VkPipelineShaderStageCreateInfo> list;
        if (computed) {
            list.push_back(
                stage(VK_SHADER_STAGE_VERTEX_BIT, module(p, stages.computeVertex.code, stages.computeVertex.bytes)));
        } else if (tessellated && patterns) {
            list.push_back(
                stage(VK_SHADER_STAGE_VERTEX_BIT, module(p, stages.patternVertex.code, stages.patternVertex.bytes)));
        } else if (tessellated) {
            list.push_back(
                stage(VK_SHADER_STAGE_VERTEX_BIT, module(p, stages.patchVertex.code, stages.patchVertex.bytes)));
            list.push_back(stage(VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT,
                                 module(p, stages.patchControl.code, stages.patchControl.bytes)));
            list.push_back(stage(VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT,
                                 module(p, stages.patchEvaluation.code, stages.patchEvaluation.bytes)));
        } else {
            list.push_back(stage(VK_SHADER_STAGE_VERTEX_BIT, module(p, stages.ippVertex.code, stages.ippVertex.bytes)));
        }
        list.push_back(stage(VK_SHADER_STAGE_FRAGMENT_BIT, fragment));
        auto vertexInput =
            vkStruct<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
        auto assembly = vkStruct<VkPipelineInputAssemblyStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
        assembly.topology = tessellated && !patterns && !computed ? VK_PRIMITIVE_TOPOLOGY_PATCH_LIST
                                                                  : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        auto tessellation =
            vkStruct<VkPipelineTessellationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO);
        tessellation.patchControlPoints = 12;
        auto viewport =
            vkStruct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
        viewport.viewportCount = viewport.scissorCount = 1;
        auto raster = vkStruct<VkPipelineRasterizationStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
        raster.cullMode = VK_CULL_MODE_NONE;
        raster.lineWidth = 1.0f;
        auto multisample =
            vkStruct<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
        multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        auto depth =
            vkStruct<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
        depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
        depth.depthCompareOp = VK_COMPARE_OP_LESS;
        VkPipelineColorBlendAttachmentState attachment{};
        attachment.colorWriteMask = 0xF;
        auto blend =
            vkStruct<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
        blend.attachmentCount = 1;
        blend.pAttachments = &attachment;
        const std::array<VkDynamicState, 2> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        auto dynamicState =
            vkStruct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
        dynamicState.dynamicStateCount = uint32_t(dynamic.size());
        dynamicState.pDynamicStates = dynamic.data();
        auto rendering = vkStruct<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
        rendering.colorAttachmentCount = 1;
        rendering.pColorAttachmentFormats = &formats.color;
        rendering.depthAttachmentFormat = formats.depth;
        auto info = vkStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
        info.pNext = &rendering;
        info.stageCount = uint32_t(list.size());
        info.pStages = list.data();
        info.pVertexInputState = &vertexInput;
        info.pInputAssemblyState = &assembly;
        info.pTessellationState = tessellated && !patterns && !computed ? &tessellation : nullptr;
        info.pViewportState = &viewport;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pDepthStencilState = &depth;
        info.pColorBlendState = &blend;
        info.pDynamicState = &dynamicState;
        info.layout = p.layout;
        VK_OK(
            vkCreateGraphicsPipelines(p.device, VK_NULL_HANDLE, 1, &info, nullptr, tessellated ? &p.patches : &p.ipps));
    }
}

// An orthographic view down -z that fits the control points into the image.
void fit(const Asset& asset, FrameSettings& frame) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (size_t i = 0; i < asset.positions.size(); ++i)
        lo[i % 3] = std::min(lo[i % 3], asset.positions[i]), hi[i % 3] = std::max(hi[i % 3], asset.positions[i]);
    const float s = 1.8f / std::max(hi[0] - lo[0], hi[1] - lo[1]), z = 0.8f / std::max(hi[2] - lo[2], 1e-6f);
    const float m[16] = {s,
                         0,
                         0,
                         0,
                         0,
                         -s,
                         0,
                         0,
                         0,
                         0,
                         -z,
                         0,
                         -s * (lo[0] + hi[0]) / 2,
                         s * (lo[1] + hi[1]) / 2,
                         0.5f + z * (lo[2] + hi[2]) / 2,
                         1};
    std::copy(m, m + 16, frame.mvp);
}

// spot at F = 8 in 96 x 96, drawn by looptess's own pipelines (level colours: every
// drawn pixel shows on black) into `ours` and by the application's, with fragment
// shader `code` (`tangent`: it reads the tangent), into `theirs`.
class VulkanPipelines : public VulkanTest {
protected:
    template <size_t N>
    void drawBoth(const uint32_t (&code)[N], bool tangent, Image& ours, Image& theirs, RenderSettings* mine = nullptr,
                  DrawPath path = DrawPath::Tessellator) {
        const Baked* b = baked(corpusMesh("spot.obj"), 3);
        ASSERT_NE(b, nullptr);
        ASSERT_FALSE(b->asset.faceUVs.empty());
        surface_ = upload(*b);
        ASSERT_NE(surface_, nullptr);
        RenderSettings own;
        own.width = own.height = 96;
        own.frame.tessFactor = 8;
        own.background[0] = own.background[1] = own.background[2] = own.background[3] = 0.0f;
        own.frame.coloring = Coloring::Levels;
        own.frame.path = path;
        own.frame.tangents = own.frame.attributes = tangent;  // what the compute path evaluates
        fit(b->asset, own.frame);
        app_.reset();
        build(*gpu, *surface_, own.frame, code, tangent, app_);
        ASSERT_NE(app_.patches, VK_NULL_HANDLE);
        RenderSettings theirSettings = own;
        theirSettings.pipelines = SurfacePipelines{app_.patches, app_.ipps, app_.layout};
        ASSERT_TRUE(renderImage(*surface_, own, ours));
        ASSERT_TRUE(renderImage(*surface_, theirSettings, theirs));
        if (mine) *mine = theirSettings;
    }
    std::unique_ptr<VulkanSurface> surface_;
    AppPipelines app_;
};

TEST_F(VulkanPipelines, AnApplicationsFragmentShaderReadsTheSurfacesTexcoords) {
    Image ours, theirs;
    RenderSettings mine;
    drawBoth(lt_test_spv_texcoord_color_frag, false, ours, theirs, &mine);
    ASSERT_FALSE(HasFatalFailure());

    // Same coverage (the same vertex stages and depth test), colours from TEXCOORD_0:
    // blue 0, red and green spread over the texture's range.
    size_t drawn = 0, coverageDiffers = 0, blue = 0;
    std::set<int> reds, greens;
    for (size_t i = 0; i < ours.rgba.size(); i += 4) {
        const bool a = ours.rgba[i] || ours.rgba[i + 1] || ours.rgba[i + 2];
        const bool c = theirs.rgba[i] || theirs.rgba[i + 1];
        coverageDiffers += a != c;
        if (!c) continue;
        ++drawn;
        blue += theirs.rgba[i + 2] != 0;
        reds.insert(theirs.rgba[i]);
        greens.insert(theirs.rgba[i + 1]);
    }
    EXPECT_GT(drawn, 96u * 96u / 10);
    EXPECT_LE(coverageDiffers, drawn / 200) << "pixels drawn by one pipeline and not the other";
    EXPECT_EQ(blue, 0u);
    EXPECT_GT(reds.size(), 64u);
    EXPECT_GT(greens.size(), 64u);

    // A layout-less set is a usage error, not a crash.
    RenderSettings broken = mine;
    broken.pipelines.layout = VK_NULL_HANDLE;
    broken.pipelines.patches = app_.patches;
    Image none;
    const Status st = renderImage(*surface_, broken, none);
    EXPECT_FALSE(st);
    std::printf(
        "[ figures  ] application pipelines: %zu pixels drawn, %zu red and %zu green levels, %zu coverage "
        "differences\n",
        drawn, reds.size(), greens.size(), coverageDiffers);
}

// The tangent (kSpecTangent) and the flat base face through an application's
// shader: the same coverage, unit tangents (interpolated between nearly parallel
// ones) in many directions, and many faces.
TEST_F(VulkanPipelines, AnApplicationsFragmentShaderReadsTangentsAndFaces) {
    Image ours, theirs;
    drawBoth(lt_test_spv_tangent_color_frag, true, ours, theirs);
    ASSERT_FALSE(HasFatalFailure());
    size_t drawn = 0, coverageDiffers = 0, unit = 0;
    std::set<int> directions, faces;
    for (size_t i = 0; i < ours.rgba.size(); i += 4) {
        const bool a = ours.rgba[i] || ours.rgba[i + 1] || ours.rgba[i + 2];
        const bool c = theirs.rgba[i] || theirs.rgba[i + 1] || theirs.rgba[i + 2];
        coverageDiffers += a != c;
        if (!c) continue;
        ++drawn;
        double t[3], len = 0;
        for (int k = 0; k < 3; ++k) {
            t[k] = theirs.rgba[i + size_t(k)] / 127.5 - 1.0;
            len += t[k] * t[k];
        }
        unit += std::fabs(std::sqrt(len) - 1.0) < 0.03;
        directions.insert(theirs.rgba[i] / 32 * 64 + theirs.rgba[i + 1] / 32 * 8 + theirs.rgba[i + 2] / 32);
        faces.insert(theirs.rgba[i + 3]);
    }
    EXPECT_GT(drawn, 96u * 96u / 10);
    EXPECT_LE(coverageDiffers, drawn / 200) << "pixels drawn by one pipeline and not the other";
    EXPECT_GE(unit, drawn * 99 / 100) << "tangents of unit length";
    EXPECT_GT(directions.size(), 20u);
    EXPECT_GT(faces.size(), 100u);
    std::printf(
        "[ figures  ] tangents through an application's shader: %zu pixels, %zu of unit length, %zu "
        "direction cells, %zu face values\n",
        drawn, unit, directions.size(), faces.size());
}

// The vertex stage of the pattern path (SurfaceStages::patternVertex) and of the
// compute path (computeVertex) in an application's pipeline, with a fragment shader
// reading TEXCOORD_0 (parameter 0), or the tangent and base face (1: the compute
// frame then evaluates them): each covers the pixels of looptess's own pipelines, and
// the two paths, which draw the same triangles with the same vertex bits, give the
// same image.
class VulkanPipelinePaths : public VulkanPipelines, public ::testing::WithParamInterface<int> {};

TEST_P(VulkanPipelinePaths, PatternAndComputePathsDrawTheSameImage) {
    const bool tangent = GetParam() == 1;
    Image images[2];
    for (DrawPath path : {DrawPath::Patterns, DrawPath::Compute}) {
        SCOPED_TRACE(path == DrawPath::Patterns ? "patterns" : "compute");
        Image ours, &theirs = images[path == DrawPath::Compute];
        if (tangent)
            drawBoth(lt_test_spv_tangent_color_frag, true, ours, theirs, nullptr, path);
        else
            drawBoth(lt_test_spv_texcoord_color_frag, false, ours, theirs, nullptr, path);
        ASSERT_FALSE(HasFatalFailure());
        size_t drawn = 0, coverageDiffers = 0;
        for (size_t i = 0; i < ours.rgba.size(); i += 4) {
            const bool a = ours.rgba[i] || ours.rgba[i + 1] || ours.rgba[i + 2];
            const bool c = theirs.rgba[i] || theirs.rgba[i + 1] || theirs.rgba[i + 2];
            coverageDiffers += a != c;
            drawn += c;
        }
        EXPECT_GT(drawn, 96u * 96u / 10);
        EXPECT_LE(coverageDiffers, drawn / 200) << "pixels drawn by one pipeline and not the other";
    }
    EXPECT_TRUE(images[0].rgba == images[1].rgba) << "the compute path's image differs from the pattern path's";
}
INSTANTIATE_TEST_SUITE_P(Shaders, VulkanPipelinePaths, ::testing::Values(0, 1));

}  // namespace
}  // namespace lt::test
