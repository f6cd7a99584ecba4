// VulkanContext: a headless device of our own, or an application's (see vulkan.h).
#include "vulkan/context.h"

#include "vulkan/draw_plan.h"
#include "vulkan/pipelines.h"

#include <algorithm>
#include <cstring>

namespace lt {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint64_t kSubmitTimeoutNs = 600ull * 1000 * 1000 * 1000;  // lavapipe is slow; a hang still ends

VKAPI_ATTR VkBool32 VKAPI_CALL recordMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* impl = static_cast<VulkanContext::Impl*>(user);
    std::string text = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error " : "warning ";
    text += data->pMessageIdName ? data->pMessageIdName : "?";
    text += ": ";
    text += data->pMessage ? data->pMessage : "";
    std::lock_guard<std::mutex> lock(impl->messagesMutex);
    impl->messages.push_back(std::move(text));
    return VK_FALSE;
}

bool hasLayer(const vk::raii::Context& context, const char* name) {
    for (const auto& layer : context.enumerateInstanceLayerProperties())
        if (std::strcmp(layer.layerName, name) == 0) return true;
    return false;
}

bool hasExtension(const std::vector<vk::ExtensionProperties>& list, const char* name) {
    for (const auto& e : list)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

// A queue family with graphics and compute, or UINT32_MAX.
uint32_t graphicsComputeFamily(const vk::raii::PhysicalDevice& device) {
    auto families = device.getQueueFamilyProperties();
    for (uint32_t i = 0; i < families.size(); ++i) {
        auto flags = families[i].queueFlags;
        if ((flags & vk::QueueFlagBits::eGraphics) && (flags & vk::QueueFlagBits::eCompute)) return i;
    }
    return UINT32_MAX;
}

// Why `device` cannot run the Vulkan path, or empty.
std::string unsuitable(const vk::raii::PhysicalDevice& device) {
    auto properties = device.getProperties();
    if (properties.apiVersion < VK_API_VERSION_1_3) return "Vulkan 1.3 not supported";
    auto features = device.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan13Features>();
    if (!features.get<vk::PhysicalDeviceVulkan13Features>().dynamicRendering) return "no dynamic rendering";
    if (graphicsComputeFamily(device) == UINT32_MAX) return "no graphics+compute queue";
    return {};
}

int typeRank(vk::PhysicalDeviceType type) {
    switch (type) {
    case vk::PhysicalDeviceType::eDiscreteGpu: return 0;
    case vk::PhysicalDeviceType::eIntegratedGpu: return 1;
    case vk::PhysicalDeviceType::eVirtualGpu: return 2;
    case vk::PhysicalDeviceType::eCpu: return 3;
    default: return 4;
    }
}

vk::raii::PhysicalDevice pickDevice(const vk::raii::Instance& instance, const std::string& wanted) {
    vk::raii::PhysicalDevices devices(instance);
    std::string report;
    int best = -1, bestRank = 1 << 30;
    for (size_t i = 0; i < devices.size(); ++i) {
        std::string name = devices[i].getProperties().deviceName.data();
        std::string why = unsuitable(devices[i]);
        if (why.empty() && !wanted.empty() && name.find(wanted) == std::string::npos) why = "not named " + wanted;
        report += (report.empty() ? "" : "; ") + name + (why.empty() ? ": suitable" : ": " + why);
        int rank = typeRank(devices[i].getProperties().deviceType);
        if (why.empty() && rank < bestRank) {
            best = int(i);
            bestRank = rank;
        }
    }
    if (best < 0)
        throw Failure(Status::Unsupported,
                      devices.empty() ? "no Vulkan device" : "no suitable Vulkan device (" + report + ")");
    return std::move(devices[size_t(best)]);
}

}  // namespace

VulkanContext::Impl::Impl(PFN_vkGetInstanceProcAddr getInstanceProcAddr) : context(getInstanceProcAddr) {}

VulkanContext::Impl::~Impl() {
    // Children first (they use the device's dispatcher), then give adopted handles back.
    pipelines.reset();
    commandPool.clear();
    if (!owned) {
        queue.clear();
        (void)device.release();
        (void)instance.release();
    }
}

void VulkanContext::Impl::finishSetup() {
    properties = physical.getProperties();
    memory = physical.getMemoryProperties();
    timestampBits = physical.getQueueFamilyProperties()[queueFamily].timestampValidBits;
    commandPool = vk::raii::CommandPool(device, {vk::CommandPoolCreateFlagBits::eResetCommandBuffer, queueFamily});
    pipelines = std::make_unique<Pipelines>(*this);
}

