// bench/bench_cpu.cpp -- the CPU evaluator against what a user would pick instead,
// OpenSubdiv's Bfr (bench/README.md, "bench_cpu").
//
//   bench_cpu [--runs N] [--corpus DIR] [--mesh NAME]... [--factor F]... [--threads N] [--json FILE]
//
// Per mesh (spot, bob, duck, torus) and factor (4, 8, 16, 32):
//   Bfr   Bfr::RefinerSurfaceFactory, then per base face a Bfr::Tessellation at
//         the factor and Surface::Evaluate at each of its points: positions only
//         ("P"), with the normal from the first derivatives ("PN"), and the full
//         vertex ("full": also the base face's texture coordinates interpolated and
//         a tangent from the derivatives, as ours emits). Points per face, shared
//         edges evaluated by both faces (Bfr's own way).
//   ours  lt::CpuEvaluator at the same factor, refinement patterns, indexed (each
//         pattern point once per patch; the default way) and as a soup: "PN" on the
//         asset baked without texture coordinates, "full" with them (tangents and
//         texture coordinates then come with every vertex). No positions-only mode.
// Each on one thread and on all (--threads, default: every CPU this process may
// use; ours through EvalSettings::threads, Bfr's faces split the same way). Times
// are medians of --runs runs after one warm-up; throughput is output points per
// second, each side's own points. "extra KiB" (one thread): the heap ours keeps
// beyond its output after the runs (subdivided points, patch list, caches; glibc's
// mallinfo2). "cold ms" (ours): a fresh evaluator constructed and one evaluation into
// a fresh output, timed together (their freeing not), median of --runs such first
// evaluations (no warm-up: each is one), measured before the warm runs; "cold/warm"
// is over the warm ms; Bfr's cold is a fresh RefinerSurfaceFactory (an empty
// patch-tree cache; the refiner kept) and one evaluation. Verdict lines after the
// table report the targets at F = 8 and 32 on spot and the torus: our cold within
// 1.3x of our warm, and our cold output points per second at least Bfr's cold ones
// (same mode and threads: a one-shot tool's evaluation, looprender --mesh);
// reported, never asserted.
// Output to stdout; exit 1 on usage errors, 2 when a mesh cannot be read or baked.
#include "bench_common.h"

#include "looptess/tools/baker.h"
#include "looptess/tools/osd.h"
#include "looptess/runtime.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/tessellation.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <malloc.h>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace OpenSubdiv;
using Clock = std::chrono::steady_clock;

enum class Mode { P, PN, Full };
const char* const kModeNames[] = {"P", "PN", "full"};

struct Args {
    int runs = 5;
    unsigned threads = 0;  // 0: every CPU
    std::string corpus = LOOPTESS_CORPUS_DIR;
    std::vector<std::string> meshes;
    std::vector<int> factors;
    bool soups = true;  // --no-soup: indexed rows only
};

const char* const kUsage =
    "usage: bench_cpu [--runs N] [--corpus DIR] [--mesh NAME]... [--factor F]... [--threads N] [--no-soup]\n"
    "  --runs N      timed runs per figure after a warm-up; the median is reported (default 5)\n"
    "  --corpus DIR  corpus root holding meshes/*.obj and gltf/Duck.glb (default " LOOPTESS_CORPUS_DIR
    ")\n"
    "  --mesh NAME   spot, bob, duck or torus; repeat for several (default: all four)\n"
    "  --factor F    tessellation factor, an integer 1..64; repeat (default: 4 8 16 32)\n"
    "  --threads N   threads of the all-core runs (default: every CPU this process may use)\n"
    "  --no-soup     our indexed rows only: the soups of the torus at F = 32 (307M vertices,\n"
    "                18 GB for the full vertex) do not fit a machine of 23 GB\n";

bool parseArgs(int argc, char** argv, Args& a) {
    for (int i = 1; i < argc; ++i) {
        const std::string o = argv[i];
        if (o == "--help" || o == "-h") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        }
        if (o == "--no-soup") {
            a.soups = false;
            continue;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "bench_cpu: %s needs a value\n%s", o.c_str(), kUsage);
            return false;
        }
        const std::string v = argv[++i];
        char* end = nullptr;
        const long n = std::strtol(v.c_str(), &end, 10);
        const bool number = end && *end == 0;
        if (o == "--runs" && number && n >= 1 && n <= 1000)
            a.runs = int(n);
        else if (o == "--threads" && number && n >= 1 && n <= 1024)
            a.threads = unsigned(n);
        else if (o == "--factor" && number && n >= 1 && n <= 64)
            a.factors.push_back(int(n));
        else if (o == "--corpus")
            a.corpus = v;
        else if (o == "--mesh" && (v == "spot" || v == "bob" || v == "duck" || v == "torus"))
            a.meshes.push_back(v);
        else {
            std::fprintf(stderr, "bench_cpu: bad %s '%s'\n%s", o.c_str(), v.c_str(), kUsage);
            return false;
        }
    }
    if (a.meshes.empty()) a.meshes = {"spot", "bob", "duck", "torus"};
    if (a.factors.empty()) a.factors = {4, 8, 16, 32};
    if (a.threads == 0) a.threads = unsigned(std::max(1, ltbench::machineInfo("").nproc));
    return true;
}

