// tests/formats/test_format.cpp -- EXT_mesh_loop_subdivision GLB: round trip, determinism,
// index widths and level-relative storage, reader safety under mutations, the spec
// files against the writer, and the Khronos glTF-Validator. The corruption
// catalogue is in test_format_corrupt.cpp; the fixture in format_fixture.h.
#include "format_fixture.h"
#include "looptess/version.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace fmttest;

// --- round trip, determinism, widths --------------------------------------------------

TEST(Format, RoundTripWithUVs) {
    const lt::Asset a = makeAsset(true);
    ASSERT_TRUE(lt::validateAsset(a, "synthetic")) << lt::validateAsset(a, "synthetic").message;
    EXPECT_EQ(a.totalVertexCount(), 4u + 10u + 5u);
    lt::TableBytes tb;
    const std::vector<uint8_t> bytes = write(a, &tb);
    lt::Asset b;
    const lt::Status st = read(bytes, &b);
    ASSERT_TRUE(st) << st.message;
    expectEqual(a, b);
    EXPECT_GT(tb.controlMesh, 0u);
    EXPECT_GT(tb.refinement, 0u);
    EXPECT_GT(tb.masks, 0u);
    EXPECT_GT(tb.patches, 0u);
    EXPECT_GT(tb.irregular, 0u);
    EXPECT_GT(tb.limit, 0u);
    EXPECT_LE(tb.encoded.total(), Glb(bytes).bin.size());

    Glb g(bytes);  // seams: the primitive has more vertices than the control mesh
    EXPECT_TRUE(g.cage().contains("controlVertex"));
    EXPECT_FALSE(g.doc.contains("extensionsRequired"));
    EXPECT_EQ(g.doc["asset"]["generator"], std::string("looptess loopbake ") + LOOPTESS_VERSION_STRING);
    EXPECT_EQ(g.doc["meshes"][0]["primitives"][0]["attributes"].size(), 2u);
}

// TEXCOORD_1 and COLOR_0 per corner: the fallback primitive's vertices split where
// any of the three attributes differs, and read back bit for bit; valid glTF.
TEST(Format, RoundTripWithSecondTexcoordsAndColours) {
    lt::Asset a = makeAsset(true);
    for (size_t c = 0; c < a.faces.size(); ++c) {
        a.faceUV1s.insert(a.faceUV1s.end(), {0.5f, c % 2 ? 0.25f : 0.75f});
        a.faceColors.insert(a.faceColors.end(), {1.0f, 0.5f, float(a.faces[c] % 3) / 2.0f, 1.0f});
    }
    const Glb g = roundTrip(a);
    EXPECT_EQ(g.doc["meshes"][0]["primitives"][0]["attributes"].size(), 4u);
}

TEST(Format, RoundTripWithoutUVs) {
    const lt::Asset a = makeAsset(false);
    Glb g = roundTrip(a);
    EXPECT_FALSE(g.cage().contains("controlVertex"));  // identity: omitted
    EXPECT_FALSE(g.doc["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_0"));
    // Empty arrays are omitted: level 0 has no refinement, level 2 no masks/creases.
    EXPECT_FALSE(g.ext()["levels"][0].contains("vertexParent"));
    EXPECT_EQ(g.ext()["levels"][0]["firstVertex"], 0);
    EXPECT_FALSE(g.ext()["levels"][2].contains("maskWeights"));
    EXPECT_FALSE(g.ext()["levels"][2].contains("creaseEdge"));
    EXPECT_FALSE(g.ext()["levels"][2].contains("regularSplitMask"));  // all zero: omitted
    EXPECT_TRUE(g.ext()["levels"][2].contains("regularBoundaryMask"));
}

TEST(Format, Deterministic) {
    const lt::Asset a = makeAsset(true);
    const std::vector<uint8_t> first = write(a), second = write(makeAsset(true));
    EXPECT_EQ(first, second);
    lt::Asset b;
    ASSERT_TRUE(read(first, &b));
    EXPECT_EQ(write(b), first);  // write(read(write(a))) == write(a)
}

