// tests/usd/test_usd_input.cpp -- USD input (looptess/tools/usd.h, loopbake).
//
// The oracle is independent of our reader: the assets in tests/data/usd were written
// by Pixar's usd-core (make_usd.py) from the corpus OBJ files (or, for scene.usd*,
// together with box.obj), so a USD mesh and its OBJ must give the same control mesh
// and the same baked tables, bit for bit.
#include "sanitizer.h"
#include "test_paths.h"
#include "tool_run.h"

#include "looptess/asset.h"
#include "looptess/runtime.h"
#include "looptess/tools/baker.h"
#include "looptess/tools/usd.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Bytes = std::vector<uint8_t>;

std::string usdDir() { return lt::test::testDataDir() + "/usd"; }

Bytes slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

lt::InputMesh readObj(const std::string& path) {
    const Bytes bytes = slurp(path);
    lt::InputMesh mesh;
    lt::Status st = lt::parseObj(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path,
                                 lt::InputOptions{}, mesh);
    EXPECT_TRUE(st) << st.message;
    return mesh;
}

// The tables lt::bake makes of `mesh`, as writeAssetGlb writes them.
Bytes bakeBytes(const lt::InputMesh& mesh, const std::string& name) {
    lt::Status st = lt::checkInput(mesh, name);
    EXPECT_TRUE(st) << st.message;
    lt::Asset asset;
    if (st) st = lt::bake(mesh, lt::BakeSettings{}, asset);
    EXPECT_TRUE(st) << st.message;
    Bytes bytes;
    if (st) { EXPECT_TRUE(lt::writeAssetGlb(asset, bytes)); }
    return bytes;
}

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectSameMesh(const lt::InputMesh& usd, const lt::InputMesh& obj) {
    EXPECT_TRUE(sameBits(usd.positions, obj.positions));
    EXPECT_EQ(usd.faces, obj.faces);
    EXPECT_TRUE(sameBits(usd.faceUVs, obj.faceUVs)) << usd.faceUVs.size() << " vs " << obj.faceUVs.size();
    ASSERT_EQ(usd.creases.size(), obj.creases.size());
    for (size_t i = 0; i < usd.creases.size(); ++i) {
        EXPECT_EQ(usd.creases[i].a, obj.creases[i].a);
        EXPECT_EQ(usd.creases[i].b, obj.creases[i].b);
        EXPECT_EQ(usd.creases[i].sharpness, obj.creases[i].sharpness);
    }
    ASSERT_EQ(usd.corners.size(), obj.corners.size());
    for (size_t i = 0; i < usd.corners.size(); ++i) {
        EXPECT_EQ(usd.corners[i].vertex, obj.corners[i].vertex);
        EXPECT_EQ(usd.corners[i].sharpness, obj.corners[i].sharpness);
    }
    EXPECT_EQ(usd.holes, obj.holes);
    EXPECT_EQ(usd.boundary, obj.boundary);
}

lt::GltfScene readUsd(const std::string& path, std::optional<double> time = {}) {
    lt::UsdOptions options;
    options.time = time;
    lt::GltfScene scene;
    lt::Status st = lt::parseUsdScene(path, options, scene);
    EXPECT_TRUE(st) << st.message;
    return scene;
}

// Corpus shapes, each as .usdc (one sharpness a crease) and .usda (chains, one a
// edge), against the corpus OBJ.
class UsdShape : public ::testing::TestWithParam<std::string> {};

TEST_P(UsdShape, MatchesTheObjBitForBit) {
    const std::string obj = lt::test::corpusDir() + "/opensubdiv-loop/" + GetParam() + ".obj";
    const lt::InputMesh reference = readObj(obj);
    const Bytes expected = bakeBytes(reference, obj);
    for (const char* ext : {".usdc", ".usda"}) {
        SCOPED_TRACE(ext);
        lt::GltfScene scene = readUsd(usdDir() + "/" + GetParam() + ext);
        ASSERT_EQ(scene.meshes.size(), 1u);
        EXPECT_EQ(scene.meshes[0].name, "/" + GetParam());
        expectSameMesh(scene.meshes[0].mesh, reference);
        EXPECT_EQ(bakeBytes(scene.meshes[0].mesh, GetParam()), expected);
    }
}

