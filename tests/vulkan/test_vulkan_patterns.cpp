// tests/vulkan/test_vulkan_patterns.cpp -- the draw path without the tessellator
// (DrawPath::Patterns, shaders/pattern.vert) on a device whose tessellationShader
// feature is off: an application's device, made here with the plain C API (and the
// validation layer, whose every warning or error fails the test), adopted by
// looptess. Captures there equal the CPU evaluator's pattern mode bit for bit, images
// equal those of the shared test device, and the tessellator path is refused. And
// the surface into an application's buffers (recordEvaluate) on the pattern path.
#include "test_vulkan_support.h"
#include "test_paths.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace lt::test {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL countMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                            VkDebugUtilsMessageTypeFlagsEXT,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT))
        static_cast<std::vector<std::string>*>(user)->push_back(data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

// An application's Vulkan 1.3 device with dynamic rendering and without tessellation
// shaders: the physical device the shared test context uses (whatever it is: lavapipe
// in CI, a GPU elsewhere), with transform feedback and drawIndirectFirstInstance where
// it has them (not multiDrawIndirect: screen-space patterns then draw once per
// pattern).
struct NoTessellationDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = UINT32_MAX;
    bool transformFeedback = false, drawIndirectFirstInstance = false;
    std::vector<std::string> messages;

    bool create(const std::string& deviceName) {
        VkApplicationInfo app{
            VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "no-tessellation", 1, nullptr, 0, VK_API_VERSION_1_3};
        const char* layers[] = {"VK_LAYER_KHRONOS_validation"};
        const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
        VkDebugUtilsMessengerCreateInfoEXT debug{
            VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
            nullptr,
            0,
            VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
            VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT,
            countMessage,
            &messages};
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
            if (!physical && deviceName == p.deviceName) physical = d;
        }
        if (!physical) return false;
        uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, nullptr);
        std::vector<VkQueueFamilyProperties> props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, props.data());
        for (uint32_t i = 0; i < families && family == UINT32_MAX; ++i)
            if ((props[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (props[i].queueFlags & VK_QUEUE_COMPUTE_BIT))
                family = i;
        if (family == UINT32_MAX) return false;
        // What the device has of what this test would use.
        auto hasFeedback = vkStruct<VkPhysicalDeviceTransformFeedbackFeaturesEXT>(
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TRANSFORM_FEEDBACK_FEATURES_EXT);
        auto has = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
        uint32_t extensionCount = 0;
        vkEnumerateDeviceExtensionProperties(physical, nullptr, &extensionCount, nullptr);
        std::vector<VkExtensionProperties> available(extensionCount);
        vkEnumerateDeviceExtensionProperties(physical, nullptr, &extensionCount, available.data());
        for (const VkExtensionProperties& e : available)
            transformFeedback =
                transformFeedback || std::string(e.extensionName) == VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME;
        if (transformFeedback) has.pNext = &hasFeedback;
        vkGetPhysicalDeviceFeatures2(physical, &has);
        transformFeedback = transformFeedback && hasFeedback.transformFeedback;
        drawIndirectFirstInstance = has.features.drawIndirectFirstInstance;

        auto feedback = vkStruct<VkPhysicalDeviceTransformFeedbackFeaturesEXT>(
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TRANSFORM_FEEDBACK_FEATURES_EXT);
        feedback.transformFeedback = VK_TRUE;
        auto v13 = vkStruct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
        v13.pNext = transformFeedback ? &feedback : nullptr;
        v13.dynamicRendering = VK_TRUE;
        VkPhysicalDeviceFeatures features{};  // tessellationShader stays VK_FALSE
        features.drawIndirectFirstInstance = drawIndirectFirstInstance;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &priority};
        const char* deviceExtensions[] = {VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME};
        VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                      &v13,
                                      0,
                                      1,
                                      &queueInfo,
                                      0,
                                      nullptr,
                                      transformFeedback ? 1u : 0u,
                                      deviceExtensions,
                                      &features};
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
        h.transformFeedback = transformFeedback;
        h.tessellationShader = false;
        h.drawIndirectFirstInstance = drawIndirectFirstInstance;
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
    ASSERT_TRUE(app.create(gpu->deviceName())) << "no " << gpu->deviceName() << " with the validation layer";
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
            if (!app.transformFeedback) break;  // captures need it; the images below do not
            FrameSettings frame;
            frame.tessFactor = f;
            frame.path = DrawPath::Patterns;
            Tessellation gpu, cpu;
            st = capture(*surface, frame, gpu);
            ASSERT_TRUE(st) << st.message;
            EvalSettings es;
            es.tessFactor = f;
            es.path = DrawPath::Patterns;
            evaluateCpu(b->asset, b->asset.positions.data(), es, cpu);
            SCOPED_TRACE("F = " + std::to_string(f));
            expectSameSurface(gpu, cpu, DrawPath::Patterns);
            checked += gpu.vertexCount();
        }

        // Screen-space factors: sorted into per-pattern lists on the GPU and drawn
        // indirect, one draw per pattern.
        if (app.transformFeedback && app.drawIndirectFirstInstance) {
            EvalSettings es;
            es.tessFactor = 8;
            es.path = DrawPath::Patterns;
            es.lod.mode = LodMode::Screen;
            const float eye[3] = {0.3f, 0.9f, 2.2f};
            std::copy(eye, eye + 3, es.lod.eye);
            es.lod.pixelsPerUnit = 400;
            es.lod.pixelsPerEdge = 6;
            const FrameSettings frame{es};
            Tessellation gpu, cpu;
            DrawStats stats;
            st = capture(*surface, frame, gpu, &stats);
            ASSERT_TRUE(st) << st.message;
            evaluateCpu(b->asset, b->asset.positions.data(), es, cpu);
            SCOPED_TRACE("screen");
            expectSameSurface(gpu, cpu, DrawPath::Patterns);
            EXPECT_GE(stats.drawCalls, 343u);  // one indirect draw per pattern (gpu_layout.h's LT_PATTERN_KEYS)
            checked += gpu.vertexCount();
        }

        // The same image as on the shared device (tessellation enabled there).
        RenderSettings rs;
        rs.width = rs.height = 96;
        rs.frame.tessFactor = 8;
        rs.frame.path = DrawPath::Patterns;
        rs.frame.coloring = Coloring::Levels;
        Image here, shared;
        st = renderImage(*surface, rs, here);
        ASSERT_TRUE(st) << st.message;
        auto reference = upload(*b);
        ASSERT_NE(reference, nullptr);
        ASSERT_TRUE(renderImage(*reference, rs, shared));
        EXPECT_EQ(here.rgba, shared.rgba);

        // The tessellator path is refused, not drawn.
        RenderSettings tessellated;
        tessellated.frame.tessFactor = 4;
        Image ignored;
        st = renderImage(*surface, tessellated, ignored);
        EXPECT_EQ(st.code, Status::Unsupported) << st.message;
        EXPECT_NE(st.message.find("DrawPath::Patterns"), std::string::npos) << st.message;
    }
    for (const std::string& m : app.messages) ADD_FAILURE() << "validation: " << m;
    std::printf("[ figures  ] without tessellation shaders: %zu captured vertices equal the CPU's\n", checked);
}

