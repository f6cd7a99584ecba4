// bench/bench_bake.cpp -- per mesh, our baker against OpenSubdiv's own table
// build: bake time, table bytes, load time (bench/README.md).
//
//   bench_bake [--quick] [--depth N] [--runs N] [--threads N] [--json FILE] [--corpus DIR] [--mesh NAME]...
//              [--save DIR]
//
// Meshes: spot, bob, fandisk (CORPUS/meshes/<name>.obj) and torus (generated,
// gen_mesh.h); --mesh picks some (repeatable), or scan1m (generated, 1,000,000
// triangles, never by default). --quick is CI's guard: spot only,
// median of 3 runs, unless --mesh or --runs say otherwise. The table and its
// verdict lines go to stdout, progress to stderr. Exit status: 0 when every figure
// was measured (targets met or not: verdicts are reported, never asserted), 1 on
// usage errors, 2 when a mesh cannot be read or baked.
#include "bench_common.h"
#include "detail.h"
#include "gen_mesh.h"
#include "osd_tables.h"
#include "report.h"

#include "looptess/tools/baker.h"
#include "looptess/tools/file_io.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using ltbench::median;
using ltbench::MeshResult;

const char* const kCorpusMeshes[] = {"spot", "bob", "fandisk"};
const char* const kGenerated = "torus";
// Only on request: a million triangles take tens of seconds and GiB a run.
const char* const kLarge = "scan1m";

struct Args {
    int depth = 6, runs = 5;
    unsigned threads = 1;  // ours; 0: one per core
    bool quick = false, runsGiven = false;
    std::string json, corpus = LOOPTESS_CORPUS_DIR, save;
    std::vector<std::string> meshes;  // empty: all (with --quick: spot)
};

// --quick: what CI runs after the tests (.ci/run). Spot alone takes a few seconds
// a run on CI's 2 cores; the median of 3 keeps one disturbed run out of the ratio.
const char* const kQuickMesh = "spot";
constexpr int kQuickRuns = 3;

const char* const kUsage =
    "usage: bench_bake [--quick] [--depth N] [--runs N] [--threads N] [--json FILE] [--corpus DIR] [--mesh NAME]...\n"
    "                  [--save DIR]\n"
    "  --quick      CI's short run: spot only, median of 3 runs (--mesh, --runs override)\n"
    "  --depth N    subdivision depth for both sides, 1..8 (default 6)\n"
    "  --runs N     timed runs per figure; the median is reported (default 5)\n"
    "  --threads N  our bake and write on N threads (default 1; 0: one per core); OpenSubdiv on 1\n"
    "  --json FILE  also write the figures as JSON to FILE\n"
    "  --corpus DIR corpus root holding meshes/*.obj (default " LOOPTESS_CORPUS_DIR
    ")\n"
    "  --mesh NAME  spot, bob, fandisk, torus or scan1m; repeat for several (default: all\n"
    "               but scan1m)\n"
    "  --save DIR   also write each baked GLB (--compress fast) to DIR/NAME.glb (for profiling a loader)\n";

// Parses argv into `args`; false (after printing why) on bad usage.
bool parseArgs(int argc, char** argv, Args& args) {
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        }
        if (a == "--quick") {
            args.quick = true;
            continue;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "bench_bake: %s needs a value\n%s", a.c_str(), kUsage);
            return false;
        }
        std::string v = argv[++i];
        if (a == "--depth" || a == "--runs" || a == "--threads") {
            char* end = nullptr;
            long n = std::strtol(v.c_str(), &end, 10);
            bool ok = end && *end == 0 &&
                      (a == "--depth"  ? (n >= 1 && n <= 8)
                       : a == "--runs" ? (n >= 1 && n <= 1000)
                                       : (n >= 0 && n <= 256));
            if (!ok) {
                std::fprintf(stderr, "bench_bake: bad %s '%s'\n%s", a.c_str(), v.c_str(), kUsage);
                return false;
            }
            if (a == "--threads")
                args.threads = unsigned(n);
            else
                (a == "--depth" ? args.depth : args.runs) = int(n);
            args.runsGiven = args.runsGiven || a == "--runs";
        } else if (a == "--json") {
            args.json = v;
        } else if (a == "--corpus") {
            args.corpus = v;
        } else if (a == "--save") {
            args.save = v;
        } else if (a == "--mesh") {
            bool known = v == kGenerated || v == kLarge;
            for (const char* m : kCorpusMeshes) known = known || v == m;
            if (!known) {
                std::fprintf(stderr, "bench_bake: unknown mesh '%s'\n%s", v.c_str(), kUsage);
                return false;
            }
            args.meshes.push_back(v);
        } else {
            std::fprintf(stderr, "bench_bake: unknown option '%s'\n%s", a.c_str(), kUsage);
            return false;
        }
    }
    if (args.quick && !args.runsGiven) args.runs = kQuickRuns;
    if (args.quick && args.meshes.empty()) args.meshes.push_back(kQuickMesh);
    if (args.meshes.empty()) {
        args.meshes.assign(std::begin(kCorpusMeshes), std::end(kCorpusMeshes));
        args.meshes.push_back(kGenerated);
    }
    return true;
}

