// tests/vulkan/test_vulkan_engine.cpp -- the embedding contract of looptess/vulkan.h, used
// the way an engine would: its own command pool, command buffer, attachments and
// rendering scope (plain Vulkan C API here), with recordSubdivision and recordDraw
// recorded into them. The result must be the pixels of the blocking renderImage.
#include "lod_check.h"
#include "test_vulkan_support.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cstring>
#include <functional>

namespace lt::test {
namespace {

// The engine side: a command buffer, a colour and a depth attachment, a readback
// buffer, all made with the plain C API on the context's device.
struct EngineFrame {
    VkDevice device = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkImage images[2] = {};
    VkImageView views[2] = {};
    VkDeviceMemory memory[3] = {};
    VkBuffer readback = VK_NULL_HANDLE;
    void* mapped = nullptr;
    ~EngineFrame() {
        if (!device) return;
        for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
        for (VkImage i : images) vkDestroyImage(device, i, nullptr);
        vkDestroyBuffer(device, readback, nullptr);
        for (VkDeviceMemory m : memory) vkFreeMemory(device, m, nullptr);
        vkDestroyCommandPool(device, pool, nullptr);
    }
};

uint32_t memoryType(VkPhysicalDevice physical, uint32_t bits, VkMemoryPropertyFlags flags) {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physical, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
    return UINT32_MAX;
}

void makeFrame(const VulkanHandles& h, uint32_t size, EngineFrame& f) {
    f.device = h.device;
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, h.queueFamily};
    VK_OK(vkCreateCommandPool(h.device, &poolInfo, nullptr, &f.pool));
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, f.pool,
                                      VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    VK_OK(vkAllocateCommandBuffers(h.device, &alloc, &f.cmd));
    const VkFormat formats[2] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT};
    const VkImageUsageFlags usage[2] = {VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT};
    const VkImageAspectFlags aspect[2] = {VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_DEPTH_BIT};
    for (int i = 0; i < 2; ++i) {
        auto info = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = formats[i];
        info.extent = {size, size, 1};
        info.mipLevels = info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = usage[i];
        VK_OK(vkCreateImage(h.device, &info, nullptr, &f.images[i]));
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(h.device, f.images[i], &req);
        VkMemoryAllocateInfo mem{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size,
                                 memoryType(h.physicalDevice, req.memoryTypeBits, 0)};
        VK_OK(vkAllocateMemory(h.device, &mem, nullptr, &f.memory[i]));
        VK_OK(vkBindImageMemory(h.device, f.images[i], f.memory[i], 0));
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                   nullptr,
                                   0,
                                   f.images[i],
                                   VK_IMAGE_VIEW_TYPE_2D,
                                   formats[i],
                                   {},
                                   {aspect[i], 0, 1, 0, 1}};
        VK_OK(vkCreateImageView(h.device, &view, nullptr, &f.views[i]));
    }
    auto buf = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    buf.size = VkDeviceSize(size) * size * 4;
    buf.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VK_OK(vkCreateBuffer(h.device, &buf, nullptr, &f.readback));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(h.device, f.readback, &req);
    VkMemoryAllocateInfo mem{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size,
                             memoryType(h.physicalDevice, req.memoryTypeBits,
                                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)};
    VK_OK(vkAllocateMemory(h.device, &mem, nullptr, &f.memory[2]));
    VK_OK(vkBindBufferMemory(h.device, f.readback, f.memory[2], 0));
    VK_OK(vkMapMemory(h.device, f.memory[2], 0, VK_WHOLE_SIZE, 0, &f.mapped));
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
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
    vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
}

