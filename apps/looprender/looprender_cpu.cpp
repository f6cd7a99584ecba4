// looprender --cpu: lt::CpuEvaluator (see looprender.cpp).
#include "looprender_common.h"

#include "looptess/tools/file_io.h"

#include <chrono>
#include <cstdio>
#include <cstring>

namespace looprender {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// --mesh's file from the evaluator's arrays, each vertex written once, in place, in
// recordEvaluate's order (Mesh): no interleaved copy first.
lt::Status writeMeshFile(const std::string& path, const lt::Tessellation& t, bool texcoords) {
    const size_t floats = meshPlyFloats(texcoords);
    std::vector<uint8_t> bytes;
    const size_t first = meshPlyLayout(t.vertexCount(), t.triangleCount(), texcoords, bytes);
    uint8_t* at = bytes.data() + first;
    for (size_t k = 0; k < t.vertexCount(); ++k, at += 4 * floats) {  // little-endian hosts only, as writePly
        std::memcpy(at, &t.positions[3 * k], 12);
        std::memcpy(at + 12, &t.normals[3 * k], 12);
        if (!texcoords) continue;
        std::memcpy(at + 24, &t.tangents[4 * k], 16);
        std::memcpy(at + 40, &t.texcoords[2 * k], 8);
    }
    putMeshFaces(t.indices, bytes);
    return lt::writeFileAtomic(path, bytes.data(), bytes.size());
}

}  // namespace

// One evaluator for the soup and the mesh, so the asset's set-up (the watertight
// plan) is built once. Not prepare(): that builds the plan for every factor, as a
// loading thread would; a one-shot tool's first evaluation builds only the levels
// its frame reads, beside its counting pass (bench/README.md, "A quiet machine").
int runCpu(const Options& o, const lt::Asset& asset) {
    auto start = std::chrono::steady_clock::now();
    lt::EvalSettings es = evalSettings(o, choosePath(o, true, true));  // the CPU evaluator has both paths
    es.lod = lodSettings(o, asset);
    std::vector<float> edits = scaledEditValues(o, asset);
    es.editValues = edits.data();
    lt::EvalSettings indexed = es;
    indexed.path = lt::DrawPath::Patterns;
    indexed.indexed = true;
    lt::CpuEvaluator evaluator(asset);
    // The drawn soup, unless the mesh is all that was asked for.
    const bool drawn = !o.capture.empty() || !o.json.empty() || o.mesh.empty();
    lt::Tessellation soup, mesh;
    if (drawn) evaluator.evaluate(asset.positions.data(), es, soup);
    if (!o.mesh.empty()) evaluator.evaluate(asset.positions.data(), indexed, mesh);
    const double ms = msSince(start);
    float factor = lt::lodTessFactor(asset, asset.positions.data(), es);
    uint32_t depth = lt::runtimeDepth(asset, factor);
    const bool texcoords = !asset.faceUVs.empty();

    if (!o.capture.empty()) {
        lt::Status st = writePlyFile(o.capture, soup);
        if (!st) return fail(st);
    }
    if (!o.mesh.empty()) {
        lt::Status st = writeMeshFile(o.mesh, mesh, texcoords);
        if (!st) return fail(st);
    }
    if (drawn)
        std::printf("%s: %u base faces, depth %u of %u, factor %g: %zu triangles\n", o.input.c_str(), asset.faceCount(),
                    depth, asset.maxDepth(), double(factor), soup.triangleCount());
    if (!o.mesh.empty()) printMesh(o, mesh.vertexCount(), mesh.triangleCount(), "CPU");
    if (o.verbose)
        std::fprintf(stderr, "looprender: evaluate %.2f ms (%s path; the evaluator's set-up included)\n", ms,
                     pathName(es.path));
    if (!o.json.empty()) {
        nlohmann::json report = baseReport(o, asset, factor, depth, soup.triangleCount(), es.path);
        report["evaluateMs"] = ms;
        if (!o.mesh.empty()) report["mesh"] = meshReport(mesh.vertexCount(), mesh.triangleCount());
        lt::Status st = writeJsonFile(o.json, report);
        if (!st) return fail(st);
    }
    return 0;
}

}  // namespace looprender
