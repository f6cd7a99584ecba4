// Resource limits: lt::checkLimits, checkInputBytes, checkOutputBytes, and the
// baker's memory estimate (see resource_limits.h and looptess/tools/baker.h).
#include "resource_limits.h"

#include "refine.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <vector>

namespace lt {
namespace {

// The memory model, from getrusage's ru_maxrss around refine + bake +
// writeAssetGlb on spot, bob, fandisk, the Duck and the 30
// OpenSubdiv Loop shapes at depths 2..8:
//
// Faces per level. Adaptive refinement refines around features only. Around an
// irregular vertex (valence other than 6, or 4 on a boundary; any sharpness; a crease
// that does not split its faces 3 + 3; non-manifold) each level holds 9 faces per
// edge of the vertex once the first levels have passed (exactly 9.0 on spot, bob,
// fandisk, the Duck and the poles). Along a semi-sharp or non-manifold edge, a level
// l holds at most 6 faces per face of the edge per 2^l sub-edges, for as long as the
// edge stays sharp (level <= ceil(sharpness) + 1; always for non-manifold edges).
// No level holds more than 4 times the faces of the one above. Summed over the levels
// this is an upper estimate on every shape above (0.99-1.06 of the actual count on
// the large meshes; tests/baker/test_limits.cpp checks it stays >= the actual count).
constexpr double kFacesPerIrregularEdge = 9;
constexpr double kFacesPerLineFace = 6;
// Bytes: loopbake's peak resident (getrusage, two threads) against the refined
// faces estimated (below) and the base faces. Deep bakes peak at 355-390 bytes per
// refined face (spot, fandisk, ycb_mustard, leeperrysmith at depth 6), the
// 1M-triangle scan (bench_bake's scan1m, depth 1: one refined level four times its
// base) at about 330 once its base faces take 64 each; the process itself (the
// libraries, the input) is about 24 MiB. This model is 0.96-1.07 of the peak on
// the corpus and real meshes of tests/data and 1.13-1.15 (1.19 on one thread) on
// the scan, 2026-12-07 (bench/README.md "Memory at scale"); a glTF scene with its
// images in memory peaks above it.
constexpr uint64_t kBytesPerRefinedFace = 400;
constexpr uint64_t kBytesPerBaseFace = 64;
constexpr uint64_t kFixedBytes = uint64_t(24) << 20;
// The written GLB (writeAssetGlb's tables plus the cage), an upper estimate: measured
// 19.4 bytes per refined face (spot, bob, fandisk at depths 2..6, indices in u16) and
// up to 26 per base face; u32 indices (a level past 65,536 vertices) and edits add
// to that, so the constants are about twice the measure. The written size is still
// checked against maxOutputBytes (checkOutputBytes); this only picks the depth.
constexpr uint64_t kOutputBytesPerRefinedFace = 48;
constexpr uint64_t kOutputBytesPerBaseFace = 128;
// The JSON and the GLB's headers: a tetrahedron's is 2.3 KB at depth 1 and grows by
// about 1.1 KB a level (each level's accessors and views), so twice that.
constexpr uint64_t kOutputFixedBytes = uint64_t(16) << 10;
constexpr uint64_t kOutputBytesPerLevel = uint64_t(2) << 10;
// Where the surface has no tangent plane each face around the vertex has a limit
// stencil of its own (face_corner.h), at every level: along a non-manifold edge
// that is every refined face beside it, twice (two ends), about 70 bytes each
// (loop_nonman_edge100: 61 bytes per refined face in all at depth 8).
constexpr uint64_t kOutputBytesPerFaceCorner = 160;

namespace Far = OpenSubdiv::Far;

bool isRegular(const Far::TopologyLevel& level, OsdIndex v) {
    if (level.IsVertexNonManifold(v) || level.GetVertexSharpness(v) > 0) return false;
    auto edges = level.GetVertexEdges(v);
    const int n = edges.size(), faces = level.GetVertexFaces(v).size();
    int sharp = 0, first = -1, second = -1;
    for (int k = 0; k < n; ++k) {
        if (isInfSharp(level, edges[k])) {
            (first < 0 ? first : second) = k;
            ++sharp;
        } else if (level.GetEdgeSharpness(edges[k]) > 0) {
            return false;  // semi-sharp: refined until it decays
        }
    }
    if (sharp == 0) return n == 6 && faces == 6;
    if (sharp != 2) return false;
    if (level.IsVertexBoundary(v)) return n == 4 && faces == 3;
    return n == 6 && faces == 6 && second - first == 3;  // a crease splitting 3 + 3
}

}  // namespace

std::string limitMessage(const std::string& value, const std::string& what, uint64_t limit, const char* option) {
    return value + " " + what + ", more than the limit of " + std::to_string(limit) + " (raise it with " + option + ")";
}

void estimateMemory(const Far::TopologyLevel& base, int maxDepth, int uniformDepth, MemoryStats& out) {
    double irregularEdges = 0;
    for (OsdIndex v = 0; v < base.GetNumVertices(); ++v)
        if (!isRegular(base, v)) irregularEdges += base.GetVertexEdges(v).size();
    // Faces along each sharp line, by the last level it is still refined at.
    std::vector<double> lineFacesUntil(size_t(maxDepth) + 2, 0.0);
    double faceCorners = 0;  // per-face stencils (no tangent plane), all levels
    for (OsdIndex v = 0; v < base.GetNumVertices(); ++v)
        if (base.IsVertexNonManifold(v) || base.IsVertexInfSharp(v))
            faceCorners += double(maxDepth + 1) * base.GetVertexFaces(v).size();
    for (OsdIndex e = 0; e < base.GetNumEdges(); ++e) {
        const float s = base.GetEdgeSharpness(e);
        const bool nonManifold = base.IsEdgeNonManifold(e);
        if (nonManifold)
            for (int l = 0; l <= maxDepth; ++l) faceCorners += 2 * std::ldexp(double(base.GetEdgeFaces(e).size()), l);
        if (!nonManifold && (base.IsEdgeBoundary(e) || !(s > 0))) continue;
        // Non-manifold and infinitely sharp lines are isolated down to maxDepth
        // (refine.cpp: no infinitely sharp patches), semi-sharp ones while sharp.
        const bool toTheEnd = nonManifold || base.IsEdgeInfSharp(e);
        const double last = toTheEnd ? maxDepth : std::min<double>(maxDepth, std::ceil(s) + 1);
        lineFacesUntil[size_t(last)] += base.GetEdgeFaces(e).size();
    }
    double previous = base.GetNumFaces(), total = 0, lineFaces = 0;
    for (int l = maxDepth; l >= 1; --l) lineFaces += lineFacesUntil[size_t(l)];
    for (int l = 1; l <= maxDepth; ++l) {  // lineFaces: lines still sharp at level l
        const double features = kFacesPerIrregularEdge * irregularEdges + kFacesPerLineFace * std::ldexp(lineFaces, l);
        previous = l <= uniformDepth ? 4 * previous : std::min(4 * previous, features);
        total += previous;
        lineFaces -= lineFacesUntil[size_t(l)];
    }
    out.estimatedRefinedFaces = uint64_t(std::ceil(total));
    out.estimatedBytes = kBytesPerRefinedFace * out.estimatedRefinedFaces +
                         kBytesPerBaseFace * uint64_t(base.GetNumFaces()) + kFixedBytes;
    out.estimatedOutputBytes = kOutputBytesPerRefinedFace * out.estimatedRefinedFaces +
                               kOutputBytesPerBaseFace * uint64_t(base.GetNumFaces()) +
                               kOutputBytesPerFaceCorner * uint64_t(std::ceil(faceCorners)) + kOutputFixedBytes +
                               kOutputBytesPerLevel * uint64_t(maxDepth);
}

Status checkLimits(const InputMesh& mesh, const Limits& limits, const std::string& name) {
    auto fail = [&](const std::string& what) { return Status::error(Status::BadInput, name + ": " + what); };
    if (mesh.faceCount() > limits.maxFaces)
        return fail(limitMessage(mesh.faceCount(), "faces", limits.maxFaces, "--max-faces"));
    if (mesh.vertexCount() > limits.maxVertices)
        return fail(limitMessage(mesh.vertexCount(), "vertices", limits.maxVertices, "--max-vertices"));
    try {
        // Valence: distinct undirected edges at each vertex. A vertex has at most two
        // for each face corner at it; only where that bound passes the limit are the
        // edges counted exactly (a sort of every edge: 10 ms on 100,000 triangles).
        const uint32_t n = mesh.vertexCount();
        {
            std::vector<uint32_t> corners(n, 0);
            for (uint32_t v : mesh.faces)
                if (v < n) ++corners[v];
            if (std::all_of(corners.begin(), corners.end(),
                            [&](uint32_t c) { return uint64_t(2) * c <= limits.maxValence; }))
                return Status::ok();
        }
        std::vector<uint64_t> edges;
        edges.reserve(mesh.faces.size());
        for (size_t f = 0; f < mesh.faceCount(); ++f)
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = mesh.faces[3 * f + k], b = mesh.faces[3 * f + (k + 1) % 3];
                if (a >= n || b >= n || a == b) continue;  // checkInput's to report
                edges.push_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
            }
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        std::vector<uint32_t> valence(n, 0);
        for (uint64_t e : edges) {
            ++valence[uint32_t(e >> 32)];
            ++valence[uint32_t(e)];
        }
        for (uint32_t v = 0; v < n; ++v)
            if (valence[v] > limits.maxValence)
                return fail("vertex " + std::to_string(v) + " has " +
                            limitMessage(valence[v], "edges", limits.maxValence, "--max-valence"));
    } catch (const std::exception& e) {  // bad_alloc, in practice
        return Status::error(Status::Internal, name + ": " + e.what());
    }
    return Status::ok();
}