GpuBuffer VulkanContext::Impl::createBuffer(vk::DeviceSize size, vk::BufferUsageFlags usage, MemoryKind kind) {
    GpuBuffer b;
    b.size = std::max<vk::DeviceSize>(size, 16);  // no empty buffers
    b.buffer = vk::raii::Buffer(device, {{}, b.size, usage, vk::SharingMode::eExclusive});
    vk::MemoryRequirements req = b.buffer.getMemoryRequirements();
    vk::MemoryPropertyFlags required = kind == MemoryKind::HostVisible ? vk::MemoryPropertyFlagBits::eHostVisible |
                                                                             vk::MemoryPropertyFlagBits::eHostCoherent
                                                                       : vk::MemoryPropertyFlags{};
    vk::MemoryPropertyFlags preferred =
        kind == MemoryKind::HostVisible ? required : vk::MemoryPropertyFlagBits::eDeviceLocal;
    uint32_t type = UINT32_MAX;
    for (int pass = 0; pass < 2 && type == UINT32_MAX; ++pass) {
        vk::MemoryPropertyFlags want = pass == 0 ? (required | preferred) : required;
        for (uint32_t i = 0; i < memory.memoryTypeCount && type == UINT32_MAX; ++i)
            if ((req.memoryTypeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & want) == want) type = i;
    }
    if (type == UINT32_MAX) throw Failure(Status::Unsupported, "no memory type for a buffer");
    b.memory = vk::raii::DeviceMemory(device, {req.size, type});
    b.allocated = req.size;
    b.buffer.bindMemory(*b.memory, 0);
    if (kind == MemoryKind::HostVisible) b.mapped = b.memory.mapMemory(0, VK_WHOLE_SIZE);
    return b;
}

void VulkanContext::Impl::submitAndWait(const std::function<void(const vk::raii::CommandBuffer&)>& record) {
    vk::raii::CommandBuffers buffers(device, {*commandPool, vk::CommandBufferLevel::ePrimary, 1});
    const vk::raii::CommandBuffer& cmd = buffers[0];
    cmd.begin(vk::CommandBufferBeginInfo{vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    record(cmd);
    cmd.end();
    vk::raii::Fence fence(device, vk::FenceCreateInfo{});
    vk::SubmitInfo submit({}, {}, *cmd);
    queue.submit(submit, *fence);
    if (device.waitForFences(*fence, VK_TRUE, kSubmitTimeoutNs) != vk::Result::eSuccess)
        throw Failure(Status::Internal, "the GPU did not finish within 10 minutes");
}

void VulkanContext::Impl::upload(GpuBuffer& dst, const void* data, vk::DeviceSize size) {
    if (size == 0) return;
    if (dst.mapped) {
        std::memcpy(dst.mapped, data, size_t(size));
        return;
    }
    GpuBuffer staging = createBuffer(size, vk::BufferUsageFlagBits::eTransferSrc, MemoryKind::HostVisible);
    std::memcpy(staging.mapped, data, size_t(size));
    submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        cmd.copyBuffer(*staging.buffer, *dst.buffer, vk::BufferCopy(0, 0, size));
    });
}

const GpuBuffer& VulkanContext::Impl::patternIndexBuffer() {
    if (patternIndices.size == 0) {
        const std::vector<uint16_t>& indices = patternLibrary().indices;
        const vk::DeviceSize bytes = vk::DeviceSize(indices.size()) * 2;
        patternIndices =
            createBuffer(bytes, vk::BufferUsageFlagBits::eIndexBuffer | vk::BufferUsageFlagBits::eTransferDst,
                         MemoryKind::DeviceLocal);
        upload(patternIndices, indices.data(), bytes);
    }
    return patternIndices;
}

const GpuBuffer& VulkanContext::Impl::patternTableBuffer() {
    if (patternTableWords.size == 0) {
        const std::vector<uint32_t> words = patternTable();
        const vk::DeviceSize bytes = vk::DeviceSize(words.size()) * 4;
        patternTableWords =
            createBuffer(bytes, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst,
                         MemoryKind::DeviceLocal);
        upload(patternTableWords, words.data(), bytes);
    }
    return patternTableWords;
}

void memoryBarrier(const vk::raii::CommandBuffer& cmd, vk::PipelineStageFlags srcStage, vk::AccessFlags srcAccess,
                   vk::PipelineStageFlags dstStage, vk::AccessFlags dstAccess) {
    vk::MemoryBarrier barrier(srcAccess, dstAccess);
    cmd.pipelineBarrier(srcStage, dstStage, {}, barrier, {}, {});
}

VulkanContext::VulkanContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
VulkanContext::~VulkanContext() = default;

