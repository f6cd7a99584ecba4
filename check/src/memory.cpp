// What a tessellation's checks take in memory (check.h, checkBytes), and what the
// machine has.
#include "looptess/tools/check.h"

#include <algorithm>
#include <cstdio>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace lt {

namespace {

// Embree's scene of a welded mesh while it is built, bytes a triangle (its BVH and
// build buffers): spot at F = 64 peaked at 11.9 GB (bench/README.md "loopcheck").
constexpr uint64_t kRaySceneBytes = 92;

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
    // most half full), the edge table (weld.cpp: 16 bytes a slot, from twice the
    // triangles).
    const uint64_t weld =
        vertices * 4 + welded * 12 + powerOfTwoAtLeast(2 * welded) * 4 + powerOfTwoAtLeast(2 * triangles) * 16;
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

uint64_t physicalMemoryBytes() {
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
    const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    if (pages > 0 && size > 0) return uint64_t(pages) * uint64_t(size);
#endif
    return 0;
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
