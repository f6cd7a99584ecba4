// looprender's scene renderer: every instance of a posed scene (scene.h) drawn with
// its glTF materials through looptess's Vulkan path, as an engine would: its own
// pipelines around lt::surfaceStages with shaders/material.frag, its own descriptor
// set 1 per drawn primitive (material factors and textures), its own attachments and
// command buffer; the library records the subdivision and the draws.
#pragma once

#include "scene.h"

#include "looptess/tools/vulkan_tools.h"

namespace looprender {

struct SceneView {
    uint32_t width = 512, height = 512;
    // Every surface's evaluation, drawn as lt::FrameSettings{eval} (indexed and
    // editValues are not read).
    lt::EvalSettings eval;
    // A camera of the command line (eye, target, vertical field of view in
    // degrees), else the pose's camera node, else a view framing every instance.
    bool camera = false;
    float eye[3] = {0, 0, 0}, target[3] = {0, 0, 0}, fovDegrees = 40;
    float background[4] = {1, 1, 1, 1};
};

// What renderScene drew.
struct SceneStats {
    uint32_t instances = 0;    // nodes drawn (each with its surface's primitives)
    uint32_t surfaces = 0;     // VulkanSurfaces: one per mesh, plus one per skinned instance
    uint32_t draws = 0;        // recordDraw calls (one per cage primitive and instance)
    uint32_t maxDepth = 0;     // deepest runtime depth of a surface
    uint64_t triangles = 0;    // over all draws (the discard of other primitives' faces not subtracted)
    bool sceneCamera = false;  // drawn from the file's camera
};

// Renders `pose` of `scene` into `out` (RGBA8, sRGB-encoded, top row first). Blocks.
// Errors: the library's (Unsupported, Internal) and Internal for a failed Vulkan call.
lt::Status renderScene(lt::VulkanContext& gpu, const Scene& scene, const ScenePose& pose, const SceneView& view,
                       lt::Image& out, SceneStats* stats = nullptr);

}  // namespace looprender
