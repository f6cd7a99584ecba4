// CpuEvaluator and evaluateCpu (runtime.h): the patches counted, the output sized
// once, and the patches evaluated in place over threads (PatchEvaluator,
// patch_evaluator.h).
#include "looptess/runtime.h"

#include "huge_pages.h"
#include "parallel.h"
#include "patch_evaluator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace lt {
namespace {

// `v` resized to `n`. A new allocation is advised onto huge pages first (Linux,
// where the kernel offers them for madvise): a first frame's output is tens of MB,
// and faulting it in 4 KiB pages on a virtual machine took a third of an evaluation
// at F = 8 (bench/README.md, bench_cpu's cold column). Advice only: the contents
// and the result are the same either way.
template <class T>
void grow(std::vector<T>& v, size_t n) {
    if (v.capacity() < n) {
        v.reserve(n);
        fmt::adviseHugePages(v.data(), n * sizeof(T));
    }
    v.resize(n);
}

// Every output array sized for `vertices` and `indices`, keeping the allocations of
// an earlier frame (the attributes empty without `attributes`). The arrays are
// grown on `threads` threads: a first frame's pages are zeroed as they are first
// touched, a fifth of spot's first evaluation at F = 32 on one thread.
void resize(const Asset& asset, bool attributes, size_t vertices, size_t indices, size_t threads, Tessellation& out) {
    const size_t with = attributes ? vertices : 0;
    const bool uvs = !asset.faceUVs.empty();
    fmt::parallelTasks(9, threads, [&](size_t k, size_t) {
        switch (k) {  // the largest first
        case 0: return grow(out.indices, indices);
        case 1: return grow(out.tangents, uvs ? 4 * with : 0);
        case 2: return grow(out.positions, 3 * vertices);
        case 3: return grow(out.normals, 3 * vertices);
        case 4: return grow(out.colors, asset.faceColors.empty() ? 0 : 4 * with);
        case 5: return grow(out.uv, 2 * vertices);
        case 6: return grow(out.texcoords, uvs ? 2 * with : 0);
        case 7: return grow(out.texcoords1, asset.faceUV1s.empty() ? 0 : 2 * with);
        default: return grow(out.face, vertices);
        }
    });
}

}  // namespace

uint32_t runtimeDepth(uint32_t maxDepth, float tessFactor) {
    uint32_t d = 0;
    while (d < maxDepth && std::ldexp(1.0f, int(d)) < tessFactor) ++d;
    return d;
}

struct CpuEvaluator::Impl {
    // One patch of the evaluation, in emission order, and where its output goes.
    struct Work {
        uint32_t level, index;
        bool irregular, split;
        size_t vertex, index0;  // its first vertex and first index in the output
    };
    explicit Impl(const Asset& a) : asset(a) {}
    const Asset& asset;
    std::unique_ptr<WatertightPlan> plan;          // built on the first watertight evaluation (planFor)
    std::unique_ptr<SplitVertexIndex> splitIndex;  // built on the first Screen-mode evaluation
    std::vector<float> vertices;                   // the subdivided points: frames reuse the allocation
    std::vector<Work> work;                        // this frame's patches
    // What the patches' counts depend on outside Screen mode: the next frame with the
    // same key keeps `work` and the totals.
    struct WorkKey {
        float tessFactor = -1;
        uint32_t depth = 0;
        DrawPath path = DrawPath::Auto;
        Spacing spacing = Spacing::Equal;
        bool indexed = false;
        uint32_t firstFace = 0, faceCount = 0;
        bool operator==(const WorkKey& o) const {
            return tessFactor == o.tessFactor && depth == o.depth && path == o.path && spacing == o.spacing &&
                   indexed == o.indexed && firstFace == o.firstFace && faceCount == o.faceCount;
        }
    };
    WorkKey workKey;  // tessFactor -1: none kept
    size_t vertexCount = 0, indexCount = 0;
    std::vector<std::unique_ptr<EvalCache>> caches;  // one a thread (the counting pass uses the first)
    float tessFactor = 1;                            // this frame's
    uint32_t depth = 0;
    void frame(const float* controlPositions, const EvalSettings& settings);
    void count(const float* controlPositions, const EvalSettings& settings);
    void planFor(uint32_t levels, size_t threads);
};

