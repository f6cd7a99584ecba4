// What a tessellation's checks take in memory (check.h, checkBytes), and what the
// machine has.
#include "check_internal.h"

#include <algorithm>
#include <cstdio>
#include <string>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace lt {

namespace {

// Embree's compact scene of a welded mesh while it is built, bytes a triangle (its
// BVH and build buffers; bench/README.md "loopcheck in pieces"). 92 before the
// compact scene.
constexpr uint64_t kRaySceneBytes = 40;

uint64_t powerOfTwoAtLeast(uint64_t n) {
    uint64_t c = 64;
    while (c < n) c *= 2;
    return c;
}

}  // namespace

uint64_t checkBytes(uint64_t vertices, uint64_t indices, bool gpu) {
    const uint64_t triangles = indices ? indices / 3 : vertices / 3;
    // The soup without attributes (EvalSettings::attributes): position, normal, base
    // face and (u, v) a vertex.
    const uint64_t soup = vertices * 36 + indices * 4;
    // Welded vertices: a soup has each about once per triangle at it (six), an
    // indexed evaluation about once.
    const uint64_t welded = indices ? vertices : vertices / 6 + 1;
    // Its triangles, chord bounds and soup triangles, and its positions.
    const uint64_t mesh = triangles * 20 + welded * 12;
    // The weld: each soup vertex's welded id, the position keys and their slots (at
    // most half full), each welded vertex's first normal and a flag, the edge table
    // (weld.cpp: 16 bytes a slot, from twice the triangles).
    const uint64_t weld =
        vertices * 4 + welded * 25 + powerOfTwoAtLeast(2 * welded) * 4 + powerOfTwoAtLeast(2 * triangles) * 16;
    const uint64_t checks = mesh + std::max(weld, triangles * kRaySceneBytes);
    if (!gpu) return soup + checks;
    // With a GPU capture, the CPU's soup is checked, then kept while the capture is
    // taken and compared: beside it the captured soup (as large: the capture honours
    // EvalSettings::attributes) and the transform feedback buffer and its read-back,
    // each a session's records at most (84 bytes a vertex, sessions of 2 GiB:
    // vulkan_tools.h), host memory on lavapipe. Then the captured soup is checked alone.
    const uint64_t session = std::min<uint64_t>(vertices * 84, uint64_t(1) << 31);
    return soup + std::max(checks, soup + 2 * session);
}

uint64_t piecesKeptBytes(uint64_t vertices, uint64_t indices, bool rays) {
    const uint64_t triangles = indices ? indices / 3 : vertices / 3;
    const uint64_t welded = indices ? vertices : vertices / 6 + 1;
    const uint64_t mesh = triangles * 20 + welded * 12;
    // The weld's table while pieces are added (weld.cpp: position keys, slots at most
    // half full, each welded vertex's first normal and a flag, the settled edges'
    // keys), then the ray scene.
    const uint64_t weld = welded * 25 + powerOfTwoAtLeast(2 * welded) * 4 + triangles * 12;
    return mesh + std::max(weld, rays ? triangles * kRaySceneBytes : 0);
}

uint64_t pieceBytes(uint64_t vertices, uint64_t indices) {
    const uint64_t triangles = indices ? indices / 3 : vertices / 3;
    // The soup without attributes, each vertex's welded id, the piece's edge table.
    return vertices * 40 + indices * 4 + powerOfTwoAtLeast(2 * triangles) * 16;
}

namespace {

std::string gib(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1ull << 30));
    return text;
}

}  // namespace

