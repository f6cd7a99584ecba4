// tests/formats/test_format_scene.cpp -- scenes in the format (spec "Scenes"): writeSceneGlb
// puts a surface on a mesh of any glTF document and keeps the rest as given;
// readSceneGlb rebuilds the control mesh from several cage primitives.
#include "format_fixture.h"

#include <gtest/gtest.h>

#include <cstring>

namespace {

using namespace fmttest;

// Appends `values` (float or u32) as an accessor on a bufferView of its own.
template <typename T>
int addAccessor(Json& doc, std::vector<uint8_t>& bin, const std::vector<T>& values, const char* type, int n) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t at = bin.size();
    bin.resize(at + values.size() * 4);
    std::memcpy(&bin[at], values.data(), values.size() * 4);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", values.size() * 4}});
    Json acc = {{"bufferView", doc["bufferViews"].size() - 1},
                {"componentType", std::is_same_v<T, float> ? 5126 : 5125},
                {"count", values.size() / size_t(n)},
                {"type", type}};
    if (std::is_same_v<T, float>) {  // POSITION needs its bounds
        std::vector<float> lo(n, 1e30f), hi(n, -1e30f);
        for (size_t i = 0; i < values.size(); ++i) {
            lo[i % n] = std::min(lo[i % n], float(values[i]));
            hi[i % n] = std::max(hi[i % n], float(values[i]));
        }
        acc["min"] = lo;
        acc["max"] = hi;
    }
    doc["accessors"].push_back(acc);
    return int(doc["accessors"].size() - 1);
}

struct Scene {
    Json doc;
    std::vector<uint8_t> bin;
    lt::SceneSurface surface;
    uint32_t firstHalf = 0;  // base faces of cage primitive 0
};

// The fixture asset's control mesh as a two-material mesh (mesh 0): primitive 0
// holds the first half of the faces on the control vertices as they are; primitive
// 1 the rest on its own vertices (numbered backwards) plus a triangle with two
// corners at one control vertex. Mesh 1 is a POINTS primitive, node 1 a camera.
Scene makeScene() {
    Scene s;
    s.surface.asset = makeAsset(false);
    const lt::Asset& a = s.surface.asset;
    const uint32_t n = a.controlVertexCount(), faces = a.faceCount();
    s.firstHalf = faces / 2;
    Json& d = s.doc;
    d = Json::parse(R"({"asset": {"version": "2.0", "generator": "a modeller", "copyright": "CC0", "extras": {"k": 1}},
      "scene": 0, "scenes": [{"nodes": [0, 1], "name": "main"}],
      "nodes": [{"mesh": 0, "name": "hero", "translation": [1, 2, 3], "children": [2]}, {"camera": 0},
                {"mesh": 1, "scale": [2, 2, 2]}],
      "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
      "materials": [{"name": "skin", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.5, 1]}}, {"name": "cloth"}],
      "meshes": [{"name": "body", "primitives": []}, {"name": "dots", "primitives": []}],
      "accessors": [], "bufferViews": [], "buffers": [{"byteLength": 0}]})");
    std::vector<uint32_t> first(a.faces.begin(), a.faces.begin() + 3 * s.firstHalf), second, back(n);
    std::vector<float> reversed(3 * size_t(n));
    for (uint32_t v = 0; v < n; ++v) {
        back[v] = n - 1 - v;
        std::memcpy(&reversed[3 * v], &a.positions[3 * size_t(n - 1 - v)], 12);
    }
    for (size_t c = 3 * size_t(s.firstHalf); c < a.faces.size(); ++c) second.push_back(n - 1 - a.faces[c]);
    second.insert(second.end(), {0, 0, 1});  // vertices 0, 0, 1: a line
    const int pos0 = addAccessor(d, s.bin, a.positions, "VEC3", 3);
    const int idx0 = addAccessor(d, s.bin, first, "SCALAR", 1);
    const int pos1 = addAccessor(d, s.bin, reversed, "VEC3", 3);
    const int idx1 = addAccessor(d, s.bin, second, "SCALAR", 1);
    d["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", pos0}}}, {"indices", idx0}, {"material", 0}});
    d["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", pos1}}}, {"indices", idx1}, {"material", 1}});
    d["meshes"][1]["primitives"].push_back({{"attributes", {{"POSITION", pos0}}}, {"mode", 0}});
    d["buffers"][0]["byteLength"] = s.bin.size();
    s.surface.mesh = 0;
    s.surface.primitives = {0, 1};
    s.surface.controlVertex = {{}, back};
    return s;
}