CpuEvaluator::CpuEvaluator(const Asset& asset) : impl_(new Impl(asset)) {}
CpuEvaluator::~CpuEvaluator() = default;
CpuEvaluator::CpuEvaluator(CpuEvaluator&&) noexcept = default;
CpuEvaluator& CpuEvaluator::operator=(CpuEvaluator&&) noexcept = default;

void evaluateCpu(const Asset& asset, const float* controlPositions, const EvalSettings& settings, Tessellation& out) {
    CpuEvaluator(asset).evaluate(controlPositions, settings, out);
}

void CpuEvaluator::prepare(const EvalSettings& settings) {
    if (settings.watertight) impl_->planFor(impl_->asset.maxDepth(), settings.threads);
    if (settings.lod.mode == LodMode::Screen && !impl_->splitIndex)
        impl_->splitIndex = std::make_unique<SplitVertexIndex>(impl_->asset);
}

// This frame's factor and depth.
void CpuEvaluator::Impl::frame(const float* controlPositions, const EvalSettings& settings) {
    tessFactor = lodTessFactor(asset, controlPositions, settings);
    depth = runtimeDepth(asset, tessFactor);
}

// A plan with levels 0 .. `levels` at least: the first build has what the first
// frame reads (on spot at F = 8, half the levels and half the time of all), a deeper
// frame after it gets the whole plan, so it is built at most twice.
void CpuEvaluator::Impl::planFor(uint32_t levels, size_t threads) {
    if (plan && plan->levels.size() > levels) return;
    const uint32_t to = plan ? asset.maxDepth() : levels;
    plan = std::make_unique<WatertightPlan>();
    buildWatertightPlan(asset, *plan, threads, to);
}

// The first of evaluate's two passes, after frame(): the frame's subdivided points,
// then its patches' counts (on this thread; kept for the next frame with the same
// factor and path outside Screen mode). Screen mode needs the split index built.
void CpuEvaluator::Impl::count(const float* controlPositions, const EvalSettings& settings) {
    subdivideCpu(asset, controlPositions, depth, vertices, settings.editValues);
    const SplitVertexIndex* split = settings.lod.mode == LodMode::Screen ? splitIndex.get() : nullptr;
    if (caches.empty()) caches.push_back(std::make_unique<EvalCache>());
    const WorkKey key{tessFactor,        depth, settings.path, settings.spacing, settings.indexed, settings.firstFace,
                      settings.faceCount};
    if (settings.lod.mode != LodMode::Screen && key == workKey) return;
    workKey = settings.lod.mode == LodMode::Screen ? WorkKey{} : key;
    work.clear();
    vertexCount = indexCount = 0;
    Tessellation none;  // the counts write nothing
    PatchEvaluator counter(asset, vertices, settings, tessFactor, nullptr, split, *caches[0],
                           none);  // no plan: counts only
    // The base faces [first, end) (EvalSettings::firstFace): a patch's counts do not
    // depend on the others, so a piece's patches keep their whole frame's output.
    const uint32_t first = settings.firstFace,
                   end = uint32_t(std::min<uint64_t>(uint64_t(first) + settings.faceCount, UINT32_MAX));
    auto drawn = [&](const PatchParam& p) { return p.baseFace >= first && p.baseFace < end; };
    size_t patches = asset.levels[depth].irregular.size();
    for (uint32_t l = 0; l <= depth; ++l) patches += asset.levels[l].regular.size();
    work.reserve(patches);
    for (uint32_t l = 0; l <= depth; ++l) {
        const Level& level = asset.levels[l];
        for (uint32_t k = 0; k < level.regular.size(); ++k) {
            if (!drawn(level.regular[k].param)) continue;
            size_t v = 0, i = 0;
            counter.countRegular(l, k, l < depth, v, i);
            work.push_back({l, k, false, l < depth, vertexCount, indexCount});
            vertexCount += v, indexCount += i;
        }
        if (l == depth)
            for (uint32_t k = 0; k < level.irregular.size(); ++k) {
                if (!drawn(level.irregular[k].param)) continue;
                work.push_back({l, k, true, false, vertexCount, indexCount});
                vertexCount += PatchEvaluator::kIrregularVertices, indexCount += counter.irregularIndices();
            }
    }
}