// A host-visible buffer of the application's (STORAGE_BUFFER usage), mapped.
struct HostBuffer {
    VkDevice device = VK_NULL_HANDLE;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    HostBuffer(const VulkanHandles& h, VkDeviceSize size) : device(h.device) {
        auto info = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
        info.size = std::max<VkDeviceSize>(size, 4);
        info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        if (vkCreateBuffer(device, &info, nullptr, &buffer) != VK_SUCCESS) return;
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device, buffer, &req);
        VkPhysicalDeviceMemoryProperties props;
        vkGetPhysicalDeviceMemoryProperties(h.physicalDevice, &props);
        const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        uint32_t type = 0;
        while (type < props.memoryTypeCount &&
               !((req.memoryTypeBits >> type & 1) && (props.memoryTypes[type].propertyFlags & want) == want))
            ++type;
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
        if (vkAllocateMemory(device, &alloc, nullptr, &memory) != VK_SUCCESS) return;
        vkBindBufferMemory(device, buffer, memory, 0);
        vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped);
    }
    ~HostBuffer() {
        vkDestroyBuffer(device, buffer, nullptr);
        vkFreeMemory(device, memory, nullptr);
    }
};

// recordSubdivision + recordEvaluate into the application's command buffer and
// buffers, then the host reads them: the vertices and indices of `frame`, as many
// as the counts say (at most evaluateSizes'; exactly those at global factors).
// With `room`: buffers of that size (at most the frame's), filled with all-ones
// words first, read back whole; the counts into `roomCounts`.
void evaluateOnGpu(VulkanContext& gpu, VulkanSurface& surface, const FrameSettings& frame, std::vector<float>& vertices,
                   std::vector<uint32_t>& indices, const VulkanSurface::EvaluateSizes* room = nullptr,
                   VulkanSurface::EvaluateCounts* roomCounts = nullptr) {
    const VulkanHandles h = gpu.handles();
    VulkanSurface::EvaluateSizes sizes;
    Status st = surface.evaluateSizes(frame, sizes);
    ASSERT_TRUE(st) << st.message;
    if (room) {  // buffers for the room, or for the frame where the room is larger
        sizes.vertices = std::min(sizes.vertices, room->vertices);
        sizes.indices = std::min(sizes.indices, room->indices);
    }
    HostBuffer vb(h, sizes.vertexBytes()), ib(h, sizes.indexBytes()), cb(h, sizeof(VulkanSurface::EvaluateCounts));
    ASSERT_NE(vb.mapped, nullptr);
    ASSERT_NE(ib.mapped, nullptr);
    ASSERT_NE(cb.mapped, nullptr);
    std::memset(vb.mapped, 0xff, sizes.vertexBytes());
    std::memset(ib.mapped, 0xff, sizes.indexBytes());
    VkCommandPool pool;
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, h.queueFamily};
    VK_OK(vkCreateCommandPool(h.device, &poolInfo, nullptr, &pool));
    VkCommandBuffer cmd;
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                      VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    VK_OK(vkAllocateCommandBuffers(h.device, &alloc, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                   VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
    VK_OK(vkBeginCommandBuffer(cmd, &begin));
    st = surface.recordSubdivision(cmd, frame);
    EXPECT_TRUE(st) << st.message;
    if (frame.lod.mode == LodMode::Screen) {  // only the GPU knows how many: the counts are needed
        EXPECT_EQ(surface.recordEvaluate(cmd, frame, vb.buffer, 0, ib.buffer, 0).code, Status::Usage);
    }
    // The counts are optional at global factors (F = 1 goes without them).
    const bool counted = frame.lod.mode == LodMode::Screen || frame.tessFactor != 1;
    st = surface.recordEvaluate(cmd, frame, vb.buffer, 0, ib.buffer, 0, counted ? cb.buffer : VK_NULL_HANDLE, 0, room);
    EXPECT_TRUE(st) << st.message;
    VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                           VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0,
                         nullptr, 0, nullptr);
    VK_OK(vkEndCommandBuffer(cmd));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO, nullptr, 0, nullptr, nullptr, 1, &cmd, 0, nullptr};
    VK_OK(vkQueueSubmit(h.queue, 1, &submit, VK_NULL_HANDLE));
    VK_OK(vkQueueWaitIdle(h.queue));
    const float* v = static_cast<const float*>(vb.mapped);
    const uint32_t* i = static_cast<const uint32_t*>(ib.mapped);
    VulkanSurface::EvaluateCounts counts{uint32_t(sizes.vertices), uint32_t(sizes.indices)};
    if (counted) std::memcpy(&counts, cb.mapped, sizeof counts);
    if (room) {  // the whole buffers
        *roomCounts = counts;
        vertices.assign(v, v + sizes.vertices * kEvaluateVertexFloats);
        indices.assign(i, i + sizes.indices);
    } else {
        if (frame.lod.mode == LodMode::Screen) {  // at most the bound F's
            EXPECT_LE(counts.vertices, sizes.vertices);
            EXPECT_LE(counts.indices, sizes.indices);
        } else {
            EXPECT_EQ(counts.vertices, sizes.vertices);
            EXPECT_EQ(counts.indices, sizes.indices);
        }
        vertices.assign(v, v + std::min<uint64_t>(counts.vertices, sizes.vertices) * kEvaluateVertexFloats);
        indices.assign(i, i + std::min<uint64_t>(counts.indices, sizes.indices));
    }
    vkDestroyCommandPool(h.device, pool, nullptr);
}

