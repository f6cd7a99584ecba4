// tests/baker/test_hard_edges.cpp -- InputOptions::hardEdges (loopbake --hard-edges):
// a glTF exporter's split normals become infinitely sharp creases, in both glTF
// readers, and only where the normals differ (not at UV seams). The oracle is the
// geometry: a cube whose twelve edges are infinitely sharp has the cube itself as
// its limit surface (Loop's crease and corner rules), which the CPU evaluator must
// draw; loopcheck compares RobotExpressive's bake against OpenSubdiv
// (test_real_meshes.cpp).
#include "looptess/runtime.h"
#include "looptess/tools/baker.h"

#include "gltf_fixture.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <utility>

namespace {

using namespace gltftest;

// A unit cube centred at the origin as a glTF exporter writes it: each of the six
// faces has four vertices of its own, so each of the 8 corners has 3 copies.
//
//       3-------2      face of axis a, side s (u x v = s e_a, outward):
//       |     / |        corner k at s/2 e_a + (x_k - 1/2) u + (y_k - 1/2) v,
//       |   /   |        (x, y) = (0,0) (1,0) (1,1) (0,1); triangles (0 1 2)
//       | /     |        and (0 2 3), counter-clockwise seen from outside
//       0-------1
//
// `smooth`: every copy's normal points from the centre to its corner (one smooth
// surface split only at UV seams); else each face's copies carry its face normal
// (a hard-edged box). UVs differ between copies either way.
Bytes cubeGlb(bool smooth, const std::function<void(Json&)>& edit = {}) {
    std::vector<float> positions, normals, uvs;
    std::vector<uint16_t> indices;
    for (int a = 0; a < 3; ++a)
        for (int s : {1, -1}) {
            int u = (a + 1) % 3, v = (a + 2) % 3;
            if (s < 0) std::swap(u, v);
            const uint16_t base = uint16_t(positions.size() / 3);
            const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (const auto& c : xy) {
                float p[3] = {0, 0, 0};
                p[a] = 0.5f * float(s);
                p[u] = c[0] - 0.5f;
                p[v] = c[1] - 0.5f;
                positions.insert(positions.end(), p, p + 3);
                float n[3] = {0, 0, 0};
                n[a] = float(s);
                if (smooth) std::copy(p, p + 3, n);
                normals.insert(normals.end(), n, n + 3);
                uvs.insert(uvs.end(), {c[0], c[1]});
            }
            for (uint16_t i : {0, 1, 2, 0, 2, 3}) indices.push_back(uint16_t(base + i));
        }
    Bytes bin;
    Json j = triangles(bin, {}, {}, {});
    bin.clear();
    auto view = [&](const void* data, size_t bytes) {
        const size_t offset = bin.size();
        const uint8_t* p = static_cast<const uint8_t*>(data);
        bin.insert(bin.end(), p, p + bytes);
        return Json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    };
    j["bufferViews"] = {view(positions.data(), 4 * positions.size()), view(indices.data(), 2 * indices.size()),
                        view(uvs.data(), 4 * uvs.size()), view(normals.data(), 4 * normals.size())};
    j["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 24}, {"type", "VEC3"}},
                      {{"bufferView", 1}, {"componentType", 5123}, {"count", 36}, {"type", "SCALAR"}},
                      {{"bufferView", 2}, {"componentType", 5126}, {"count", 24}, {"type", "VEC2"}},
                      {{"bufferView", 3}, {"componentType", 5126}, {"count", 24}, {"type", "VEC3"}}};
    j["buffers"] = {{{"byteLength", bin.size()}}};
    j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 3;
    if (edit) edit(j);
    return makeGlb(j, bin);
}

lt::InputOptions hardEdges(bool on) {
    lt::InputOptions o;
    o.hardEdges = on;
    return o;
}

lt::Status parse(const Bytes& glb, const lt::InputOptions& options, lt::InputMesh& mesh) {
    return lt::parseGltf(glb.data(), glb.size(), "cube.glb", "", options, mesh);
}

// The creases of `mesh` as edges between positions (the welded numbering is the
// reader's), each checked infinitely sharp.
std::set<std::pair<std::vector<float>, std::vector<float>>> creasePositions(const lt::InputMesh& mesh) {
    std::set<std::pair<std::vector<float>, std::vector<float>>> out;
    for (const lt::InputMesh::Crease& c : mesh.creases) {
        EXPECT_LT(c.a, c.b);
        EXPECT_GE(c.sharpness, 10.0f);
        std::vector<float> a(&mesh.positions[3 * c.a], &mesh.positions[3 * c.a] + 3);
        std::vector<float> b(&mesh.positions[3 * c.b], &mesh.positions[3 * c.b] + 3);
        out.insert(std::minmax(a, b));
    }
    return out;
}

// Whether edge (a, b) is one of the cube's twelve: its corners differ in one coordinate.
bool cubeEdge(const std::vector<float>& a, const std::vector<float>& b) {
    int differ = 0;
    for (int k = 0; k < 3; ++k) differ += a[size_t(k)] != b[size_t(k)];
    return differ == 1;
}

TEST(HardEdges, SplitNormalsMakeTheCubesTwelveEdgesSharp) {
    lt::InputMesh mesh;
    ASSERT_TRUE(parse(cubeGlb(false), hardEdges(true), mesh));
    EXPECT_EQ(mesh.vertexCount(), 8u);
    const auto creases = creasePositions(mesh);
    EXPECT_EQ(creases.size(), 12u);
    for (const auto& [a, b] : creases) EXPECT_TRUE(cubeEdge(a, b));
}

TEST(HardEdges, OffWithoutTheOptionAndAtUvSeams) {
    lt::InputMesh mesh;
    ASSERT_TRUE(parse(cubeGlb(false), hardEdges(false), mesh));
    EXPECT_TRUE(mesh.creases.empty());
    ASSERT_TRUE(parse(cubeGlb(true), hardEdges(true), mesh));  // split for UVs only
    EXPECT_TRUE(mesh.creases.empty());
}

TEST(HardEdges, NormalsFollowAMirroringNodeTransform) {
    lt::InputMesh mesh;
    ASSERT_TRUE(parse(cubeGlb(false, [](Json& j) { j["nodes"][0]["scale"] = {-1, 2, 1}; }), hardEdges(true), mesh));
    EXPECT_EQ(creasePositions(mesh).size(), 12u);
    ASSERT_TRUE(parse(cubeGlb(true, [](Json& j) { j["nodes"][0]["scale"] = {-1, 1, 1}; }), hardEdges(true), mesh));
    EXPECT_TRUE(mesh.creases.empty());
}

TEST(HardEdges, TheSceneReaderFindsThemToo) {
    const Bytes glb = cubeGlb(false);
    lt::GltfScene scene;
    ASSERT_TRUE(lt::parseGltfScene(glb.data(), glb.size(), "cube.glb", "", hardEdges(true), scene));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(creasePositions(scene.meshes[0].mesh).size(), 12u);
    // The cage keeps its split normals: nothing is welded back in the document.
    EXPECT_NE(scene.document.find("\"NORMAL\""), std::string::npos);
}

// A primitive without NORMAL, or one whose normals are zero, decides nothing.
TEST(HardEdges, CornersWithoutNormalsMakeNoCrease) {
    lt::InputMesh mesh;
    ASSERT_TRUE(parse(cubeGlb(false, [](Json& j) { j["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL"); }),
                      hardEdges(true), mesh));
    EXPECT_TRUE(mesh.creases.empty());
}

// The limit surface of the hard-edged cube is the cube: every sample on a face
// plane's square, the corners themselves reached.
TEST(HardEdges, TheHardEdgedCubeBakesIntoTheCube) {
    lt::InputMesh mesh;
    ASSERT_TRUE(parse(cubeGlb(false), hardEdges(true), mesh));
    ASSERT_TRUE(lt::checkInput(mesh, "cube.glb"));
    lt::Asset asset;
    lt::BakeSettings settings;
    settings.maxDepth = 3;
    ASSERT_TRUE(lt::bake(mesh, settings, asset));
    lt::EvalSettings es;
    es.tessFactor = 8;
    lt::Tessellation t;
    lt::evaluateCpu(asset, asset.positions.data(), es, t);
    ASSERT_GT(t.vertexCount(), 0u);
    size_t corners = 0;
    for (size_t i = 0; i < t.vertexCount(); ++i) {
        const float* p = &t.positions[3 * i];
        int onPlane = 0, atCorner = 0;
        for (int k = 0; k < 3; ++k) {
            EXPECT_LE(std::fabs(p[k]), 0.5f + 1e-6f) << "vertex " << i;
            onPlane += std::fabs(std::fabs(p[k]) - 0.5f) <= 1e-6f;
            atCorner += std::fabs(p[k]) == 0.5f;
        }
        EXPECT_GE(onPlane, 1) << "vertex " << i << " (" << p[0] << ", " << p[1] << ", " << p[2]
                              << ") is inside the cube";
        corners += atCorner == 3;
    }
    EXPECT_GT(corners, 0u);
}

// loopbake --hard-edges on the cube: twelve creases in its report; on an OBJ a
// usage error that says where creases come from there.
TEST(HardEdges, LoopbakeTakesTheOptionForGltfOnly) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(testing::TempDir()) / "hard_edges_cli";
    fs::create_directories(dir);
    const Bytes glb = cubeGlb(false);
    std::ofstream(dir / "cube.glb", std::ios::binary)
        .write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
    auto bake = [&](const std::string& in, bool hard) {
        std::vector<std::string> args = {(dir / in).string(), "-o", (dir / "out.glb").string(), "-v"};
        if (hard) args.push_back("--hard-edges");
        return lt::test::runTool(LOOPBAKE_EXE, args, dir);
    };
    lt::test::RunResult r = bake("cube.glb", true);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(lt::test::contains(r.err, "12 creases")) << r.err;
    r = bake("cube.glb", false);
    EXPECT_TRUE(lt::test::contains(r.err, "0 creases")) << r.err;
    std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    r = bake("tri.obj", true);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(lt::test::contains(r.err, "'t crease' tags")) << r.err;
    fs::remove_all(dir);
}

}  // namespace
