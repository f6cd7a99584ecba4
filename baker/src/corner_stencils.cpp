// corner_stencils.cpp -- the limit stencils of a level's IPP corners (corner_stencils.h).
#include "corner_stencils.h"

#include "face_corner.h"

#include "parallel.h"

#include <algorithm>
#include <cassert>
#include <string>
#include <tuple>

namespace lt {

namespace {

// Corners a thread range takes at least: each costs a limit stencil or more.
constexpr size_t kCornerGrain = 64;
constexpr uint32_t kNoSector = ~0u;

struct Corner {
    uint32_t global;
    OsdIndex sector, own, vertex, face;  // own: the face whose corner is the stencil, or -1
    int ownLevel = kFaceCornerLevel;     // the level own's corner is refined to
    uint32_t shared = 0;                 // its sector's stencil (index into the sectors)
    auto key() const { return std::make_tuple(global, sector, own); }
    bool operator<(const Corner& o) const { return key() < o.key(); }
    bool operator==(const Corner& o) const { return key() == o.key(); }
};

// A face's corner while its stencil is chosen (faces[i / 3]'s corner i % 3): 16
// bytes, where a Corner takes 28 (5.6M face corners at the 1M-triangle scan's
// level 1, beside its sector stencils).
struct FaceCorner {
    enum Own : uint8_t {
        kShares,      // the sector's stencil
        kSpike,       // its own: no tangent plane by topology, at the deepest level drawn
        kDegenerate,  // its own: the sector's tangents degenerate, at kFaceCornerLevel
    };
    OsdIndex vertex, sector;
    uint32_t shared = 0;  // as Corner::shared
    Own own = kShares;
};
static_assert(sizeof(FaceCorner) == 16);

// The emitted stencils of one range of corners, CSR ends relative to the range.
// Cache-line aligned: neighbouring parts are filled by different threads.
struct alignas(64) Part {
    std::vector<uint32_t> ring, ringEnd, masked, maskEnd;
    std::vector<float> position, tangentU, tangentV;
    OsdIndex refused = -1;  // the first vertex whose 1-ring OpenSubdiv refused
};

// Frees `v`'s memory now (clear() keeps the capacity): a level's sector stencils
// are the bake's largest transient, so nothing else should sit beside them longer
// than it must.
template <typename T>
void release(T& v) {
    T().swap(v);
}

// A level's sector stencils, flat: a LimitStencil each would be four vectors and a
// heap block of its own (1.6M sectors at the 1M-triangle scan's level 1, where the
// bake peaks). Sector s reads points_ [start_[s], start_[s + 1]); where it has
// weights of its own (not smooth: smooth ones are implied, limit.h) they run
// parallel to its points from weightAt_[s] in position_, tangentU_ and tangentV_.
//
//   sector:     0                 1           2
//   points_:    v a b c d e f     v a b c     v a b c d e f g     ...
//   start_:     0                 7           11                  19
//   weightAt_:  kImplied          0           kImplied
//
// Cache-line aligned: the parts of one computation are filled by different threads.
class alignas(64) SectorStencils {
public:
    size_t size() const { return sector_.size(); }
    // Sector s's ring points (its vertex excepted).
    size_t ringSize(size_t s) const { return start_[s + 1] - start_[s] - 1; }
    // Sector s as limitStencil gave it, into `out` (its buffers reused).
    void get(size_t s, LimitStencil& out) const {
        out.points.assign(points_.begin() + start_[s], points_.begin() + start_[s + 1]);
        out.sector = sector_[s];
        out.smooth = smooth_[s] != 0;
        const size_t n = out.points.size(), at = weightAt_[s];
        for (auto [from, to] : {std::pair(&position_, &out.position), std::pair(&tangentU_, &out.tangentU),
                                std::pair(&tangentV_, &out.tangentV)}) {
            if (at == kImplied)
                to->clear();
            else
                to->assign(from->begin() + ptrdiff_t(at), from->begin() + ptrdiff_t(at + n));
        }
    }
    // Sector s's tangentV, from `stencil` (sector s, oriented).
    void setTangentV(size_t s, const LimitStencil& stencil) {
        if (weightAt_[s] != kImplied)
            std::copy(stencil.tangentV.begin(), stencil.tangentV.end(), tangentV_.begin() + ptrdiff_t(weightAt_[s]));
    }
    void append(const LimitStencil& stencil) {
        assert(stencil.position.empty() ||
               (stencil.position.size() == stencil.points.size() && stencil.tangentU.size() == stencil.points.size() &&
                stencil.tangentV.size() == stencil.points.size()));
        sector_.push_back(stencil.sector);
        smooth_.push_back(stencil.smooth);
        points_.insert(points_.end(), stencil.points.begin(), stencil.points.end());
        start_.push_back(uint32_t(points_.size()));
        weightAt_.push_back(stencil.position.empty() ? kImplied : uint32_t(position_.size()));
        position_.insert(position_.end(), stencil.position.begin(), stencil.position.end());
        tangentU_.insert(tangentU_.end(), stencil.tangentU.begin(), stencil.tangentU.end());
        tangentV_.insert(tangentV_.end(), stencil.tangentV.begin(), stencil.tangentV.end());
    }
    // The stencils of `parts` appended in order, each freed once copied (reserved to
    // the exact size: no growth by doubling).
    void concatenate(std::vector<SectorStencils>& parts) {
        size_t sectors = 0, points = 0, weights = 0;
        for (const SectorStencils& p : parts)
            sectors += p.size(), points += p.points_.size(), weights += p.position_.size();
        sector_.reserve(sectors);
        smooth_.reserve(sectors);
        weightAt_.reserve(sectors);
        start_.reserve(sectors + 1);
        points_.reserve(points);
        for (std::vector<double>* w : {&position_, &tangentU_, &tangentV_}) w->reserve(weights);
        for (SectorStencils& p : parts) {
            const uint32_t pointBase = uint32_t(points_.size()), weightBase = uint32_t(position_.size());
            sector_.insert(sector_.end(), p.sector_.begin(), p.sector_.end());
            smooth_.insert(smooth_.end(), p.smooth_.begin(), p.smooth_.end());
            for (uint32_t at : p.weightAt_) weightAt_.push_back(at == kImplied ? kImplied : weightBase + at);
            for (size_t k = 1; k < p.start_.size(); ++k) start_.push_back(pointBase + p.start_[k]);
            points_.insert(points_.end(), p.points_.begin(), p.points_.end());
            position_.insert(position_.end(), p.position_.begin(), p.position_.end());
            tangentU_.insert(tangentU_.end(), p.tangentU_.begin(), p.tangentU_.end());
            tangentV_.insert(tangentV_.end(), p.tangentV_.begin(), p.tangentV_.end());
            p = SectorStencils{};
        }
    }

private:
    static constexpr uint32_t kImplied = ~0u;
    std::vector<OsdIndex> points_, sector_;
    std::vector<uint32_t> start_{0}, weightAt_;
    std::vector<uint8_t> smooth_;
    std::vector<double> position_, tangentU_, tangentV_;
};

// Appends `stencil` (of global vertex `g`'s numbering) to `part` as corner `index`
// of its range: the ring from the neighbour with the smallest global index; the
// vertex's own weight (entry 0) is implied by affinity.
void emit(const LimitStencil& stencil, const std::vector<uint32_t>& g, uint32_t index, Part& part) {
    size_t n = stencil.points.size() - 1, first = 0;
    for (size_t k = 1; k < n; ++k)
        if (g[stencil.points[1 + k]] < g[stencil.points[1 + first]]) first = k;
    for (size_t k = 0; k < n; ++k) part.ring.push_back(g[stencil.points[1 + (first + k) % n]]);
    part.ringEnd.push_back(uint32_t(part.ring.size()));
    if (stencil.smooth) return;
    part.masked.push_back(index);
    for (size_t k = 0; k < n; ++k) {
        size_t w = 1 + (first + k) % n;
        part.position.push_back(float(stencil.position[w]));
        part.tangentU.push_back(float(stencil.tangentU[w]));
        part.tangentV.push_back(float(stencil.tangentV[w]));
    }
    part.maskEnd.push_back(uint32_t(part.position.size()));
}

}  // namespace

Status buildCornerStencils(const Topology& topology, int l, int maxDepth, const StencilOrienter& orienter,
                           std::vector<StencilOrienter::Cache>& caches, const std::vector<uint32_t>& g,
                           const std::vector<OsdIndex>& faces, LimitStencils& ls, std::vector<uint32_t>& cornerOf) {
    const Far::TopologyLevel& topo = topology.level(l);
    const Far::TopologyRefiner& refiner = topology.refiner(l);
    const int local = topology.local(l);
    const size_t threads = caches.size();
    // Every stage below runs per face, sector or corner, each writing its own slot.
    std::vector<FaceCorner> faceCorners(3 * faces.size());
    fmt::parallelFor(faces.size(), threads, kCornerGrain, [&](size_t i, size_t) {
        const OsdIndex face = faces[i];
        auto fv = topo.GetFaceVertices(face);
        for (int k = 0; k < 3; ++k) {
            const OsdIndex v = fv[k];
            // No tangent plane by topology: a spike whose limit lies below float
            // resolution; the face's corner at the deepest level drawn (spec).
            const FaceCorner::Own own =
                tangentPlaneAt(refiner, local, v, face) ? FaceCorner::kShares : FaceCorner::kSpike;
            faceCorners[3 * i + size_t(k)] = {v, limitSector(refiner, local, v, face), 0, own};
        }
    });
    auto faceOf = [&](size_t i) { return faces[i / 3]; };
    // Face corner i's key and stencil.
    auto corner = [&](size_t i) {
        const FaceCorner& c = faceCorners[i];
        const OsdIndex own = c.own == FaceCorner::kShares ? -1 : faceOf(i);
        const int ownLevel = c.own == FaceCorner::kSpike ? maxDepth : kFaceCornerLevel;
        return Corner{g[c.vertex], c.sector, own, c.vertex, faceOf(i), ownLevel, c.shared};
    };
    // The sectors' stencils, numbered in face order of first use and each computed
    // at its first corner; a slit's (no normal on the baked positions) gives each of
    // its faces one of its own. Most corners are in their vertex's only sector (-1),
    // numbered through a table per vertex; the others (creases, boundaries, sheets)
    // through their group's first corner, found by one sort of their indices by
    // (vertex, sector, index).
    std::vector<uint32_t> open;  // corners in open sectors; each one's `shared` is first its group's first corner
    for (size_t i = 0; i < faceCorners.size(); ++i)
        if (faceCorners[i].sector >= 0) open.push_back(uint32_t(i));
    std::sort(open.begin(), open.end(), [&](uint32_t a, uint32_t b) {
        const FaceCorner &x = faceCorners[a], &y = faceCorners[b];
        return std::tie(x.vertex, x.sector, a) < std::tie(y.vertex, y.sector, b);
    });
    for (size_t k = 0, first = 0; k < open.size(); ++k) {
        const FaceCorner& c = faceCorners[open[k]];
        if (c.vertex != faceCorners[open[first]].vertex || c.sector != faceCorners[open[first]].sector) first = k;
        faceCorners[open[k]].shared = open[first];
    }
    release(open);
    std::vector<uint32_t> closedSector(size_t(topo.GetNumVertices()), kNoSector);
    std::vector<size_t> firstCorner;
    for (size_t i = 0; i < faceCorners.size(); ++i) {
        FaceCorner& c = faceCorners[i];
        if (c.sector >= 0) {
            if (c.shared != i) {
                c.shared = faceCorners[c.shared].shared;  // numbered already: the group's first corner comes first
                continue;
            }
        } else if (closedSector[size_t(c.vertex)] != kNoSector) {
            c.shared = closedSector[size_t(c.vertex)];
            continue;
        } else {
            closedSector[size_t(c.vertex)] = uint32_t(firstCorner.size());
        }
        c.shared = uint32_t(firstCorner.size());
        firstCorner.push_back(i);
    }
    release(closedSector);
    SectorStencils sectors;
    {
        std::vector<SectorStencils> parts(fmt::rangeCount(firstCorner.size(), threads, kCornerGrain));
        fmt::parallelRanges(firstCorner.size(), threads, kCornerGrain, [&](size_t r, size_t begin, size_t end, size_t) {
            LimitStencil stencil;
            for (size_t s = begin; s < end; ++s) {
                const size_t i = firstCorner[s];
                limitStencil(refiner, local, faceCorners[i].vertex, faceOf(i), stencil, /*smoothWeights=*/false);
                parts[r].append(stencil);
            }
        });
        release(firstCorner);
        sectors.concatenate(parts);
    }
    std::vector<LimitStencil> scratch(threads);  // a sector's stencil, per thread
    // Degeneracy, judged once per sector at its first corner that would share the
    // sector's stencil: its verdict is the sector's (orient.h: by the vertex and the
    // sector it comes from), so every face corner of the sector takes it.
    std::vector<size_t> judged(sectors.size(), faceCorners.size());
    for (size_t i = faceCorners.size(); i-- > 0;)
        if (faceCorners[i].own == FaceCorner::kShares) judged[faceCorners[i].shared] = i;
    std::vector<uint8_t> degenerate(sectors.size(), 0);
    fmt::parallelFor(sectors.size(), threads, kCornerGrain, [&](size_t s, size_t worker) {
        if (judged[s] == faceCorners.size()) return;
        const size_t i = judged[s];
        sectors.get(s, scratch[worker]);
        degenerate[s] = orienter.degenerate(l, faceCorners[i].vertex, faceOf(i), scratch[worker], caches[worker]);
    });
    release(judged);
    // The corners that keep the sector's stencil, and those with their own, one
    // entry per distinct key.
    // Counted first, so that `corners` is allocated once at its size.
    std::vector<uint8_t> kept(sectors.size(), 0);  // 1: kept; 2: and its corner taken
    size_t count = 0;
    for (FaceCorner& c : faceCorners) {
        if (c.own == FaceCorner::kShares && degenerate[c.shared]) c.own = FaceCorner::kDegenerate;
        if (c.own != FaceCorner::kShares)
            ++count;
        else if (!kept[c.shared])
            kept[c.shared] = 1, ++count;
    }
    release(degenerate);
    std::vector<Corner> corners;  // unique keys, in the stencils' order
    corners.reserve(count);
    for (size_t i = 0; i < faceCorners.size(); ++i) {
        const FaceCorner& c = faceCorners[i];
        if (c.own != FaceCorner::kShares)
            corners.push_back(corner(i));
        else if (kept[c.shared] == 1)
            kept[c.shared] = 2, corners.push_back(corner(i));
    }
    // Orient the sector stencils that some face uses for its normal.
    fmt::parallelFor(sectors.size(), threads, kCornerGrain, [&](size_t s, size_t worker) {
        if (!kept[s]) return;
        sectors.get(s, scratch[worker]);
        orienter.orient(l, scratch[worker], caches[worker]);
        sectors.setTangentV(s, scratch[worker]);
    });
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    // Each face corner's stencil, now, so that the face corners are freed before the
    // stencils are emitted beside the sectors.
    std::vector<uint32_t> sectorCorner(sectors.size(), 0);  // a kept sector's entry in `corners`
    for (size_t k = 0; k < corners.size(); ++k)
        if (corners[k].own < 0) sectorCorner[corners[k].shared] = uint32_t(k);
    cornerOf.resize(faceCorners.size());
    fmt::parallelFor(faceCorners.size(), threads, kCornerGrain, [&](size_t i, size_t) {
        const FaceCorner& c = faceCorners[i];
        cornerOf[i] = c.own == FaceCorner::kShares
                          ? sectorCorner[c.shared]
                          : uint32_t(std::lower_bound(corners.begin(), corners.end(), corner(i)) - corners.begin());
    });
    release(sectorCorner);
    release(kept);
    release(faceCorners);
    // Each range of corners emits into a part of its own; the parts are then
    // concatenated in order.
    const uint32_t base = ls.count();
    std::vector<Part> parts(fmt::rangeCount(corners.size(), threads, kCornerGrain));
    fmt::parallelRanges(corners.size(), threads, kCornerGrain, [&](size_t r, size_t begin, size_t end, size_t worker) {
        Part& part = parts[r];
        size_t ring = 0;  // about the range's ring entries (a face's own stencil may read others)
        for (size_t i = begin; i < end; ++i) ring += sectors.ringSize(corners[i].shared);
        part.ring.reserve(ring);
        part.ringEnd.reserve(end - begin);
        LimitStencil sector, own, shared;
        for (size_t i = begin; i < end; ++i) {
            const Corner& c = corners[i];
            sectors.get(c.shared, sector);
            const LimitStencil* stencil = &sector;
            if (c.own >= 0) {
                if (!orienter.faceStencil(l, c.vertex, c.own, c.ownLevel, maxDepth, withWeights(sector, shared), own,
                                          caches[worker])) {
                    part.refused = c.vertex;
                    return;
                }
                stencil = &own;
            }
            emit(*stencil, g, base + uint32_t(i), part);
        }
    });
    sectors = SectorStencils{};
    // Exact sizes: no growth by doubling, whose old and new blocks would coexist.
    size_t ring = 0, ends = 0, masked = 0, maskEnds = 0, weights = 0;
    for (const Part& part : parts) {
        if (part.refused >= 0)
            return Status::error(Status::Internal, "OpenSubdiv refused the 1-ring of level " + std::to_string(l) +
                                                       " vertex " + std::to_string(part.refused));
        ring += part.ring.size();
        ends += part.ringEnd.size();
        masked += part.masked.size();
        maskEnds += part.maskEnd.size();
        weights += part.position.size();
    }
    ls.vertex.reserve(ls.vertex.size() + corners.size());
    ls.start.reserve(ls.start.size() + 1 + ends);
    ls.ring.reserve(ls.ring.size() + ring);
    ls.masked.reserve(ls.masked.size() + masked);
    ls.maskStart.reserve(ls.maskStart.size() + 1 + maskEnds);
    for (std::vector<float>* w : {&ls.position, &ls.tangentU, &ls.tangentV}) w->reserve(w->size() + weights);
    for (const Corner& c : corners) ls.vertex.push_back(c.global);
    ls.start.push_back(0);
    for (Part& part : parts) {
        const uint32_t ringBase = uint32_t(ls.ring.size()), weightBase = uint32_t(ls.position.size());
        ls.ring.insert(ls.ring.end(), part.ring.begin(), part.ring.end());
        for (uint32_t end : part.ringEnd) ls.start.push_back(ringBase + end);
        if (!part.masked.empty() && ls.masked.empty()) ls.maskStart.push_back(0);
        ls.masked.insert(ls.masked.end(), part.masked.begin(), part.masked.end());
        for (uint32_t end : part.maskEnd) ls.maskStart.push_back(weightBase + end);
        ls.position.insert(ls.position.end(), part.position.begin(), part.position.end());
        ls.tangentU.insert(ls.tangentU.end(), part.tangentU.begin(), part.tangentU.end());
        ls.tangentV.insert(ls.tangentV.end(), part.tangentV.begin(), part.tangentV.end());
        part = Part{};
    }
    if (ls.count() == 0) ls.start.clear();
    return Status::ok();
}

}  // namespace lt