// How case `cpu` fits settings.maxMemoryBytes (CheckSettings): whole, in `pieces` of
// base faces (EvalSettings::firstFace; each within what the welded whole leaves), or
// not at all, then L1 goes into the report unevaluated. `gpu`: why the GPU capture is
// not taken ("" when it is): the capture is whole, beside the CPU's whole soup.
bool refusedForMemory(CheckContext& ctx, const CheckInputs& in, const EvalSettings& eval, TessellationChecks& cpu,
                      CheckReport& report, std::vector<FacePiece>& pieces, GpuPlan& gpu) {
    const CheckSettings& settings = *ctx.settings;
    const float* positions = ctx.asset->positions.data();
    size_t vertices = 0, indices = 0;
    ctx.evaluator->count(positions, eval, vertices, indices);
    cpu.path = "cpu";
    cpu.eval = eval;
    cpu.factor = lodTessFactor(*ctx.asset, positions, eval);
    cpu.depth = runtimeDepth(*ctx.asset, cpu.factor);
    cpu.triangles = indices ? indices / 3 : vertices / 3;
    pieces.clear();
    gpu = GpuPlan{};
    const uint64_t resident = residentBytes();
    const uint64_t available = availableMemoryBytes();
    // Without --max-memory-mb, a tenth of what is available is left: the estimates are
    // within a few percent (bench/README.md "loopcheck in pieces"), and past the
    // machine's memory the system kills the process with no report.
    const uint64_t limit = settings.maxMemoryBytes ? settings.maxMemoryBytes
                           : available             ? resident + available - available / 10
                                                   : 0;
    auto fits = [&](uint64_t bytes) { return limit == 0 || resident + bytes <= limit; };
    const std::string over =
        " beside the " + gib(resident) + " in use, more than the limit of " + gib(limit) +
        (settings.maxMemoryBytes ? " (--max-memory-mb)" : " (what the machine has available; --max-memory-mb)");
    const bool forced = settings.pieceTriangles > 0 && cpu.triangles > settings.pieceTriangles;
    cpu.estimatedBytes = checkBytes(vertices, indices, bool(in.gpuCapture));
    if (!forced && fits(cpu.estimatedBytes)) return false;
    // The GPU's capture session by session beside its welded whole: a session's soup,
    // and its transform feedback buffer and read-back (host memory on lavapipe).
    const uint64_t kept = piecesKeptBytes(vertices, indices, ctx.topology.closed() && settings.rays > 0);
    const uint64_t session = std::min<uint64_t>(vertices * 84, uint64_t(1) << 31);
    if (in.gpuCapture && (!in.gpuCaptureSessions || !fits(kept + 2 * session + session / 84 * 40)))
        gpu.notRun = "the GPU capture needs an estimated " + gib(cpu.estimatedBytes) + over +
                     (in.gpuCaptureSessions ? ", and session by session " + gib(kept + 2 * session + session / 84 * 40)
                                            : std::string());
    gpu.sessions = in.gpuCapture && gpu.notRun.empty();
    cpu.estimatedBytes = checkBytes(vertices, indices, false);
    const bool wholeFits = fits(cpu.estimatedBytes);
    if (!forced && wholeFits) return false;
    // In pieces: halves of a range until each fits beside the welded whole.
    const uint64_t budget = limit == 0 ? UINT64_MAX : limit > resident + kept ? limit - resident - kept : 0;
    uint64_t largest = 0;
    auto split = [&](auto&& self, uint32_t first, uint32_t count) -> bool {
        EvalSettings e = eval;
        e.firstFace = first, e.faceCount = count;
        size_t v = 0, i = 0;
        ctx.evaluator->count(positions, e, v, i);
        const uint64_t bytes = pieceBytes(v, i), triangles = i ? i / 3 : v / 3;
        if (bytes <= budget && (count == 1 || settings.pieceTriangles == 0 || triangles <= settings.pieceTriangles)) {
            if (triangles > 0) pieces.push_back({first, count, v, triangles});
            largest = std::max(largest, bytes);
            return true;
        }
        return count > 1 && self(self, first, count / 2) && self(self, first + count / 2, count - count / 2);
    };
    const uint32_t faces = ctx.asset->faceCount();  // two pieces at least: one would be the whole
    if (budget > 0 && faces > 1 && split(split, 0, faces / 2) && split(split, faces / 2, faces - faces / 2)) {
        cpu.estimatedBytes = kept + largest;
        ctx.say("  in " + std::to_string(pieces.size()) + " pieces of base faces: an estimated " +
                gib(cpu.estimatedBytes) + " (the whole needs " + gib(checkBytes(vertices, indices, false)) + ")");
        return false;
    }
    pieces.clear();
    if (wholeFits) return false;  // pieces asked for (pieceTriangles), but one face is the whole
    cpu.estimatedBytes = checkBytes(vertices, indices, bool(in.gpuCapture));
    cpu.notRun = std::to_string(cpu.triangles) + " triangles need an estimated " + gib(cpu.estimatedBytes) + over +
                 (budget == 0 ? ", and in pieces of base faces their welded whole alone " + gib(kept)
                              : ", and in pieces of base faces one face is more than the " + gib(budget) +
                                    " left beside their welded whole") +
                 "; a lower factor checks the same tables";
    ctx.say("  not run: " + cpu.notRun);
    report.tessellations.push_back(cpu);
    if (in.gpuCapture) {
        TessellationChecks g = cpu;
        g.path = "gpu";
        report.tessellations.push_back(g);
    }
    return true;
}

uint64_t physicalMemoryBytes() {
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
    const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    if (pages > 0 && size > 0) return uint64_t(pages) * uint64_t(size);
#endif
    return 0;
}

uint64_t availableMemoryBytes() {
#if defined(__linux__)
    // /proc/meminfo's MemAvailable, in kB: free memory and what the kernel can
    // reclaim without swapping (page cache, reclaimable slabs).
    if (FILE* f = std::fopen("/proc/meminfo", "r")) {
        char line[256];
        unsigned long long kb = 0;
        bool found = false;
        while (!found && std::fgets(line, sizeof line, f)) found = std::sscanf(line, "MemAvailable: %llu kB", &kb) == 1;
        std::fclose(f);
        if (found) return uint64_t(kb) * 1024;
    }
#endif
    return physicalMemoryBytes();
}

uint64_t residentBytes() {
#if defined(__linux__)
    // /proc/self/statm: total and resident pages.
    unsigned long long total = 0, resident = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        const int read = std::fscanf(f, "%llu %llu", &total, &resident);
        std::fclose(f);
        const long size = sysconf(_SC_PAGESIZE);
        if (read == 2 && size > 0) return uint64_t(resident) * uint64_t(size);
    }
#endif
    return 0;
}

}  // namespace lt