// expectTruncatedWhenShort's checks at one `room`.
void expectPrefix(VulkanContext& gpu, VulkanSurface& surface, const FrameSettings& frame,
                  const std::vector<float>& full, const std::vector<uint32_t>& fullIndices,
                  const VulkanSurface::EvaluateSizes& room) {
    SCOPED_TRACE("room for " + std::to_string(room.vertices) + " vertices and " + std::to_string(room.indices) +
                 " indices");
    std::vector<float> vertices;
    std::vector<uint32_t> indices;
    VulkanSurface::EvaluateCounts counts;
    evaluateOnGpu(gpu, surface, frame, vertices, indices, &room, &counts);
    ASSERT_FALSE(::testing::Test::HasFatalFailure());
    EXPECT_EQ(counts.vertices, full.size() / kEvaluateVertexFloats);
    EXPECT_EQ(counts.indices, fullIndices.size());
    // Written: a prefix equal to the full output's; the rest still all ones.
    auto writtenPrefix = [](const auto& got, const auto& want, const char* what) {
        size_t n = 0;
        while (n < got.size() && std::memcmp(&got[n], &want[n], sizeof got[n]) == 0) ++n;
        size_t stray = 0;
        for (size_t k = n; k < got.size(); ++k) {
            uint32_t bits;
            std::memcpy(&bits, &got[k], 4);
            stray += bits != 0xffffffffu;
        }
        EXPECT_EQ(stray, 0u) << what << ": written past the prefix of " << n << " of room for " << got.size();
        return n;
    };
    const size_t v = writtenPrefix(vertices, full, "vertices"), i = writtenPrefix(indices, fullIndices, "indices");
    EXPECT_GT(v, vertices.size() / 2) << "most of the room used";
    EXPECT_GT(i, indices.size() / 4);
    // Whole records: the written triangles use exactly the written vertices, and the
    // next one needs a vertex that is not there.
    const uint32_t written = uint32_t(v / kEvaluateVertexFloats);
    ASSERT_GT(i, 0u);
    EXPECT_EQ(*std::max_element(indices.begin(), indices.begin() + i) + 1, written);
    if (i < fullIndices.size()) { EXPECT_GE(fullIndices[i], written); }
}

