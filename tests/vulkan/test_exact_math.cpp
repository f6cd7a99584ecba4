// tests/vulkan/test_exact_math.cpp -- shaders/exact_math.glsl on the Vulkan device against
// the CPU's correctly rounded float division and square root, bit for bit, through a
// test-only compute shader (tests/vulkan/exact_math_probe.comp). lavapipe's own / and sqrt
// are already correctly rounded, so each query also starts from wrong neighbours
// (up to 3 ULP off either way, what Vulkan's precision allows a device): the
// correction must land on the CPU's bits from every one of them.
#include "compute_probe.h"
#include "test_vulkan_support.h"

#include <cmath>
#include <cstring>

#include "exact_math_probe_spv.h"

namespace lt::test {
namespace {

struct MathQuery {
    uint32_t op;
    float a, b, start, expected;
};

using VulkanExactMath = VulkanTest;

TEST_F(VulkanExactMath, DivisionAndSquareRootRoundLikeTheCpuFromAnyStart) {
    std::vector<MathQuery> qs;
    uint32_t state = 12345;
    auto next = [&] {  // a positive float over about 2^-40 .. 2^40, all significands
        state = state * 1664525u + 1013904223u;
        const uint32_t significand = state >> 9;
        state = state * 1664525u + 1013904223u;
        return std::ldexp(1.0f + float(significand) * 0x1p-23f, int(state >> 26) - 32);
    };
    for (int n = 0; n < 3000; ++n) {
        const float a = next(), b = next();
        const float q = a / b, s = std::sqrt(a);
        for (int off = -3; off <= 3; ++off) {
            qs.push_back({0, a, b, bitsFloat(floatBits(q) + uint32_t(off)), q});
            qs.push_back({1, a, 0, bitsFloat(floatBits(s) + uint32_t(off)), s});
        }
        qs.push_back({2, a, b, 0, q});
        qs.push_back({3, a, 0, 0, s});
    }
    // Powers of two (a neighbour below at half the distance), squares, zero.
    for (float x : {1.0f, 2.0f, 0.5f, 4.0f, 1024.0f, 9.0f, 0.25f, 1.0f + 0x1p-23f, 2.0f - 0x1p-22f}) {
        for (float y : {1.0f, 3.0f, 0.1f, 2.0f - 0x1p-23f})
            for (int off = -3; off <= 3; ++off)
                qs.push_back({0, x, y, bitsFloat(floatBits(x / y) + uint32_t(off)), x / y});
        for (int off = -3; off <= 3; ++off)
            qs.push_back({1, x, 0, bitsFloat(floatBits(std::sqrt(x)) + uint32_t(off)), std::sqrt(x)});
    }
    qs.push_back({2, 0.0f, 3.0f, 0, 0.0f});
    qs.push_back({3, 0.0f, 0, 0, 0.0f});

    std::vector<uint32_t> words{uint32_t(qs.size())};
    for (const MathQuery& q : qs) words.insert(words.end(), {q.op, floatBits(q.a), floatBits(q.b), floatBits(q.start)});
    const std::vector<float> got =
        runComputeProbe(*gpu, lt_spv_exact_math_probe, sizeof lt_spv_exact_math_probe, words, 0, qs.size());
    ASSERT_EQ(got.size(), qs.size());
    size_t wrong = 0;
    for (size_t i = 0; i < qs.size(); ++i)
        if (floatBits(got[i]) != floatBits(qs[i].expected) && wrong++ < 5)
            ADD_FAILURE() << "query " << i << " op " << qs[i].op << " a " << qs[i].a << " b " << qs[i].b << " start "
                          << qs[i].start << ": GPU " << got[i] << ", CPU " << qs[i].expected;
    EXPECT_EQ(wrong, 0u);
    std::printf(
        "[ figures  ] exact division and square root: %zu queries, the CPU's bits from starts up to 3 ULP off\n",
        qs.size());
}

}  // namespace
}  // namespace lt::test
