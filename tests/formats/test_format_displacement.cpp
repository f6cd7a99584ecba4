// tests/formats/test_format_displacement.cpp -- the optional displacement map of
// EXT_mesh_loop_subdivision: GLB round trip, table bytes, files without a map
// unchanged, the Khronos validator, and rules 36..39 (plus the generic accessor
// rules 7 and 14 applied to the map's accessors) through the reader and validator.
#include "format_fixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace fmttest;

// The fixture's tetrahedron (faces 0 2 1, 0 1 3, 0 3 2, 1 2 3) with a resolution-4
// map: 6 edges numbered by first use, samples 0, 1000, 2000, ...
lt::Asset withMap(lt::Asset a, uint32_t R = 4) {
    lt::DisplacementMap& m = a.displacement;
    m.resolution = R;
    m.scale = 0.1f;
    m.bias = -1.0f / 3.0f;
    // Edges 0..5: (0,2) (2,1) (1,0) (1,3) (3,0) (3,2).
    const uint32_t edges[12] = {0, 1, 2, 2, 3, 4, 4, 5, 0, 1, 5, 3};
    m.faceEdges.assign(edges, edges + 12);
    const uint64_t count = lt::displacementSampleCount(R, a.controlVertexCount(), a.faceCount(), 6);
    for (uint64_t k = 0; k < count; ++k) m.values.push_back(uint16_t(k * 1000 % 65536));
    return a;
}

const std::vector<uint8_t>& mapBytes() {
    static const std::vector<uint8_t> bytes = write(withMap(makeAsset(true)), nullptr, lt::Compression::None);
    return bytes;
}

void corruptMap(const std::function<void(Glb&)>& edit, int rule) {
    Glb g(mapBytes());
    edit(g);
    expectRule(read(g.bytes()), rule);
}

Json& disp(Glb& g) { return g.ext()["displacement"]; }

TEST(FormatDisplacement, RoundTrip) {
    const lt::Asset a = withMap(makeAsset(true));
    ASSERT_TRUE(lt::validateAsset(a, "a"));
    lt::TableBytes tb;
    const std::vector<uint8_t> bytes = write(a, &tb);
    EXPECT_EQ(tb.displacement, 12u * 2 + a.displacement.values.size() * 2);
    lt::Asset back;
    const lt::Status st = read(bytes, &back);
    ASSERT_TRUE(st) << st.message;
    expectEqual(a, back);
    EXPECT_EQ(back.displacement.resolution, 4u);
    EXPECT_TRUE(sameBits(std::vector<float>{back.displacement.scale, back.displacement.bias},
                         std::vector<float>{0.1f, -1.0f / 3.0f}));
    EXPECT_EQ(back.displacement.faceEdges, a.displacement.faceEdges);
    EXPECT_EQ(back.displacement.values, a.displacement.values);
    EXPECT_EQ(write(back), bytes);  // deterministic, and the float text round-trips

    Glb g(bytes);
    EXPECT_EQ(disp(g)["resolution"], 4);
    EXPECT_EQ(g.doc["accessors"][disp(g)["values"].get<int>()]["componentType"], 5123);
    EXPECT_EQ(g.doc["accessors"][disp(g)["faceEdges"].get<int>()]["type"], "VEC3");
    // Every resolution, 1 (vertex samples only) to 64.
    for (uint32_t R = 1; R <= 64; R *= 2) {
        lt::Asset r = withMap(makeAsset(false), R);
        lt::Asset rb;
        const lt::Status s2 = read(write(r), &rb);
        ASSERT_TRUE(s2) << "R " << R << ": " << s2.message;
        EXPECT_EQ(rb.displacement.values, r.displacement.values);
    }
}

TEST(FormatDisplacement, WithoutAMapTheFileIsUnchanged) {
    lt::Asset a = withMap(makeAsset(true));
    a.displacement = lt::DisplacementMap{};
    EXPECT_EQ(write(a, nullptr, lt::Compression::None), fixtureBytes());
    lt::Asset back;
    ASSERT_TRUE(read(fixtureBytes(), &back));
    EXPECT_FALSE(back.displacement.present());
    EXPECT_TRUE(back.displacement.values.empty() && back.displacement.faceEdges.empty());
}

// The Khronos glTF-Validator accepts a file with a map (no errors, no warnings).
TEST(FormatDisplacement, KhronosValidator) { expectValidatorClean(mapBytes(), "displaced.glb"); }

TEST(FormatDisplacement, MutationsNeverCrash) {
    const std::vector<uint8_t>& bytes = mapBytes();
    std::mt19937 rng(777);
    for (int i = 0; i < 2000; ++i) {
        std::vector<uint8_t> b = bytes;
        for (int k = 0; k < 1 + int(rng() % 3); ++k) b[rng() % b.size()] ^= uint8_t(1u << (rng() % 8));
        lt::Asset a;
        if (lt::readAssetGlb(b.data(), b.size(), "m.glb", a)) { EXPECT_TRUE(lt::validateAsset(a, "m.glb")); }
    }
}

TEST(FormatDisplacement, Rule36Object) {
    corruptMap([](Edit g) { disp(g) = 5; }, 36);
    corruptMap([](Edit g) { disp(g).erase("scale"); }, 36);
    corruptMap([](Edit g) { disp(g)["bias"] = "zero"; }, 36);
    corruptMap([](Edit g) { disp(g)["resolution"] = 2.5; }, 36);
    corruptMap([](Edit g) { disp(g).erase("values"); }, 36);
    corruptMap([](Edit g) { disp(g)["faceEdges"] = -1; }, 36);
}