INSTANTIATE_TEST_SUITE_P(Corpus, UsdShape,
                         ::testing::Values("loop_icos_semisharp", "loop_cubes_infsharp", "loop_triangle_edgenone",
                                           "loop_triangle_edgecorner", "loop_saddle_edgeonly", "loop_fvar_bound2",
                                           "loop_xord_boundary"));

// scene.usd*: quads, vertex st, a crease chain, a corner, a hole, edgeAndCorner by
// default; the Catmull-Clark mesh beside it passes through.
TEST(UsdScene, LoopMeshMatchesItsObjTwinAndTheRestPassesThrough) {
    const lt::InputMesh reference = readObj(usdDir() + "/box.obj");
    const Bytes expected = bakeBytes(reference, "box.obj");
    for (const char* ext : {".usdc", ".usda"}) {
        SCOPED_TRACE(ext);
        lt::GltfScene scene = readUsd(usdDir() + "/scene" + ext);
        ASSERT_EQ(scene.meshes.size(), 1u);
        EXPECT_EQ(scene.meshes[0].name, "/World/Body/Group/Box");
        expectSameMesh(scene.meshes[0].mesh, reference);
        EXPECT_EQ(bakeBytes(scene.meshes[0].mesh, "box"), expected);
        bool warned = false;
        for (const std::string& w : scene.warnings) warned |= w.find("/World/Smooth") != std::string::npos;
        EXPECT_TRUE(warned);
        // The hierarchy, names kept: World > Body > Group > Box, World > Smooth.
        for (const char* name : {"\"World\"", "\"Body\"", "\"Group\"", "\"Box\"", "\"Smooth\""})
            EXPECT_NE(scene.document.find(std::string("\"name\":") + name), std::string::npos) << name;
    }
}

TEST(UsdScene, TimeSamplesAreReadAtTheRequestedTime) {
    lt::GltfScene atDefault = readUsd(usdDir() + "/scene.usdc");
    lt::GltfScene at10 = readUsd(usdDir() + "/scene.usdc", 10.0);
    lt::GltfScene at5 = readUsd(usdDir() + "/scene.usdc", 5.0);  // no sample: the default
    ASSERT_EQ(at10.meshes.size(), 1u);
    EXPECT_EQ(atDefault.meshes[0].mesh.positions[0], -1.0f);
    EXPECT_EQ(at10.meshes[0].mesh.positions[0], 2.0f);
    EXPECT_EQ(at5.meshes[0].mesh.positions[0], -1.0f);
}

// A flat open quad with USD's default boundary rule (edgeAndCorner) keeps its four
// corners where a DCC shows them: the surface passes through each control point,
// bit for bit, whatever diagonal split the quad. Its OBJ twin (a tag for the rule)
// reads and bakes the same.
TEST(UsdScene, AnOpenQuadKeepsItsFourCorners) {
    lt::GltfScene scene = readUsd(usdDir() + "/open_quad.usda");
    ASSERT_EQ(scene.meshes.size(), 1u);
    const lt::InputMesh& mesh = scene.meshes[0].mesh;
    EXPECT_EQ(mesh.boundary, lt::BoundaryInterpolation::EdgeAndCorner);
    const lt::InputMesh twin = readObj(usdDir() + "/open_quad.obj");
    expectSameMesh(mesh, twin);
    EXPECT_EQ(bakeBytes(mesh, "quad"), bakeBytes(twin, "quad"));
    lt::Asset asset;
    lt::BakeSettings settings;
    settings.maxDepth = 3;
    ASSERT_TRUE(lt::bake(mesh, settings, asset));
    lt::EvalSettings es;
    es.tessFactor = 4;
    lt::Tessellation soup;
    lt::evaluateCpu(asset, asset.positions.data(), es, soup);
    bool reached[4] = {false, false, false, false};
    for (size_t i = 0; i < soup.vertexCount(); ++i)
        for (uint32_t v = 0; v < 4; ++v)
            reached[v] |= std::memcmp(&soup.positions[3 * i], &mesh.positions[3 * v], 12) == 0;
    for (uint32_t v = 0; v < 4; ++v) EXPECT_TRUE(reached[v]) << "corner " << v << " rounded off";
}

