// looprender --cpu: lt::evaluateCpu (see looprender.cpp).
#include "looprender_common.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace looprender {
namespace {

// An indexed tessellation in recordEvaluate's layout (Mesh); `texcoords`: the asset
// has TEXCOORD_0 (as on the device, also for an empty frame).
Mesh meshOf(const lt::Tessellation& t, bool texcoords) {
    Mesh m;
    m.indices = t.indices;
    m.texcoords = texcoords;
    m.vertices.resize(t.vertexCount() * kMeshFloats);
    for (size_t k = 0; k < t.vertexCount(); ++k) {
        float* v = &m.vertices[k * kMeshFloats];
        std::copy_n(&t.positions[3 * k], 3, v);
        std::copy_n(&t.normals[3 * k], 3, v + 3);
        const float noTangent[4] = {0, 0, 0, 1}, noTexcoord[2] = {0, 0};
        std::copy_n(m.texcoords ? &t.tangents[4 * k] : noTangent, 4, v + 6);
        std::copy_n(m.texcoords ? &t.texcoords[2 * k] : noTexcoord, 2, v + 10);
    }
    return m;
}

}  // namespace

int runCpu(const Options& o, const lt::Asset& asset) {
    auto start = std::chrono::steady_clock::now();
    lt::EvalSettings es = evalSettings(o, choosePath(o, true, true));  // the CPU evaluator has both paths
    es.lod = lodSettings(o, asset);
    std::vector<float> edits = scaledEditValues(o, asset);
    es.editValues = edits.data();
    // The drawn soup, unless the mesh is all that was asked for.
    const bool drawn = !o.capture.empty() || !o.json.empty() || o.mesh.empty();
    lt::Tessellation soup;
    if (drawn) lt::evaluateCpu(asset, asset.positions.data(), es, soup);
    Mesh mesh;
    if (!o.mesh.empty()) {
        lt::EvalSettings indexed = es;
        indexed.path = lt::DrawPath::Patterns;
        indexed.indexed = true;
        lt::Tessellation t;
        lt::evaluateCpu(asset, asset.positions.data(), indexed, t);
        mesh = meshOf(t, !asset.faceUVs.empty());
    }
    auto evaluated = std::chrono::steady_clock::now();
    float factor = lt::lodTessFactor(asset, asset.positions.data(), es);
    uint32_t depth = lt::runtimeDepth(asset, factor);

    if (!o.capture.empty()) {
        lt::Status st = writePlyFile(o.capture, soup);
        if (!st) return fail(st);
    }
    if (!o.mesh.empty()) {
        lt::Status st = writeMeshFile(o.mesh, mesh);
        if (!st) return fail(st);
    }
    if (drawn)
        std::printf("%s: %u base faces, depth %u of %u, factor %g: %zu triangles\n", o.input.c_str(), asset.faceCount(),
                    depth, asset.maxDepth(), double(factor), soup.triangleCount());
    if (!o.mesh.empty()) printMesh(o, mesh, "CPU");
    double ms = std::chrono::duration<double, std::milli>(evaluated - start).count();
    if (o.verbose) std::fprintf(stderr, "looprender: evaluate %.2f ms (%s path)\n", ms, pathName(es.path));
    if (!o.json.empty()) {
        nlohmann::json report = baseReport(o, asset, factor, depth, soup.triangleCount(), es.path);
        report["evaluateMs"] = ms;
        if (!o.mesh.empty()) report["mesh"] = meshReport(mesh);
        lt::Status st = writeJsonFile(o.json, report);
        if (!st) return fail(st);
    }
    return 0;
}

}  // namespace looprender
