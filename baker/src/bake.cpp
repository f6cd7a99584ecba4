// lt::bake: from OpenSubdiv's adaptive topology to the asset's tables.
//
// 1. Candidates. Level 0's candidates are the base faces (holes excepted); level
//    l+1's are the children of level l's irregular candidates. A regular candidate
//    is a patch (RPP, or NPP when an edge neighbour is an irregular candidate).
// 2. Needed vertices (numbering.h). Patch points and the 1-rings of irregular
//    corners (for their limit stencils) are needed; a needed vertex of level l needs
//    the vertices its vertex or edge rule reads at level l-1, down to level 0.
// 3. Numbering (numbering.h). Level l keeps its needed vertex points (by their
//    parent's global index) then its needed edge points (by their parent edge's
//    smaller, then larger end global index); tables index this global numbering.
// Hierarchical edits (edit_region.h) add faces to refine in step 1 and fill each
// level's edit table after step 3.
#include "bake_trace.h"

#include "corner_stencils.h"
#include "edit_region.h"
#include "numbering.h"
#include "orient.h"
#include "resource_limits.h"
#include "patches.h"
#include "refine.h"
#include "refinement_table.h"

#include "parallel.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string_view>

namespace lt {
namespace {

// Adds the wall-clock time since the previous lap to stats->stages under `name`
// (to the entry of that name when there is one: a stage that runs per level).
class StageClock {
public:
    explicit StageClock(BakeStats* stats) : stats_(stats), last_(std::chrono::steady_clock::now()) {}
    void lap(const char* name) {
        if (!stats_) return;
        const auto now = std::chrono::steady_clock::now();
        add(name, std::chrono::duration<double>(now - last_).count());
        last_ = now;
    }
    // The next lap counts from now.
    void restart() { last_ = std::chrono::steady_clock::now(); }
    bool timing() const { return stats_ != nullptr; }
    // Adds `seconds` to the stage `name`.
    void add(const char* name, double seconds) {
        if (!stats_) return;
        auto& stages = stats_->stages;
        auto it = std::find_if(stages.begin(), stages.end(),
                               [&](const BakeStats::Stage& s) { return std::string_view(s.name) == name; });
        if (it == stages.end())
            stages.push_back({name, seconds});
        else
            it->seconds += seconds;
    }

private:
    BakeStats* stats_;
    std::chrono::steady_clock::time_point last_;
};

// Frees `v`'s memory now (clear() keeps the capacity): the bake's peak is the
// largest level's corner stencils, so what earlier stages leave behind adds to it.
template <typename T>
void release(T& v) {
    T().swap(v);
}

// Parameters of child `i` of a face with parameters `p` (children keep corner i;
// child 3 is the middle triangle, rotated 180 degrees).
PatchParam childParam(const PatchParam& p, int i) {
    PatchParam c = p;
    c.level = uint8_t(p.level + 1);
    int sign = p.rotated ? -1 : 1;
    int u = 2 * p.ui, v = 2 * p.vi;
    if (i == 1 || i == 3) u += sign;
    if (i == 2 || i == 3) v += sign;
    c.ui = uint16_t(u);
    c.vi = uint16_t(v);
    c.rotated = i == 3 ? !p.rotated : p.rotated;
    return c;
}

class Baker {
public:
    Baker(const InputMesh& mesh, const Topology& topology, const EditRegion& edits, int maxDepth,
          const std::string& name, size_t threads, StageClock& clock)
        : mesh_(mesh),
          topology_(topology),
          edits_(edits),
          maxDepth_(maxDepth),
          name_(name),
          threads_(threads),
          clock_(clock) {}

    Status run(Asset& asset, BakeStats* stats, BakeTrace* trace);

private:
    const Far::TopologyLevel& level(int l) const { return topology_.level(l); }
    const Far::TopologyRefiner& refiner(int l) const { return topology_.refiner(l); }
    int local(int l) const { return topology_.local(l); }
    // Refined for a hierarchical edit at a finer level (edit_region.h).
    bool refinedForEdit(int l, OsdIndex face) const {
        return size_t(l) < edits_.refine.size() && edits_.refine[size_t(l)][size_t(face)];
    }
    void fillTrace(BakeTrace& trace) const;
    Status selectCandidates();
    Status selectOnce();
    bool needCandidateAcross(int l, OsdIndex face, int e);
    Status fillLevels(Asset& asset);
    Status fillPatches(int l, Level& out, StageClock& clock, std::vector<StencilOrienter::Cache>& caches);

