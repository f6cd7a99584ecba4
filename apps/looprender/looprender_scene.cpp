// looprender --color material: the whole scene of a GLB (scene.h, scene_render.h).
#include "looprender_common.h"
#include "scene_render.h"

#include <cstdio>
#include <memory>

namespace looprender {

int runScene(const Options& o, const std::vector<uint8_t>& bytes) {
    Scene scene;
    lt::Status st = loadScene(bytes.data(), bytes.size(), o.input, scene);
    if (!st) return fail(st);
    for (const std::string& w : scene.warnings)
        std::fprintf(stderr, "looprender: warning: %s: %s\n", o.input.c_str(), w.c_str());
    if (o.animation >= 0 && size_t(o.animation) >= scene.animations.size())
        return fail(lt::Status::error(lt::Status::Usage, "--animation " + std::to_string(o.animation) + ": " + o.input +
                                                             " has " + std::to_string(scene.animations.size()) +
                                                             " animations"));
    // --time alone plays the first animation; neither: the rest pose.
    const int animation = o.animation >= 0 ? o.animation : o.time >= 0 && !scene.animations.empty() ? 0 : -1;
    const ScenePose pose = poseScene(scene, animation, o.time < 0 ? 0.0f : o.time);
    if (pose.instances.empty())
        return fail(
            lt::Status::error(lt::Status::BadInput, o.input + ": the scene has no node with a subdivided mesh"));

    lt::HeadlessOptions ho;
    ho.validation = o.validation;
    ho.deviceName = o.device;
    std::unique_ptr<lt::VulkanContext> gpu;
    st = lt::VulkanContext::createHeadless(ho, gpu);
    if (!st) return fail(st);
    SceneView view;
    view.width = o.width;
    view.height = o.height;
    view.eval = evalSettings(o, choosePath(o, *gpu));
    view.camera = o.camera;
    std::copy(o.eye, o.eye + 3, view.eye);
    std::copy(o.target, o.target + 3, view.target);
    view.fovDegrees = o.fovDegrees;
    lt::Image image;
    SceneStats stats;
    st = renderScene(*gpu, scene, pose, view, image, &stats);
    if (st && !o.png.empty()) st = writePngFile(o.png, image.width, image.height, image.rgba);
    if (!st) return fail(st);
    std::vector<std::string> messages = gpu->messages();
    for (const std::string& m : messages) std::fprintf(stderr, "looprender: validation: %s\n", m.c_str());
    if (!messages.empty())
        return fail(lt::Status::error(lt::Status::Internal, std::to_string(messages.size()) + " validation messages"));

    std::printf("%s: %u nodes with %zu surfaces, %u draws, depth up to %u, factor %g: %llu triangles (%s)\n",
                o.input.c_str(), stats.instances, scene.surfaces.size(), stats.draws, stats.maxDepth, double(o.tess),
                static_cast<unsigned long long>(stats.triangles), gpu->deviceName().c_str());
    if (o.verbose)
        std::fprintf(
            stderr,
            "looprender: %s path, %s camera, %u Vulkan surfaces (one per mesh and per skinned node), %s at %g s\n",
            pathName(view.eval.path), stats.sceneCamera ? "the file's" : "a framing", stats.surfaces,
            animation < 0
                ? "rest pose"
                : ("animation " + std::to_string(animation) + " '" + scene.animations[size_t(animation)] + "'").c_str(),
            double(o.time < 0 ? 0 : o.time));
    if (!o.json.empty()) {
        nlohmann::json report = {{"input", o.input},
                                 {"path", "vulkan"},
                                 {"drawPath", pathName(view.eval.path)},
                                 {"color", "material"},
                                 {"animation", animation},
                                 {"time", o.time < 0 ? 0.0f : o.time},
                                 {"tessFactor", o.tess},
                                 {"instances", stats.instances},
                                 {"surfaces", scene.surfaces.size()},
                                 {"draws", stats.draws},
                                 {"maxDepth", stats.maxDepth},
                                 {"triangles", stats.triangles},
                                 {"sceneCamera", stats.sceneCamera},
                                 {"device", gpu->deviceName()},
                                 {"warnings", scene.warnings},
                                 {"size", {o.width, o.height}}};
        st = writeJsonFile(o.json, report);
        if (!st) return fail(st);
    }
    return 0;
}

}  // namespace looprender
