// fuzz/entry_points.cpp -- see entry_points.h.
#include "entry_points.h"

#include "scene.h"  // looprender's scene model (viewer/)

#include "looptess/tools/baker.h"
#include "looptess/runtime.h"

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace lt::fuzz {
namespace {

// A broken cross-function promise: report and abort (a libFuzzer crash).
[[noreturn]] void broken(const char* what, const std::string& detail) {
    std::fprintf(stderr, "fuzz contract broken: %s: %s\n", what, detail.c_str());
    std::abort();
}

}  // namespace

Status asset(const uint8_t* data, size_t size) {
    std::vector<SceneSurface> surfaces;
    Status st = readSceneGlb(data, size, "fuzz.glb", surfaces);
    if (!st) return st;
    for (const SceneSurface& s : surfaces) {
        Status again = validateAsset(s.asset, "fuzz.glb");
        if (!again) broken("readSceneGlb accepted an asset validateAsset rejects", again.message);
        if (s.primitiveFaces.size() != s.primitives.size() + 1 || s.primitiveFaces.back() != s.asset.faceCount())
            broken("readSceneGlb", "primitiveFaces does not cover the base faces");
        if (s.controlVertex.size() != s.primitives.size())
            broken("readSceneGlb", "a cage primitive has no controlVertex map");
        for (const std::vector<uint32_t>& cv : s.controlVertex)
            for (uint32_t v : cv)
                if (v >= s.asset.controlVertexCount())
                    broken("readSceneGlb", "controlVertex names a missing control vertex");
    }
    return st;
}

Status scene(const uint8_t* data, size_t size) {
    looprender::Scene sc;
    Status st = looprender::loadScene(data, size, "fuzz.glb", sc);
    if (!st) return st;
    for (int animation : {-1, 0}) {
        const looprender::ScenePose pose = looprender::poseScene(sc, animation, 0.37f);
        if (pose.world.size() != sc.nodes.size()) broken("poseScene", "a world matrix per node");
        for (const looprender::SceneInstance& inst : pose.instances) {
            const Asset& a = sc.surfaces[size_t(sc.meshes[inst.mesh].surface)].asset;
            if (!inst.controlPoints.empty() && inst.controlPoints.size() != a.positions.size())
                broken("poseScene", "posed control points differ in count from the surface's");
        }
    }
    return st;
}

Status obj(const uint8_t* data, size_t size) {
    InputMesh mesh;
    std::string_view text(reinterpret_cast<const char*>(data), size);
    Status st = parseObj(text, "fuzz.obj", InputOptions{}, mesh);
    if (st) st = checkInput(mesh, "fuzz.obj");
    if (st) addCreasesByAngle(mesh, 30.0f);
    return st;
}

Status edits(const uint8_t* data, size_t size) {
    // An icosahedron: 12 vertices, 20 faces.
    static const InputMesh icosahedron = [] {
        const float t = 1.6180339887f;
        InputMesh m;
        m.positions = {-1, t,  0,  1, t, 0,  -1, -t, 0,  1, -t, 0, 0,  -1, t,  0,  1, t,
                       0,  -1, -t, 0, 1, -t, t,  0,  -1, t, 0,  1, -t, 0,  -1, -t, 0, 1};
        m.faces = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
                   3, 9,  4, 3, 4, 2, 3, 2, 6, 3, 6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
        return m;
    }();
    InputMesh mesh = icosahedron;
    Status st = parseEditsJson(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json", mesh);
    if (st) st = checkInput(mesh, "fuzz.json");
    if (!st) return st;
    BakeSettings settings;
    settings.maxDepth = 3;
    Asset asset;
    st = bake(mesh, settings, asset);
    if (!st && st.code != Status::BadInput) broken("bake failed on edits checkInput accepted", st.message);
    if (st)
        if (Status valid = validateAsset(asset, "fuzz.glb"); !valid)
            broken("bake made an asset validateAsset rejects", valid.message);
    return st;
}

Status gltf(const uint8_t* data, size_t size, const std::string& baseDir) {
    InputMesh mesh;
    Status st = parseGltf(data, size, "fuzz.gltf", baseDir, mesh);
    if (st) st = checkInput(mesh, "fuzz.gltf");
    // The scene reader (loopbake's path for glTF): every mesh, the document kept.
    GltfScene scene;
    Status sceneSt = parseGltfScene(data, size, "fuzz.gltf", baseDir, Limits{}, scene);
    for (size_t m = 0; sceneSt && m < scene.meshes.size(); ++m) {
        const GltfScene::Mesh& sm = scene.meshes[m];
        if (sm.controlVertex.size() != sm.primitives.size())
            broken("parseGltfScene", "a controlVertex map per cage primitive");
        for (const std::vector<uint32_t>& cv : sm.controlVertex)
            for (uint32_t v : cv)
                if (v >= sm.mesh.vertexCount()) broken("parseGltfScene", "controlVertex out of range");
        checkInput(sm.mesh, "fuzz.gltf");
    }
    return st ? sceneSt : st;
}

Status evaluate(const uint8_t* data, size_t size) {
    Asset a;
    Status st = readAssetGlb(data, size, "fuzz.glb", a);
    if (!st) return st;
    size_t patches = 0;
    for (const Level& l : a.levels) patches += l.regular.size() + l.irregular.size();
    if (a.totalVertexCount() > kMaxEvalVertices || patches > kMaxEvalPatches)
        return Status::error(Status::Unsupported, "fuzz: asset above the evaluation caps");
    EvalSettings settings;
    settings.tessFactor = 3.0f;
    settings.spacing = (size & 4) ? Spacing::FractionalOdd : Spacing::Equal;
    Tessellation out;
    evaluateCpu(a, a.positions.data(), settings, out);
    if (out.positions.size() != 3 * out.vertexCount() || out.normals.size() != 3 * out.vertexCount() ||
        out.uv.size() != 2 * out.vertexCount() || out.vertexCount() % 3 != 0)
        broken("evaluateCpu", "inconsistent output array sizes");
    for (uint32_t f : out.face)
        if (f >= a.faceCount()) broken("evaluateCpu", "base face " + std::to_string(f) + " does not exist");
    return st;
}

}  // namespace lt::fuzz
