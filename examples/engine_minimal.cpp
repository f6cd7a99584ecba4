// examples/engine_minimal.cpp -- what an engine does with a baked asset, using only
// the public headers (docs/engine-integration.md quotes it):
//
//   1. load the GLB that loopbake wrote (lt::readAssetGlb);
//   2. evaluate the limit surface on the CPU (lt::evaluateCpu, lt::CpuEvaluator);
//   3. on the engine's own Vulkan 1.3 device: adopt it, upload the asset once, and
//      record subdivision and draw into the engine's command buffer every frame
//      (setUpSurface, frameOf, recordFrame), or write the surface into the engine's
//      own buffers (recordIntoBuffers).
//
// main runs steps 1 and 2 (the tests run it on a baked file). Step 3 needs the
// engine's device, command buffers and attachments, so main does not call it; it is
// compiled with the rest, so the calls shown here stay the library's.
//
//   engine_minimal ASSET.glb    exit 0 ok, 1 usage, 2 unreadable or invalid asset
#include <looptess/asset.h>
#include <looptess/runtime.h>
#include <looptess/vulkan.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

// ---- Step 3: the Vulkan calls of an engine (compiled, not run by main) ------------

// Once per asset: wrap the engine's device (borrowed, never destroyed by looptess)
// and upload the asset's tables.
lt::Status setUpSurface(const lt::VulkanHandles& engine, const lt::Asset& asset,
                        std::unique_ptr<lt::VulkanContext>& context, std::unique_ptr<lt::VulkanSurface>& surface) {
    lt::Status st = lt::VulkanContext::adopt(engine, context);
    if (st) st = lt::VulkanSurface::create(*context, asset, surface);  // blocks until uploaded
    return st;
}

// A frame of the evaluation the CPU path takes (step 2's settings): the same
// EvalSettings give the same surface; the frame adds the draw's camera.
lt::FrameSettings frameOf(const lt::EvalSettings& settings, const float mvp[16]) {
    lt::FrameSettings frame{settings};    // tessFactor, spacing, path, lod, watertight, displace
    std::copy(mvp, mvp + 16, frame.mvp);  // column-major, object to clip
    return frame;
}

// Every frame, into the engine's command buffer: subdivision (compute, outside any
// rendering scope), then per batch an evaluation (compute path only) and the draw
// inside the engine's own rendering scope. One loop serves every DrawPath.
lt::Status recordFrame(lt::VulkanSurface& surface, VkCommandBuffer cmd, const lt::FrameSettings& frame,
                       const lt::DrawTarget& formats, VkImageView color, VkImageView depth, VkExtent2D extent,
                       const float* skinnedPositions) {
    if (skinnedPositions) {  // animation: 3 floats per control vertex; the tables never change
        if (lt::Status st = surface.setControlPoints(skinnedPositions); !st) return st;
    }
    if (lt::Status st = surface.recordSubdivision(cmd, frame); !st) return st;
    uint32_t batches = 1;
    if (lt::Status st = surface.drawBatches(frame, batches); !st) return st;
    for (uint32_t b = 0; b < batches; ++b) {
        if (lt::Status st = surface.recordBatch(cmd, frame, b); !st) return st;

        VkRenderingAttachmentInfo colorAttachment{};
        colorAttachment.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
        colorAttachment.imageView = color;
        colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        colorAttachment.loadOp = b == 0 ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        colorAttachment.clearValue.color = {{1.0f, 1.0f, 1.0f, 1.0f}};
        VkRenderingAttachmentInfo depthAttachment{};
        depthAttachment.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
        depthAttachment.imageView = depth;
        depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depthAttachment.loadOp = b == 0 ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depthAttachment.clearValue.depthStencil = {1.0f, 0};
        VkRenderingInfo rendering{};
        rendering.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
        rendering.renderArea = {{0, 0}, extent};
        rendering.layerCount = 1;
        rendering.colorAttachmentCount = 1;
        rendering.pColorAttachments = &colorAttachment;
        rendering.pDepthAttachment = &depthAttachment;

        vkCmdBeginRendering(cmd, &rendering);  // attachment formats as `formats` says
        const VkViewport viewport{0, 0, float(extent.width), float(extent.height), 0, 1};
        const VkRect2D scissor{{0, 0}, extent};
        vkCmdSetViewport(cmd, 0, 1, &viewport);  // dynamic state of looptess's pipelines
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        lt::Status st = surface.recordDraw(cmd, formats, frame);  // draws batch b
        vkCmdEndRendering(cmd);
        if (!st) return st;
    }
    return lt::Status::ok();
}

// The surface as indexed triangles in the engine's own buffers (ray tracing,
// physics, export), outside any rendering scope. The buffers need STORAGE_BUFFER
// usage and room for evaluateSizes' counts; the engine records the barrier from
// these compute writes to its own reads.
lt::Status recordIntoBuffers(lt::VulkanSurface& surface, VkCommandBuffer cmd, lt::FrameSettings frame,
                             VkBuffer vertices, VkBuffer indices, VkBuffer counts) {
    frame.path = lt::DrawPath::Patterns;  // any path but the tessellator's
    lt::VulkanSurface::EvaluateSizes sizes;
    if (lt::Status st = surface.evaluateSizes(frame, sizes); !st) return st;
    // The engine sizes `vertices` to sizes.vertexBytes(), `indices` to sizes.indexBytes().
    if (lt::Status st = surface.recordSubdivision(cmd, frame); !st) return st;
    return surface.recordEvaluate(cmd, frame, vertices, 0, indices, 0, counts, 0);
}

// ---- Steps 1 and 2 ------------------------------------------------------------------

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: engine_minimal ASSET.glb\n");
        return 1;
    }
    std::ifstream file(argv[1], std::ios::binary);
    if (!file) {
        std::fprintf(stderr, "engine_minimal: %s: cannot open\n", argv[1]);
        return 2;
    }
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};

    // 1. Load: every range checked, then validateAsset; the message names the file.
    lt::Asset asset;
    if (lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), argv[1], asset); !st) {
        std::fprintf(stderr, "%s\n", st.message.c_str());
        return 2;
    }

    // 2. One evaluation on the CPU: the same bits a Vulkan device draws.
    lt::EvalSettings settings;
    settings.tessFactor = 4;  // depth ceil(log2 4) = 2, capped at the asset's
    lt::Tessellation soup;
    lt::evaluateCpu(asset, asset.positions.data(), settings, soup);

    // ... or per frame, with control points that change (here: the baked ones moved
    // up by 0.1) and an evaluator that keeps what depends on the asset alone.
    lt::CpuEvaluator evaluator(asset);
    std::vector<float> moved = asset.positions;
    for (size_t i = 1; i < moved.size(); i += 3) moved[i] += 0.1f;
    lt::Tessellation frame;
    evaluator.evaluate(moved.data(), settings, frame);

    std::printf("engine_minimal: %u control vertices, depth %u of %u, %zu triangles at F = %g (moved: %zu)\n",
                asset.controlVertexCount(), lt::runtimeDepth(asset, settings.tessFactor), asset.maxDepth(),
                soup.triangleCount(), double(settings.tessFactor), frame.triangleCount());
    return soup.triangleCount() > 0 && frame.triangleCount() == soup.triangleCount() ? 0 : 2;
}