// --- Bfr ----------------------------------------------------------------------------

// The mesh as a Far topology at level 0: its triangles, creases and corners, and the
// baker's boundary and crease options (the same surface the asset holds).
struct Output {
    std::vector<float> positions, normals, texcoords, tangents;
    std::vector<int> triangles;
    size_t points = 0, triangleCount = 0;
};

void normalize(float v[3]) {
    const float l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; ++k) v[k] = l > 0 ? v[k] / l : 0;
}

// Faces [begin, end) at `rate` into `out` (resized as needed, reused across runs).
void bfrFaces(const Bfr::RefinerSurfaceFactory<>& factory, const lt::InputMesh& mesh, int rate, Mode mode, int begin,
              int end, Output& out) {
    Bfr::Surface<float> surface;
    const Bfr::Surface<float>::PointDescriptor desc(3);
    std::vector<float> patch, coords;
    std::vector<int> facets;
    out.points = out.triangleCount = 0;
    out.triangles.clear();
    for (int f = begin; f < end; ++f) {
        if (!factory.InitVertexSurface(f, &surface)) continue;
        patch.resize(size_t(surface.GetNumPatchPoints()) * 3);
        surface.PreparePatchPoints(mesh.positions.data(), desc, patch.data(), desc);
        Bfr::Tessellation tess(surface.GetParameterization(), rate, Bfr::Tessellation::Options());
        const size_t n = size_t(tess.GetNumCoords());
        coords.resize(2 * n);
        tess.GetCoords(coords.data());
        facets.resize(3 * size_t(tess.GetNumFacets()));
        tess.GetFacets(facets.data());
        const size_t at = out.points;
        out.points += n;
        if (out.positions.size() < 3 * out.points) {
            out.positions.resize(6 * out.points);
            out.normals.resize(6 * out.points);
            out.texcoords.resize(4 * out.points);
            out.tangents.resize(8 * out.points);
        }
        for (int x : facets) out.triangles.push_back(int(at) + x);  // the indexed mesh, as ours writes
        out.triangleCount += facets.size() / 3;
        const float* uv = mesh.faceUVs.empty() ? nullptr : &mesh.faceUVs[6 * size_t(f)];
        for (size_t i = 0; i < n; ++i) {
            float* p = &out.positions[3 * (at + i)];
            if (mode == Mode::P) {
                surface.Evaluate(&coords[2 * i], patch.data(), desc, p);
                continue;
            }
            float du[3], dv[3];
            surface.Evaluate(&coords[2 * i], patch.data(), desc, p, du, dv);
            float* nrm = &out.normals[3 * (at + i)];
            nrm[0] = du[1] * dv[2] - du[2] * dv[1];
            nrm[1] = du[2] * dv[0] - du[0] * dv[2];
            nrm[2] = du[0] * dv[1] - du[1] * dv[0];
            normalize(nrm);
            if (mode != Mode::Full || !uv) continue;
            const float u = coords[2 * i], v = coords[2 * i + 1], w = 1 - u - v;
            float* st = &out.texcoords[2 * (at + i)];
            st[0] = w * uv[0] + u * uv[2] + v * uv[4];
            st[1] = w * uv[1] + u * uv[3] + v * uv[5];
            float* t = &out.tangents[4 * (at + i)];  // du made orthogonal to the normal
            const float d = du[0] * nrm[0] + du[1] * nrm[1] + du[2] * nrm[2];
            for (int k = 0; k < 3; ++k) t[k] = du[k] - d * nrm[k];
            normalize(t);
            t[3] = 1;
        }
    }
}

// --- timing -------------------------------------------------------------------------

double seconds(const std::function<void()>& f) {
    const auto t0 = Clock::now();
    f();
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Median seconds of `runs` runs of `f` after one warm-up run.
double timed(int runs, const std::function<void()>& f) {
    f();
    std::vector<double> t;
    for (int r = 0; r < runs; ++r) t.push_back(seconds(f));
    return ltbench::median(t);
}

// `work(t, threads)` on `threads` threads (t = 0 .. threads - 1), joined.
void onThreads(unsigned threads, const std::function<void(unsigned, unsigned)>& work) {
    if (threads == 1) return work(0, 1);
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work, t, threads);
    for (std::thread& th : pool) th.join();
}