double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Per-run wall-clock seconds of every timed step.
struct RunTimes {
    std::vector<double> bake, write, load, writeNone, loadNone, copy, scan;
    std::vector<double> osdRefiner, osdStencils, osdPatches, osdAppend, osdTotal;
    std::vector<std::pair<std::string, std::vector<double>>> stages;  // lt::bake's, by name
};

// One run of our side: bake, write and read back with --compress fast and none
// (plus the two loader floors, on the plain file). The first run also fills the
// byte and count figures of `r`, and writes --compress max once.
lt::Status runOurs(const lt::InputMesh& mesh, const std::string& name, int depth, unsigned threads, bool first,
                   MeshResult& r, RunTimes& t, const std::string& saveDir) {
    lt::BakeSettings settings;
    settings.maxDepth = depth;
    settings.threads = threads;
    lt::Asset asset, back;
    lt::BakeStats stats;
    std::vector<uint8_t> glb;
    auto start = Clock::now();
    lt::Status st = lt::bake(mesh, settings, asset, &stats);
    t.bake.push_back(since(start));
    if (!st) return st;
    for (const lt::BakeStats::Stage& s : stats.stages) {
        auto it = std::find_if(t.stages.begin(), t.stages.end(), [&](const auto& e) { return e.first == s.name; });
        if (it == t.stages.end()) it = t.stages.insert(t.stages.end(), {s.name, {}});
        it->second.push_back(s.seconds);
    }

    // The default (--compress fast) and plain (--compress none) files, each written
    // and read back.
    std::vector<uint8_t> packed;
    start = Clock::now();
    st = lt::writeAssetGlb(asset, packed, &r.tables, lt::Compression::Fast, threads);
    t.write.push_back(since(start));
    if (!st) return st;
    start = Clock::now();
    st = lt::writeAssetGlb(asset, glb, nullptr, lt::Compression::None, threads);
    t.writeNone.push_back(since(start));
    if (!st) return st;

    for (auto [bytes, times] : {std::pair{&packed, &t.load}, std::pair{&glb, &t.loadNone}}) {
        start = Clock::now();
        st = lt::readAssetGlb(bytes->data(), bytes->size(), name + ".glb", back);
        times->push_back(since(start));
        if (!st) return st;
        if (back.totalVertexCount() != asset.totalVertexCount() || back.levels.size() != asset.levels.size())
            return lt::Status::error(lt::Status::Internal, name + ": the GLB read back differs from the baked asset");
    }

    // The floor of any loader: one copy of the file into fresh memory.
    start = Clock::now();
    std::vector<uint8_t> copy(glb.begin(), glb.end());
    t.copy.push_back(since(start));
    start = Clock::now();
    const uint64_t scanned = ltbench::scanGlbInPlace(glb);
    t.scan.push_back(since(start));
    if (scanned == 0 || copy.size() != glb.size())
        return lt::Status::error(lt::Status::Internal, name + ": cannot scan the GLB in place");

    if (first) {
        if (!saveDir.empty()) {
            st = lt::writeFileAtomic(saveDir + "/" + name + ".glb", packed.data(), packed.size());
            if (!st) return st;
        }
        std::vector<uint8_t> smallest;
        start = Clock::now();
        st = lt::writeAssetGlb(asset, smallest, nullptr, lt::Compression::Max, threads);
        r.writeMax = since(start);
        if (!st) return st;
        r.glbBytes = glb.size();
        r.glbFast = packed.size();
        r.glbMax = smallest.size();
        r.properties = ltbench::glbPropertyBytes(glb);
        r.estimates = ltbench::estimateSavings(asset);
        r.refinedVertices = asset.totalVertexCount() - asset.controlVertexCount();
        for (const lt::Level& l : asset.levels) {
            r.regularPatches += uint32_t(l.regular.size());
            r.irregularFaces += uint32_t(l.irregular.size());
            r.limitStencils += l.limit.count();
        }
    }
    return lt::Status::ok();
}

