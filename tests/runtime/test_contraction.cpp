// tests/runtime/test_contraction.cpp -- bits that no engine flag can change (issue
// 42): every public runtime function an engine may call on its own data, called from
// contraction_consumer.cpp (compiled with -ffp-contract=fast -mfma -O2) and from
// this file (the project's flags, -ffp-contract=off), gives the same bits; and the
// consumer's faceTexcoord / faceAttribute at the CPU evaluator's own points give the
// evaluator's texture coordinates. Before face_attributes.cpp, faceAttribute,
// faceTexcoord and faceTangent were inline in runtime.h and the consumer's copies
// fused their multiply-adds. The asset: tests/data/golden/loop_icos_semisharp.glb,
// read as an engine would (readAssetGlb; no baker).
#include "contraction_calls.h"

#include "looptess/asset.h"
#include "looptess/runtime.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "contraction_calls.inc"

namespace lt::test {

void callsWithProjectFlags(const ContractionInputs& in, ContractionOutputs& out) { callEverything(in, out); }

namespace {

// A float in [lo, hi) with all 24 mantissa bits in use, from a counter.
struct Pseudo {
    uint32_t state = 0x2545F491u;
    float next(float lo, float hi) {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        return lo + (hi - lo) * (float(state >> 8) / 16777216.0f);
    }
};

std::string bits(float f) {
    uint32_t b;
    std::memcpy(&b, &f, 4);
    char s[64];
    std::snprintf(s, sizeof s, "%.9g (0x%08x)", double(f), b);
    return s;
}
std::string bits(uint32_t v) { return std::to_string(v); }
std::string bits(uint8_t v) { return std::to_string(v); }

// Same bits element for element; else how many differ and the first few.
template <class T>
::testing::AssertionResult sameBits(const char* what, const std::vector<T>& engine, const std::vector<T>& project) {
    if (engine.size() != project.size())
        return ::testing::AssertionFailure() << what << ": " << engine.size() << " values, expected " << project.size();
    size_t differ = 0;
    std::ostringstream first;
    for (size_t i = 0; i < engine.size(); ++i)
        if (std::memcmp(&engine[i], &project[i], sizeof(T)) != 0 && ++differ <= 3)
            first << "\n  [" << i << "] engine " << bits(engine[i]) << ", library " << bits(project[i]);
    if (differ == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << ": " << differ << " of " << engine.size() << " values differ"
                                         << first.str();
}

void expectSame(const std::string& what, const Tessellation& a, const Tessellation& b) {
    EXPECT_TRUE(sameBits((what + " positions").c_str(), a.positions, b.positions));
    EXPECT_TRUE(sameBits((what + " normals").c_str(), a.normals, b.normals));
    EXPECT_TRUE(sameBits((what + " face").c_str(), a.face, b.face));
    EXPECT_TRUE(sameBits((what + " uv").c_str(), a.uv, b.uv));
    EXPECT_TRUE(sameBits((what + " texcoords").c_str(), a.texcoords, b.texcoords));
    EXPECT_TRUE(sameBits((what + " texcoords1").c_str(), a.texcoords1, b.texcoords1));
    EXPECT_TRUE(sameBits((what + " colors").c_str(), a.colors, b.colors));
    EXPECT_TRUE(sameBits((what + " tangents").c_str(), a.tangents, b.tangents));
    EXPECT_TRUE(sameBits((what + " indices").c_str(), a.indices, b.indices));
}

Asset loadGolden() {
    const std::string path = std::string(LOOPTESS_TEST_DATA) + "/golden/loop_icos_semisharp.glb";
    std::ifstream f(path, std::ios::binary);
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
    Asset asset;
    const Status st = readAssetGlb(bytes.data(), bytes.size(), path, asset);
    EXPECT_TRUE(st) << st.message;
    return asset;
}

TEST(Contraction, AnEngineWithFusedMultiplyAddGetsTheLibrarysBits) {
    if (!__builtin_cpu_supports("fma"))
        GTEST_SKIP() << "this CPU has no FMA: contraction_consumer.cpp (-mfma) cannot run here";
    const Asset asset = loadGolden();
    ASSERT_FALSE(asset.faceUVs.empty()) << "the golden asset lost its UVs";

    // The CPU evaluator's own points, then points anywhere on the base faces.
    EvalSettings eight;
    eight.tessFactor = 8;
    eight.path = DrawPath::Patterns;
    Tessellation soup;
    evaluateCpu(asset, asset.positions.data(), eight, soup);
    ASSERT_FALSE(soup.texcoords.empty());
    const size_t soupPoints = soup.vertexCount();

    ContractionInputs in;
    in.asset = &asset;
    Pseudo rnd;
    auto addPoint = [&](float u, float v, const float* c2, const float* normal) {
        in.uv.insert(in.uv.end(), {u, v});
        in.corners2.insert(in.corners2.end(), c2, c2 + 6);
        for (int k = 0; k < 12; ++k) in.corners4.push_back(rnd.next(-3.0f, 3.0f));
        for (int k = 0; k < 3; ++k) in.pu.push_back(rnd.next(-2.0f, 2.0f));
        for (int k = 0; k < 3; ++k) in.pv.push_back(rnd.next(-2.0f, 2.0f));
        in.n.insert(in.n.end(), normal, normal + 3);
    };
    for (size_t i = 0; i < soupPoints; ++i)
        addPoint(soup.uv[2 * i], soup.uv[2 * i + 1], &asset.faceUVs[6 * size_t(soup.face[i])], &soup.normals[3 * i]);
    const float up[3] = {0.0f, 0.0f, 1.0f};
    for (int i = 0; i < 4096; ++i) {
        float u = rnd.next(0.0f, 1.0f), v = rnd.next(0.0f, 1.0f);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        float c2[6];
        for (float& c : c2) c = rnd.next(-4.0f, 4.0f);
        if (i % 64 == 0)  // degenerate UVs: faceTangent's fallback to pu
            for (int k = 2; k < 6; ++k) c2[k] = c2[k % 2];
        addPoint(u, v, c2, up);
    }

    in.controlPositions = asset.positions;
    for (float& p : in.controlPositions) p += rnd.next(-0.01f, 0.01f);  // posed
    in.editValues = bakedEditValues(asset);
    for (float& e : in.editValues) e = e * 0.75f;
    in.eye[0] = 0.3f, in.eye[1] = -0.7f, in.eye[2] = 5.1f;
    in.factors = {0.5f, 1.0f, 1.5f, 3.0f, 7.9f, 8.0f, 100.0f};
    EvalSettings s;
    s.tessFactor = 5.3f;
    s.spacing = Spacing::FractionalOdd;
    in.settings.push_back(s);  // tessellator points
    s = eight;
    in.settings.push_back(s);  // pattern soup
    s.indexed = true;
    in.settings.push_back(s);  // pattern mesh
    s = EvalSettings{};
    s.lod = cameraLod(LodMode::Screen, in.eye, 45.0f, 720, 6.0f);
    in.settings.push_back(s);  // screen-space factors
    s.watertight = false;
    in.settings.push_back(s);
    s.lod = cameraLod(LodMode::Distance, in.eye, 45.0f, 720, 6.0f);
    s.editValues = in.editValues.empty() ? nullptr : in.editValues.data();
    in.settings.push_back(s);  // distance, edited

    ContractionOutputs engine, project;
    callsAsAnEngine(in, engine);
    callsWithProjectFlags(in, project);

    EXPECT_TRUE(sameBits("faceAttribute width 2", engine.attribute2, project.attribute2));
    EXPECT_TRUE(sameBits("faceAttribute width 4", engine.attribute4, project.attribute4));
    EXPECT_TRUE(sameBits("faceTexcoord", engine.texcoord, project.texcoord));
    EXPECT_TRUE(sameBits("faceTangent", engine.tangent, project.tangent));
    // At the evaluator's own points the engine's faceTexcoord is the evaluator's.
    const std::vector<float> engineAtSoup(engine.texcoord.begin(), engine.texcoord.begin() + 2 * soupPoints);
    EXPECT_TRUE(
        sameBits("faceTexcoord at evaluateCpu's points vs Tessellation::texcoords", engineAtSoup, soup.texcoords));
    const std::vector<float> attributeAtSoup(engine.attribute2.begin(), engine.attribute2.begin() + 2 * soupPoints);
    EXPECT_TRUE(sameBits("faceAttribute(2) at evaluateCpu's points vs Tessellation::texcoords", attributeAtSoup,
                         soup.texcoords));

    ASSERT_EQ(engine.lods.size(), project.lods.size());
    for (size_t k = 0; k < engine.lods.size(); ++k) {
        const Lod &a = engine.lods[k], &b = project.lods[k];
        EXPECT_EQ(a.mode, b.mode);
        EXPECT_TRUE(sameBits("cameraLod",
                             std::vector<float>{a.eye[0], a.eye[1], a.eye[2], a.pixelsPerUnit, a.pixelsPerEdge},
                             std::vector<float>{b.eye[0], b.eye[1], b.eye[2], b.pixelsPerUnit, b.pixelsPerEdge}));
    }
    EXPECT_TRUE(sameBits("drawsPatterns", engine.drawsPatterns, project.drawsPatterns));
    EXPECT_TRUE(sameBits("runtimeDepth, displacementSampleCount", engine.depths, project.depths));
    EXPECT_TRUE(sameBits("lodTessFactor", engine.lodFactors, project.lodFactors));
    EXPECT_TRUE(sameBits("subdivideCpu", engine.subdivided, project.subdivided));
    EXPECT_TRUE(sameBits("bakedEditValues", engine.bakedEdits, project.bakedEdits));
    ASSERT_EQ(engine.evaluated.size(), in.settings.size());
    ASSERT_EQ(project.evaluated.size(), in.settings.size());
    for (size_t k = 0; k < in.settings.size(); ++k) {
        EXPECT_GT(project.evaluated[k].vertexCount(), 0u);
        expectSame("evaluateCpu #" + std::to_string(k), engine.evaluated[k], project.evaluated[k]);
        expectSame("CpuEvaluator #" + std::to_string(k), engine.reused[k], project.evaluated[k]);
    }
}

}  // namespace
}  // namespace lt::test