// Any thread may read at any time (loopbake --manifest --threads): each read runs Sdf
// in a child of its own, and this process, never running Sdf, holds none of its
// locks when another thread forks. The same scene from every read.
TEST(UsdScene, ReadsFromManyThreadsAtOnce) {
    // clang 14's ASan allocator is not fork-safe: a child forked while another
    // thread holds one of its size-class locks waits forever (seen: the child stuck in
    // SizeClassAllocator64::GetFromAllocator). glibc's malloc, which loopbake runs on,
    // re-arms its locks at fork; the release run checks this.
    if (lt::test::kAsan) GTEST_SKIP() << "fork from many threads under ASan's allocator (see the comment)";
    const lt::GltfScene first = readUsd(usdDir() + "/scene.usdc");
    std::vector<std::thread> threads;
    std::atomic<int> same{0};
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&] {
            for (int i = 0; i < 5; ++i) {
                const std::string layer = usdDir() + (i % 2 ? "/scene.usdc" : "/scene.usda");
                lt::GltfScene scene;
                if (lt::parseUsdScene(layer, lt::UsdOptions{}, scene) && scene.document == first.document &&
                    scene.bin == first.bin)
                    ++same;
            }
        });
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(same.load(), 20);
}

// loopbake end to end: the scene's surface holds the tables the OBJ twin bakes to.
TEST(UsdLoopbake, SceneBakesToTheObjTwinsTables) {
    const fs::path dir = fs::temp_directory_path() / ("usd_bake_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    auto usd =
        lt::test::runTool(lt::test::loopbakeExe(), {usdDir() + "/scene.usdc", "-o", (dir / "s.glb").string()}, dir);
    ASSERT_EQ(usd.exitCode, 0) << usd.err;
    auto obj = lt::test::runTool(lt::test::loopbakeExe(), {usdDir() + "/box.obj", "-o", (dir / "b.glb").string()}, dir);
    ASSERT_EQ(obj.exitCode, 0) << obj.err;
    const Bytes scene = slurp(dir / "s.glb"), box = slurp(dir / "b.glb");
    std::vector<lt::SceneSurface> surfaces;
    lt::Status st = lt::readSceneGlb(scene.data(), scene.size(), "s.glb", surfaces);
    ASSERT_TRUE(st) << st.message;
    ASSERT_EQ(surfaces.size(), 1u);
    lt::Asset boxAsset;
    st = lt::readAssetGlb(box.data(), box.size(), "b.glb", boxAsset);
    ASSERT_TRUE(st) << st.message;
    // displayColor (uniform) reached the asset as the faces' colours; the OBJ has none.
    lt::Asset& usdAsset = surfaces[0].asset;
    ASSERT_EQ(usdAsset.faceColors.size(), size_t(12) * usdAsset.faceCount());
    EXPECT_EQ(usdAsset.faceColors[0], 0.0f);  // face 0: (0, 0.5, 1)
    EXPECT_EQ(usdAsset.faceColors[2], 1.0f);
    usdAsset.faceColors.clear();
    Bytes a, b;
    ASSERT_TRUE(lt::writeAssetGlb(usdAsset, a));
    ASSERT_TRUE(lt::writeAssetGlb(boxAsset, b));
    EXPECT_EQ(a, b);
    fs::remove_all(dir);
}

// loopcheck --source the USD layer: the asset's control meshes are the layer's as
// loopbake read it, and the surface is OpenSubdiv's limit surface with the layer's
// creases, corners, holes and boundary rule. Every corpus shape in both files and
// the scene (whose Catmull-Clark mesh passes through unchecked).
TEST(UsdLoopcheck, EveryBakePassesWithItsLayerAsSource) {
    const fs::path dir = fs::temp_directory_path() / ("usd_check_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::vector<std::string> layers = {"scene.usdc", "scene.usda", "open_quad.usda"};
    for (const char* shape :
         {"loop_icos_semisharp", "loop_cubes_infsharp", "loop_triangle_edgenone", "loop_triangle_edgecorner",
          "loop_saddle_edgeonly", "loop_fvar_bound2", "loop_xord_boundary"})
        for (const char* ext : {".usdc", ".usda"}) layers.push_back(std::string(shape) + ext);
    for (const std::string& layer : layers) {
        SCOPED_TRACE(layer);
        const std::string in = usdDir() + "/" + layer, out = (dir / "out.glb").string();
        auto bake = lt::test::runTool(lt::test::loopbakeExe(), {in, "-o", out}, dir);
        ASSERT_EQ(bake.exitCode, 0) << bake.err;
        // The validator once (it reads the GLB, not the layer), the rest without it.
        std::vector<std::string> args = {out, "--source", in, "--rays", "2000", "--tess", "1", "3.3:odd", "8", "-q"};
        if (layer != "scene.usdc") args.push_back("--no-validator");
        auto check = lt::test::runTool(LOOPCHECK_EXE, args, dir);
        EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
    }
    // Another time: the layer read at --time 10 is not what loopbake baked at the
    // default time (its points move), and loopcheck says so; at --time 10 both agree.
    const std::string scene = usdDir() + "/scene.usdc", out = (dir / "t.glb").string();
    ASSERT_EQ(lt::test::runTool(lt::test::loopbakeExe(), {scene, "-o", out}, dir).exitCode, 0);
    auto check = lt::test::runTool(
        LOOPCHECK_EXE, {out, "--source", scene, "--time", "10", "--rays", "0", "--no-validator", "-q"}, dir);
    EXPECT_NE(check.exitCode, 0);
    EXPECT_TRUE(lt::test::contains(check.out + check.err, "at a different position")) << check.out << check.err;
    ASSERT_EQ(lt::test::runTool(lt::test::loopbakeExe(), {scene, "-o", out, "--time", "10"}, dir).exitCode, 0);
    check = lt::test::runTool(LOOPCHECK_EXE,
                              {out, "--source", scene, "--time", "10", "--rays", "0", "--no-validator", "-q"}, dir);
    EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
    fs::remove_all(dir);
}

// Malformed input: exit 2, one line naming the prim and the attribute, no output.
struct BadCase {
    const char* file;
    const char* names;
};

TEST(UsdLoopbake, MalformedInputIsOneLineNamingPrimAndAttribute) {
    const BadCase cases[] = {
        {"counts_mismatch.usda", "/Mesh: faceVertexIndices:"},
        {"counts_mismatch.usdc", "/Mesh: faceVertexIndices:"},
        {"index_out_of_range.usda", "/Mesh: faceVertexIndices: [23] = 8 is out of range"},
        {"negative_count.usda", "/Mesh: faceVertexCounts: [5] = -4"},
        {"crease_one_vertex.usda", "/Mesh: creaseLengths: [0] = 1"},
        {"missing_points.usda", "/Mesh: points: missing"},
        {"sharpness_length.usda", "/Mesh: creaseSharpnesses:"},
        {"st_count.usda", "/Mesh: primvars:st:"},
        {"points_type.usda", "/Mesh: points:"},
        {"reference.usda", "/Ref: uses composition (references)"},
        {"truncated.usdc", "not a USD layer Sdf can read"},
        {"garbled.usdc", "not a USD layer Sdf can read"},
        // Found by fuzz_usd in seconds: its path table sends Sdf's crate reader past
        // the mapping (SIGSEGV). Read in a child, it is this error, not a crash.
        {"crash_paths.usdc", "Sdf crashed reading it"},
    };
    const fs::path dir = fs::temp_directory_path() / ("usd_bad_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const BadCase& c : cases) {
        SCOPED_TRACE(c.file);
        const fs::path out = dir / "out.glb";
        auto r = lt::test::runTool(lt::test::loopbakeExe(), {usdDir() + "/bad/" + c.file, "-o", out.string()}, dir);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
        // One error line (after warnings, if any).
        const size_t at = r.err.find("loopbake: error: ");
        EXPECT_NE(at, std::string::npos) << r.err;
        EXPECT_EQ(r.err.find('\n', at), r.err.size() - 1) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    fs::remove_all(dir);
}

}  // namespace