// One run of OpenSubdiv's side; the first run also measures its bytes.
lt::Status runOsd(const lt::InputMesh& mesh, int depth, bool first, MeshResult& r, RunTimes& t) {
    ltbench::OsdTimes o;
    lt::Status st =
        ltbench::buildOsdTables(mesh, depth, o, first ? &r.osdBytes : nullptr, first ? &r.osdCounts : nullptr);
    if (!st) return st;
    t.osdRefiner.push_back(o.refiner);
    t.osdStencils.push_back(o.stencils);
    t.osdPatches.push_back(o.patches);
    t.osdAppend.push_back(o.append);
    t.osdTotal.push_back(o.total());
    return lt::Status::ok();
}

// Runs both sides `runs` times, interleaved (ours, OpenSubdiv, ours, ...) so that
// both see the same machine load, and keeps the medians.
lt::Status measure(const lt::InputMesh& mesh, const std::string& name, const Args& args, MeshResult& r) {
    const int depth = args.depth;
    RunTimes t;
    for (int run = 0; run < args.runs; ++run) {
        lt::Status st = runOurs(mesh, name, depth, args.threads, run == 0, r, t, args.save);
        if (st) st = runOsd(mesh, depth, run == 0, r, t);
        if (!st) return st;
    }
    r.bake = median(t.bake);
    for (auto& [stage, times] : t.stages) r.bakeStages.push_back({stage, median(times)});
    r.write = median(t.write);
    r.load = median(t.load);
    r.writeNone = median(t.writeNone);
    r.loadNone = median(t.loadNone);
    r.copy = median(t.copy);
    r.scan = median(t.scan);
    r.osd.refiner = median(t.osdRefiner);
    r.osd.stencils = median(t.osdStencils);
    r.osd.patches = median(t.osdPatches);
    r.osd.append = median(t.osdAppend);
    r.osdTotal = median(t.osdTotal);
    std::vector<double> ratios;
    for (size_t k = 0; k < t.osdTotal.size(); ++k) ratios.push_back((t.bake[k] + t.write[k]) / t.osdTotal[k]);
    r.pairedBakeRatio = median(ratios);
    return lt::Status::ok();
}

}  // namespace

int main(int argc, char** argv) {
    Args args;
    if (!parseArgs(argc, argv, args)) return 1;
    ltbench::Report report;
    report.machine = ltbench::machineInfo(LOOPTESS_BENCH_BUILD_TYPE);
    report.depth = args.depth;
    report.runs = args.runs;
    report.threads = args.threads ? args.threads : std::max(1u, std::thread::hardware_concurrency());
    report.quick = args.quick;

    for (const std::string& name : args.meshes) {
        MeshResult r;
        r.name = name;
        lt::InputMesh mesh;
        lt::Status st = ltbench::loadMesh(args.corpus, name, mesh, &r.source);
        if (st) {
            r.vertices = mesh.vertexCount();
            r.triangles = mesh.faceCount();
            r.extraordinary = ltbench::countExtraordinary(mesh);
            std::fprintf(stderr, "bench_bake: %s (%u triangles)...\n", name.c_str(), r.triangles);
            st = measure(mesh, name, args, r);
        }
        if (!st) {
            std::fprintf(stderr, "bench_bake: %s\n", st.message.c_str());
            return 2;
        }
        report.meshes.push_back(std::move(r));
    }

    std::fputs(ltbench::formatTable(report).c_str(), stdout);
    if (!args.json.empty()) {
        std::string json = ltbench::formatJson(report);
        lt::Status st = lt::writeFileAtomic(args.json, reinterpret_cast<const uint8_t*>(json.data()), json.size());
        if (!st) {
            std::fprintf(stderr, "bench_bake: %s\n", st.message.c_str());
            return 2;
        }
    }
    return 0;
}