Status VulkanContext::createHeadless(const HeadlessOptions& options, std::unique_ptr<VulkanContext>& out) {
    return guarded("Vulkan", [&]() -> Status {
        auto impl = std::make_unique<Impl>(&vkGetInstanceProcAddr);
        std::vector<const char*> layers, extensions;
        vk::DebugUtilsMessengerCreateInfoEXT messengerInfo(
            {}, vk::DebugUtilsMessageSeverityFlagBitsEXT::eWarning | vk::DebugUtilsMessageSeverityFlagBitsEXT::eError,
            vk::DebugUtilsMessageTypeFlagBitsEXT::eGeneral | vk::DebugUtilsMessageTypeFlagBitsEXT::eValidation |
                vk::DebugUtilsMessageTypeFlagBitsEXT::ePerformance,
            &recordMessage, impl.get());
        std::vector<vk::ValidationFeatureEnableEXT> enables;
        if (options.synchronizationValidation)
            enables.push_back(vk::ValidationFeatureEnableEXT::eSynchronizationValidation);
        vk::ValidationFeaturesEXT features(enables, {});
        if (options.validation) {
            if (!hasLayer(impl->context, kValidationLayer))
                throw Failure(Status::Unsupported, std::string(kValidationLayer) + " is not installed");
            layers.push_back(kValidationLayer);
            extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
            messengerInfo.pNext = enables.empty() ? nullptr : &features;
        }
        if (impl->context.enumerateInstanceVersion() < VK_API_VERSION_1_3)
            throw Failure(Status::Unsupported, "the Vulkan loader does not support Vulkan 1.3");
        vk::ApplicationInfo app("looptess", 1, "looptess", 1, VK_API_VERSION_1_3);
        vk::InstanceCreateInfo instanceInfo({}, &app, layers, extensions,
                                            options.validation ? &messengerInfo : nullptr);
        try {
            impl->instance = vk::raii::Instance(impl->context, instanceInfo);
        } catch (const vk::IncompatibleDriverError& e) {  // no driver (ICD) at all
            throw Failure(Status::Unsupported, std::string("no Vulkan driver: ") + e.what());
        } catch (const vk::InitializationFailedError& e) {
            throw Failure(Status::Unsupported, std::string("no Vulkan driver: ") + e.what());
        }
        if (options.validation) {
            messengerInfo.pNext = nullptr;
            impl->messenger = vk::raii::DebugUtilsMessengerEXT(impl->instance, messengerInfo);
        }
        impl->physical = pickDevice(impl->instance, options.deviceName);
        impl->queueFamily = graphicsComputeFamily(impl->physical);

        auto available = impl->physical.enumerateDeviceExtensionProperties();
        auto supported = impl->physical.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan13Features,
                                                     vk::PhysicalDeviceTransformFeedbackFeaturesEXT>();
        impl->transformFeedback = hasExtension(available, VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME) &&
                                  supported.get<vk::PhysicalDeviceTransformFeedbackFeaturesEXT>().transformFeedback;
        const vk::PhysicalDeviceFeatures& have = supported.get<vk::PhysicalDeviceFeatures2>().features;
        vk::PhysicalDeviceFeatures enable;
        enable.tessellationShader = have.tessellationShader;  // without it: DrawPath::Patterns only
        enable.fillModeNonSolid = have.fillModeNonSolid;
        enable.pipelineStatisticsQuery = have.pipelineStatisticsQuery;
        enable.drawIndirectFirstInstance = have.drawIndirectFirstInstance;
        enable.multiDrawIndirect = have.multiDrawIndirect;
        vk::StructureChain<vk::DeviceCreateInfo, vk::PhysicalDeviceVulkan13Features,
                           vk::PhysicalDeviceTransformFeedbackFeaturesEXT>
            chain;
        float priority = 1.0f;
        vk::DeviceQueueCreateInfo queueInfo({}, impl->queueFamily, 1, &priority);
        std::vector<const char*> deviceExtensions;
        if (impl->transformFeedback) deviceExtensions.push_back(VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME);
        chain.get<vk::DeviceCreateInfo>()
            .setQueueCreateInfos(queueInfo)
            .setPEnabledExtensionNames(deviceExtensions)
            .setPEnabledFeatures(&enable);
        chain.get<vk::PhysicalDeviceVulkan13Features>().dynamicRendering = VK_TRUE;
        // maintenance4 where the device has it: a fragment shader may then leave some of
        // the vertex stages' outputs unread (an application's own, vulkan.h) without
        // the validation layer's performance warning.
        chain.get<vk::PhysicalDeviceVulkan13Features>().maintenance4 =
            supported.get<vk::PhysicalDeviceVulkan13Features>().maintenance4;
        chain.get<vk::PhysicalDeviceTransformFeedbackFeaturesEXT>().transformFeedback = VK_TRUE;
        if (!impl->transformFeedback) chain.unlink<vk::PhysicalDeviceTransformFeedbackFeaturesEXT>();
        impl->fillModeNonSolid = enable.fillModeNonSolid;
        impl->pipelineStatistics = enable.pipelineStatisticsQuery;
        impl->tessellation = enable.tessellationShader;
        impl->drawIndirectFirstInstance = enable.drawIndirectFirstInstance;
        impl->multiDrawIndirect = enable.multiDrawIndirect;
        try {
            impl->device = vk::raii::Device(impl->physical, chain.get<vk::DeviceCreateInfo>());
        } catch (const vk::FeatureNotPresentError& e) {
            throw Failure(Status::Unsupported, e.what());
        } catch (const vk::ExtensionNotPresentError& e) { throw Failure(Status::Unsupported, e.what()); }
        impl->queue = vk::raii::Queue(impl->device, impl->queueFamily, 0);
        impl->finishSetup();
        out.reset(new VulkanContext(std::move(impl)));
        return Status::ok();
    });
}

