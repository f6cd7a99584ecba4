// looprender: a scene's cages posed on the GPU (shaders/skin.comp): each posed
// instance's control points morphed and skinned from what poseScene kept of its pose
// (SceneInstance::morphWeights and joints), bit for bit poseControlPoints' on the
// CPU, into one device buffer that the instances' surfaces read through
// lt::VulkanSurface::setControlPoints(VkBuffer, offset): an engine's GPU animation
// feeding the surface without a round trip through the host.
#pragma once

#include "scene.h"
#include "scene_vk.h"

#include <vector>

namespace looprender {

class ScenePoser {
public:
    // Uploads the rest positions, morph targets, skin influences and pose of every
    // instance of `pose` that has control points of its own (SceneInstance::
    // controlPoints not empty).
    ScenePoser(const Device& dev, const Scene& scene, const ScenePose& pose);
    ~ScenePoser();
    ScenePoser(const ScenePoser&) = delete;
    ScenePoser& operator=(const ScenePoser&) = delete;

    // Records the posing dispatches, then the barrier from their writes to transfer
    // reads (the surfaces' recordSubdivision copies the control points).
    void record(VkCommandBuffer cmd) const;
    // Whether instance i is posed here, and where its control points go.
    bool posed(size_t instance) const { return firstFloat_[instance] != kNone; }
    VkBuffer buffer() const { return output_->buffer; }
    VkDeviceSize offset(size_t instance) const { return VkDeviceSize(firstFloat_[instance]) * 4; }
    // The posed control points, read back (after `record`'s command buffer is done).
    std::vector<float> readBack(size_t instance, size_t floats) const;

private:
    static constexpr uint32_t kNone = 0xffffffffu;
    struct Dispatch {
        uint32_t words[12];  // skin.comp's push constants
    };
    const Device& dev_;
    std::vector<uint32_t> firstFloat_;  // per instance
    std::vector<Dispatch> dispatches_;
    std::unique_ptr<Buffer> input_, output_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace looprender
