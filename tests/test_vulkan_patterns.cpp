// tests/test_vulkan_patterns.cpp -- the draw path without the tessellator
// (DrawPath::Patterns, shaders/pattern.vert) on a device whose tessellationShader
// feature is off: an application's device, made here with the plain C API (and the
// validation layer, whose every warning or error fails the test), adopted by
// looptess. Captures there equal the CPU evaluator's pattern mode bit for bit, images
// equal those of the shared test device, and the tessellator path is refused.
#include "test_vulkan_support.h"

#include <vulkan/vulkan.h>

#include <cstring>
#include <string>
#include <vector>

namespace lt::test {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL countMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                           const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT))
        static_cast<std::vector<std::string>*>(user)->push_back(data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

// An application's Vulkan 1.3 device on lavapipe with dynamic rendering and transform
// feedback, and without tessellation shaders.
struct NoTessellationDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = UINT32_MAX;
    std::vector<std::string> messages;

    bool create() {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "no-tessellation", 1, nullptr, 0, VK_API_VERSION_1_3};
        const char* layers[] = {"VK_LAYER_KHRONOS_validation"};
        const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
        VkDebugUtilsMessengerCreateInfoEXT debug{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT, nullptr, 0,
                                                 VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                                     VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
                                                 VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
                                                 countMessage, &messages};
        VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, &debug, 0, &app, 1, layers, 1, extensions};
        if (vkCreateInstance(&info, nullptr, &instance) != VK_SUCCESS) return false;
        auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        if (!createMessenger || createMessenger(instance, &debug, nullptr, &messenger) != VK_SUCCESS) return false;
        uint32_t count = 0;
        vkEnumeratePhysicalDevices(instance, &count, nullptr);
        std::vector<VkPhysicalDevice> devices(count);
        vkEnumeratePhysicalDevices(instance, &count, devices.data());
        for (VkPhysicalDevice d : devices) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(d, &p);
            if (std::string(p.deviceName).find("llvmpipe") != std::string::npos) physical = d;
        }
        if (!physical) return false;
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, nullptr);
        std::vector<VkQueueFamilyProperties> props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, props.data());
        for (uint32_t i = 0; i < families && family == UINT32_MAX; ++i)
            if ((props[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (props[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) family = i;
        if (family == UINT32_MAX) return false;
        auto feedback = vkStruct<VkPhysicalDeviceTransformFeedbackFeaturesEXT>(
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TRANSFORM_FEEDBACK_FEATURES_EXT);
        feedback.transformFeedback = VK_TRUE;
        auto v13 = vkStruct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
        v13.pNext = &feedback;
        v13.dynamicRendering = VK_TRUE;
        VkPhysicalDeviceFeatures features{};   // tessellationShader stays VK_FALSE
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &priority};
        const char* deviceExtensions[] = {VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME};
        VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &v13, 0, 1, &queueInfo, 0, nullptr, 1,
                                      deviceExtensions, &features};
        if (vkCreateDevice(physical, &deviceInfo, nullptr, &device) != VK_SUCCESS) return false;
        vkGetDeviceQueue(device, family, 0, &queue);
        return true;
    }

    VulkanHandles handles() const {
        VulkanHandles h;
        h.instance = instance;
        h.physicalDevice = physical;
        h.device = device;
        h.queue = queue;
        h.queueFamily = family;
        h.transformFeedback = true;
        h.tessellationShader = false;
        return h;
    }

    ~NoTessellationDevice() {
        if (device) vkDestroyDevice(device, nullptr);
        if (messenger) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
            if (destroy) destroy(instance, messenger, nullptr);
        }
        if (instance) vkDestroyInstance(instance, nullptr);
    }
};

using VulkanPatterns = VulkanTest;

TEST_F(VulkanPatterns, DrawWithoutTessellationShaders) {
    NoTessellationDevice app;
    ASSERT_TRUE(app.create()) << "no lavapipe device with the validation layer";
    size_t checked = 0;
    {
        std::unique_ptr<VulkanContext> adopted;
        Status st = VulkanContext::adopt(app.handles(), adopted);
        ASSERT_TRUE(st) << st.message;
        const Baked* b = baked(corpusMesh("spot.obj"), 3, true);
        ASSERT_NE(b, nullptr);
        std::unique_ptr<VulkanSurface> surface;
        st = VulkanSurface::create(*adopted, b->asset, surface);
        ASSERT_TRUE(st) << st.message;

        for (float f : {1.0f, 3.0f, 8.0f}) {
            FrameSettings frame;
            frame.tessFactor = f;
            frame.path = DrawPath::Patterns;
            Tessellation gpu, cpu;
            st = surface->capture(frame, gpu);
            ASSERT_TRUE(st) << st.message;
            EvalSettings es;
            es.tessFactor = f;
            es.path = DrawPath::Patterns;
            evaluateCpu(b->asset, b->asset.positions.data(), es, cpu);
            ASSERT_EQ(gpu.vertexCount(), cpu.vertexCount()) << "F = " << f;
            EXPECT_EQ(std::memcmp(gpu.positions.data(), cpu.positions.data(), cpu.positions.size() * 4), 0) << "F = " << f;
            EXPECT_EQ(std::memcmp(gpu.normals.data(), cpu.normals.data(), cpu.normals.size() * 4), 0) << "F = " << f;
            EXPECT_EQ(gpu.face, cpu.face);
            checked += gpu.vertexCount();
        }

        // The same image as on the shared device (tessellation enabled there).
        RenderSettings rs;
        rs.width = rs.height = 96;
        rs.frame.tessFactor = 8;
        rs.frame.path = DrawPath::Patterns;
        rs.frame.coloring = Coloring::Levels;
        Image here, shared;
        st = surface->renderImage(rs, here);
        ASSERT_TRUE(st) << st.message;
        auto reference = upload(*b);
        ASSERT_NE(reference, nullptr);
        ASSERT_TRUE(reference->renderImage(rs, shared));
        EXPECT_EQ(here.rgba, shared.rgba);

        // The tessellator path is refused, not drawn.
        FrameSettings tessellated;
        tessellated.tessFactor = 4;
        Tessellation ignored;
        st = surface->capture(tessellated, ignored);
        EXPECT_EQ(st.code, Status::Unsupported) << st.message;
        EXPECT_NE(st.message.find("DrawPath::Patterns"), std::string::npos) << st.message;
    }
    for (const std::string& m : app.messages) ADD_FAILURE() << "validation: " << m;
    std::printf("[ figures  ] without tessellation shaders: %zu captured vertices equal the CPU's\n", checked);
}

} // namespace
} // namespace lt::test
