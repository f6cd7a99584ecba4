// tests/vulkan/test_exact_math.cpp -- shaders/exact_math.glsl on the Vulkan device against
// the CPU's correctly rounded float division and square root, bit for bit, through a
// test-only compute shader (tests/vulkan/exact_math_probe.comp). lavapipe's own / and sqrt
// are already correctly rounded, so each query also starts from wrong neighbours
// (up to 3 ULP off either way, what Vulkan's precision allows a device): the
// correction must land on the CPU's bits from every one of them.
#include "compute_probe.h"
#include "test_vulkan_support.h"

#include <array>
#include <cmath>
#include <cstring>

#include "exact_math_probe_spv.h"
#include "looptess/runtime.h"
#include "unit_normal_probe_spv.h"

#include <limits>

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

// The unit normal (spec "Unit normals") is the CPU's bits on the device, and neither
// is ever zero or non-finite: ordinary vectors, ones whose |n|^2 under- or overflows
// (scaled first), and ones with no direction ((0, 0, 1)).
TEST_F(VulkanExactMath, UnitNormalsAreTheCpusAndNeverZero) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float tiny = std::numeric_limits<float>::denorm_min(), big = std::numeric_limits<float>::max();
    std::vector<std::array<float, 3>> qs = {
        {1, 2, 3},         {0, 0, -5},      {3e-20f, -4e-20f, 0}, {1e-30f, 1e-30f, 1e-30f},
        {3e20f, 4e20f, 0}, {big, big, big}, {0, -big, 1e-3f},     {0, 0, 0},
        {-0.0f, 0, -0.0f}, {tiny, 0, 0},    {1e-39f, 1e-39f, 0},  {inf, 0, 0},
        {1, nan, 0},       {nan, nan, nan}, {-inf, inf, 1}};
    uint32_t state = 777;
    for (int n = 0; n < 2000; ++n) {  // random signs and exponents over 2^-80 .. 2^80
        std::array<float, 3> v;
        for (float& x : v) {
            state = state * 1664525u + 1013904223u;
            x = std::ldexp(float(state >> 8) * 0x1p-24f, int(state % 161u) - 80) * ((state & 128u) ? -1.0f : 1.0f);
        }
        qs.push_back(v);
    }
    std::vector<uint32_t> words{uint32_t(qs.size())};
    for (const auto& q : qs)
        for (float x : q) words.push_back(floatBits(x));
    const std::vector<float> got =
        runComputeProbe(*gpu, lt_spv_unit_normal_probe, sizeof lt_spv_unit_normal_probe, words, 0, 3 * qs.size());
    ASSERT_EQ(got.size(), 3 * qs.size());
    size_t wrong = 0;
    for (size_t i = 0; i < qs.size(); ++i) {
        float cpu[3];
        unitNormal(qs[i].data(), cpu);
        const double len2 = double(cpu[0]) * cpu[0] + double(cpu[1]) * cpu[1] + double(cpu[2]) * cpu[2];
        EXPECT_TRUE(std::isfinite(len2) && std::fabs(len2 - 1.0) < 1e-6) << "query " << i << ": |n|^2 " << len2;
        for (int k = 0; k < 3; ++k)
            if (floatBits(got[3 * i + size_t(k)]) != floatBits(cpu[k]) && wrong++ < 5)
                ADD_FAILURE() << "query " << i << " (" << qs[i][0] << ", " << qs[i][1] << ", " << qs[i][2]
                              << ") component " << k << ": GPU " << got[3 * i + size_t(k)] << ", CPU " << cpu[k];
    }
    EXPECT_EQ(wrong, 0u);
    float none[3];
    unitNormal(std::array<float, 3>{0, 0, 0}.data(), none);
    EXPECT_EQ(none[2], 1.0f);
}

}  // namespace
}  // namespace lt::test