TEST(FormatDisplacement, Rule37Parameters) {
    corruptMap([](Edit g) { disp(g)["resolution"] = 3; }, 37);
    corruptMap([](Edit g) { disp(g)["resolution"] = 0; }, 37);
    corruptMap([](Edit g) { disp(g)["resolution"] = 128; }, 37);
    corruptMap([](Edit g) { disp(g)["scale"] = 1e39; }, 37);
    lt::Asset a = withMap(makeAsset(true));
    a.displacement.bias = NAN;
    lt::Status st = lt::validateAsset(a, "t.glb");
    expectRule(st, 37);
    EXPECT_NE(st.message.find("displacement.bias"), std::string::npos) << st.message;
    a = withMap(makeAsset(true));
    a.displacement.resolution = 0;  // "no map", yet samples
    expectRule(lt::validateAsset(a, "t.glb"), 37);
}

TEST(FormatDisplacement, AccessorRules7And14) {
    corruptMap([](Edit g) { disp(g)["values"] = g.widen(disp(g)["values"].get<int>(), 5125); }, 7);
    corruptMap([](Edit g) { g.doc["accessors"][disp(g)["faceEdges"].get<int>()]["type"] = "SCALAR"; }, 7);
    corruptMap([](Edit g) { disp(g)["values"] = g.accessor(1, "edgeVerts"); }, 14);  // u16 SCALAR too, but shared
    corruptMap([](Edit g) { disp(g)["faceEdges"] = g.accessor(1, "irregularCorners"); }, 14);
    corruptMap([](Edit g) { g.doc["accessors"][disp(g)["values"].get<int>()]["count"] = 100000; }, 6);
}

TEST(FormatDisplacement, Rule38FaceEdges) {
    lt::Asset a = withMap(makeAsset(true));
    a.displacement.faceEdges[4] = 3;  // face 1 edge 1 (vertices 1, 3) is edge 3 already: fine, then break it
    ASSERT_TRUE(lt::validateAsset(a, "t.glb"));
    a.displacement.faceEdges[4] = 2;  // edge 2 joins 1, 0
    lt::Status st = lt::validateAsset(a, "t.glb");
    expectRule(st, 38);
    EXPECT_NE(st.message.find("displacement.faceEdges[4]"), std::string::npos) << st.message;

    a = withMap(makeAsset(true));
    a.displacement.faceEdges[11] = 7;  // E = 8: edge 6 is never used
    expectRule(lt::validateAsset(a, "t.glb"), 38);
    a = withMap(makeAsset(true));
    a.displacement.faceEdges[11] = 12;  // more edges than face corners
    expectRule(lt::validateAsset(a, "t.glb"), 38);
    a = withMap(makeAsset(true));
    a.displacement.faceEdges.pop_back();
    expectRule(lt::validateAsset(a, "t.glb"), 38);
    corruptMap([](Edit g) { g.setIndex(disp(g)["faceEdges"].get<int>(), 7, 0); }, 38);  // face 2 edge 1 (3, 2) as 0
    corruptMap([](Edit g) { g.setIndex(disp(g)["faceEdges"].get<int>(), 0, 60000); }, 38);
    // Two numbers for one vertex pair: edge 0 (0, 2) renumbered 6 where face 2 uses it.
    a = withMap(makeAsset(true));
    a.displacement.faceEdges[8] = 6;
    a.displacement.values.resize(a.displacement.values.size() + 3);
    st = lt::validateAsset(a, "t.glb");
    expectRule(st, 38);
    EXPECT_NE(st.message.find("both join vertices 0, 2"), std::string::npos) << st.message;
}

TEST(FormatDisplacement, Rule39SampleCount) {
    lt::Asset a = withMap(makeAsset(true));
    a.displacement.values.pop_back();
    const lt::Status st = lt::validateAsset(a, "t.glb");
    expectRule(st, 39);
    EXPECT_NE(st.message.find("expected " + std::to_string(a.displacement.values.size() + 1)), std::string::npos)
        << st.message;
    corruptMap(
        [](Edit g) {
            Json& acc = g.doc["accessors"][disp(g)["values"].get<int>()];
            acc["count"] = acc["count"].get<int>() - 1;
        },
        39);
}

// The displacement object's properties are those of the spec's table and schema.
TEST(FormatDisplacement, SpecMatchesWriter) {
    const std::string dir = std::string(LOOPTESS_TEST_DATA) + "/../../formats/EXT_mesh_loop_subdivision/";
    std::ifstream readmeFile(dir + "README.md"), schemaFile(dir + "schema/mesh.EXT_mesh_loop_subdivision.schema.json");
    const std::string readme((std::istreambuf_iterator<char>(readmeFile)), std::istreambuf_iterator<char>());
    const Json schema = Json::parse(schemaFile, nullptr, false);
    ASSERT_TRUE(schema.is_object());
    Glb g(mapBytes());
    for (const auto& [key, value] : disp(g).items()) {
        EXPECT_TRUE(schema["$defs"]["displacement"]["properties"].contains(key)) << key;
        EXPECT_NE(readme.find("| `" + key + "` |"), std::string::npos) << key << " missing from the README table";
    }
    EXPECT_EQ(schema["$defs"]["displacement"]["required"].size(), disp(g).size());
}

}  // namespace