TEST(Format, IndexWidths) {
    Glb small(write(makeAsset(true), nullptr, lt::Compression::None));
    auto type = [](Glb& g, int acc) { return g.doc["accessors"][acc]["componentType"].get<int>(); };
    EXPECT_EQ(type(small, small.accessor(1, "vertexParent")), 5123);
    EXPECT_EQ(type(small, small.accessor(1, "edgeVerts")), 5123);
    EXPECT_EQ(type(small, small.doc["meshes"][0]["primitives"][0]["indices"].get<int>()), 5123);
    EXPECT_EQ(type(small, small.accessor(1, "regularBoundaryMask")), 5121);
    EXPECT_EQ(type(small, small.accessor(1, "regularOrigin")), 5121);
    EXPECT_EQ(type(small, small.accessor(1, "maskWeights")), 5126);

    // 70000 control vertices: indices into level 0 that reach 65536 need u32; the
    // other levels' tables hold indices relative to their level and stay u16.
    lt::Asset big = makeBigAsset();
    const std::vector<uint8_t> bytes = write(big, nullptr, lt::Compression::None);
    lt::Asset back;
    const lt::Status st = read(bytes, &back);
    ASSERT_TRUE(st) << st.message;
    expectEqual(big, back);
    Glb g(bytes);
    for (auto [level, prop] : {std::pair<int, const char*>{0, "regularPoints"}, {1, "edgeVerts"}})
        EXPECT_EQ(type(g, g.accessor(level, prop)), 5125) << level << " " << prop;
    for (auto [level, prop] : {std::pair<int, const char*>{1, "vertexParent"},
                               {2, "vertexParent"},
                               {2, "edgeVerts"},
                               {1, "regularPoints"},
                               {1, "limitVertex"},
                               {1, "limitRing"},
                               {1, "vertexRingStart"},
                               {1, "limitStart"}})
        EXPECT_EQ(type(g, g.accessor(level, prop)), 5123) << level << " " << prop;
    // Stored relative to level 1's first vertex (70004).
    EXPECT_EQ(g.index(g.accessor(2, "vertexParent"), 1), 1u);
    EXPECT_EQ(g.index(g.accessor(1, "limitVertex"), 2), 2u);
    // Base faces as differences mod 2^32: level 0's irregular faces 0 1 2 3, level 1's patches 3 0.
    EXPECT_EQ(g.index(g.accessor(0, "irregularBaseFace"), 3), 1u);
    EXPECT_EQ(g.index(g.accessor(1, "regularBaseFace"), 1), uint32_t(-3));
    // The 70000 unused vertices come last in the primitive: indices stay u16.
    EXPECT_EQ(type(g, g.doc["meshes"][0]["primitives"][0]["indices"].get<int>()), 5123);
    EXPECT_EQ(type(g, g.cage()["controlVertex"].get<int>()), 5125);

    // Exactly 65535 primitive vertices: tables fit u16 but indices must not use
    // the u16 primitive restart value 65535.
    lt::Asset edge = makeAsset(false, 65535 - 4);
    edge.faces[11] = 65534;
    for (auto& l : edge.levels) l = lt::Level{};
    edge.levels.resize(1);
    Glb e(write(edge, nullptr, lt::Compression::None));
    EXPECT_EQ(type(e, e.doc["meshes"][0]["primitives"][0]["indices"].get<int>()), 5123);
    edge.positions.insert(edge.positions.end(), {1, 2, 3});
    edge.faces[11] = 65535;
    Glb e2(write(edge, nullptr, lt::Compression::None));
    EXPECT_EQ(type(e2, e2.doc["meshes"][0]["primitives"][0]["indices"].get<int>()), 5125);
}

TEST(Format, WriterRejectsInvalidAsset) {
    lt::Asset a = makeAsset(false);
    a.levels[1].refinement.edgeVerts[5] = 999;
    std::vector<uint8_t> bytes;
    const lt::Status st = lt::writeAssetGlb(a, bytes);
    EXPECT_FALSE(st);
    EXPECT_NE(st.message.find("levels[1].edgeVerts[5]: rule 25: relative index 999 (vertex 999) is not below level "
                              "0's vertex count 4"),
              std::string::npos)
        << st.message;
}

// --- reader safety: truncations and random byte flips never crash -------------------

TEST(Format, MutationsNeverCrash) {
    const std::vector<uint8_t> bytes = write(makeAsset(true));
    for (size_t n = 0; n < bytes.size(); n += 7) {
        std::vector<uint8_t> b(bytes.begin(), bytes.begin() + n);
        EXPECT_FALSE(read(b));
    }
    std::mt19937 rng(12345);
    int accepted = 0;
    for (int i = 0; i < 3000; ++i) {
        std::vector<uint8_t> b = bytes;
        const int flips = 1 + int(rng() % 4);
        for (int k = 0; k < flips; ++k) b[rng() % b.size()] ^= uint8_t(1u << (rng() % 8));
        lt::Asset a;
        if (lt::readAssetGlb(b.data(), b.size(), "m.glb", a)) {
            ++accepted;
            EXPECT_TRUE(lt::validateAsset(a, "m.glb"));
        }
    }
    EXPECT_LT(accepted, 3000);
}