struct Row {
    std::string mesh, side, mode;
    int factor = 0;
    unsigned threads = 1;
    size_t points = 0, triangles = 0;
    double seconds = 0;
    double extraKiB = -1;     // ours: heap the evaluator keeps beyond its output (< 0: not measured)
    double coldSeconds = -1;  // ours: construction + one evaluation (< 0: not measured)
};

// Median seconds of `runs` first evaluations: `first()` constructs, evaluates once and
// returns the seconds of that alone (freeing them is no part of a first evaluation).
// Run before the warm runs, while no frame of that size is held: beside a warm
// frame's output, a first frame's fresh memory costs this VM's host far more
// (bench/README.md "Fresh memory").
double timedCold(int runs, const std::function<double()>& first) {
    std::vector<double> t;
    for (int r = 0; r < runs; ++r) t.push_back(first());
    return ltbench::median(t);
}

constexpr double kColdTarget = 1.3;  // a first evaluation within 1.3x of a warm one
constexpr double kColdVsBfr = 1.0;   // and at least Bfr's output points per second

// Bytes of the heap in use (glibc's allocator: the main arena's chunks and the
// mmapped ones), for what an evaluator keeps. Other threads' arenas are not counted:
// measure on one thread.
size_t heapInUse() {
    const struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
}

size_t outputBytes(const lt::Tessellation& t) {
    auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return bytes(t.positions) + bytes(t.normals) + bytes(t.face) + bytes(t.uv) + bytes(t.texcoords) +
           bytes(t.tangents) + bytes(t.texcoords1) + bytes(t.colors) + bytes(t.indices);
}