// At screen-space factors, with less room than the frame (`full`, its output with
// room for all) needs: the counts are the frame's all the same, and the buffers hold
// a prefix of `full`, whole records, with nothing written past it. Half the room
// (records cut), or all but 2 indices (IPP corners cut: their vertices too).
void expectTruncatedWhenShort(VulkanContext& gpu, VulkanSurface& surface, const FrameSettings& frame,
                              const std::vector<float>& full, const std::vector<uint32_t>& fullIndices) {
    const uint64_t fullVertices = full.size() / kEvaluateVertexFloats;
    for (const VulkanSurface::EvaluateSizes room :
         {VulkanSurface::EvaluateSizes{fullVertices / 2, fullIndices.size() / 2},
          VulkanSurface::EvaluateSizes{fullVertices, fullIndices.size() - 2}})
        expectPrefix(gpu, surface, frame, full, fullIndices, room);
}

// recordEvaluate's vertices (kEvaluateVertexFloats each) and indices as an indexed
// tessellation; base faces and (u,v), which they do not carry, from `cpu`.
Tessellation fromEvaluated(const std::vector<float>& vertices, const std::vector<uint32_t>& indices,
                           const Tessellation& cpu) {
    Tessellation t;
    const size_t n = vertices.size() / kEvaluateVertexFloats;
    for (size_t k = 0; k < n; ++k) {
        const float* v = &vertices[k * kEvaluateVertexFloats];
        t.positions.insert(t.positions.end(), v, v + 3);
        t.normals.insert(t.normals.end(), v + 3, v + 6);
        if (!cpu.tangents.empty()) t.tangents.insert(t.tangents.end(), v + 6, v + 10);
        if (!cpu.texcoords.empty()) t.texcoords.insert(t.texcoords.end(), v + 10, v + 12);
    }
    t.face.assign(cpu.face.begin(), cpu.face.begin() + std::min(n, cpu.face.size()));
    t.uv.assign(cpu.uv.begin(), cpu.uv.begin() + std::min(2 * n, cpu.uv.size()));
    t.indices = indices;
    return t;
}