    const InputMesh& mesh_;
    const Topology& topology_;
    const EditRegion& edits_;
    int maxDepth_;
    std::string name_;
    size_t threads_;  // resolved: at least 1
    StageClock& clock_;
    int levels_ = 0;                                  // levels with topology
    std::vector<std::vector<Candidate>> candidates_;  // per level
    std::vector<std::vector<PatchPoints>> points_;    // per level: the regular candidates' patch points
    std::vector<std::vector<int32_t>> candidateOf_;   // per level: face -> candidate or -1
    std::vector<std::vector<uint8_t>> transition_;    // per level: face refined for a transition
    NeededVertices needed_;                           // step 2
    Numbering numbering_;                             // step 3
    std::optional<StencilOrienter> orienter_;         // explicit stencils' normals face out (built in run)
};

// Candidates, then transitions: a refined face's edge neighbours must be candidates
// of its level, so that its children border patches at most one level coarser
// (NPP split patterns). Far keeps that around its features, but refines the two
// sides of an infinitely sharp edge independently; there the coarser side's patch
// is refined too (it is next to a sharp edge, so Far has refined it: buildRefiner
// does not use infinitely sharp patches), until nothing changes.
Status Baker::selectCandidates() {
    transition_.assign(size_t(maxDepth_) + 1, {});
    for (;;) {
        if (Status st = selectOnce(); !st) return st;
        bool added = false;
        for (int l = 1; l < levels_; ++l)
            for (const Candidate& c : candidates_[l])
                if (!c.regular && l < maxDepth_)
                    for (int e = 0; e < 3; ++e) added |= needCandidateAcross(l, c.face, e);
        if (!added) return Status::ok();
    }
}

// The face across edge `e` of candidate `face` of level `l` must be a candidate of
// level l: else its parent, the face across the same edge of our parent, must be
// refined. Returns whether a face was newly marked for refinement.
bool Baker::needCandidateAcross(int l, OsdIndex face, int e) {
    OsdIndex q = faceAcrossEdge(level(l), face, e);
    if (q >= 0 && (candidateOf_[l][q] >= 0 || level(l).IsFaceHole(q))) return false;
    if (l == 0) return false;  // a hole or a face without a limit surface
    const OsdIndex parent = topology_.parentFace(l, face);
    const auto siblings = level(l - 1).GetFaceChildFaces(parent);
    const int child = int(std::find(siblings.begin(), siblings.end(), face) - siblings.begin());
    if (child == 3 || e == (child + 1) % 3) return false;  // a sibling: always a candidate
    // Child i's edge e (e != i + 1) lies on the parent's edge e.
    OsdIndex r = faceAcrossEdge(level(l - 1), parent, e);
    if (r >= 0 && candidateOf_[l - 1][r] >= 0) {
        Candidate& c = candidates_[l - 1][candidateOf_[l - 1][r]];
        if (!c.regular) return false;
        uint8_t& mark = transition_[l - 1][r];
        bool added = !mark;
        mark = 1;
        return added;
    }
    if (r >= 0 && level(l - 1).IsFaceHole(r)) return false;
    return needCandidateAcross(l - 1, parent, e);
}

Status Baker::selectOnce() {
    levels_ = std::min(maxDepth_, topology_.maxLevel()) + 1;
    candidates_.assign(size_t(maxDepth_) + 1, {});
    points_.assign(size_t(maxDepth_) + 1, {});
    candidateOf_.assign(size_t(maxDepth_) + 1, {});
    bool noBoundary = mesh_.boundary == BoundaryInterpolation::None;
    candidates_[0].reserve(size_t(level(0).GetNumFaces()));
    for (OsdIndex f = 0; f < level(0).GetNumFaces(); ++f) {
        if (level(0).IsFaceHole(f)) continue;
        bool onBoundary = false;
        for (OsdIndex v : level(0).GetFaceVertices(f)) onBoundary |= level(0).IsVertexBoundary(v);
        if (noBoundary && onBoundary) continue;  // no limit surface without boundary rules
        Candidate c;
        c.face = f;
        c.param.baseFace = uint32_t(f);
        candidates_[0].push_back(c);
    }
    for (int l = 0; l < levels_; ++l) {
        const auto& topo = level(l);
        candidateOf_[l].assign(size_t(topo.GetNumFaces()), -1);
        transition_[l].resize(size_t(topo.GetNumFaces()), 0);
        std::vector<Candidate>& cands = candidates_[l];
        for (size_t k = 0; k < cands.size(); ++k) candidateOf_[l][cands[k].face] = int32_t(k);
        // Each thread with a finder of its own (it remembers corner kinds); each range
        // keeps its patches' points, then joined in order.
        struct alignas(64) Found {  // filled by different threads side by side
            std::vector<PatchPoints> points;
        };
        const size_t ranges = fmt::rangeCount(cands.size(), threads_, kFaceGrain);
        std::vector<PatchFinder> finders(std::min(threads_, ranges), PatchFinder(topo));
        std::vector<Found> found(ranges);
        fmt::parallelRanges(cands.size(), threads_, kFaceGrain, [&](size_t r, size_t begin, size_t end, size_t worker) {
            PatchPoints points;
            for (size_t k = begin; k < end; ++k) {
                Candidate& c = cands[k];
                c.regular =
                    finders[worker].regular(c.face, points) && !refinedForEdit(l, c.face) && !transition_[l][c.face];
                if (c.regular) found[r].points.push_back(points);
            }
        });
        size_t regular = 0;
        for (const Found& f : found) regular += f.points.size();
        points_[l].reserve(regular);
        for (Found& f : found) {
            points_[l].insert(points_[l].end(), f.points.begin(), f.points.end());
            release(f.points);
        }
        if (l + 1 >= levels_ && l < maxDepth_) {
            for (const Candidate& c : candidates_[l])
                if (!c.regular)
                    return Status::error(Status::Internal, "level " + std::to_string(l) + " face " +
                                                               std::to_string(c.face) +
                                                               " is irregular but OpenSubdiv did not refine it");
            continue;
        }
        if (l == maxDepth_) break;
        const size_t refined =
            size_t(std::count_if(cands.begin(), cands.end(), [](const Candidate& c) { return !c.regular; }));
        candidates_[l + 1].reserve(4 * refined);
        for (const Candidate& c : candidates_[l]) {
            if (c.regular) continue;
            auto children = topo.GetFaceChildFaces(c.face);
            for (int i = 0; i < 4; ++i) {
                if (children.size() != 4 || children[i] < 0)
                    return Status::error(Status::Internal, "level " + std::to_string(l) + " face " +
                                                               std::to_string(c.face) + " was not refined completely");
                Candidate child;
                child.face = children[i];
                child.param = childParam(c.param, i);
                candidates_[l + 1].push_back(child);
            }
        }
    }
    return Status::ok();
}

Status Baker::fillPatches(int l, Level& out, StageClock& clock, std::vector<StencilOrienter::Cache>& caches) {
    const auto& topo = level(l);
    const auto& g = numbering_.global[l];
    const std::vector<Candidate>& cands = candidates_[l];
    std::vector<OsdIndex> irregular;           // faces of the IPPs, in candidate order
    std::vector<PatchParam> irregularParam;    // their parameters
    std::vector<uint32_t> slot(cands.size());  // a regular candidate's patch
    for (size_t k = 0; k < cands.size(); ++k) {
        slot[k] = uint32_t(k - irregular.size());
        if (cands[k].regular) continue;
        irregular.push_back(cands[k].face);
        irregularParam.push_back(cands[k].param);
    }
    out.regular.resize(cands.size() - irregular.size());
    fmt::parallelFor(cands.size(), threads_, kFaceGrain, [&](size_t k, size_t) {
        const Candidate& c = cands[k];
        if (!c.regular) return;
        RegularPatch& p = out.regular[slot[k]];
        const PatchPoints& points = points_[l][slot[k]];
        for (int i = 0; i < 12; ++i) p.points[i] = g[points.points[i]];
        p.boundaryMask = points.boundaryMask;
        p.param = c.param;
        if (l < maxDepth_) {
            for (int i = 0; i < 3; ++i) {
                OsdIndex n = faceAcrossEdge(topo, c.face, i);
                if (n >= 0 && candidateOf_[l][n] >= 0 && !cands[candidateOf_[l][n]].regular)
                    p.splitMask |= uint8_t(1u << i);
            }
        }
    });
    // The level's candidates are done with (later levels read only the numbering).
    release(candidates_[l]);
    release(points_[l]);
    release(candidateOf_[l]);
    release(slot);
    clock.lap("patches");
    std::vector<uint32_t> corners;
    Status st = buildCornerStencils(topology_, l, maxDepth_, *orienter_, caches, g, irregular, out.limit, corners);
    clock.lap("corner stencils");
    if (!st) return st;
    out.irregular.resize(irregular.size());
    for (size_t k = 0; k < irregular.size(); ++k) {
        IrregularFace& f = out.irregular[k];
        for (int i = 0; i < 3; ++i) f.corners[i] = corners[3 * k + size_t(i)];
        f.param = irregularParam[k];
    }
    return Status::ok();
}

Status Baker::run(Asset& asset, BakeStats* stats, BakeTrace* trace) {
    // The orienter's refined positions (OpenSubdiv's interpolation, level by level,
    // serial) are read first by the corner stencils: they are built beside steps 1
    // to 3, which do not read them, on a thread of their own while those take the
    // other threads (and this one once the orienter is done); beside the needed
    // vertices and numbering alone it was the needed vertices that kept the others
    // waiting.
    // The stage timers run on the first task alone (on one thread the tasks run in
    // order); "refined positions" is what is left to wait for after it.
    Status st;
    fmt::parallelTasks(2, threads_, [&](size_t task, size_t) {
        if (task == 1) {
            orienter_.emplace(topology_, mesh_.positions);
            return;
        }
        st = selectCandidates();
        release(transition_);
        clock_.lap("candidates");
        if (!st) return;
        st = collectNeeded(topology_, levels_, candidates_, points_, threads_, needed_);
        clock_.lap("needed vertices");
        if (!st) return;
        number(topology_, levels_, needed_, threads_, numbering_);
        release(needed_);
        clock_.lap("numbering");
    });
    clock_.lap("refined positions");
    if (!st) return st;

    asset = Asset{};
    asset.positions = mesh_.positions;
    asset.faces = mesh_.faces;
    asset.faceUVs = mesh_.faceUVs;
    asset.boundary = mesh_.boundary;
    asset.creaseMethod = mesh_.creaseMethod;
    asset.levels.resize(size_t(maxDepth_) + 1);
    st = fillLevels(asset);
    if (!st) return st;
    st = fillEdits(mesh_, edits_, numbering_.global, name_, asset.levels);
    clock_.lap("edit tables");
    if (!st) return st;
    if (stats) {
        stats->levels.assign(size_t(maxDepth_) + 1, {});
        for (int l = 0; l <= maxDepth_; ++l) {
            LevelStats& s = stats->levels[l];
            const Level& lv = asset.levels[l];
            s.vertices = l == 0 ? asset.controlVertexCount() : lv.refinement.vertexCount();
            for (const auto& p : lv.regular) (p.splitMask ? s.npp : s.rpp)++;
            s.ipp = uint32_t(lv.irregular.size());
            s.limitStencils = lv.limit.count();
        }
    }
    if (trace) fillTrace(*trace);
    return Status::ok();
}

// Each level's refinement table (from level l - 1; none at level 0), regular
// patches and corner stencils. They read only the numbering, the level's
// candidates and the orienter, and write the level's own tables, so levels run two
// at a time, each taking the threads the other leaves idle (parallel.h): the serial
// parts of one level's stages no longer keep the other threads waiting. More levels
// at once would multiply the bake's largest transient, a level's sector stencils.
// Each level's stages are timed on a clock of its own and added up in level order
// (on several threads they add up to more than the wall time).
Status Baker::fillLevels(Asset& asset) {
    constexpr size_t kLevelsAtOnce = 2;
    const size_t levels = size_t(levels_), workers = std::min(std::min(threads_, kLevelsAtOnce), levels);
    std::vector<Status> status(levels);
    std::vector<BakeStats> stages(levels);
    std::vector<std::vector<StencilOrienter::Cache>> caches(workers, std::vector<StencilOrienter::Cache>(threads_));
    fmt::parallelTasks(levels, workers, [&](size_t l, size_t worker) {
        StageClock clock(clock_.timing() ? &stages[l] : nullptr);
        Level& out = asset.levels[l];
        if (l >= 1 && !numbering_.order[l].empty()) {
            status[l] = buildRefinement(topology_, int(l), numbering_.global[l - 1], numbering_.global[l],
                                        numbering_.order[l], numbering_.pointCount[l], threads_, out.refinement);
            clock.lap("refinement tables");
            if (!status[l]) return;
        }
        status[l] = fillPatches(int(l), out, clock, caches[worker]);
    });
    for (size_t l = 0; l < levels; ++l) {
        if (!status[l]) return status[l];
        for (const BakeStats::Stage& stage : stages[l].stages) clock_.add(stage.name, stage.seconds);
    }
    clock_.restart();
    // Levels without topology past the deepest refined one: empty, numbered on.
    uint32_t total = mesh_.vertexCount();
    for (int l = 1; l <= maxDepth_; ++l) {
        Refinement& r = asset.levels[l].refinement;
        if (size_t(l) >= levels || numbering_.order[l].empty()) {
            r.firstVertex = total;
            r.vertexRingStart.clear();
        }
        total = r.firstVertex + r.vertexCount();
    }
    return Status::ok();
}

void Baker::fillTrace(BakeTrace& trace) const {
    trace = BakeTrace{};
    // Each face's sub-triangle path, level by level through the child links.
    std::vector<std::pair<uint32_t, std::vector<uint8_t>>> path(size_t(level(0).GetNumFaces())), next;
    for (OsdIndex f = 0; f < level(0).GetNumFaces(); ++f) path[size_t(f)].first = uint32_t(f);
    for (int l = 0; l < levels_; ++l) {
        const auto& topo = level(l);
        for (OsdIndex v : numbering_.order[l]) {
            trace.osdLevel.push_back(uint32_t(l));
            trace.osdVertex.push_back(uint32_t(v));
            auto faces = topo.GetVertexFaces(v);
            OsdIndex f = faces.empty() ? -1 : faces[0];
            trace.face.push_back(f < 0 ? ~0u : path[size_t(f)].first);
            trace.path.push_back(f < 0 ? std::vector<uint8_t>{} : path[size_t(f)].second);
            trace.corner.push_back(uint8_t(f < 0 ? 0 : localIndex(topo, f, v)));
        }
        if (l + 1 >= levels_) break;
        next.assign(size_t(level(l + 1).GetNumFaces()), {~0u, {}});
        for (OsdIndex f = 0; f < topo.GetNumFaces(); ++f) {
            auto children = topo.GetFaceChildFaces(f);
            for (int i = 0; i < children.size(); ++i) {
                if (children[i] < 0) continue;
                auto& c = next[size_t(children[i])];
                c = path[size_t(f)];
                c.second.push_back(uint8_t(i));
            }
        }
        path.swap(next);
    }
}

}  // namespace

Status bakeTraced(const InputMesh& mesh, const BakeSettings& settings, Asset& asset, BakeStats* stats,
                  BakeTrace* trace) {
    if (settings.maxDepth < 0 || settings.maxDepth > 8)
        return Status::error(Status::Usage,
                             "max depth " + std::to_string(settings.maxDepth) + " is not in 1..8 (or 0: automatic)");
    auto start = std::chrono::steady_clock::now();
    if (stats) stats->stages.clear();
    StageClock clock(stats);
    Status st = checkLimits(mesh, settings.limits, settings.name);
    clock.lap("limits");
    if (!st) return st;
    // Depth and memory: estimated on the unrefined topology, refused before refining.
    const int editDepth = int(mesh.editDepth());
    if (settings.maxDepth > 0 && editDepth > settings.maxDepth) {
        for (size_t i = 0; i < mesh.edits.size(); ++i)
            if (int(mesh.edits[i].path.size()) > settings.maxDepth)
                return Status::error(Status::BadInput, settings.name + ": vertex edit " + std::to_string(i) + " (" +
                                                           editName(mesh.edits[i]) + ") is at level " +
                                                           std::to_string(mesh.edits[i].path.size()) +
                                                           ", deeper than the maximum depth " +
                                                           std::to_string(settings.maxDepth) + " (raise --max-depth)");
    }
    MemoryStats memory;
    int depth = settings.maxDepth;
    std::string reason;
    auto chooseHook = [&](const Far::TopologyRefiner& unrefined, int& maxDepth) {
        Status chosen = chooseDepth(unrefined.GetLevel(0), settings, editDepth, depth, memory, reason);
        maxDepth = depth;
        return chosen;
    };
    Topology topology;
    const int deepest = settings.maxDepth > 0 ? settings.maxDepth : std::max(kDefaultMaxDepth, editDepth);
    st = buildTopology(mesh, deepest, editDepth, settings.name, topology, chooseHook);
    clock.lap("refiner (OpenSubdiv)");
    if (stats) {
        stats->memory = memory;
        stats->depth = depth;
        stats->depthLowered = settings.maxDepth == 0 && depth < kDefaultMaxDepth;
        stats->depthReason = reason;
    }
    if (!st) return st;
    for (int l = 1; l <= topology.maxLevel(); ++l) memory.refinedFaces += uint64_t(topology.level(l).GetNumFaces());
    EditRegion edits;
    st = planEdits(mesh, topology, settings.name, edits);
    clock.lap("edit plan");
    if (!st) return st;
    Baker baker(mesh, topology, edits, depth, settings.name, fmt::threadCount(settings.threads), clock);
    st = baker.run(asset, stats, trace);
    if (stats) stats->memory = memory;
    if (stats) stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return st;
}

Status bake(const InputMesh& mesh, const BakeSettings& settings, Asset& asset, BakeStats* stats) {
    return bakeTraced(mesh, settings, asset, stats, nullptr);
}

}  // namespace lt
