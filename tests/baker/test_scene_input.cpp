// tests/baker/test_scene_input.cpp -- lt::parseGltfScene on small files built in memory
// (gltf_fixture.h): what each mesh's control mesh and cage are, strips and fans, and
// bad input that a scene would otherwise carry on unseen (broken references, nodes
// that are not trees): each a clear error naming the file and the glTF object.
#include "looptess/tools/baker.h"

#include "gltf_fixture.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace {

using namespace gltftest;

lt::Status parseScene(const Bytes& bytes, lt::GltfScene& scene) {
    return lt::parseGltfScene(bytes.data(), bytes.size(), "test.glb", "", lt::Limits{}, scene);
}

void expectSceneError(const Bytes& bytes, const std::string& text) {
    lt::GltfScene scene;
    const lt::Status st = parseScene(bytes, scene);
    EXPECT_FALSE(st) << "accepted; expected an error containing: " << text;
    EXPECT_EQ(st.code, lt::Status::BadInput);
    EXPECT_NE(st.message.find(text), std::string::npos) << st.message;
    EXPECT_EQ(st.message.rfind("test.glb: ", 0), 0u) << st.message;
}

// The tetrahedron as one mesh: its own space (the node's scale is not applied), its
// vertices in primitive order, its one primitive the cage.
TEST(SceneInput, AMeshIsItsCageInItsOwnSpace) {
    lt::GltfScene scene;
    ASSERT_TRUE(parseScene(tetraGlb([](Json& j, Bytes&) { j["nodes"][0]["scale"] = {2, 2, 2}; }), scene));
    ASSERT_EQ(scene.meshes.size(), 1u);
    const lt::GltfScene::Mesh& m = scene.meshes[0];
    EXPECT_EQ(m.primitives, std::vector<uint32_t>{0});
    EXPECT_EQ(m.controlVertex, (std::vector<std::vector<uint32_t>>{{0, 1, 2, 3}}));
    EXPECT_EQ(m.mesh.positions, (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}));
    EXPECT_EQ(m.mesh.faces, (std::vector<uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}));
}

// A strip and a fan give the triangles glTF defines, as lists in the cage.
TEST(SceneInput, StripsAndFansBecomeTriangleLists) {
    for (int mode : {5, 6}) {
        SCOPED_TRACE(mode);
        lt::GltfScene scene;
        // Strip 0 1 2 3: (0 1 2) (1 3 2); fan 0 1 2 3: (1 2 0) (2 3 0) (glTF 2.0 3.7.2.1).
        ASSERT_TRUE(parseScene(tetraGlb([&](Json& j, Bytes& bin) {
                                   const uint16_t strip[4] = {0, 1, 2, 3};
                                   std::memcpy(&bin[48], strip, sizeof strip);  // over the first indices
                                   j["accessors"][1]["count"] = 4;
                                   j["meshes"][0]["primitives"][0]["mode"] = mode;
                                   j["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
                               }),
                               scene));
        const std::vector<uint32_t> expected =
            mode == 5 ? std::vector<uint32_t>{0, 1, 2, 1, 3, 2} : std::vector<uint32_t>{1, 2, 0, 2, 3, 0};
        EXPECT_EQ(scene.meshes[0].mesh.faces, expected);
        const Json doc = Json::parse(scene.document);
        EXPECT_EQ(doc["meshes"][0]["primitives"][0]["mode"], 4);  // with new indices
        EXPECT_EQ(doc["meshes"][0]["primitives"][0]["indices"], doc["accessors"].size() - 1);
    }
}

TEST(SceneInput, BrokenReferencesAndCountsAreErrors) {
    expectSceneError(
        tetraGlb([](Json& j, Bytes&) {
            j["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
            j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 3;
        }),
        "meshes[0].primitives[0].attributes.NORMAL: count 2 differs from POSITION count 4");
    expectSceneError(
        tetraGlb([](Json& j, Bytes&) {
            j["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
            j["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 3}}};
        }),
        "meshes[0].primitives[0].targets[0].POSITION: count 3 differs from POSITION count 4");
    expectSceneError(tetraGlb([](Json& j, Bytes&) {
                         j["skins"] = {{{"joints", {0, 7}}}};
                         j["nodes"][0]["skin"] = 0;
                     }),
                     "skins[0].joints[1]: node 7 does not exist (1)");
    expectSceneError(tetraGlb([](Json& j, Bytes&) {
                         j["textures"] = {{{"source", 3}}};
                     }),
                     "textures[0].source: image 3 does not exist (0)");
    expectSceneError(tetraGlb([](Json& j, Bytes&) { j["images"] = {{{"uri", "missing.png"}}}; }), "images[0].uri");
}

// The node graph goes to the output as it is, so it must be the forest glTF asks
// for, with every scene's nodes existing: before, a cycle of children (even one no
// scene reaches), a node that is its own child or a scene naming a missing node
// baked with exit 0 into a file the glTF-Validator rejects.
TEST(SceneInput, NodesThatAreNotTreesAreErrors) {
    expectSceneError(tetraGlb([](Json& j, Bytes&) {
                         j["nodes"].push_back({{"children", {2}}});
                         j["nodes"].push_back({{"children", {1}}, {"mesh", 0}});
                     }),
                     "test.glb: nodes[1]: is its own ancestor (a cycle of children)");
    expectSceneError(tetraGlb([](Json& j, Bytes&) {
                         j["nodes"].push_back({{"children", {1}}});
                     }),
                     "test.glb: nodes[1]: is its own ancestor (a cycle of children)");
    expectSceneError(tetraGlb([](Json& j, Bytes&) {
                         j["nodes"].push_back({{"children", {0}}});
                         j["nodes"].push_back({{"children", {0}}});
                     }),
                     "nodes[2].children: nodes[0] already has parent nodes[1] (nodes must form trees)");
    expectSceneError(tetraGlb([](Json& j, Bytes&) {
                         j["scenes"] = {{{"nodes", {0, 57}}}};
                     }),
                     "scenes[0].nodes[1]: node 57 does not exist (1)");
    expectSceneError(tetraGlb([](Json& j, Bytes&) {
                         j["scenes"] = {{{"nodes", {0}}}};
                         j["scene"] = 3;
                     }),
                     "scene: scene 3 does not exist (1)");
}

}  // namespace
