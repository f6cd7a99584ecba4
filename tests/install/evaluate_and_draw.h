// tests/install/evaluate_and_draw.h -- what both install consumers (consumer.cpp,
// engine/engine_consumer.cpp) do with a loaded asset through the installed headers:
// evaluate it on the CPU at F = 4 and draw it headless on the first Vulkan device,
// 64 x 64. Prints one line starting with `who`; returns 0 when the CPU made
// triangles and the image shows the surface, 1 otherwise (the message on stderr).
#pragma once

#include <looptess/asset.h>
#include <looptess/runtime.h>
#include <looptess/status.h>
#include <looptess/tools/vulkan_tools.h>
#include <looptess/vulkan.h>

#include <cstdio>
#include <memory>

inline int evaluateAndDraw(const char* who, const lt::Asset& asset) {
    auto fail = [who](const char* step, const lt::Status& st) {
        std::fprintf(stderr, "%s: %s: %s\n", who, step, st.message.c_str());
        return 1;
    };
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
    std::printf("%s: %zu CPU triangles at F = 4, %zu of %u pixels drawn\n", who, soup.triangleCount(), drawn,
                render.width * render.height);
    return soup.triangleCount() > 0 && drawn > 0 ? 0 : 1;
}