Status checkInputBytes(uint64_t bytes, const Limits& limits, const std::string& name) {
    if (bytes <= limits.maxInputBytes) return Status::ok();
    return Status::error(Status::BadInput,
                         name + ": " + limitMessage(bytes, "bytes", limits.maxInputBytes, "--max-input-bytes"));
}

Status checkOutputBytes(uint64_t bytes, const Limits& limits, const std::string& name) {
    if (bytes <= limits.maxOutputBytes) return Status::ok();
    return Status::error(
        Status::BadInput,
        name + ": the baked asset has " + limitMessage(bytes, "bytes", limits.maxOutputBytes, "--max-output-bytes"));
}

Status chooseDepth(const Far::TopologyLevel& base, const BakeSettings& settings, int editDepth, int& depth,
                   MemoryStats& memory, std::string& reason) {
    const Limits& limits = settings.limits;
    const uint64_t mib = uint64_t(1) << 20;
    // Rounded up, in KiB below 1 MiB (a small mesh's output estimate is tens of KiB).
    auto sizeText = [&](uint64_t bytes) {
        return bytes < mib ? std::to_string((bytes + 1023) / 1024) + " KiB"
                           : std::to_string((bytes + mib - 1) / mib) + " MiB";
    };
    // Why `d` does not fit ("" when it does), and the option that raises the limit.
    const char* option = "";
    auto overLimit = [&](int d, MemoryStats& m) -> std::string {
        estimateMemory(base, d, editDepth, m);
        if (m.estimatedBytes > limits.maxMemoryBytes) {
            option = "--max-memory-mb";
            return "depth " + std::to_string(d) + " needs an estimated " + sizeText(m.estimatedBytes) + " (" +
                   std::to_string(m.estimatedRefinedFaces) + " refined faces), more than the memory limit of " +
                   std::to_string(limits.maxMemoryBytes / mib) + " MiB";
        }
        if (settings.maxDepth == 0 && m.estimatedOutputBytes > limits.maxOutputBytes) {
            option = "--max-output-bytes";
            return "depth " + std::to_string(d) + " would write an estimated " + sizeText(m.estimatedOutputBytes) +
                   ", more than the output limit of " + std::to_string(limits.maxOutputBytes) + " bytes";
        }
        return "";
    };
    if (settings.maxDepth > 0) {
        depth = settings.maxDepth;
        const std::string over = overLimit(depth, memory);
        if (over.empty()) return Status::ok();
        return Status::error(Status::BadInput, settings.name + ": baking to " + over + " (raise it with " + option +
                                                   ", or lower --max-depth)");
    }
    const int deepest = std::max(kDefaultMaxDepth, editDepth), shallowest = std::max(1, editDepth);
    std::string first;
    for (depth = deepest; depth >= shallowest; --depth) {
        const std::string over = overLimit(depth, memory);
        if (over.empty()) break;
        if (first.empty()) first = over + " (" + option + ")";
        if (depth == shallowest)
            return Status::error(Status::BadInput,
                                 settings.name + ": even " + over + " (raise it with " + option + ")");
    }
    reason =
        "depth " + std::to_string(depth) + " (automatic): " +
        (first.empty() ? "the default, within the memory and output limits" : first + "; --max-depth sets a depth");
    return Status::ok();
}

}  // namespace lt