// Records one engine frame as vulkan.h's example does: subdivision, then per batch
// (one but on the compute path) its evaluation and its draws in the engine's scope,
// which clears the attachments first and loads them after.
void recordFrame(VulkanSurface& surface, const FrameSettings& frame, uint32_t size, const EngineFrame& f) {
    VkCommandBuffer cmd = f.cmd;
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    VK_OK(vkBeginCommandBuffer(cmd, &begin));
    Status st = surface.recordSubdivision(cmd, frame);
    ASSERT_TRUE(st) << st.message;
    imageBarrier(cmd, f.images[0], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                 VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    imageBarrier(cmd, f.images[1], VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                 VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    auto color = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    color.imageView = f.views[0];
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.clearValue.color = {{1, 1, 1, 1}};
    auto depth = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    depth.imageView = f.views[1];
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {1.0f, 0};
    auto rendering = vkStruct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
    rendering.renderArea = {{0, 0}, {size, size}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &color;
    rendering.pDepthAttachment = &depth;
    uint32_t batches = 0;
    st = surface.drawBatches(frame, batches);
    ASSERT_TRUE(st) << st.message;
    for (uint32_t b = 0; b < batches; ++b) {
        st = surface.recordBatch(cmd, frame, b);
        ASSERT_TRUE(st) << st.message;
        color.loadOp = depth.loadOp = b == 0 ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        depth.storeOp = b + 1 < batches ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
        vkCmdBeginRendering(cmd, &rendering);
        VkViewport viewport{0, 0, float(size), float(size), 0, 1};
        VkRect2D scissor{{0, 0}, {size, size}};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        st = surface.recordDraw(cmd, DrawTarget{VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT}, frame);
        ASSERT_TRUE(st) << st.message;
        vkCmdEndRendering(cmd);
    }
    imageBarrier(cmd, f.images[0], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {size, size, 1}};
    vkCmdCopyImageToBuffer(cmd, f.images[0], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, f.readback, 1, &region);
    VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                         VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host, 0, nullptr, 0,
                         nullptr);
    VK_OK(vkEndCommandBuffer(cmd));
}

void submitAndWait(const VulkanHandles& h, VkCommandBuffer cmd) {
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VK_OK(vkQueueSubmit(h.queue, 1, &submit, VK_NULL_HANDLE));
    VK_OK(vkQueueWaitIdle(h.queue));
}

// spot at depth 3 on the shared context, for the tests that draw it.
class VulkanEngine : public VulkanTest {
protected:
    void uploadSpot() {
        spot = baked(corpusMesh("spot.obj"), 3);
        ASSERT_NE(spot, nullptr);
        surface = upload(*spot);
        ASSERT_NE(surface, nullptr);
    }
    const Baked* spot = nullptr;
    std::unique_ptr<VulkanSurface> surface;
};

constexpr uint32_t kSize = 96;  // the engine frames' width and height

// One engine frame of `frame` (recordFrame) in `f` (made on first use; its command
// buffer reset), submitted and waited for; `pixels`: its colour attachment.
void drawEngineFrame(const VulkanHandles& h, VulkanSurface& surface, const FrameSettings& frame, EngineFrame& f,
                     std::vector<uint8_t>& pixels) {
    if (!f.device) makeFrame(h, kSize, f);
    VK_OK(vkResetCommandPool(h.device, f.pool, 0));
    recordFrame(surface, frame, kSize, f);
    submitAndWait(h, f.cmd);
    pixels.assign(static_cast<uint8_t*>(f.mapped), static_cast<uint8_t*>(f.mapped) + kSize * kSize * 4);
}

// An engine frame of `frame` in `f`, which must show `reference`'s pixels, many of
// them drawn (not the white background); the pixels drawn.
size_t expectEngineFrame(const VulkanHandles& h, VulkanSurface& surface, const FrameSettings& frame, EngineFrame& f,
                         const Image& reference) {
    std::vector<uint8_t> pixels;
    drawEngineFrame(h, surface, frame, f, pixels);
    EXPECT_TRUE(pixels == reference.rgba) << "recordDraw into the engine's scope differs from renderImage";
    size_t drawn = 0;
    for (size_t i = 0; i < pixels.size(); i += 4) drawn += pixels[i] != 255;
    EXPECT_GT(drawn, 500u);
    return drawn;
}

// renderImage's settings for a size x size frame seen through `mvp`.
RenderSettings engineSettings(uint32_t size, const float (&mvp)[16]) {
    RenderSettings rs;
    rs.width = rs.height = size;
    std::memcpy(rs.frame.mvp, mvp, sizeof mvp);
    return rs;
}

// renderImage's settings for spot seen from the front, filling the frame.
RenderSettings spotSettings() {
    return engineSettings(kSize, {1.2f, 0, 0, 0, 0, -1.2f, 0, 0, 0, 0, -0.2f, 0, 0, 0, 0.5f, 1});
}

TEST_F(VulkanEngine, RecordIntoTheApplicationsCommandBuffer) {
    const Baked* b = baked(corpusShape("loop_cubes_semisharp.obj"), 3);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    RenderSettings rs = engineSettings(kSize, {0.45f, 0, 0, 0, 0, -0.45f, 0, 0, 0, 0, -0.2f, 0, 0, 0, 0.5f, 1});
    rs.frame.tessFactor = 5.5f;
    Image reference;
    ASSERT_TRUE(renderImage(*surface, rs, reference));

    VulkanHandles h = gpu->handles();
    EngineFrame f;
    // Two frames through the same command buffer and surface: the second, with
    // moved control points, must match the reference rendered from those points.
    std::vector<uint8_t> pixels;
    drawEngineFrame(h, *surface, rs.frame, f, pixels);
    EXPECT_TRUE(pixels == reference.rgba) << "recordDraw into the engine's scope differs from renderImage";

    std::vector<float> moved = b->asset.positions;
    for (float& x : moved) x *= 0.8f;
    ASSERT_TRUE(surface->setControlPoints(moved.data()));
    Image movedReference;
    ASSERT_TRUE(renderImage(*surface, rs, movedReference));
    EXPECT_FALSE(movedReference.rgba == reference.rgba);
    drawEngineFrame(h, *surface, rs.frame, f, pixels);
    EXPECT_TRUE(pixels == movedReference.rgba);
}

// Screen-space factors on the pattern path: recordSubdivision sorts the patterns for
// its frame (pattern_sort.comp), and the engine's frame equals renderImage's; a draw
// whose eye or factor was not sorted for is refused.
TEST_F(VulkanEngine, ScreenSpacePatternsInTheApplicationsCommandBuffer) {
    RenderSettings rs = spotSettings();
    ASSERT_NO_FATAL_FAILURE(uploadSpot());
    const EvalSettings es = lodForFactor(spot->asset, LodMode::Screen, 0, 6.0f);
    static_cast<EvalSettings&>(rs.frame) = es;
    rs.frame.path = DrawPath::Patterns;
    Image reference;
    FrameReport report;
    Status st = renderImage(*surface, rs, reference, &report);
    ASSERT_TRUE(st) << st.message;
    EXPECT_GT(report.draw.triangles, 0u);

    VulkanHandles h = gpu->handles();
    EngineFrame f;
    expectEngineFrame(h, *surface, rs.frame, f, reference);

    VK_OK(vkResetCommandPool(h.device, f.pool, 0));
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    VK_OK(vkBeginCommandBuffer(f.cmd, &begin));
    ASSERT_TRUE(surface->recordSubdivision(f.cmd, rs.frame));
    FrameSettings moved = rs.frame;
    moved.lod.eye[0] += 0.25f;
    st = surface->recordDraw(f.cmd, DrawTarget{}, moved);
    EXPECT_EQ(st.code, Status::Usage);
    EXPECT_NE(st.message.find("sort"), std::string::npos) << st.message;
    ASSERT_TRUE(surface->recordSubdivision(f.cmd, rs.frame.tessFactor));  // no sort: only refinement
    EXPECT_EQ(surface->recordDraw(f.cmd, DrawTarget{}, rs.frame).code, Status::Usage);
    VK_OK(vkEndCommandBuffer(f.cmd));
}

// DrawPath::Compute in the engine's command buffer, at a global factor and at
// screen-space ones, in several batches (a small FrameSettings::computeBytes): the
// pixels of renderImage, and of the pattern path, which draws the same triangles.
TEST_F(VulkanEngine, ComputeBatchesInTheApplicationsCommandBuffer) {
    RenderSettings rs = spotSettings();
    ASSERT_NO_FATAL_FAILURE(uploadSpot());
    VulkanHandles h = gpu->handles();
    EngineFrame f;
    const EvalSettings screen = lodForFactor(spot->asset, LodMode::Screen, 0, 6.0f);
    for (bool atScreen : {false, true}) {
        SCOPED_TRACE(atScreen ? "screen-space factors" : "F = 6");
        rs.frame.tessFactor = atScreen ? screen.tessFactor : 6.0f;
        rs.frame.lod = atScreen ? screen.lod : Lod{};
        rs.frame.path = DrawPath::Patterns;
        Image patterns;
        ASSERT_TRUE(renderImage(*surface, rs, patterns));
        rs.frame.path = DrawPath::Compute;
        rs.frame.computeBytes = 600000;  // about 10,000 vertices a batch
        uint32_t batches = 0;
        ASSERT_TRUE(surface->drawBatches(rs.frame, batches));
        EXPECT_GT(batches, 4u);
        Image reference;
        FrameReport report;
        Status st = renderImage(*surface, rs, reference, &report);
        ASSERT_TRUE(st) << st.message;
        EXPECT_EQ(report.draw.batches, batches);
        EXPECT_EQ(report.draw.path, DrawPath::Compute);
        EXPECT_TRUE(reference.rgba == patterns.rgba) << "the compute path draws other pixels than the pattern path";
        const size_t drawn = expectEngineFrame(h, *surface, rs.frame, f, reference);
        std::printf("[ figures  ] compute path, %s: %u batches, %zu pixels drawn, GPU ms evaluate %.3f, draw %.3f\n",
                    atScreen ? "screen-space factors" : "F = 6", batches, drawn, report.evaluateMs, report.drawMs);
    }
    // A draw without its batch's evaluation, and a batch past the frame's, are refused.
    VK_OK(vkResetCommandPool(h.device, f.pool, 0));
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    VK_OK(vkBeginCommandBuffer(f.cmd, &begin));
    ASSERT_TRUE(surface->recordSubdivision(f.cmd, rs.frame));
    EXPECT_EQ(surface->recordDraw(f.cmd, DrawTarget{}, rs.frame).code, Status::Usage);
    uint32_t batches = 0;
    ASSERT_TRUE(surface->drawBatches(rs.frame, batches));
    EXPECT_EQ(surface->recordBatch(f.cmd, rs.frame, batches).code, Status::Usage);
    VK_OK(vkEndCommandBuffer(f.cmd));
    EXPECT_GT(surface->deviceMemory().compute, 600000u);
}

// DrawPath::Auto in the engine's command buffer: the first frames carry trials of
// every path the device has (timed into the surface's own image), the path is kept
// once each has three times, the fastest, and from then on frames draw with it: the
// pixels of renderImage with that path named.
TEST_F(VulkanEngine, AutoKeepsTheFastestPathItMeasured) {
    RenderSettings rs = spotSettings();
    ASSERT_NO_FATAL_FAILURE(uploadSpot());
    rs.frame.tessFactor = 6;
    rs.frame.path = DrawPath::Auto;
    EXPECT_EQ(surface->drawnPath(rs.frame), DrawPath::Patterns) << "undecided";
    VulkanHandles h = gpu->handles();
    EngineFrame f;
    std::vector<uint8_t> pixels;
    int frames = 0;
    for (; frames < 8 && !(surface->pathChoices().size() == 1 && surface->pathChoices()[0].decided); ++frames)
        drawEngineFrame(h, *surface, rs.frame, f, pixels);
    drawEngineFrame(h, *surface, rs.frame, f, pixels);  // the decision is read here
    const std::vector<VulkanSurface::PathChoice> choices = surface->pathChoices();
    ASSERT_EQ(choices.size(), 1u);
    const VulkanSurface::PathChoice& c = choices[0];
    ASSERT_TRUE(c.decided) << "after " << frames << " frames";
    EXPECT_EQ(c.depth, 3u);
    EXPECT_GE(c.trials, 3u);
    double fastest = 1e300;
    for (double ms : c.ms) {
        EXPECT_GT(ms, 0.0) << "every path measured (the device has tessellation shaders)";
        fastest = std::min(fastest, ms);
    }
    EXPECT_EQ(c.ms[size_t(c.kept)], fastest);
    EXPECT_EQ(surface->drawnPath(rs.frame), c.kept);
    RenderSettings named = rs;
    named.frame.path = c.kept;
    Image reference;
    ASSERT_TRUE(renderImage(*surface, named, reference));
    EXPECT_TRUE(pixels == reference.rgba) << "a decided frame draws with the path kept";
    EXPECT_EQ(surface->deviceMemory().trials, 0u) << "the trial image is gone";
    const char* names[3] = {"tessellator", "patterns", "compute"};
    std::printf(
        "[ figures  ] DrawPath::Auto on %s: kept %s after %d frames; median ms tessellator %.2f, patterns %.2f, "
        "compute %.2f\n",
        gpu->deviceName().c_str(), names[size_t(c.kept)], frames, c.ms[0], c.ms[1], c.ms[2]);
}

TEST_F(VulkanEngine, DrawingADepthNotSubdividedIsAUsageError) {
    const Baked* b = baked(corpusShape("loop_cube.obj"), 3);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    VulkanHandles h = gpu->handles();
    EngineFrame f;
    makeFrame(h, 8, f);
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    VK_OK(vkBeginCommandBuffer(f.cmd, &begin));
    ASSERT_TRUE(surface->recordSubdivision(f.cmd, 2.0f));  // depth 1
    FrameSettings frame;
    frame.tessFactor = 8;  // depth 3
    EXPECT_EQ(surface->recordDraw(f.cmd, DrawTarget{}, frame).code, Status::Usage);
    EXPECT_EQ(surface->recordSubdivision(VK_NULL_HANDLE, 2.0f).code, Status::Usage);
    VK_OK(vkEndCommandBuffer(f.cmd));
}

}  // namespace
}  // namespace lt::test
