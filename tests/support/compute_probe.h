// A test-only compute shader run on the shared Vulkan context (test_vulkan): the
// GLSL twins of CPU functions (displacement.glsl, exact_math.glsl) against the CPU,
// bit for bit. The shader sees the library's descriptor set 0 (gpu_layout.h): its
// input words in binding LT_BINDING_TABLES, its output floats in
// LT_BINDING_VERTICES, and pc.base = the first input word; one thread per output.
#pragma once

#include "looptess/vulkan.h"

#include <cstdint>
#include <cstring>
#include <vector>

namespace lt::test {

// A float's bits and back, for the probes' inputs and outputs.
inline uint32_t floatBits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
inline float bitsFloat(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// Runs `spirv` (`bytes` long) over `words`, input starting at word `base`, with
// `outputs` threads; returns their output floats.
std::vector<float> runComputeProbe(VulkanContext& context, const uint32_t* spirv, size_t bytes,
                                   const std::vector<uint32_t>& words, uint32_t base, size_t outputs);

}  // namespace lt::test
