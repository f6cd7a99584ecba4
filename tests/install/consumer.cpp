// tests/install/consumer.cpp -- what an engine's tool chain does with an installed
// looptess: bake a control mesh, write and read the GLB, evaluate it on the CPU, and
// draw it headless on the first Vulkan device. Prints one line; exit 0 when all
// of it worked and the image shows the surface.
#include <looptess/asset.h>
#include <looptess/tools/baker.h>
#include <looptess/runtime.h>
#include <looptess/vulkan.h>
#include <looptess/tools/vulkan_tools.h>

#include <cstdio>
#include <memory>
#include <vector>

int fail(const char* step, const lt::Status& st) {
    std::fprintf(stderr, "consumer: %s: %s\n", step, st.message.c_str());
    return 1;
}

int main() {
    // A tetrahedron, counter-clockwise seen from outside; its limit surface (a blob
    // about a third its size) lies inside the clip volume.
    lt::InputMesh mesh;
    mesh.positions = {-1.5f, -1.5f, 0.2f, 1.5f, -1.5f, 0.2f, 0.0f, 1.5f, 0.2f, 0.0f, 0.0f, 0.8f};
    mesh.faces = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    lt::BakeSettings settings;
    settings.maxDepth = 2;
    lt::Asset baked, loaded;
    if (lt::Status st = lt::bake(mesh, settings, baked); !st) return fail("bake", st);
    std::vector<uint8_t> glb;
    if (lt::Status st = lt::writeAssetGlb(baked, glb); !st) return fail("writeAssetGlb", st);
    if (lt::Status st = lt::readAssetGlb(glb.data(), glb.size(), "tetrahedron.glb", loaded); !st)
        return fail("readAssetGlb", st);

    lt::EvalSettings eval;
    eval.tessFactor = 4;
    lt::Tessellation soup;
    lt::evaluateCpu(loaded, loaded.positions.data(), eval, soup);

    std::unique_ptr<lt::VulkanContext> gpu;
    if (lt::Status st = lt::VulkanContext::createHeadless({}, gpu); !st) return fail("createHeadless", st);
    std::unique_ptr<lt::VulkanSurface> surface;
    if (lt::Status st = lt::VulkanSurface::create(*gpu, loaded, surface); !st) return fail("VulkanSurface", st);
    lt::RenderSettings render;
    render.width = render.height = 64;
    render.frame.tessFactor = 4;
    lt::Image image;
    if (lt::Status st = lt::renderImage(*surface, render, image); !st) return fail("renderImage", st);
    size_t drawn = 0;  // pixels that are not the white background
    for (size_t i = 0; i < image.rgba.size(); i += 4) drawn += image.rgba[i] != 255 || image.rgba[i + 1] != 255;
    std::printf("consumer: %zu-byte GLB, %zu CPU triangles at F = 4, %zu of %u pixels drawn\n", glb.size(),
                soup.triangleCount(), drawn, render.width * render.height);
    return soup.triangleCount() > 0 && drawn > 0 ? 0 : 1;
}
