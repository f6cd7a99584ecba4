// tests/install/engine/engine_consumer.cpp -- an engine with a runtime-only install:
// load a baked GLB, evaluate it on the CPU, draw it headless on the first Vulkan
// device. Prints one line; exit 0 when all of it worked and the image shows the
// surface.
//
//   engine_consumer ASSET.glb
#include <looptess/asset.h>
#include <looptess/runtime.h>
#include <looptess/status.h>
#include <looptess/tools/vulkan_tools.h>
#include <looptess/version.h>
#include <looptess/vulkan.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

static int fail(const char* step, const lt::Status& st) {
    std::fprintf(stderr, "engine_consumer: %s: %s\n", step, st.message.c_str());
    return 1;
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: engine_consumer ASSET.glb\n");
        return 1;
    }
    std::ifstream file(argv[1], std::ios::binary);
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    lt::Asset asset;
    if (lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), argv[1], asset); !st)
        return fail("readAssetGlb", st);

    lt::EvalSettings eval;
    eval.tessFactor = 4;
    lt::Tessellation soup;
    lt::evaluateCpu(asset, asset.positions.data(), eval, soup);

    std::unique_ptr<lt::VulkanContext> gpu;
    if (lt::Status st = lt::VulkanContext::createHeadless({}, gpu); !st) return fail("createHeadless", st);
    std::unique_ptr<lt::VulkanSurface> surface;
    if (lt::Status st = lt::VulkanSurface::create(*gpu, asset, surface); !st) return fail("VulkanSurface", st);
    lt::RenderSettings render;
    render.width = render.height = 64;
    render.frame.tessFactor = 4;
    lt::Image image;
    if (lt::Status st = lt::renderImage(*surface, render, image); !st) return fail("renderImage", st);
    size_t drawn = 0;  // pixels that are not the white background
    for (size_t i = 0; i < image.rgba.size(); i += 4) drawn += image.rgba[i] != 255 || image.rgba[i + 1] != 255;
    std::printf("engine_consumer (looptess %s): %zu CPU triangles at F = 4, %zu of %u pixels drawn\n",
                LOOPTESS_VERSION_STRING, soup.triangleCount(), drawn, render.width * render.height);
    return soup.triangleCount() > 0 && drawn > 0 ? 0 : 1;
}