void print(const Row& r, double bfrPointsPerSecond) {
    const double pps = r.seconds > 0 ? double(r.points) / r.seconds : 0;
    std::printf("%-6s %3d %-12s %-5s %3u %11zu %11zu %10.2f %8.3f %8.2f", r.mesh.c_str(), r.factor, r.side.c_str(),
                r.mode.c_str(), r.threads, r.triangles, r.points, 1e3 * r.seconds,
                r.points ? 1e9 * r.seconds / double(r.points) : 0.0, pps / 1e6);
    if (bfrPointsPerSecond > 0)
        std::printf(" %7.2fx", pps / bfrPointsPerSecond);
    else if (r.coldSeconds >= 0)
        std::printf(" %8s", "");  // Bfr's own row
    if (r.coldSeconds >= 0) {
        if (r.extraKiB >= 0)
            std::printf(" %9.0f", r.extraKiB);
        else
            std::printf(" %9s", "");  // measured on one thread only
        std::printf(" %9.2f %8.2fx", 1e3 * r.coldSeconds, r.coldSeconds / r.seconds);
    } else if (r.extraKiB >= 0) {
        std::printf(" %9.0f", r.extraKiB);
    }
    std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
    Args args;
    if (!parseArgs(argc, argv, args)) return 1;
    const ltbench::Machine machine = ltbench::machineInfo(LOOPTESS_BENCH_BUILD_TYPE);
    std::printf("bench_cpu: median of %d runs after a warm-up; %s, %d CPUs; %s, %s; OpenSubdiv %s\n", args.runs,
                machine.cpuModel.c_str(), machine.nproc, machine.compiler.c_str(), machine.buildType.c_str(),
                machine.osdVersion.c_str());
    std::printf("%-6s %3s %-12s %-5s %3s %11s %11s %10s %8s %8s %8s %9s %9s %9s\n", "mesh", "F", "evaluator", "mode",
                "thr", "triangles", "points", "ms", "ns/pt", "Mpt/s", "vs Bfr", "extra KiB", "cold ms", "cold/warm");
    std::vector<std::string> verdicts;
    for (const std::string& name : args.meshes) {
        lt::InputMesh mesh;
        lt::Status st = ltbench::loadMesh(args.corpus, name, mesh);
        lt::Asset full, plain;
        if (st) st = lt::bake(mesh, lt::BakeSettings{}, full);
        lt::InputMesh noUVs = mesh;
        noUVs.faceUVs.clear();
        if (st) st = lt::bake(noUVs, lt::BakeSettings{}, plain);
        if (!st) {
            std::fprintf(stderr, "bench_cpu: %s: %s\n", name.c_str(), st.message.c_str());
            return 2;
        }
        std::fprintf(stderr, "bench_cpu: %s: %zu faces, depth %u\n", name.c_str(), size_t(mesh.faceCount()),
                     full.maxDepth());
        std::unique_ptr<Far::TopologyRefiner> refiner;  // level 0, as the baker maps the mesh
        if (const lt::Status refused = lt::createRefiner(mesh, name, refiner); !refused) {
            std::fprintf(stderr, "bench_cpu: %s\n", refused.message.c_str());
            return 2;
        }
        const Bfr::RefinerSurfaceFactory<> factory(*refiner);
        for (int factor : args.factors) {
            std::vector<unsigned> threadCounts = {1};
            if (args.threads > 1) threadCounts.push_back(args.threads);
            for (unsigned threads : threadCounts) {
                double bfr[3] = {0, 0, 0};      // points per second by mode
                double bfrCold[3] = {0, 0, 0};  // points per second by mode, a fresh factory
                for (Mode mode : {Mode::P, Mode::PN, Mode::Full}) {
                    std::vector<Output> outs(threads);
                    const int faces = int(mesh.faceCount());
                    auto evaluate = [&](const Bfr::RefinerSurfaceFactory<>& f) {
                        onThreads(threads, [&](unsigned t, unsigned n) {
                            bfrFaces(f, mesh, factor, mode, int(faces * size_t(t) / n), int(faces * size_t(t + 1) / n),
                                     outs[t]);
                        });
                    };
                    Row r{name, "Bfr", kModeNames[int(mode)], factor, threads};
                    // Cold: a fresh factory (its patch-tree cache empty), the refiner kept.
                    r.coldSeconds = timedCold(args.runs, [&] {
                        std::optional<Bfr::RefinerSurfaceFactory<>> fresh;
                        return seconds([&] { evaluate(fresh.emplace(*refiner)); });
                    });
                    r.seconds = timed(args.runs, [&] { evaluate(factory); });
                    for (const Output& o : outs) r.points += o.points, r.triangles += o.triangleCount;
                    bfr[int(mode)] = double(r.points) / r.seconds;
                    bfrCold[int(mode)] = double(r.points) / r.coldSeconds;
                    print(r, 0);
                }
                for (bool indexed : {true, false})
                    for (Mode mode : {Mode::PN, Mode::Full}) {
                        if (!indexed && !args.soups) continue;
                        const lt::Asset& asset = mode == Mode::Full ? full : plain;
                        lt::EvalSettings settings;
                        settings.tessFactor = float(factor);
                        settings.path = lt::DrawPath::Patterns;
                        settings.indexed = indexed;
                        settings.threads = threads;
                        Row r{name, indexed ? "ours" : "ours (soup)", kModeNames[int(mode)], factor, threads};
                        r.coldSeconds = timedCold(args.runs, [&] {
                            std::optional<lt::CpuEvaluator> fresh;
                            lt::Tessellation first;
                            return seconds(
                                [&] { fresh.emplace(asset).evaluate(asset.positions.data(), settings, first); });
                        });
                        const size_t heapBefore = heapInUse();
                        lt::CpuEvaluator evaluator(asset);
                        lt::Tessellation out;
                        r.seconds =
                            timed(args.runs, [&] { evaluator.evaluate(asset.positions.data(), settings, out); });
                        r.points = out.vertexCount();
                        r.triangles = out.triangleCount();
                        if (threads == 1)
                            r.extraKiB = (double(heapInUse()) - double(heapBefore) - double(outputBytes(out))) / 1024;
                        print(r, bfr[int(mode)]);
                        if ((name == "spot" || name == "torus") && (factor == 8 || factor == 32)) {
                            const double ratio = r.coldSeconds / r.seconds;
                            // A one-shot tool's evaluation (looprender --mesh: indexed,
                            // cold) against Bfr's, per output point.
                            const double vsBfr = double(r.points) / r.coldSeconds / bfrCold[int(mode)];
                            char line[240];
                            std::snprintf(line, sizeof line,
                                          "verdict %s F=%d %s %s %u thr: cold/warm %.2fx (target <= %.1fx): %s; "
                                          "cold vs Bfr %.2fx (target >= %.1fx): %s",
                                          name.c_str(), factor, r.side.c_str(), r.mode.c_str(), threads, ratio,
                                          kColdTarget, ratio <= kColdTarget ? "met" : "MISSED", vsBfr, kColdVsBfr,
                                          vsBfr >= kColdVsBfr ? "met" : "MISSED");
                            verdicts.push_back(line);
                        }
                    }
            }
        }
    }
    for (const std::string& v : verdicts) std::printf("%s\n", v.c_str());
    return 0;
}
