// fuzz/entry_points.cpp -- see entry_points.h.
#include "entry_points.h"

#include "looptess/baker.h"
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

} // namespace

Status asset(const uint8_t* data, size_t size) {
    Asset a;
    Status st = readAssetGlb(data, size, "fuzz.glb", a);
    if (!st) return st;
    Status again = validateAsset(a, "fuzz.glb");
    if (!again) broken("readAssetGlb accepted an asset validateAsset rejects", again.message);
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

Status gltf(const uint8_t* data, size_t size, const std::string& baseDir) {
    InputMesh mesh;
    Status st = parseGltf(data, size, "fuzz.gltf", baseDir, mesh);
    if (st) st = checkInput(mesh, "fuzz.gltf");
    return st;
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

} // namespace lt::fuzz
