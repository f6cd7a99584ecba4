// tests/viewer/test_scene_pose.cpp -- looprender's scene model (viewer/scene.h):
// animation sampling and CPU skinning against values worked out by hand from the
// glTF 2.0 spec (Appendix C interpolation, "Skins"), and loadScene on a baked
// skinned, animated character (the Fox).
#include "scene.h"

#include "looptess/tools/file_io.h"
#include "looptess/glb.h"
#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <functional>
#include <stdexcept>

#include <unistd.h>

namespace looprender {
namespace {

constexpr float kEps = 1e-5f;

// A scene of `nodes` plain nodes and one mesh (three control points) on node 0.
Scene sceneWith(size_t nodes) {
    Scene s;
    s.nodes.resize(nodes);
    s.roots = {0};
    s.surfaces.resize(1);
    s.surfaces[0].asset.positions = {1, 0, 0, 0, 2, 0, 0, 0, 3};
    s.meshes.resize(1);
    s.meshes[0].surface = 0;
    s.nodes[0].mesh = 0;
    return s;
}

AnimationChannel channel(uint32_t node, AnimationChannel::Path path, AnimationChannel::Interpolation interp,
                         std::vector<float> times, std::vector<float> values) {
    AnimationChannel ch;
    ch.node = node;
    ch.path = path;
    ch.interpolation = interp;
    ch.components = path == AnimationChannel::Rotation ? 4 : 3;
    ch.times = std::move(times);
    ch.values = std::move(values);
    return ch;
}

float translationX(const Scene& s, int animation, float time) { return poseScene(s, animation, time).world[0][12]; }

TEST(ScenePose, TranslationsInterpolateLinearlyStepAndClamp) {
    Scene s = sceneWith(1);
    s.animations = {"linear", "step"};
    s.channels.push_back(
        channel(0, AnimationChannel::Translation, AnimationChannel::Linear, {0, 2}, {0, 0, 0, 4, 0, 0}));
    s.channels.push_back(channel(0, AnimationChannel::Translation, AnimationChannel::Step, {0, 2}, {0, 0, 0, 4, 0, 0}));
    s.channels.back().animation = 1;
    EXPECT_NEAR(translationX(s, 0, 0.5f), 1.0f, kEps);
    EXPECT_NEAR(translationX(s, 0, 5.0f), 4.0f, kEps);  // after the last key: its value
    EXPECT_NEAR(translationX(s, 1, 1.9f), 0.0f, kEps);  // STEP holds the earlier key
    EXPECT_NEAR(translationX(s, 1, 2.0f), 4.0f, kEps);
    EXPECT_NEAR(translationX(s, -1, 1.0f), 0.0f, kEps);  // the rest pose
}

TEST(ScenePose, CubicSplineUsesTheTangentsScaledByTheKeyInterval) {
    // Keys at 0 and 2, values 0 and 1, out-tangent 2 at key 0, in-tangent 0 at key 1.
    // At s = 0.5 (time 1): h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125, so
    // 0.5 * 0 + 0.125 * 2 * 2 + 0.5 * 1 + (-0.125) * 2 * 0 = 1.0.
    Scene s = sceneWith(1);
    s.animations = {"cubic"};
    s.channels.push_back(channel(0, AnimationChannel::Translation, AnimationChannel::CubicSpline, {0, 2},
                                 {0, 0, 0, 0, 0, 0, 2, 0, 0, /* key 1: */ 0, 0, 0, 1, 0, 0, 9, 0, 0}));
    EXPECT_NEAR(translationX(s, 0, 1.0f), 1.0f, kEps);
    EXPECT_NEAR(translationX(s, 0, 2.0f), 1.0f, kEps);
}

TEST(ScenePose, RotationsSlerpAndChildrenCompose) {
    // Node 0 turns from 0 to 90 degrees about z over one second; its child node 1 is
    // translated by (1, 0, 0) in node 0's frame.
    Scene s = sceneWith(2);
    s.nodes[0].children = {1};
    s.nodes[1].translation[0] = 1;
    s.animations = {"turn"};
    const float h = std::sqrt(0.5f);
    s.channels.push_back(
        channel(0, AnimationChannel::Rotation, AnimationChannel::Linear, {0, 1}, {0, 0, 0, 1, 0, 0, h, h}));
    ScenePose pose = poseScene(s, 0, 0.5f);
    const float c = std::sqrt(0.5f), sn = std::sqrt(0.5f);  // 45 degrees
    EXPECT_NEAR(pose.world[0][0], c, kEps);
    EXPECT_NEAR(pose.world[0][1], sn, kEps);
    EXPECT_NEAR(pose.world[1][12], c, kEps);  // the child's origin turned with its parent
    EXPECT_NEAR(pose.world[1][13], sn, kEps);
    ASSERT_EQ(pose.instances.size(), 1u);
    EXPECT_TRUE(pose.instances[0].controlPoints.empty());  // unskinned: the asset's points, moved by `model`
}

TEST(ScenePose, MorphTargetsMoveTheControlPointsByTheirWeights) {
    // Two targets: d0 moves every point by (1, 0, 0), d1 by (0, 0, 2). Weights: the
    // mesh's (0.5, 0), the node's (0, 1) when it has them, animated ones over both.
    Scene s = sceneWith(1);
    s.meshes[0].targets = {{1, 0, 0, 1, 0, 0, 1, 0, 0}, {0, 0, 2, 0, 0, 2, 0, 0, 2}};
    s.meshes[0].weights = {0.5f, 0};
    auto first = [](const ScenePose& p) {
        return std::vector<float>(p.instances[0].controlPoints.begin(), p.instances[0].controlPoints.begin() + 3);
    };
    EXPECT_EQ(first(poseScene(s, -1, 0)), (std::vector<float>{1.5f, 0, 0}));
    s.nodes[0].weights = {0, 1};
    EXPECT_EQ(first(poseScene(s, -1, 0)), (std::vector<float>{1, 0, 2}));
    s.animations = {"blink"};
    AnimationChannel ch = channel(0, AnimationChannel::Weights, AnimationChannel::Linear, {0, 1}, {0, 0, 1, 1});
    ch.components = 2;
    s.channels.push_back(ch);
    const std::vector<float> half = first(poseScene(s, 0, 0.5f));  // weights (0.5, 0.5)
    ASSERT_EQ(half.size(), 3u);
    EXPECT_NEAR(half[0], 1.5f, kEps);
    EXPECT_NEAR(half[2], 1.0f, kEps);
    s.meshes[0].weights = {0, 0};
    s.nodes[0].weights.clear();
    s.channels.clear();
    EXPECT_TRUE(poseScene(s, -1, 0).instances[0].controlPoints.empty());  // unmorphed: the asset's own points
}

TEST(ScenePose, SkinsBlendJointMatricesAndIgnoreTheMeshNode) {
    // Joints: node 1 (translated by (0, 0, 10)) and node 2 (at rest). The mesh node 0
    // is moved by (100, 0, 0), which a skinned mesh ignores (glTF "Skins").
    Scene s = sceneWith(3);
    s.roots = {0, 1, 2};
    s.nodes[0].translation[0] = 100;
    s.nodes[0].skin = 0;
    s.nodes[1].translation[2] = 10;
    SceneSkin skin;
    skin.joints = {1, 2};
    skin.inverseBind.assign(2, Mat4{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
    skin.inverseBind[0][14] = -10;  // bound where joint 1 rests: no move at rest
    s.skins.push_back(skin);
    SkinWeights& w = s.meshes[0].skin;
    w.sets = 1;
    w.joints = {0, 0, 0, 0, /**/ 0, 1, 0, 0, /**/ 0, 0, 0, 0};
    w.weights = {1, 0, 0, 0, /**/ 0.25f, 0.25f, 0, 0, /**/ 0, 0, 0, 0};  // vertex 1: drawn normalized; 2 unweighted
    s.animations = {"lift"};
    s.channels.push_back(
        channel(1, AnimationChannel::Translation, AnimationChannel::Linear, {0, 1}, {0, 0, 10, 0, 4, 10}));

    ScenePose rest = poseScene(s, -1, 0);
    ASSERT_EQ(rest.instances.size(), 1u);
    EXPECT_EQ(rest.instances[0].controlPoints, s.surfaces[0].asset.positions);
    EXPECT_FLOAT_EQ(rest.instances[0].model[12], 0.0f);  // identity: the mesh node's move ignored

    ScenePose lifted = poseScene(s, 0, 1.0f);  // joint 1 moved by (0, 4, 0)
    const std::vector<float>& p = lifted.instances[0].controlPoints;
    const std::vector<float> expected = {1, 4, 0, /**/ 0, 2 + 2, 0, /**/ 0, 0, 3};
    ASSERT_EQ(p.size(), expected.size());
    for (size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(p[i], expected[i], kEps) << "coordinate " << i;
}

// The Fox baked by loopbake, read once.
const std::vector<uint8_t>& bakedFox() {
    static std::vector<uint8_t> bytes = [] {
        namespace fs = std::filesystem;
        // One folder per process: ctest runs the tests of this file side by side.
        const fs::path scratch = fs::path(::testing::TempDir()) / ("scene_load_fox_" + std::to_string(getpid()));
        fs::create_directories(scratch);
        const std::string glb = (scratch / "fox.glb").string();
        lt::test::RunResult bake =
            lt::test::runTool(LOOPBAKE_EXE, {std::string(LOOPTESS_TEST_DATA) + "/real/fox.glb", "-o", glb}, scratch);
        EXPECT_EQ(bake.exitCode, 0) << bake.err;
        std::vector<uint8_t> out;
        EXPECT_TRUE(lt::readFile(glb, out));
        fs::remove_all(scratch);
        return out;
    }();
    return bytes;
}

void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

// `glb` with its JSON chunk edited by `edit` (the chunks after it kept as they are).
template <class Edit>
std::vector<uint8_t> withJson(const std::vector<uint8_t>& glb, Edit edit) {
    lt::GlbChunks chunks;
    const lt::Status st = lt::readGlb(glb.data(), glb.size(), "fox.glb", lt::GlbLayout::Strict, chunks);
    if (!st) throw std::runtime_error(st.message);
    nlohmann::json doc = nlohmann::json::parse(chunks.json.begin(), chunks.json.end());
    edit(doc);
    std::string text = doc.dump();
    text.append((4 - text.size() % 4) % 4, ' ');
    const size_t binAt = 20 + chunks.json.size();  // chunk 0's data starts at byte 20
    std::vector<uint8_t> out;
    put32(out, lt::kGlbMagic);
    put32(out, lt::kGlbVersion);
    put32(out, uint32_t(12 + 8 + text.size() + glb.size() - binAt));
    put32(out, uint32_t(text.size()));
    put32(out, lt::kGlbChunkJson);
    out.insert(out.end(), text.begin(), text.end());
    out.insert(out.end(), glb.begin() + long(binAt), glb.end());
    return out;
}

TEST(SceneLoad, BadScenesAreErrorsNamingTheObject) {
    using Json = nlohmann::json;
    struct Case {
        const char* what;
        std::function<void(Json&)> edit;
        const char* message;
    };
    const Case cases[] = {
        {"a vertex names a joint the skin lacks",
         [](Json& d) {
             d["skins"][0]["joints"] = Json::array({0, 1});
             d["skins"][0].erase("inverseBindMatrices");
         },
         "meshes[0]: a vertex names joint"},
        {"too few inverse bind matrices",
         [](Json& d) {
             d["skins"][0]["joints"] = Json::array({0, 1});
         },
         "skins[0].inverseBindMatrices: count differs from the joints'"},
        {"an animation's input names no accessor", [](Json& d) { d["animations"][0]["samplers"][0]["input"] = 100000; },
         "animations[0].samplers[0].input: no accessor 100000"},
        {"a node is its own child", [](Json& d) { d["nodes"][2]["children"] = Json::array({2}); },
         "nodes[2]: has more than one parent or is its own child"},
        {"an undecodable image", [](Json& d) { d["images"][0]["bufferView"] = d["accessors"][0]["bufferView"]; },
         "images[0]: cannot decode its image/png"},
    };
    for (const Case& c : cases) {
        std::vector<uint8_t> bytes = withJson(bakedFox(), c.edit);
        Scene scene;
        lt::Status st = loadScene(bytes.data(), bytes.size(), "fox.glb", scene);
        EXPECT_EQ(st.code, lt::Status::BadInput) << c.what;
        EXPECT_NE(st.message.find(std::string("fox.glb: ") + c.message), std::string::npos)
            << c.what << ": " << st.message;
    }
}

TEST(SceneLoad, ABakedFoxKeepsItsSkinAnimationsAndTexture) {
    const std::vector<uint8_t>& bytes = bakedFox();
    ASSERT_FALSE(bytes.empty());
    Scene scene;
    lt::Status st = loadScene(bytes.data(), bytes.size(), "fox.glb", scene);
    ASSERT_TRUE(st) << st.message;
    EXPECT_TRUE(scene.warnings.empty());
    ASSERT_EQ(scene.surfaces.size(), 1u);
    EXPECT_EQ(scene.animations, (std::vector<std::string>{"Survey", "Walk", "Run"}));
    ASSERT_EQ(scene.skins.size(), 1u);
    EXPECT_EQ(scene.skins[0].joints.size(), 24u);
    const SkinWeights& w = scene.meshes[0].skin;
    ASSERT_EQ(w.sets, 1u);
    ASSERT_EQ(w.weights.size(), 4 * scene.surfaces[0].asset.controlVertexCount());
    for (size_t v = 0; v < w.weights.size() / 4; ++v) {  // glTF: each vertex's weights sum to 1
        const float sum = w.weights[4 * v] + w.weights[4 * v + 1] + w.weights[4 * v + 2] + w.weights[4 * v + 3];
        ASSERT_NEAR(sum, 1.0f, 2e-3f) << "control vertex " << v;
    }
    ASSERT_EQ(scene.images.size(), 1u);
    EXPECT_GT(scene.images[0].width, 0u);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].baseColorTexture.image, 0);

    // Posed by the walk, the skinned cage moves; the rest pose is the bind pose.
    ScenePose walk = poseScene(scene, 1, 0.35f);
    ASSERT_EQ(walk.instances.size(), 1u);
    ASSERT_EQ(walk.instances[0].controlPoints.size(), scene.surfaces[0].asset.positions.size());
    EXPECT_NE(walk.instances[0].controlPoints, poseScene(scene, 1, 0.0f).instances[0].controlPoints);
}

// Without --color material looprender draws one surface of a scene: on a file of
// several it says so (before, kenney_alien's six meshes gave a mesh of the first
// with no word of the other five).
TEST(SceneLoad, LooprenderSaysItDrawsTheFirstOfSeveralSurfaces) {
    namespace fs = std::filesystem;
    const fs::path scratch = fs::path(::testing::TempDir()) / ("looprender_surfaces_" + std::to_string(getpid()));
    fs::create_directories(scratch);
    const std::string glb = (scratch / "alien.glb").string(), ply = (scratch / "alien.ply").string();
    lt::test::RunResult bake = lt::test::runTool(
        LOOPBAKE_EXE, {std::string(LOOPTESS_TEST_DATA) + "/real/kenney_alien.glb", "-o", glb}, scratch);
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
    lt::test::RunResult render = lt::test::runTool(LOOPRENDER_EXE, {"--cpu", glb, "--mesh", ply}, scratch);
    EXPECT_EQ(render.exitCode, 0) << render.err;
    EXPECT_NE(render.err.find("has 6 surfaces"), std::string::npos) << render.err;
    EXPECT_NE(render.err.find("draws the first"), std::string::npos) << render.err;
    fs::remove_all(scratch);
}

}  // namespace
}  // namespace looprender
