// looprender's scene renderer (see scene_render.h).
//
// One command buffer per image:
//   texture uploads -> per VulkanSurface recordSubdivision -> begin rendering ->
//   per instance, per cage primitive: bind set 1 (its material), recordDraw with the
//   material pipelines and mvp = view-projection * model -> end rendering -> copy the
//   colour attachment into a host buffer.
// A mesh's surface is shared by its unskinned instances; a skinned instance gets a
// surface of its own (its control points differ), so one submission draws them all.
#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include "scene_render.h"

#include "scene_vk.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>

namespace looprender {
namespace {

// material.frag's uniform block `Draw` (std140: every member 16-byte aligned).
struct DrawBlock {
    float model[16], normalMatrix[16];
    float baseColor[4], emissive[4], light[4], eye[4], factors[4], alpha[4];
    uint32_t faces[4];
};

struct Camera {
    glm::mat4 viewProjection{1};
    glm::vec3 eye{0}, towardsLight{0, 0, 1};
};

glm::mat4 toGlm(const Mat4& m) { return glm::make_mat4(m.data()); }

// The world-space control points of an instance (its own, posed, or its asset's,
// through its model matrix: the identity for a skinned one).
std::vector<float> worldPoints(const Scene& scene, const SceneInstance& inst) {
    const std::vector<float>& p = !inst.controlPoints.empty()
                                      ? inst.controlPoints
                                      : scene.surfaces[size_t(scene.meshes[inst.mesh].surface)].asset.positions;
    std::vector<float> out(p.size());
    for (size_t i = 0; i + 2 < p.size(); i += 3) transformPoint(inst.model, &p[i], &out[i]);
    return out;
}

Camera makeCamera(const Scene& scene, const ScenePose& pose, const SceneView& view, SceneStats& stats) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const SceneInstance& inst : pose.instances) {
        std::vector<float> p = worldPoints(scene, inst);
        for (size_t i = 0; i + 2 < p.size(); i += 3) {
            lo = glm::min(lo, glm::vec3(p[i], p[i + 1], p[i + 2]));
            hi = glm::max(hi, glm::vec3(p[i], p[i + 1], p[i + 2]));
        }
    }
    if (!(lo.x <= hi.x)) lo = hi = glm::vec3(0);
    const glm::vec3 centre = (lo + hi) * 0.5f;
    const float radius = std::max(glm::length(hi - lo) * 0.5f, 1e-6f);
    const float aspect = float(view.width) / float(view.height);
    Camera c;
    glm::mat4 viewMatrix, projection;
    if (!view.camera && pose.cameraNode >= 0) {   // the file's camera
        const Scene::Camera& cam = scene.cameras[size_t(scene.nodes[size_t(pose.cameraNode)].camera)];
        const glm::mat4 world = toGlm(pose.world[size_t(pose.cameraNode)]);
        viewMatrix = glm::inverse(world);
        c.eye = glm::vec3(world[3]);
        const float zfar = cam.zfar > cam.znear ? cam.zfar : glm::length(c.eye - centre) + 2 * radius + cam.znear;
        projection = glm::perspective(cam.yfov, aspect, cam.znear, zfar);
        stats.sceneCamera = true;
    } else {
        const float fov = glm::radians(view.camera ? view.fovDegrees : 40.0f);
        glm::vec3 target = centre;
        if (view.camera) {
            c.eye = glm::vec3(view.eye[0], view.eye[1], view.eye[2]);
            target = glm::vec3(view.target[0], view.target[1], view.target[2]);
        } else {   // three-quarter view from the front right, y up (as for one surface)
            c.eye = centre + glm::normalize(glm::vec3(0.6f, 0.35f, 1.0f)) * (radius / std::sin(fov * 0.5f) * 0.9f);
        }
        const float distance = std::max(glm::length(c.eye - target), 1e-6f);
        const glm::vec3 up = std::fabs(glm::normalize(c.eye - target).y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
        viewMatrix = glm::lookAt(c.eye, target, up);
        const float dEye = glm::length(c.eye - centre);
        projection = glm::perspective(fov, aspect, std::max(dEye - radius * 1.5f, distance * 1e-3f), dEye + radius * 1.5f);
    }
    projection[1][1] *= -1.0f;   // Vulkan's clip space has y down
    c.viewProjection = projection * viewMatrix;
    // The light: from above, left of and behind the camera (camera-space direction).
    const glm::mat4 cameraToWorld = glm::inverse(viewMatrix);
    c.towardsLight = glm::normalize(glm::vec3(cameraToWorld * glm::vec4(-0.35f, 0.6f, 0.7f, 0.0f)));
    return c;
}

VkSamplerAddressMode wrap(int mode) {
    return mode == 33071 ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
           : mode == 33648 ? VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT
                           : VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

// Textures, samplers and the descriptor sets of one image.
class Resources {
public:
    Resources(const Device& dev, const Scene& scene) : dev_(dev), scene_(scene) {
        for (size_t s = 0; s <= scene.samplers.size(); ++s) {   // the last: glTF's default
            SceneSampler g = s < scene.samplers.size() ? scene.samplers[s] : SceneSampler{};
            auto info = zeroed<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
            info.magFilter = g.magFilter == 9728 ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
            info.minFilter = g.minFilter == 9728 || g.minFilter == 9984 || g.minFilter == 9986 ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
            info.addressModeU = wrap(g.wrapS);
            info.addressModeV = wrap(g.wrapT);
            info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
            samplers_.push_back(VK_NULL_HANDLE);
            vkCheck(vkCreateSampler(dev.device, &info, nullptr, &samplers_.back()), "vkCreateSampler");
        }
    }
    ~Resources() {
        for (VkSampler s : samplers_) vkDestroySampler(dev_.device, s, nullptr);
        if (pool_) vkDestroyDescriptorPool(dev_.device, pool_, nullptr);
    }

    // The view and sampler of `ref` (base colour and emissive: sRGB), uploading the
    // image on first use; `fallback` (RGBA8) where there is no decoded image.
    VkDescriptorImageInfo texture(VkCommandBuffer cmd, const TextureRef& ref, bool srgb, const uint8_t fallback[4]) {
        const SceneImage* image = ref.image >= 0 && !scene_.images[size_t(ref.image)].rgba.empty() ? &scene_.images[size_t(ref.image)] : nullptr;
        const int key = image ? ref.image * 2 + srgb : -1 - int(fallback[0] != 255 ? 1 : 0);
        auto it = textures_.find(key);
        if (it == textures_.end()) {
            const uint32_t w = image ? image->width : 1, h = image ? image->height : 1;
            const uint8_t* pixels = image ? image->rgba.data() : fallback;
            auto t = std::make_unique<Texture>(dev_, srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM, w, h,
                                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
            staging_.push_back(std::make_unique<Buffer>(dev_, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT));
            std::memcpy(staging_.back()->mapped, pixels, size_t(w) * h * 4);
            transition(cmd, t->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
            VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {w, h, 1}};
            vkCmdCopyBufferToImage(cmd, staging_.back()->buffer, t->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            transition(cmd, t->image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
            it = textures_.emplace(key, std::move(t)).first;
        }
        const size_t sampler = ref.sampler >= 0 ? size_t(ref.sampler) : samplers_.size() - 1;
        return {samplers_[sampler], it->second->view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    }

    // `count` sets of `layout` (one per draw).
    std::vector<VkDescriptorSet> sets(VkDescriptorSetLayout layout, uint32_t count) {
        const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, count},
                                               {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 5 * count}};
        VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, count, 2, sizes};
        vkCheck(vkCreateDescriptorPool(dev_.device, &info, nullptr, &pool_), "vkCreateDescriptorPool");
        std::vector<VkDescriptorSetLayout> layouts(count, layout);
        std::vector<VkDescriptorSet> out(count);
        VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, pool_, count, layouts.data()};
        if (count) vkCheck(vkAllocateDescriptorSets(dev_.device, &alloc, out.data()), "vkAllocateDescriptorSets");
        return out;
    }

private:
    const Device& dev_;
    const Scene& scene_;
    std::vector<VkSampler> samplers_;
    std::map<int, std::unique_ptr<Texture>> textures_;
    std::vector<std::unique_ptr<Buffer>> staging_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

// One recordDraw: an instance's cage primitive.
struct Draw {
    lt::VulkanSurface* surface = nullptr;
    const SceneInstance* instance = nullptr;
    int material = -1;
    uint32_t faceBegin = 0, faceEnd = 0;
};

DrawBlock drawBlock(const Draw& d, const SceneMaterial& m, const Camera& cam) {
    DrawBlock b{};
    const glm::mat4 model = toGlm(d.instance->model);
    const glm::mat4 normal = glm::transpose(glm::inverse(model));
    std::copy(glm::value_ptr(model), glm::value_ptr(model) + 16, b.model);
    std::copy(glm::value_ptr(normal), glm::value_ptr(normal) + 16, b.normalMatrix);
    std::copy(m.baseColor, m.baseColor + 4, b.baseColor);
    std::copy(m.emissive, m.emissive + 3, b.emissive);
    const float light[4] = {cam.towardsLight.x, cam.towardsLight.y, cam.towardsLight.z, 0.25f};   // w: ambient
    std::copy(light, light + 4, b.light);
    const float eye[4] = {cam.eye.x, cam.eye.y, cam.eye.z, 1};
    std::copy(eye, eye + 4, b.eye);
    const float factors[4] = {m.metallic, m.roughness, m.normalScale, m.occlusionStrength};
    std::copy(factors, factors + 4, b.factors);
    b.alpha[0] = m.alphaCutoff;
    b.alpha[1] = m.mask ? 1.0f : 0.0f;
    b.alpha[2] = m.doubleSided ? 1.0f : 0.0f;
    b.faces[0] = d.faceBegin;
    b.faces[1] = d.faceEnd;
    const TextureRef* refs[5] = {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture, &m.occlusionTexture,
                                 &m.emissiveTexture};
    for (uint32_t t = 0; t < 5; ++t) b.faces[2] |= refs[t]->texCoord << t;
    b.faces[3] = m.normalTexture.image >= 0 ? 1u : 0u;
    return b;
}

void render(lt::VulkanContext& gpu, const Scene& scene, const ScenePose& pose, const SceneView& view, lt::Image& out,
            SceneStats& stats) {
    const Device dev(gpu.handles());
    lt::FrameSettings frame;
    frame.tessFactor = view.tessFactor;
    frame.spacing = view.spacing;
    frame.watertight = view.watertight;
    frame.displace = view.displace;

    // Surfaces and draws.
    std::vector<std::unique_ptr<lt::VulkanSurface>> surfaces;
    std::map<uint32_t, lt::VulkanSurface*> shared;   // mesh -> its unskinned surface
    std::vector<Draw> draws;
    auto newSurface = [&](const lt::Asset& asset) {
        std::unique_ptr<lt::VulkanSurface> s;
        lt::Status st = lt::VulkanSurface::create(gpu, asset, s);
        if (!st) throw st;
        surfaces.push_back(std::move(s));
        return surfaces.back().get();
    };
    for (const SceneInstance& inst : pose.instances) {
        const SceneMesh& mesh = scene.meshes[inst.mesh];
        const lt::SceneSurface& ss = scene.surfaces[size_t(mesh.surface)];
        lt::VulkanSurface* surface = nullptr;
        if (!inst.controlPoints.empty()) {
            surface = newSurface(ss.asset);
            if (lt::Status st = surface->setControlPoints(inst.controlPoints.data()); !st) throw st;
        } else {
            auto it = shared.find(inst.mesh);
            surface = it != shared.end() ? it->second : (shared[inst.mesh] = newSurface(ss.asset));
        }
        ++stats.instances;
        const bool whole = ss.primitives.size() == 1;   // no face to leave out
        for (size_t k = 0; k < ss.primitives.size(); ++k) {
            const uint32_t begin = ss.primitiveFaces[k], end = ss.primitiveFaces[k + 1];
            if (begin < end) draws.push_back({surface, &inst, mesh.materials[k], whole ? 0u : begin, whole ? UINT32_MAX : end});
        }
    }
    stats.surfaces = uint32_t(surfaces.size());
    stats.draws = uint32_t(draws.size());
    const Camera cam = makeCamera(scene, pose, view, stats);

    MaterialPipelines pipelines(dev, gpu, view.spacing);
    Resources resources(dev, scene);
    const VkDeviceSize align = std::max<VkDeviceSize>(dev.properties.limits.minUniformBufferOffsetAlignment, 16);
    const VkDeviceSize blockBytes = (sizeof(DrawBlock) + align - 1) / align * align;
    Buffer blocks(dev, std::max<VkDeviceSize>(blockBytes * draws.size(), 16), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    std::vector<VkDescriptorSet> sets = resources.sets(pipelines.setLayout(), uint32_t(draws.size()));

    const lt::DrawTarget formats = gpu.imageFormats();
    Texture color(dev, formats.color, view.width, view.height, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  VK_IMAGE_ASPECT_COLOR_BIT);
    Texture depth(dev, formats.depth, view.width, view.height, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    Buffer readback(dev, VkDeviceSize(view.width) * view.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);

    OneShot shot(dev);
    VkCommandBuffer cmd = shot.record();
    static const uint8_t kWhite[4] = {255, 255, 255, 255}, kFlatNormal[4] = {128, 128, 255, 255};
    for (size_t i = 0; i < draws.size(); ++i) {
        const SceneMaterial m = draws[i].material >= 0 ? scene.materials[size_t(draws[i].material)] : SceneMaterial{};
        const DrawBlock block = drawBlock(draws[i], m, cam);
        std::memcpy(static_cast<uint8_t*>(blocks.mapped) + i * blockBytes, &block, sizeof block);
        VkDescriptorBufferInfo ubo{blocks.buffer, i * blockBytes, sizeof(DrawBlock)};
        VkDescriptorImageInfo images[5] = {resources.texture(cmd, m.baseColorTexture, true, kWhite),
                                           resources.texture(cmd, m.metallicRoughnessTexture, false, kWhite),
                                           resources.texture(cmd, m.normalTexture, false, kFlatNormal),
                                           resources.texture(cmd, m.occlusionTexture, false, kWhite),
                                           resources.texture(cmd, m.emissiveTexture, true, kWhite)};
        VkWriteDescriptorSet writes[2] = {
            {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, sets[i], 0, 0, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, nullptr, &ubo, nullptr},
            {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, sets[i], 1, 0, 5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, images, nullptr,
             nullptr}};
        vkUpdateDescriptorSets(dev.device, 2, writes, 0, nullptr);
    }
    for (auto& s : surfaces) {
        if (lt::Status st = s->recordSubdivision(cmd, frame); !st) throw st;
    }
    transition(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    transition(cmd, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
               VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
               VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    VkClearValue clearColor{}, clearDepth{};
    std::copy(view.background, view.background + 4, clearColor.color.float32);
    clearDepth.depthStencil = {1.0f, 0};
    VkRenderingAttachmentInfo colorInfo{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO, nullptr, color.view,
                                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_RESOLVE_MODE_NONE, VK_NULL_HANDLE,
                                        VK_IMAGE_LAYOUT_UNDEFINED, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE, clearColor};
    VkRenderingAttachmentInfo depthInfo = colorInfo;
    depthInfo.imageView = depth.view;
    depthInfo.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depthInfo.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depthInfo.clearValue = clearDepth;
    const VkRect2D area{{0, 0}, {view.width, view.height}};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO, nullptr, 0, area, 1, 0, 1, &colorInfo, &depthInfo, nullptr};
    vkCmdBeginRendering(cmd, &rendering);
    const VkViewport viewport{0, 0, float(view.width), float(view.height), 0, 1};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &area);
    for (size_t i = 0; i < draws.size(); ++i) {
        const Draw& d = draws[i];
        const glm::mat4 mvp = cam.viewProjection * toGlm(d.instance->model);
        std::copy(glm::value_ptr(mvp), glm::value_ptr(mvp) + 16, frame.mvp);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.layout(), 1, 1, &sets[i], 0, nullptr);
        lt::DrawStats ds;
        if (lt::Status st = d.surface->recordDraw(cmd, pipelines.get(d.surface->specialization(frame)), frame, &ds); !st) throw st;
        stats.triangles += ds.triangles;
        stats.maxDepth = std::max(stats.maxDepth, ds.depth);
    }
    vkCmdEndRendering(cmd);
    transition(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {view.width, view.height, 1}};
    vkCmdCopyImageToBuffer(cmd, color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &region);
    VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0, nullptr);
    shot.submitAndWait();

    out.width = view.width;
    out.height = view.height;
    out.rgba.assign(static_cast<const uint8_t*>(readback.mapped),
                    static_cast<const uint8_t*>(readback.mapped) + size_t(view.width) * view.height * 4);
}

} // namespace

lt::Status renderScene(lt::VulkanContext& gpu, const Scene& scene, const ScenePose& pose, const SceneView& view, lt::Image& out,
                       SceneStats* stats) {
    SceneStats local;
    try {
        render(gpu, scene, pose, view, out, local);
    } catch (const lt::Status& st) {
        return st;
    } catch (const VkFailure& f) {
        return lt::Status::error(lt::Status::Internal, f.call + " failed (VkResult " + std::to_string(int(f.result)) + ")");
    } catch (const std::bad_alloc&) {
        return lt::Status::error(lt::Status::Internal, "out of host memory");
    }
    if (stats) *stats = local;
    return lt::Status::ok();
}

} // namespace looprender
