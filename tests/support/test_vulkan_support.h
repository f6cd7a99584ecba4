// Shared by the Vulkan tests (test_vulkan*.cpp): one headless context (lavapipe in
// CI, any conformant Vulkan 1.3 device elsewhere) with the validation layers on,
// baked test assets, and the comparisons of surface_compare.h.
//
// Every test derives from VulkanTest: it fails (never skips) when no Vulkan device
// is available, and fails when the validation layers report anything during it.
#pragma once

#include "looptess/tools/baker.h"
#include "looptess/runtime.h"
#include "looptess/tools/vulkan_tools.h"
#include "osd_reference.h"  // corpusShapes, corpusMesh, loadObj, bboxDiagonal
#include "surface_compare.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace lt::test {

// For tests that use the plain Vulkan C API as an application would.
#define VK_OK(call) ASSERT_EQ((call), VK_SUCCESS) << #call

// A zeroed Vulkan structure with its sType.
template <class T>
T vkStruct(VkStructureType type) {
    T t{};
    t.sType = type;
    return t;
}

// The process-wide headless context (validation and synchronization validation
// on), created on first use, destroyed when the tests end; null if creation failed
// (the failure is reported). LOOPTESS_DEVICE picks a device by a substring of its
// name (HeadlessOptions::deviceName).
VulkanContext* vulkanContext();

class VulkanTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    VulkanContext* gpu = nullptr;
    size_t messagesBefore = 0;
};

// A baked test asset, cached per (path, depth) for the whole run.
struct Baked {
    std::string name;  // file name
    InputMesh mesh;
    Asset asset;
    double diagonal = 0;  // of the control mesh's bounding box
};
// Bakes an OBJ or glTF/GLB file at `depth`; null (and the test fails) when the
// input is rejected, unless `rejectedIsOk` (some corpus shapes are invalid input).
const Baked* baked(const std::string& path, int depth, bool rejectedIsOk = false);

// Every corpus shape that bakes, spot, bob and the Duck.
std::vector<std::string> allTestMeshes();
std::string corpusShape(const char* name);  // tests/data/corpus/opensubdiv-loop/<name>
std::string duckPath();

// How two float arrays compare.
struct Agreement {
    size_t count = 0, bitwise = 0, outside = 0;
    double worst = 0;
    size_t firstOutside = SIZE_MAX;
    std::string summary(double tolerance) const;
};
Agreement compareFloats(const std::vector<float>& gpu, const std::vector<float>& cpu, double tolerance);

// `device` against `cpu` as surface_compare.h says, for a frame drawn on `path`:
// the tessellator's triangles in any order (the implementation's), the other paths'
// in emission order (ours); positions bit for bit unless `positionTolerance`. Adds a
// failure with the summary when they differ; returns the comparison (for figures).
SurfaceDiff expectSameSurface(const Tessellation& device, const Tessellation& cpu, DrawPath path,
                              double positionTolerance = 0);

// A GPU surface of `b` on the shared context (fails the test on error).
std::unique_ptr<VulkanSurface> upload(const Baked& b);

}  // namespace lt::test
