// tests/vulkan/test_vulkan_pose.cpp -- animation without a round trip through the host:
// control points from an application's device buffer (VulkanSurface::
// setControlPoints(VkBuffer, offset)) are subdivided as the same points given from
// the host, bit for bit; and looprender's posing of a scene's cages on the GPU
// (viewer/scene_skin.h, shaders/skin.comp) gives the control points of its CPU
// posing (poseScene, the oracle; test_scene_pose.cpp checks that one by hand), bit
// for bit, for a skinned, animated character (the Fox) and one with morph targets
// and unnormalized skin weights (RobotExpressive), at several times.
#include "test_vulkan_support.h"
#include "test_paths.h"
#include "tool_run.h"

#include "scene.h"
#include "scene_skin.h"
#include "scene_vk.h"

#include "looptess/tools/file_io.h"

#include <cstring>
#include <filesystem>

#include <unistd.h>

namespace lt::test {
namespace {

using VulkanPose = VulkanTest;

// The control points of spot moved, in a host-visible buffer of the application's,
// at an offset: the refined vertices equal those of the same points set from the
// host, and those of the CPU.
TEST_F(VulkanPose, ControlPointsFromADeviceBufferAreSubdividedAsFromTheHost) {
    const Baked* b = baked(corpusMesh("spot.obj"), 3);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    std::vector<float> moved = b->asset.positions;
    for (size_t i = 0; i < moved.size(); i += 3) moved[i + 1] += 0.04f * std::sin(4.0f * moved[i]);
    const looprender::Device dev(gpu->handles());
    const VkDeviceSize offset = 64;
    looprender::Buffer buffer(dev, offset + moved.size() * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    std::memcpy(static_cast<char*>(buffer.mapped) + offset, moved.data(), moved.size() * 4);
    ASSERT_TRUE(surface->setControlPoints(buffer.buffer, offset));
    std::vector<float> fromDevice, fromHost, cpu;
    ASSERT_TRUE(readVertices(*surface, 8, fromDevice));
    ASSERT_TRUE(surface->setControlPoints(moved.data()));
    ASSERT_TRUE(readVertices(*surface, 8, fromHost));
    subdivideCpu(b->asset, moved.data(), runtimeDepth(b->asset, 8), cpu);
    EXPECT_TRUE(fromDevice == fromHost);
    EXPECT_TRUE(fromDevice == cpu);
    EXPECT_FALSE(fromDevice == std::vector<float>(fromDevice.size(), 0.0f));
}

// `name` (tests/data/real) baked by loopbake and loaded as a scene.
looprender::Scene bakedScene(const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path scratch = fs::path(::testing::TempDir()) / ("pose_" + name + "_" + std::to_string(getpid()));
    fs::create_directories(scratch);
    const std::string glb = (scratch / "baked.glb").string();
    RunResult bake = runTool(loopbakeExe(), {testDataDir() + "/real/" + name, "-o", glb}, scratch);
    EXPECT_EQ(bake.exitCode, 0) << bake.err;
    std::vector<uint8_t> bytes;
    EXPECT_TRUE(readFile(glb, bytes));
    fs::remove_all(scratch);
    looprender::Scene scene;
    const Status st = looprender::loadScene(bytes.data(), bytes.size(), name, scene);
    EXPECT_TRUE(st) << st.message;
    return scene;
}

TEST_F(VulkanPose, GpuPosingIsTheCpusBitForBit) {
    size_t instances = 0, points = 0;
    for (const char* name : {"fox.glb", "robotexpressive.glb"}) {
        const looprender::Scene scene = bakedScene(name);
        ASSERT_FALSE(HasFailure());
        const looprender::Device dev(gpu->handles());
        for (int animation = 0; animation < int(std::min<size_t>(scene.animations.size(), 3)); ++animation)
            for (float time : {0.0f, 0.35f, 1.1f}) {
                SCOPED_TRACE(std::string(name) + " animation " + std::to_string(animation) + " at " +
                             std::to_string(time));
                const looprender::ScenePose pose = looprender::poseScene(scene, animation, time);
                const looprender::ScenePoser poser(dev, scene, pose);
                looprender::OneShot shot(dev);
                poser.record(shot.record());
                shot.submitAndWait();
                for (size_t i = 0; i < pose.instances.size(); ++i) {
                    const std::vector<float>& cpu = pose.instances[i].controlPoints;
                    ASSERT_EQ(poser.posed(i), !cpu.empty());
                    if (cpu.empty()) continue;
                    const std::vector<float> gpuPoints = poser.readBack(i, cpu.size());
                    size_t differ = 0;
                    for (size_t k = 0; k < cpu.size(); ++k) differ += std::memcmp(&gpuPoints[k], &cpu[k], 4) != 0;
                    EXPECT_EQ(differ, 0u) << "of " << cpu.size() << " coordinates, instance " << i;
                    ++instances;
                    points += cpu.size() / 3;
                }
            }
    }
    EXPECT_GT(instances, 10u);
    std::printf("[ figures  ] GPU posing: %zu posed instances, %zu control points, the CPU's bit for bit\n", instances,
                points);
}

}  // namespace
}  // namespace lt::test
