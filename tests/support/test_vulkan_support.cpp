// Shared fixture and helpers of the Vulkan tests (see test_vulkan_support.h).
#include "test_vulkan_support.h"
#include "test_paths.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace lt::test {

namespace {

// The process-wide context lives in a GoogleTest environment, destroyed when the
// tests end and before main returns: a context left to static destruction would be
// torn down after the Vulkan driver's own exit handlers have run, which crashed a
// hardware driver at exit.
class VulkanEnvironment : public ::testing::Environment {
public:
    VulkanContext* get() {
        if (!tried_) {
            tried_ = true;
            HeadlessOptions options;
            options.validation = true;
            options.synchronizationValidation = true;
            if (const char* name = std::getenv("LOOPTESS_DEVICE")) options.deviceName = name;
            status_ = VulkanContext::createHeadless(options, context_);
            if (status_) std::printf("[ vulkan   ] %s\n", context_->deviceName().c_str());
        }
        EXPECT_TRUE(status_) << "no Vulkan device (CI installs lavapipe: scripts/setup-debian.sh): " << status_.message;
        return context_.get();
    }
    void TearDown() override { context_.reset(); }

private:
    std::unique_ptr<VulkanContext> context_;
    Status status_;
    bool tried_ = false;
};

VulkanEnvironment* const environment =
    static_cast<VulkanEnvironment*>(::testing::AddGlobalTestEnvironment(new VulkanEnvironment));

}  // namespace

VulkanContext* vulkanContext() { return environment->get(); }

void VulkanTest::SetUp() {
    gpu = vulkanContext();
    ASSERT_NE(gpu, nullptr);
    messagesBefore = gpu->messages().size();
}

void VulkanTest::TearDown() {
    if (!gpu) return;
    std::vector<std::string> all = gpu->messages();
    for (size_t i = messagesBefore; i < all.size() && i < messagesBefore + 5; ++i)
        ADD_FAILURE() << "validation: " << all[i];
    EXPECT_EQ(all.size(), messagesBefore) << "validation messages during the test";
}

std::string corpusShape(const char* name) { return corpusDir() + "/opensubdiv-loop/" + name; }

std::string duckPath() { return corpusDir() + "/gltf/Duck.glb"; }

std::vector<std::string> allTestMeshes() {
    std::vector<std::string> all = corpusShapes();
    all.push_back(corpusMesh("spot.obj"));
    all.push_back(corpusMesh("bob.obj"));
    all.push_back(duckPath());
    return all;
}

const Baked* baked(const std::string& path, int depth, bool rejectedIsOk) {
    static std::map<std::pair<std::string, int>, std::unique_ptr<Baked>> cache;
    auto key = std::make_pair(path, depth);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second.get();
    auto b = std::make_unique<Baked>();
    b->name = path.substr(path.find_last_of('/') + 1);
    bool gltf = path.size() > 4 && (path.substr(path.size() - 4) == ".glb" || path.substr(path.size() - 5) == ".gltf");
    if (gltf) {
        std::ifstream in(path, std::ios::binary);
        std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        Status st = parseGltf(bytes.data(), bytes.size(), path, path.substr(0, path.find_last_of('/')), b->mesh);
        EXPECT_TRUE(st) << st.message;
        if (!st) return nullptr;
    } else {
        b->mesh = loadObj(path);
    }
    Status st = checkInput(b->mesh, path);
    if (!st) {
        if (!rejectedIsOk) ADD_FAILURE() << st.message;
        cache[key] = nullptr;
        return nullptr;
    }
    BakeSettings settings;
    settings.maxDepth = depth;
    st = bake(b->mesh, settings, b->asset);
    EXPECT_TRUE(st) << st.message;
    if (!st) return nullptr;
    b->diagonal = bboxDiagonal(b->mesh);
    return (cache[key] = std::move(b)).get();
}

std::string Agreement::summary(double tolerance) const {
    std::ostringstream s;
    s << count << " floats, " << bitwise << " bitwise equal ("
      << (count ? 100.0 * double(bitwise) / double(count) : 100.0) << "%), worst difference " << worst << " (tolerance "
      << tolerance << ")";
    if (outside) s << ", " << outside << " outside, first at " << firstOutside;
    return s.str();
}

Agreement compareFloats(const std::vector<float>& gpu, const std::vector<float>& cpu, double tolerance) {
    Agreement a;
    a.count = std::min(gpu.size(), cpu.size());
    for (size_t i = 0; i < a.count; ++i) {
        if (std::memcmp(&gpu[i], &cpu[i], sizeof(float)) == 0) {
            ++a.bitwise;
            continue;
        }
        double d = std::fabs(double(gpu[i]) - double(cpu[i]));
        if (!(d <= tolerance)) {
            if (!a.outside++) a.firstOutside = i;
            if (std::isnan(d)) d = INFINITY;
        }
        a.worst = std::max(a.worst, d);
    }
    return a;
}

SurfaceDiff expectSameSurface(const Tessellation& device, const Tessellation& cpu, DrawPath path,
                              double positionTolerance) {
    SurfaceMatch match;
    match.order = path == DrawPath::Tessellator ? Order::Any : Order::Emission;
    match.positionTolerance = positionTolerance;
    SurfaceDiff diff = compareSurfaces(device, cpu, match);
    EXPECT_TRUE(diff.ok()) << diff.summary();
    return diff;
}

std::unique_ptr<VulkanSurface> upload(const Baked& b) {
    std::unique_ptr<VulkanSurface> surface;
    VulkanContext* gpu = vulkanContext();
    if (!gpu) return nullptr;
    Status st = VulkanSurface::create(*gpu, b.asset, surface);
    EXPECT_TRUE(st) << b.name << ": " << st.message;
    return surface;
}

}  // namespace lt::test
