// looprender's Vulkan objects (see scene_vk.h).
#include "scene_vk.h"

#include "looptess/tools/vulkan_tools.h"

#include <array>
#include <cstddef>

namespace looprender {

lt::Status VkFailure::status() const {
    return lt::Status::error(lt::Status::Internal, call + " failed (VkResult " + std::to_string(int(result)) + ")");
}

void vkCheck(VkResult r, const char* call) {
    if (r != VK_SUCCESS) throw VkFailure{call, r};
}

Device::Device(const lt::VulkanHandles& h)
    : device(h.device), physical(h.physicalDevice), queue(h.queue), queueFamily(h.queueFamily) {
    vkGetPhysicalDeviceMemoryProperties(physical, &memory);
    vkGetPhysicalDeviceProperties(physical, &properties);
}

uint32_t Device::memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const {
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw VkFailure{"no memory type for a buffer or image", VK_ERROR_OUT_OF_DEVICE_MEMORY};
}

Buffer::Buffer(const Device& d, VkDeviceSize size, VkBufferUsageFlags usage) : dev(&d) {
    VkBufferCreateInfo info{
        VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, usage, VK_SHARING_MODE_EXCLUSIVE, 0, nullptr};
    vkCheck(vkCreateBuffer(d.device, &info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(d.device, buffer, &req);
    VkMemoryAllocateInfo alloc{
        VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size,
        d.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)};
    vkCheck(vkAllocateMemory(d.device, &alloc, nullptr, &memory), "vkAllocateMemory");
    vkCheck(vkBindBufferMemory(d.device, buffer, memory, 0), "vkBindBufferMemory");
    vkCheck(vkMapMemory(d.device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
}

Buffer::~Buffer() {
    vkDestroyBuffer(dev->device, buffer, nullptr);
    vkFreeMemory(dev->device, memory, nullptr);
}

Texture::Texture(const Device& d, VkFormat f, uint32_t w, uint32_t h, VkImageUsageFlags usage,
                 VkImageAspectFlags aspect)
    : dev(&d), width(w), height(h), format(f) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                           nullptr,
                           0,
                           VK_IMAGE_TYPE_2D,
                           f,
                           {w, h, 1},
                           1,
                           1,
                           VK_SAMPLE_COUNT_1_BIT,
                           VK_IMAGE_TILING_OPTIMAL,
                           usage,
                           VK_SHARING_MODE_EXCLUSIVE,
                           0,
                           nullptr,
                           VK_IMAGE_LAYOUT_UNDEFINED};
    vkCheck(vkCreateImage(d.device, &info, nullptr, &image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(d.device, image, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size,
                               d.memoryType(req.memoryTypeBits, 0)};
    vkCheck(vkAllocateMemory(d.device, &alloc, nullptr, &memory), "vkAllocateMemory");
    vkCheck(vkBindImageMemory(d.device, image, memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                   nullptr,
                                   0,
                                   image,
                                   VK_IMAGE_VIEW_TYPE_2D,
                                   f,
                                   {},
                                   {aspect, 0, 1, 0, 1}};
    vkCheck(vkCreateImageView(d.device, &viewInfo, nullptr, &view), "vkCreateImageView");
}

Texture::~Texture() {
    vkDestroyImageView(dev->device, view, nullptr);
    vkDestroyImage(dev->device, image, nullptr);
    vkFreeMemory(dev->device, memory, nullptr);
}

void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                VkAccessFlags dstAccess) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
                           nullptr,
                           srcAccess,
                           dstAccess,
                           from,
                           to,
                           VK_QUEUE_FAMILY_IGNORED,
                           VK_QUEUE_FAMILY_IGNORED,
                           image,
                           {aspect, 0, 1, 0, 1}};
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

OneShot::OneShot(const Device& d) : dev_(d) {
    VkCommandPoolCreateInfo info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, d.queueFamily};
    vkCheck(vkCreateCommandPool(d.device, &info, nullptr, &pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool_,
                                      VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    vkCheck(vkAllocateCommandBuffers(d.device, &alloc, &cmd_), "vkAllocateCommandBuffers");
}

OneShot::~OneShot() { vkDestroyCommandPool(dev_.device, pool_, nullptr); }

VkCommandBuffer OneShot::record() {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                   VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
    vkCheck(vkBeginCommandBuffer(cmd_, &begin), "vkBeginCommandBuffer");
    return cmd_;
}

void OneShot::submitAndWait() {
    vkCheck(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO, nullptr, 0, nullptr, nullptr, 1, &cmd_, 0, nullptr};
    vkCheck(vkQueueSubmit(dev_.queue, 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
    vkCheck(vkQueueWaitIdle(dev_.queue), "vkQueueWaitIdle");
}

ClientPipelines::ClientPipelines(const Device& d, lt::VulkanContext& gpu, const ClientShading& shading)
    : dev_(d), shading_(shading), stages_(lt::surfaceStages(shading.spacing)), formats_(lt::imageFormats(gpu)) {
    std::vector<VkDescriptorSetLayout> sets = {gpu.surfaceSetLayout()};
    if (shading.materialSet) {
        std::array<VkDescriptorSetLayoutBinding, 6> bindings{};
        for (uint32_t b = 0; b < bindings.size(); ++b)
            bindings[b] = {b, b == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                           VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr, 0,
                                                uint32_t(bindings.size()), bindings.data()};
        vkCheck(vkCreateDescriptorSetLayout(d.device, &setInfo, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
        sets.push_back(setLayout_);
    }
    const VkPushConstantRange range = gpu.surfacePushConstants();
    VkPipelineLayoutCreateInfo layoutInfo{
        VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, uint32_t(sets.size()), sets.data(), 1, &range};
    vkCheck(vkCreatePipelineLayout(d.device, &layoutInfo, nullptr, &layout_), "vkCreatePipelineLayout");
}

ClientPipelines::~ClientPipelines() {
    for (const Built& b : built_) {
        vkDestroyPipeline(dev_.device, b.patches, nullptr);
        vkDestroyPipeline(dev_.device, b.ipps, nullptr);
    }
    for (VkShaderModule m : modules_) vkDestroyShaderModule(dev_.device, m, nullptr);
    vkDestroyPipelineLayout(dev_.device, layout_, nullptr);
    vkDestroyDescriptorSetLayout(dev_.device, setLayout_, nullptr);
}

VkShaderModule ClientPipelines::module(const lt::SpirvModule& m) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, m.bytes, m.code};
    VkShaderModule out = VK_NULL_HANDLE;
    vkCheck(vkCreateShaderModule(dev_.device, &info, nullptr, &out), "vkCreateShaderModule");
    modules_.push_back(out);
    return out;
}

lt::SurfacePipelines ClientPipelines::get(const lt::VulkanSurface::Specialization& given) {
    for (const Built& b : built_)
        if (b.watertight == given.watertight && b.displace == given.displace) return {b.patches, b.ipps, layout_};
    const bool tessellator = shading_.path == lt::DrawPath::Tessellator;
    if (modules_.empty()) {  // tessellator: vertex stages 0..3, fragment 4; the others: 0..1, fragment 2
        if (tessellator)
            for (const lt::SpirvModule& m : {stages_.patchVertex, stages_.patchControl, stages_.patchEvaluation})
                module(m);
        else
            module(shading_.path == lt::DrawPath::Compute ? stages_.computeVertex : stages_.patternVertex);
        module(stages_.ippVertex);
        module(shading_.fragment);
    }
    lt::VulkanSurface::Specialization values = given;
    values.tangent = values.attributes = shading_.attributes ? VK_TRUE : VK_FALSE;
    using S = lt::VulkanSurface::Specialization;
    const std::array<VkSpecializationMapEntry, 4> entries = {{{lt::kSpecWatertight, offsetof(S, watertight), 4},
                                                              {lt::kSpecDisplace, offsetof(S, displace), 4},
                                                              {lt::kSpecTangent, offsetof(S, tangent), 4},
                                                              {lt::kSpecAttributes, offsetof(S, attributes), 4}}};
    const VkSpecializationInfo spec{4, entries.data(), sizeof values, &values};
    auto stage = [&](VkShaderStageFlagBits s, size_t m) {
        return VkPipelineShaderStageCreateInfo{
            VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, s, modules_[m], "main", &spec};
    };
    const auto noInput =
        zeroed<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    const VkPipelineTessellationStateCreateInfo tess{VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO, nullptr,
                                                     0, 12};
    const VkPipelineViewportStateCreateInfo viewport{
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, nullptr, 0, 1, nullptr, 1, nullptr};
    auto raster =
        zeroed<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    raster.polygonMode = shading_.wireframe ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;  // single-sided back faces are hidden by depth on closed meshes
    raster.lineWidth = 1;
    auto ms = zeroed<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    auto depth =
        zeroed<VkPipelineDepthStencilStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
    depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState opaque{};
    opaque.colorWriteMask = 0xF;
    const VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                                    nullptr,
                                                    0,
                                                    VK_FALSE,
                                                    VK_LOGIC_OP_COPY,
                                                    1,
                                                    &opaque,
                                                    {0, 0, 0, 0}};
    const std::array<VkDynamicState, 2> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    const VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO, nullptr, 0, 2,
                                               dynamic.data()};
    const VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
                                                  nullptr,
                                                  0,
                                                  1,
                                                  &formats_.color,
                                                  formats_.depth,
                                                  VK_FORMAT_UNDEFINED};
    built_.push_back(
        {given.watertight, given.displace, VK_NULL_HANDLE, VK_NULL_HANDLE});  // destroyed even if one fails
    Built& b = built_.back();
    const size_t ipp = modules_.size() - 2, fragment = modules_.size() - 1;
    for (bool patches : {true, false}) {
        std::vector<VkPipelineShaderStageCreateInfo> list;
        if (patches && tessellator)
            list = {stage(VK_SHADER_STAGE_VERTEX_BIT, 0), stage(VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT, 1),
                    stage(VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT, 2)};
        else
            list = {stage(VK_SHADER_STAGE_VERTEX_BIT, patches ? 0 : ipp)};
        list.push_back(stage(VK_SHADER_STAGE_FRAGMENT_BIT, fragment));
        const bool patchList = patches && tessellator;
        const VkPipelineInputAssemblyStateCreateInfo assembly{
            VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO, nullptr, 0,
            patchList ? VK_PRIMITIVE_TOPOLOGY_PATCH_LIST : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST, VK_FALSE};
        VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
                                          &rendering,
                                          0,
                                          uint32_t(list.size()),
                                          list.data(),
                                          &noInput,
                                          &assembly,
                                          patchList ? &tess : nullptr,
                                          &viewport,
                                          &raster,
                                          &ms,
                                          &depth,
                                          &blend,
                                          &dyn,
                                          layout_,
                                          VK_NULL_HANDLE,
                                          0,
                                          VK_NULL_HANDLE,
                                          -1};
        vkCheck(
            vkCreateGraphicsPipelines(dev_.device, VK_NULL_HANDLE, 1, &info, nullptr, patches ? &b.patches : &b.ipps),
            "vkCreateGraphicsPipelines");
    }
    return {b.patches, b.ipps, layout_};
}

}  // namespace looprender