void CpuEvaluator::count(const float* controlPositions, const EvalSettings& settings, size_t& vertices,
                         size_t& indices) {
    EvalSettings counting = settings;
    counting.watertight = false;  // the counts need no watertight plan (Screen mode's split index only)
    prepare(counting);
    impl_->frame(controlPositions, settings);
    impl_->count(controlPositions, settings);
    vertices = impl_->vertexCount;
    indices = impl_->indexCount;
}

// Two passes: the patches' counts (Impl::count), then their evaluation in chunks of
// contiguous patches over the threads, each patch writing its vertices and indices in
// place. Each thread's evaluator keeps caches of its own; what a patch emits depends
// only on the patch, so every thread count and schedule gives the same bits.
void CpuEvaluator::evaluate(const float* controlPositions, const EvalSettings& settings, Tessellation& out) {
    const Asset& asset = impl_->asset;
    EvalSettings split = settings;
    split.watertight = false;
    prepare(split);  // Screen mode's split index, which the counts read
    impl_->frame(controlPositions, settings);
    // The plan this depth reads (when not built yet) beside the counting pass and the
    // output's sizing.
    fmt::parallelTasks(2, settings.threads, [&](size_t task, size_t) {
        if (task == 0 && settings.watertight) impl_->planFor(impl_->depth, settings.threads);
        if (task == 1) {
            impl_->count(controlPositions, settings);
            resize(asset, settings.attributes, impl_->vertexCount, impl_->indexCount, settings.threads, out);
        }
    });
    const float tessFactor = impl_->tessFactor;
    const std::vector<float>& vertices = impl_->vertices;
    const WatertightPlan* plan = settings.watertight ? impl_->plan.get() : nullptr;
    const SplitVertexIndex* splitIndex = settings.lod.mode == LodMode::Screen ? impl_->splitIndex.get() : nullptr;
    const std::vector<Impl::Work>& work = impl_->work;
    std::vector<std::unique_ptr<EvalCache>>& caches = impl_->caches;
    const size_t vertexCount = impl_->vertexCount;

    // Threads: at most one per kMinVertices of output (below, a thread costs more than
    // it saves). Work: contiguous chunks of patches of about kChunkVertices each, taken
    // in turn by whichever thread is free, so that a thread given costlier patches
    // (watertight edges, irregular faces) does not hold the others up.
    constexpr size_t kMinVertices = 16384, kChunkVertices = 4096;
    size_t threads = settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
    threads = std::max<size_t>(1, std::min({threads, work.size(), vertexCount / kMinVertices + 1}));
    const size_t chunks = threads == 1 ? 1 : std::min(work.size(), vertexCount / kChunkVertices + 1);
    auto chunkStart = [&](size_t c) {
        // The first patch whose first vertex is at or past c / chunks of the output.
        const size_t from = c * vertexCount / chunks;
        return size_t(std::lower_bound(work.begin(), work.end(), from,
                                       [](const Impl::Work& w, size_t v) { return w.vertex < v; }) -
                      work.begin());
    };
    while (caches.size() < threads) caches.push_back(std::make_unique<EvalCache>());
    std::atomic<size_t> nextChunk{0};
    auto evaluateChunks = [&](size_t t) {
        PatchEvaluator eval(asset, vertices, settings, tessFactor, plan, splitIndex, *caches[t], out);
        for (size_t c = nextChunk++; c < chunks; c = nextChunk++)
            for (size_t w = chunkStart(c), end = chunkStart(c + 1); w < end; ++w) {
                eval.at(work[w].vertex, work[w].index0);
                if (work[w].irregular)
                    eval.irregular(work[w].level, work[w].index);
                else
                    eval.regular(work[w].level, work[w].index, work[w].split);
            }
    };
    fmt::parallelTasks(threads, threads, [&](size_t, size_t worker) { evaluateChunks(worker); });
}

}  // namespace lt
