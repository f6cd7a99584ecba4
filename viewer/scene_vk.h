// looprender's Vulkan objects (scene_render.cpp, looprender_gpu.cpp): what any engine
// has around looptess (buffers, textures, attachments, its own pipelines), written with
// the plain C API on the device of an lt::VulkanContext. A failed call throws
// VkFailure, which renderScene turns into a Status; every object is destroyed by its
// owner's destructor.
#pragma once

#include "looptess/vulkan.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace looprender {

struct VkFailure {
    std::string call;
    VkResult result;
    // Internal: "<call> failed (VkResult <result>)".
    lt::Status status() const;
};

// A zeroed Vulkan structure with its sType.
template <class T>
T zeroed(VkStructureType type) {
    T t{};
    t.sType = type;
    return t;
}

// Throws VkFailure naming `call` unless r is VK_SUCCESS.
void vkCheck(VkResult r, const char* call);

struct Device {
    VkDevice device = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkPhysicalDeviceMemoryProperties memory{};
    VkPhysicalDeviceProperties properties{};
    explicit Device(const lt::VulkanHandles& h);
    // A memory type in `bits` with `flags`; throws when there is none.
    uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const;
};

struct Buffer {
    const Device* dev = nullptr;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    Buffer(const Device& d, VkDeviceSize size, VkBufferUsageFlags usage);  // host-visible, coherent, mapped
    ~Buffer();
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
};

struct Texture {
    const Device* dev = nullptr;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    uint32_t width = 0, height = 0;
    VkFormat format = VK_FORMAT_UNDEFINED;
    Texture(const Device& d, VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage,
            VkImageAspectFlags aspect);
    ~Texture();
    Texture(const Texture&) = delete;
    Texture& operator=(const Texture&) = delete;
};

// Records an image layout transition of the whole image.
void transition(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                VkAccessFlags dstAccess);

// A one-shot command buffer: record() gives it, submitAndWait() runs it on the queue.
class OneShot {
public:
    explicit OneShot(const Device& d);
    ~OneShot();
    VkCommandBuffer record();
    void submitAndWait();

private:
    const Device& dev_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

// What a client's pipelines draw with: its fragment shader and what that reads.
struct ClientShading {
    lt::SpirvModule fragment;
    // Which stages draw the regular patches (DrawPath::Compute: the whole surface; then
    // the frames' FrameSettings::tangents and attributes must be `attributes`).
    lt::DrawPath path = lt::DrawPath::Tessellator;
    lt::Spacing spacing = lt::Spacing::Equal;
    bool wireframe = false;    // polygon mode LINE (needs fillModeNonSolid)
    bool materialSet = false;  // set 1: a uniform block and five combined image samplers
    bool attributes = false;   // kSpecTangent and kSpecAttributes on (the fragment shader reads them)
};

// looprender's own pipelines around the surface, built as an engine builds them
// (vulkan.h, "An application's own pipelines"): a layout with looptess's set 0, for
// materialSet this tool's set 1 (material.frag: binding 0 its uniform block, 1..5 base
// colour, metallic-roughness, normal, occlusion, emissive), looptess's push
// constants; and per specialization (watertight, displace) the patch and IPP
// pipelines of shading.path with shading.fragment.
class ClientPipelines {
public:
    ClientPipelines(const Device& d, lt::VulkanContext& gpu, const ClientShading& shading);
    ~ClientPipelines();
    ClientPipelines(const ClientPipelines&) = delete;
    ClientPipelines& operator=(const ClientPipelines&) = delete;
    VkDescriptorSetLayout setLayout() const { return setLayout_; }  // null without materialSet
    VkPipelineLayout layout() const { return layout_; }
    lt::SurfacePipelines get(const lt::VulkanSurface::Specialization& values);

private:
    struct Built {
        VkBool32 watertight, displace;
        VkPipeline patches, ipps;
    };
    VkShaderModule module(const lt::SpirvModule& m);
    const Device& dev_;
    ClientShading shading_;
    lt::SurfaceStages stages_;
    lt::DrawTarget formats_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    std::vector<VkShaderModule> modules_;
    std::vector<Built> built_;
};

}  // namespace looprender