Status VulkanContext::adopt(const VulkanHandles& h, std::unique_ptr<VulkanContext>& out) {
    return guarded("Vulkan", [&]() -> Status {
        if (!h.instance || !h.physicalDevice || !h.device || !h.queue)
            return Status::error(Status::Usage, "adopt: null instance, physical device, device or queue");
        auto impl = std::make_unique<Impl>(h.getInstanceProcAddr ? h.getInstanceProcAddr : &vkGetInstanceProcAddr);
        impl->owned = false;  // from here on, ~Impl releases instead of destroying
        impl->instance = vk::raii::Instance(impl->context, h.instance);
        impl->physical = vk::raii::PhysicalDevice(impl->instance, h.physicalDevice);
        std::string why = unsuitable(impl->physical);
        if (!why.empty()) return Status::error(Status::Unsupported, "the application's device: " + why);
        auto families = impl->physical.getQueueFamilyProperties();
        if (h.queueFamily >= families.size() || !(families[h.queueFamily].queueFlags & vk::QueueFlagBits::eGraphics) ||
            !(families[h.queueFamily].queueFlags & vk::QueueFlagBits::eCompute))
            return Status::error(Status::Usage, "adopt: queue family without graphics and compute");
        impl->device = vk::raii::Device(impl->physical, h.device);
        impl->queue = vk::raii::Queue(impl->device, h.queue);
        impl->queueFamily = h.queueFamily;
        impl->transformFeedback = h.transformFeedback;
        impl->fillModeNonSolid = h.fillModeNonSolid;
        impl->pipelineStatistics = h.pipelineStatisticsQuery;
        impl->tessellation = h.tessellationShader;
        impl->drawIndirectFirstInstance = h.drawIndirectFirstInstance;
        impl->multiDrawIndirect = h.multiDrawIndirect;
        const vk::PhysicalDeviceFeatures have = impl->physical.getFeatures();
        if ((h.tessellationShader && !have.tessellationShader) ||
            (h.drawIndirectFirstInstance && !have.drawIndirectFirstInstance) ||
            (h.multiDrawIndirect && !have.multiDrawIndirect))
            return Status::error(Status::Usage,
                                 "adopt: a feature said enabled (tessellationShader, drawIndirectFirstInstance "
                                 "or multiDrawIndirect) that the device does not have");
        impl->finishSetup();
        out.reset(new VulkanContext(std::move(impl)));
        return Status::ok();
    });
}

std::string VulkanContext::deviceName() const { return impl_->properties.deviceName.data(); }

bool canCapture(const VulkanContext& context) { return VulkanAccess::context(context).transformFeedback; }

VulkanHandles VulkanContext::handles() const {
    VulkanHandles h;
    h.instance = *impl_->instance;
    h.physicalDevice = *impl_->physical;
    h.device = *impl_->device;
    h.queue = *impl_->queue;
    h.queueFamily = impl_->queueFamily;
    h.transformFeedback = impl_->transformFeedback;
    h.fillModeNonSolid = impl_->fillModeNonSolid;
    h.pipelineStatisticsQuery = impl_->pipelineStatistics;
    h.tessellationShader = impl_->tessellation;
    h.drawIndirectFirstInstance = impl_->drawIndirectFirstInstance;
    h.multiDrawIndirect = impl_->multiDrawIndirect;
    return h;
}

VkDescriptorSetLayout VulkanContext::surfaceSetLayout() const { return *impl_->pipelines->setLayout; }

VkPushConstantRange VulkanContext::surfacePushConstants() const {
    return VkPushConstantRange{VkShaderStageFlags(kAllStages), 0, LT_PUSH_CONSTANT_SIZE};
}

std::vector<std::string> VulkanContext::messages() const {
    std::lock_guard<std::mutex> lock(impl_->messagesMutex);
    return impl_->messages;
}

}  // namespace lt
