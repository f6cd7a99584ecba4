// Private to looptess_vulkan: the device (VulkanContext::Impl), buffers, one-shot
// submissions, and the boundary that turns exceptions into lt::Status.
//
// Built with VULKAN_HPP_ENABLE_DYNAMIC_LOADER_TOOL=0 (runtime/CMakeLists.txt): the
// RAII context takes vkGetInstanceProcAddr from us, so an adopted device can bring
// its own. Vulkan-Hpp's RAII classes throw (vk::SystemError) on failed calls. Internal code
// lets them propagate and throws Failure for its own errors; every public function
// of looptess/vulkan.h runs its body through guarded(), so nothing escapes.
#pragma once

#include "looptess/tools/vulkan_tools.h"

#include <vulkan/vulkan_raii.hpp>

#include <functional>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace lt {

// An error of ours (not a failed Vulkan call), with the Status code to report.
struct Failure : std::runtime_error {
    Status::Code code;
    Failure(Status::Code c, const std::string& message) : std::runtime_error(message), code(c) {}
};

// Runs `body` (returning Status) and converts any exception into a Status whose
// message starts with `what`.
template <class Body>
Status guarded(const char* what, Body&& body) noexcept {
    try {
        return body();
    } catch (const Failure& e) {
        return Status::error(e.code, std::string(what) + ": " + e.what());
    } catch (const vk::SystemError& e) {
        return Status::error(Status::Internal, std::string(what) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        return Status::error(Status::Internal, std::string(what) + ": out of host memory");
    } catch (const std::exception& e) {
        return Status::error(Status::Internal, std::string(what) + ": " + e.what());
    } catch (...) { return Status::error(Status::Internal, std::string(what) + ": unknown exception"); }
}

// A buffer with its own memory allocation (the library makes a handful, so no
// sub-allocator). `mapped` is set for host-visible buffers (persistently mapped).
struct GpuBuffer {
    vk::raii::Buffer buffer{nullptr};
    vk::raii::DeviceMemory memory{nullptr};
    vk::DeviceSize size = 0;       // usable bytes
    vk::DeviceSize allocated = 0;  // bytes of device memory
    void* mapped = nullptr;
};

enum class MemoryKind { DeviceLocal, HostVisible };

class Pipelines;

struct VulkanContext::Impl {
    // `getInstanceProcAddr`: the application's, or the loader's (we link libvulkan).
    explicit Impl(PFN_vkGetInstanceProcAddr getInstanceProcAddr);
    ~Impl();

    vk::raii::Context context;
    vk::raii::Instance instance{nullptr};
    vk::raii::DebugUtilsMessengerEXT messenger{nullptr};
    vk::raii::PhysicalDevice physical{nullptr};
    vk::raii::Device device{nullptr};
    vk::raii::Queue queue{nullptr};
    uint32_t queueFamily = 0;
    bool owned = true;  // false: adopted handles, released (not destroyed) at the end
    bool transformFeedback = false;
    bool fillModeNonSolid = false;
    bool pipelineStatistics = false;
    bool tessellation = true;                // tessellationShader enabled: DrawPath::Tessellator works
    bool drawIndirectFirstInstance = false;  // enabled: screen-space LOD on DrawPath::Patterns works
    bool multiDrawIndirect = false;
    // Stages that read the surface's buffers while drawing (the tessellation stages
    // only where the feature is enabled: barriers may not name them otherwise).
    vk::PipelineStageFlags drawStages() const {
        vk::PipelineStageFlags s = vk::PipelineStageFlagBits::eVertexShader;
        if (tessellation)
            s |= vk::PipelineStageFlagBits::eTessellationControlShader |
                 vk::PipelineStageFlagBits::eTessellationEvaluationShader;
        return s;
    }
    uint32_t timestampBits = 0;
    vk::PhysicalDeviceProperties properties;
    vk::PhysicalDeviceMemoryProperties memory;
    vk::raii::CommandPool commandPool{nullptr};  // for the blocking helpers
    std::unique_ptr<Pipelines> pipelines;        // built by the first surface
    // Every refinement pattern's indices (draw_plan.h's patternLibrary), shared by
    // the surfaces; made by the first VulkanSurface::create (patternIndexBuffer).
    GpuBuffer patternIndices;
    const GpuBuffer& patternIndexBuffer();
    // evaluate.comp's pattern table (draw_plan.h's patternTable), made likewise.
    GpuBuffer patternTableWords;
    const GpuBuffer& patternTableBuffer();

    mutable std::mutex messagesMutex;
    std::vector<std::string> messages;

    // Queries the device, makes the command pool and the pipelines.
    void finishSetup();

    GpuBuffer createBuffer(vk::DeviceSize size, vk::BufferUsageFlags usage, MemoryKind kind);
    // Records with `record` into a fresh command buffer, submits it to the queue and
    // waits for it (Internal on timeout or device loss).
    void submitAndWait(const std::function<void(const vk::raii::CommandBuffer&)>& record);
    // Copies `size` bytes into a device-local buffer through a staging buffer.
    void upload(GpuBuffer& dst, const void* data, vk::DeviceSize size);
};

// The library's way from vulkan.h's objects to their state (their friend): the
// blocking helpers of vulkan_tools.h, and the tests' private seam
// (looptess_vulkan_internal), go through it.
struct VulkanAccess {
    static VulkanContext::Impl& context(VulkanContext& c) { return *c.impl_; }
    static const VulkanContext::Impl& context(const VulkanContext& c) { return *c.impl_; }
    static VulkanSurface::Impl& surface(VulkanSurface& s) { return *s.impl_; }
};

// An application's command buffer seen as a vk::raii::CommandBuffer, so recording
// goes through the device's dispatcher (extensions included). Released, never freed.
class BorrowedCommandBuffer {
public:
    BorrowedCommandBuffer(const vk::raii::Device& device, VkCommandBuffer cmd) : cmd_(device, cmd, VK_NULL_HANDLE) {}
    ~BorrowedCommandBuffer() { (void)cmd_.release(); }
    BorrowedCommandBuffer(const BorrowedCommandBuffer&) = delete;
    BorrowedCommandBuffer& operator=(const BorrowedCommandBuffer&) = delete;
    const vk::raii::CommandBuffer& operator*() const { return cmd_; }

private:
    vk::raii::CommandBuffer cmd_;
};

// Memory barrier helper (legacy vkCmdPipelineBarrier: no synchronization2 needed).
void memoryBarrier(const vk::raii::CommandBuffer& cmd, vk::PipelineStageFlags srcStage, vk::AccessFlags srcAccess,
                   vk::PipelineStageFlags dstStage, vk::AccessFlags dstAccess);

}  // namespace lt
