// looprender --cpu: lt::evaluateCpu (see looprender.cpp).
#include "looprender_common.h"

#include <chrono>
#include <cstdio>

namespace looprender {

int runCpu(const Options& o, const lt::Asset& asset) {
    auto start = std::chrono::steady_clock::now();
    lt::EvalSettings es;
    es.tessFactor = o.tess;
    es.spacing = o.spacing;
    es.path = choosePath(o, true, true, true);   // the CPU evaluator has both paths, as lavapipe
    es.watertight = o.watertight;
    es.displace = o.displace;
    es.lod = lodSettings(o, asset);
    std::vector<float> edits = scaledEditValues(o, asset);
    es.editValues = edits.data();
    lt::Tessellation soup;
    lt::evaluateCpu(asset, asset.positions.data(), es, soup);
    auto evaluated = std::chrono::steady_clock::now();
    float factor = lt::lodTessFactor(asset, asset.positions.data(), es);
    uint32_t depth = lt::runtimeDepth(asset, factor);

    if (!o.capture.empty()) {
        lt::Status st = writePlyFile(o.capture, soup);
        if (!st) return fail(st);
    }
    std::printf("%s: %u base faces, depth %u of %u, factor %g: %zu triangles\n", o.input.c_str(), asset.faceCount(), depth,
                asset.maxDepth(), double(factor), soup.triangleCount());
    double ms = std::chrono::duration<double, std::milli>(evaluated - start).count();
    if (o.verbose)
        std::fprintf(stderr, "looprender: evaluate %.2f ms (%s path)\n", ms,
                     pathName(es.path));
    if (!o.json.empty()) {
        nlohmann::json report = baseReport(o, asset, factor, depth, soup.triangleCount(), es.path);
        report["evaluateMs"] = ms;
        lt::Status st = writeJsonFile(o.json, report);
        if (!st) return fail(st);
    }
    return 0;
}

} // namespace looprender