TEST(FormatScene, CagePrimitivesGiveTheControlMesh) {
    Scene s = makeScene();
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(lt::writeSceneGlb(s.doc.dump(), s.bin, {s.surface}, bytes));
    std::vector<lt::SceneSurface> read;
    const lt::Status st = lt::readSceneGlb(bytes.data(), bytes.size(), "scene.glb", read);
    ASSERT_TRUE(st) << st.message;
    ASSERT_EQ(read.size(), 1u);
    EXPECT_EQ(read[0].mesh, 0u);
    EXPECT_EQ(read[0].name, "body");
    EXPECT_EQ(read[0].primitives, (std::vector<uint32_t>{0, 1}));
    const uint32_t faces = s.surface.asset.faceCount();
    EXPECT_EQ(read[0].primitiveFaces, (std::vector<uint32_t>{0, s.firstHalf, faces}));  // the line is no face
    expectEqual(read[0].asset, s.surface.asset);

    // Everything but the extension is as given: the document's own objects, and
    // the tables appended after its accessors and bufferViews.
    Glb out(bytes);
    for (const char* key : {"asset", "scene", "scenes", "nodes", "cameras", "materials"})
        EXPECT_EQ(out.doc[key], s.doc[key]) << key;
    EXPECT_EQ(out.doc["meshes"][1], s.doc["meshes"][1]);
    Json mesh = out.doc["meshes"][0];
    mesh.erase("extensions");
    for (Json& p : mesh["primitives"]) p.erase("extensions");
    EXPECT_EQ(mesh, s.doc["meshes"][0]);
    for (size_t i = 0; i < s.doc["accessors"].size(); ++i) EXPECT_EQ(out.doc["accessors"][i], s.doc["accessors"][i]);
    EXPECT_EQ(out.doc["extensionsUsed"], Json::array({kExt}));
    EXPECT_FALSE(out.doc["meshes"][0]["primitives"][0]["extensions"][kExt].contains("controlVertex"));  // identity
    EXPECT_TRUE(out.doc["meshes"][0]["primitives"][1]["extensions"][kExt].contains("controlVertex"));

    std::vector<uint8_t> again;
    ASSERT_TRUE(lt::writeSceneGlb(s.doc.dump(), s.bin, {s.surface}, again));
    EXPECT_EQ(again, bytes);  // deterministic
    expectValidatorClean(bytes, "format_scene.glb");
}

// Copies of a control vertex in two cage primitives must agree (rule 11), and the
// tables name base faces of every cage primitive.
TEST(FormatScene, CagePrimitivesAgreeOnEachControlVertex) {
    Scene s = makeScene();
    std::vector<uint8_t> bytes;  // plain accessors: the edits below drop a controlVertex reference
    ASSERT_TRUE(lt::writeSceneGlb(s.doc.dump(), s.bin, {s.surface}, bytes, nullptr, lt::Compression::None));
    Glb g(bytes);
    g.setFloat(g.doc["meshes"][0]["primitives"][1]["attributes"]["POSITION"].get<int>(), 0, 7.0f);
    std::vector<lt::SceneSurface> read;
    const std::vector<uint8_t> moved = g.bytes();
    lt::Status st = lt::readSceneGlb(moved.data(), moved.size(), "t.glb", read);
    expectRule(st, 11);
    EXPECT_NE(st.message.find("meshes[0].primitives[1].attributes.POSITION"), std::string::npos) << st.message;

    Glb h(bytes);
    h.doc["meshes"][0]["primitives"][1].erase("extensions");  // half the cage: too few base faces
    const std::vector<uint8_t> half = h.bytes();
    st = lt::readSceneGlb(half.data(), half.size(), "t.glb", read);
    expectRule(st, 32);
}

}  // namespace