// --- the spec files list exactly what the writer emits ----------------------------

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(Format, SpecMatchesWriter) {
    const std::string dir = std::string(LOOPTESS_TEST_DATA) + "/../../formats/EXT_mesh_loop_subdivision/";
    const std::string readme = slurp(dir + "README.md");
    const Json schema = Json::parse(slurp(dir + "schema/mesh.EXT_mesh_loop_subdivision.schema.json"), nullptr, false);
    ASSERT_FALSE(readme.empty());
    ASSERT_TRUE(schema.is_object());
    lt::Asset a = makeAsset(true);  // level 1 of the fixture has every array but edits:
    const uint32_t v = a.levels[1].refinement.firstVertex + 1;
    a.levels[1].edits = lt::VertexEdits{{v}, {0, 1}, {lt::EditOp::Add}, {0.0f, 0.5f, 0.0f}};
    Glb g(write(a));
    std::vector<std::string> written, specified;
    for (const auto& [key, value] : g.ext()["levels"][1].items()) written.push_back(key);
    for (const auto& [key, value] : schema["$defs"]["level"]["properties"].items())
        if (key != "extensions" && key != "extras") specified.push_back(key);
    std::sort(written.begin(), written.end());
    std::sort(specified.begin(), specified.end());
    EXPECT_EQ(written, specified);
    for (const std::string& name : written)
        EXPECT_NE(readme.find("| `" + name + "` |"), std::string::npos) << name << " missing from the README table";
    for (const auto& [key, value] : g.ext().items()) { EXPECT_TRUE(schema["properties"].contains(key)) << key; }
    const Json cage =
        Json::parse(slurp(dir + "schema/mesh.primitive.EXT_mesh_loop_subdivision.schema.json"), nullptr, false);
    ASSERT_TRUE(cage.is_object());
    for (const auto& [key, value] : g.cage().items()) EXPECT_TRUE(cage["properties"].contains(key)) << key;
    for (int rule = 1; rule <= 46; ++rule)  // numbered rules 1..46, nothing after
        EXPECT_NE(readme.find("\n" + std::to_string(rule) + ". **"), std::string::npos) << "rule " << rule;
    EXPECT_EQ(readme.find("\n47. **"), std::string::npos);
}

// --- the Khronos glTF-Validator --------------------------------------------------------

void expectKhronosValid(const std::vector<uint8_t>& bytes, const std::string& fileName) {
    ASSERT_EQ(std::system("command -v node > /dev/null 2>&1"), 0)
        << "node is not installed: the Khronos glTF-Validator cannot run";
    const std::string dir = ::testing::TempDir();
    const std::string file = dir + "/" + fileName, report = file + ".report.json";
    {
        std::ofstream out(file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        ASSERT_TRUE(out.good());
    }
    const std::string cmd = std::string("node '") + VALIDATOR_JS + "' '" + file + "' > '" + report + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream in(report);
    std::stringstream text;
    text << in.rdbuf();
    ASSERT_EQ(rc, 0) << "glTF-Validator rejected " << file << ":\n" << text.str();
    const Json r = Json::parse(text.str(), nullptr, false);
    ASSERT_FALSE(r.is_discarded()) << text.str();
    EXPECT_EQ(r["issues"]["numErrors"], 0);
    EXPECT_EQ(r["issues"]["numWarnings"], 0);
    std::remove(file.c_str());
    std::remove(report.c_str());
}

TEST(Format, KhronosValidatorWithUVs) { expectKhronosValid(write(makeAsset(true)), "uvs.glb"); }
TEST(Format, KhronosValidatorWithColours) {
    lt::Asset a = makeAsset(true);
    a.faceColors.assign(4 * a.faces.size(), 0.5f);
    expectKhronosValid(write(a), "colours.glb");
}
TEST(Format, KhronosValidatorWithoutUVs) { expectKhronosValid(write(makeAsset(false)), "plain.glb"); }
TEST(Format, KhronosValidatorU32) { expectKhronosValid(write(makeBigAsset()), "u32.glb"); }
TEST(Format, KhronosValidatorUncompressed) {
    expectKhronosValid(write(makeBigAsset(), nullptr, lt::Compression::None), "none.glb");
}
TEST(Format, KhronosValidatorMax) {
    expectKhronosValid(write(makeBigAsset(), nullptr, lt::Compression::Max), "max.glb");
}

}  // namespace
