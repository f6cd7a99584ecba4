// tests/vulkan/test_device_independence.cpp -- what keeps the Vulkan tests and the bitwise
// promises true on any conformant device, not only on lavapipe (docs/devices.md):
//   - every floating-point addition, subtraction and multiplication of the embedded
//     shaders that compute the surface is decorated NoContraction (GLSL `precise`),
//     so a device that fuses multiply-adds rounds them as the CPU does;
//   - the comparison of the tests (surface_compare.h) accepts a device that emits
//     the tessellator's triangles in another order and rounds normals within the
//     stated bound, and still catches a moved position or a turned normal.
// Neither needs a device.
#include "surface_compare.h"
#include "test_vulkan_support.h"

#include "looptess_spirv.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

namespace lt::test {
namespace {

// SPIR-V opcodes and the one decoration this test reads (SPIR-V 1.5 unified spec).
enum : uint32_t {
    kOpExtInstImport = 11,
    kOpExtInst = 12,
    kOpDecorate = 71,
    kOpFNegate = 127,
    kOpFAdd = 129,
    kOpFSub = 131,
    kOpFMul = 133,
    kOpVectorTimesScalar = 142,
    kOpMatrixTimesScalar = 143,
    kOpVectorTimesMatrix = 144,
    kOpMatrixTimesVector = 145,
    kOpMatrixTimesMatrix = 146,
    kOpOuterProduct = 147,
    kOpDot = 148,
    kDecorationNoContraction = 42,
    kGlslFma = 50,
};

struct Module {
    const char* name;
    const uint32_t* words;
    size_t bytes;
};

// What a module does that a contracting device could round differently: float
// arithmetic results without NoContraction (by opcode), and GLSL.std.450 Fma calls.
struct Contractible {
    std::map<uint32_t, size_t> unmarked;  // opcode -> results without NoContraction
    size_t fma = 0;
};

Contractible inspect(const Module& m) {
    const uint32_t* w = m.words;
    const size_t count = m.bytes / 4;
    std::set<uint32_t> noContraction, glsl;
    std::vector<std::pair<uint32_t, uint32_t>> arithmetic;  // (opcode, result id)
    Contractible c;
    for (size_t at = 5; at < count;) {  // after the 5-word header
        const uint32_t length = w[at] >> 16, op = w[at] & 0xffffu;
        if (length == 0 || at + length > count) break;
        if (op == kOpDecorate && length >= 3 && w[at + 2] == kDecorationNoContraction) noContraction.insert(w[at + 1]);
        if (op == kOpExtInstImport && std::strcmp(reinterpret_cast<const char*>(&w[at + 2]), "GLSL.std.450") == 0)
            glsl.insert(w[at + 1]);
        if (op == kOpExtInst && length >= 5 && glsl.count(w[at + 3]) && w[at + 4] == kGlslFma) ++c.fma;
        switch (op) {
        case kOpFAdd:
        case kOpFSub:
        case kOpFMul:
        case kOpVectorTimesScalar:
        case kOpMatrixTimesScalar:
        case kOpVectorTimesMatrix:
        case kOpMatrixTimesMatrix:
        case kOpOuterProduct:
        case kOpDot: arithmetic.push_back({op, w[at + 2]}); break;
        default: break;
        }
        at += length;
    }
    for (auto [op, id] : arithmetic)
        if (!noContraction.count(id)) ++c.unmarked[op];
    return c;
}

// Every module that computes a surface value: subdivision, edits, limit and
// watertight passes, the draws' evaluation stages, the screen-space factors and the
// evaluation into buffers. (Not the fragment shaders; gl_Position's matrix product,
// OpMatrixTimesVector, is not part of the promise and not counted.)
std::vector<Module> surfaceModules() {
#define LT_MODULE(name) \
    Module { #name, lt_spv_##name, sizeof(lt_spv_##name) }
    return {LT_MODULE(subdivide_vertices),
            LT_MODULE(subdivide_edges),
            LT_MODULE(apply_edits),
            LT_MODULE(limit),
            LT_MODULE(watertight_points),
            LT_MODULE(watertight_normals),
            LT_MODULE(watertight_roots),
            LT_MODULE(patch_vert),
            LT_MODULE(patch_tesc),
            LT_MODULE(patch_tese_equal),
            LT_MODULE(patch_tese_odd),
            LT_MODULE(patch_tese_equal_capture),
            LT_MODULE(patch_tese_odd_capture),
            LT_MODULE(pattern_vert),
            LT_MODULE(pattern_vert_capture),
            LT_MODULE(pattern_sort),
            LT_MODULE(evaluate),
            LT_MODULE(ipp_vert),
            LT_MODULE(ipp_vert_capture)};
#undef LT_MODULE
}

TEST(DeviceIndependence, SurfaceArithmeticIsNeverContracted) {
    size_t modules = 0;
    for (const Module& m : surfaceModules()) {
        SCOPED_TRACE(m.name);
        const Contractible c = inspect(m);
        for (auto [op, n] : c.unmarked) ADD_FAILURE() << n << " results of opcode " << op << " without NoContraction";
        EXPECT_EQ(c.fma, 0u) << "fma() rounds once where the CPU rounds twice";
        ++modules;
    }
    std::printf("[ figures  ] %zu shader modules: every float +, -, * of the surface is NoContraction\n", modules);
}

// The check itself catches an unmarked product (a module of this test's making:
// OpFMul without the decoration, then with it).
TEST(DeviceIndependence, AnUnmarkedProductIsFound) {
    const uint32_t header[5] = {0x07230203, 0x00010500, 0, 100, 0};
    std::vector<uint32_t> words(header, header + 5);
    words.insert(words.end(), {(5u << 16) | kOpFMul, 1, 7, 2, 3});
    const Module unmarked{"unmarked", words.data(), words.size() * 4};
    EXPECT_EQ(inspect(unmarked).unmarked[kOpFMul], 1u);
    words.insert(words.begin() + 5, {(3u << 16) | kOpDecorate, 7, kDecorationNoContraction});
    const Module marked{"marked", words.data(), words.size() * 4};
    EXPECT_TRUE(inspect(marked).unmarked.empty());
}

// `soup` as another device might emit it: triangles in reverse order, each starting
// at its second corner (the winding kept).
Tessellation reordered(const Tessellation& soup) {
    Tessellation out = soup;
    const size_t triangles = soup.triangleCount();
    auto copy = [](const std::vector<float>& from, std::vector<float>& to, size_t width, size_t dst, size_t src) {
        if (!from.empty()) std::copy_n(&from[src * width], width, &to[dst * width]);
    };
    for (size_t t = 0; t < triangles; ++t)
        for (size_t k = 0; k < 3; ++k) {
            const size_t dst = 3 * (triangles - 1 - t) + k, src = 3 * t + (k + 1) % 3;
            copy(soup.positions, out.positions, 3, dst, src);
            copy(soup.normals, out.normals, 3, dst, src);
            copy(soup.uv, out.uv, 2, dst, src);
            copy(soup.texcoords, out.texcoords, 2, dst, src);
            copy(soup.tangents, out.tangents, 4, dst, src);
            out.face[dst] = soup.face[src];
        }
    return out;
}

// Every copy of the point of vertex `v` with its normal turned by `radians`.
void turnNormal(Tessellation& soup, size_t v, double radians) {
    const float* n = &soup.normals[3 * v];
    const double a[3] = {n[0], n[1], n[2]};
    // A unit axis orthogonal to n, then n cos + (axis x n) sin.
    double axis[3] = {-a[1], a[0], 0};
    if (std::fabs(a[2]) > 0.9) axis[0] = 0, axis[1] = -a[2], axis[2] = a[1];
    const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (double& x : axis) x /= len;
    const double c[3] = {axis[1] * a[2] - axis[2] * a[1], axis[2] * a[0] - axis[0] * a[2],
                         axis[0] * a[1] - axis[1] * a[0]};
    float turned[3];
    for (int k = 0; k < 3; ++k) turned[k] = float(a[k] * std::cos(radians) + c[k] * std::sin(radians));
    const std::vector<float> uv(soup.uv.begin() + 2 * v, soup.uv.begin() + 2 * v + 2);
    const uint32_t face = soup.face[v];
    for (size_t w = 0; w < soup.vertexCount(); ++w)
        if (soup.face[w] == face && soup.uv[2 * w] == uv[0] && soup.uv[2 * w + 1] == uv[1])
            std::copy_n(turned, 3, &soup.normals[3 * w]);
}

// A device with another tessellator order and other rounding of normals passes; a
// moved position, a turned normal or a missing point does not.
TEST(DeviceIndependence, TheComparisonAcceptsAnotherOrderAndRoundingOnly) {
    const Baked* b = baked(duckPath(), 3);  // with TEXCOORD_0 and TANGENT
    ASSERT_NE(b, nullptr);
    EvalSettings es;
    es.tessFactor = 5;
    Tessellation cpu;
    evaluateCpu(b->asset, b->asset.positions.data(), es, cpu);
    ASSERT_FALSE(cpu.tangents.empty());

    Tessellation device = reordered(cpu);
    EXPECT_FALSE(compareSurfaces(device, cpu, {Order::Emission}).ok()) << "another order, compared in order";
    SurfaceDiff any = compareSurfaces(device, cpu, {Order::Any});
    EXPECT_TRUE(any.ok()) << any.summary();

    const size_t v = 3 * (cpu.triangleCount() / 2) + 1;
    Tessellation rounded = device;
    turnNormal(rounded, v, 0.5 * kNormalRadians);
    any = compareSurfaces(rounded, cpu, {Order::Any});
    EXPECT_TRUE(any.ok()) << "a normal within the bound: " << any.summary();
    EXPECT_GT(any.worstNormal, 0.25 * kNormalRadians);

    Tessellation turned = device;
    turnNormal(turned, v, 2.0 * kNormalRadians);
    any = compareSurfaces(turned, cpu, {Order::Any});
    EXPECT_FALSE(any.ok());
    EXPECT_GT(any.normals, 0u) << any.summary();

    Tessellation moved = device;
    moved.positions[3 * v + 1] = std::nextafter(moved.positions[3 * v + 1], INFINITY);
    any = compareSurfaces(moved, cpu, {Order::Any});
    EXPECT_FALSE(any.ok());
    EXPECT_GT(any.positions, 0u) << any.summary();

    Tessellation shifted = device;  // a domain point the CPU does not have
    shifted.uv[2 * v] = std::nextafter(shifted.uv[2 * v], INFINITY);
    any = compareSurfaces(shifted, cpu, {Order::Any});
    EXPECT_FALSE(any.ok());
    EXPECT_GT(any.unmatched, 0u) << any.summary();

    Tessellation fewer = device;  // a triangle less
    for (auto* attribute : {&fewer.positions, &fewer.normals, &fewer.uv, &fewer.texcoords, &fewer.tangents}) {
        const size_t width = attribute->size() / fewer.vertexCount();
        attribute->resize(attribute->size() - 3 * width);
    }
    fewer.face.resize(fewer.face.size() - 3);
    EXPECT_FALSE(compareSurfaces(fewer, cpu, {Order::Any}).ok());
}

}  // namespace
}  // namespace lt::test
