// bench/report.h -- bench_bake's figures, their targets, and the two outputs (a
// text table for stdout, JSON for --json). Pure formatting: no timing here.
#pragma once

#include "bench_common.h"
#include "detail.h"
#include "osd_tables.h"

#include "looptess/asset.h"

#include <cstdint>
#include <string>
#include <vector>

namespace ltbench {

// Targets (bench/README.md): table bytes ours/OpenSubdiv at most kMaxBytesRatio;
// the default (--compress fast) GLB at most kMaxCompressedRatio of the
// uncompressed one; load speed-up (OpenSubdiv build / our load of the default
// GLB) at least kMinLoadSpeedup; bake + write (default GLB) at most kMaxBakeRatio
// of OpenSubdiv's table build, single-threaded. Reported, never
// asserted: a missed target leaves the exit status alone.
constexpr double kMaxBytesRatio = 0.35;
constexpr double kMaxCompressedRatio = 0.30;
constexpr double kMinLoadSpeedup = 25.0;
constexpr double kMaxBakeRatio = 1.0;

// Every figure of one mesh. Times are medians over `runs`, in seconds.
struct MeshResult {
    std::string name, source;  // source: file path or how it was generated
    uint32_t vertices = 0, triangles = 0, extraordinary = 0;
    // Ours.
    double bake = 0, write = 0, load = 0;  // write, load: --compress fast (the default)
    // lt::bake's stages (BakeStats::stages), each the median over the runs.
    std::vector<std::pair<std::string, double>> bakeStages;
    double writeNone = 0, loadNone = 0;  // --compress none
    double writeMax = 0;                 // --compress max (first run only)
    double copy = 0;                     // copying the GLB once (the floor of any loader)
    double scan = 0;                     // scanGlbInPlace: a zero-copy validating loader's floor
    lt::TableBytes tables;               // raw, and `encoded` as --compress fast stores them
    size_t glbBytes = 0;                 // --compress none (the format before compression)
    size_t glbFast = 0, glbMax = 0;
    std::vector<PropertyBytes> properties;
    Savings estimates;
    uint32_t refinedVertices = 0, regularPatches = 0, irregularFaces = 0, limitStencils = 0;
    // OpenSubdiv.
    OsdTimes osd;         // per-phase medians
    double osdTotal = 0;  // median of the per-run totals
    // The median over the runs of each run's (bake + write) / OpenSubdiv total: the
    // two sides of a run are taken back to back, so a change in the machine's speed
    // from run to run cancels out.
    double pairedBakeRatio = 0;
    OsdBytes osdBytes;
    OsdCounts osdCounts;

    // Our subdivision tables: everything in the extension but the control mesh
    // (OpenSubdiv's tables do not hold the control mesh either).
    size_t oursTableBytes() const { return tables.total() - tables.controlMesh; }
    double bytesRatio() const { return double(oursTableBytes()) / double(osdBytes.total()); }
    double glbRatio() const { return double(glbBytes) / double(osdBytes.total()); }
    double loadSpeedup() const { return load > 0 ? osdTotal / load : 0.0; }
    // Our bake + write of the default GLB over OpenSubdiv's table build, run by run
    // (the verdict), and the ratio of the medians.
    double bakeRatio() const { return pairedBakeRatio; }
    double medianBakeRatio() const { return osdTotal > 0 ? (bake + write) / osdTotal : 0.0; }
    double compressedRatio() const { return double(glbFast) / double(glbBytes); }
    // Decoded table MB per second of the whole load of the default GLB.
    double loadThroughput() const { return load > 0 ? double(tables.total()) / load / 1e6 : 0.0; }
    bool bytesPass() const { return bytesRatio() <= kMaxBytesRatio; }
    bool compressedPass() const { return compressedRatio() <= kMaxCompressedRatio; }
    bool loadPass() const { return loadSpeedup() >= kMinLoadSpeedup; }
    bool bakePass() const { return bakeRatio() <= kMaxBakeRatio; }
};

struct Report {
    Machine machine;
    int depth = 6, runs = 5;
    unsigned threads = 1;  // ours (BakeSettings::threads, resolved); OpenSubdiv: one
    bool quick = false;    // --quick: CI's short run (bench/README.md, "The guard")
    std::vector<MeshResult> meshes;
};

// The figures as one table (rows: figures, columns: meshes, last column: target),
// then PASS/MISS per target, then one "verdict" line per mesh and guarded target
// (bake + write / OpenSubdiv, load speed-up) for CI's log.
std::string formatTable(const Report& report);

// The same figures as a JSON document (times in milliseconds, sizes in bytes).
std::string formatJson(const Report& report);

}  // namespace ltbench