// The surface into the application's buffers (recordEvaluate): the CPU evaluator's
// indexed vertices and indices (surface_compare.h), and, de-indexed, the draw's
// capture; at
// global factors and at screen-space ones (each patch its own pattern, F = 8 the
// bound; the eye close to one side, so the factors range from 1 to 8), there also
// into buffers with less room than the frame needs.
TEST_F(VulkanPatterns, RecordEvaluateEqualsTheCpuAndTheDraw) {
    size_t vertices = 0;
    for (const char* mesh : {"spot.obj", "loop_icos_semisharp.obj"}) {
        const std::string path =
            std::string(mesh) == "spot.obj" ? corpusMesh(mesh) : corpusDir() + "/opensubdiv-loop/" + mesh;
        const Baked* b = baked(path, 3, true);
        ASSERT_NE(b, nullptr) << mesh;
        auto surface = upload(*b);
        ASSERT_NE(surface, nullptr);
        size_t atBound = 0;  // vertices at F = 8, the screen-space view's bound
        for (float f : {1.0f, 3.0f, 8.0f, 0.0f}) {
            const bool screen = f == 0;
            SCOPED_TRACE(std::string(mesh) + (screen ? " screen-space factors" : " F = " + std::to_string(f)));
            FrameSettings frame;
            frame.tessFactor = screen ? 8 : f;
            frame.path = DrawPath::Patterns;
            if (screen) {
                const float eye[3] = {0.3f, 0.9f, 2.2f};
                frame.lod = cameraLod(LodMode::Screen, eye, 45, 512, 6);
            }
            std::vector<float> gpuVertices;
            std::vector<uint32_t> gpuIndices;
            evaluateOnGpu(*gpu, *surface, frame, gpuVertices, gpuIndices);
            ASSERT_FALSE(HasFatalFailure());

            EvalSettings es = frame;
            es.indexed = true;
            Tessellation cpu;
            evaluateCpu(b->asset, b->asset.positions.data(), es, cpu);
            ASSERT_EQ(gpuIndices.size(), cpu.indices.size());
            const auto mismatch = std::mismatch(gpuIndices.begin(), gpuIndices.end(), cpu.indices.begin());
            ASSERT_TRUE(mismatch.first == gpuIndices.end())
                << "index " << (mismatch.first - gpuIndices.begin()) << " of " << gpuIndices.size() << ": "
                << *mismatch.first << " against the CPU's " << *mismatch.second;
            ASSERT_EQ(gpuVertices.size(), cpu.vertexCount() * kEvaluateVertexFloats);
            // The buffers as a tessellation (their vertices carry no base face or (u,v):
            // the CPU's, which the order gives), against the CPU's and the draw's.
            Tessellation evaluated = fromEvaluated(gpuVertices, gpuIndices, cpu);
            expectSameSurface(evaluated, cpu, DrawPath::Patterns);
            Tessellation drawn;
            Status st = capture(*surface, frame, drawn);
            ASSERT_TRUE(st) << st.message;
            ASSERT_EQ(drawn.vertexCount(), gpuIndices.size());
            expectSameSurface(evaluated, drawn, DrawPath::Patterns);
            if (screen) expectTruncatedWhenShort(*gpu, *surface, frame, gpuVertices, gpuIndices);
            if (f == 3) {  // more room than the frame needs counts as the frame's (no wrapped byte counts)
                const VulkanSurface::EvaluateSizes huge{uint64_t(1) << 60, uint64_t(1) << 60};
                std::vector<float> roomy;
                std::vector<uint32_t> roomyIndices;
                VulkanSurface::EvaluateCounts counts;
                evaluateOnGpu(*gpu, *surface, frame, roomy, roomyIndices, &huge, &counts);
                EXPECT_TRUE(roomy == gpuVertices && roomyIndices == gpuIndices) << "with room for 2^60";
            }
            vertices += cpu.vertexCount();
            // On spot the view is coarser than the bound: patches of many patterns.
            if (f == 8) atBound = cpu.vertexCount();
            if (screen && std::string(mesh) == "spot.obj") { EXPECT_LT(cpu.vertexCount(), atBound); }
        }
    }
    // A capture lavapipe cannot write (over 2 GiB) in one session, on a path that draws
    // in one, is refused before drawing, not a crash (spot baked to depth 6, whose
    // F = 48 is not capped, on the compute path: millions of triangles; the batched
    // paths take it in several sessions: test_vulkan_capture.cpp).
    {
        const Baked* spot = baked(corpusMesh("spot.obj"), 6, true);
        ASSERT_NE(spot, nullptr);
        auto big = upload(*spot);
        FrameSettings f48;
        f48.tessFactor = 48;
        f48.path = DrawPath::Compute;
        Tessellation none;
        const Status st = capture(*big, f48, none);
        EXPECT_EQ(st.code, Status::Unsupported) << st.message;
    }
    // The tessellator path has no such layout.
    FrameSettings tessellated;
    VulkanSurface::EvaluateSizes sizes;
    const Baked* b = baked(corpusMesh("spot.obj"), 3, true);
    auto surface = upload(*b);
    EXPECT_EQ(surface->evaluateSizes(tessellated, sizes).code, Status::Usage);
    std::printf("[ figures  ] recordEvaluate: %zu vertices equal the CPU's indexed evaluation\n", vertices);
}

}  // namespace
}  // namespace lt::test
