// The tables buffer of the Vulkan path (see gpu_tables.h, shaders/gpu_layout.h).
#include "vulkan/gpu_tables.h"

#include "vulkan/draw_plan.h"

#include "lod.h"
#include "sub_patches.h"
#include "subdivide_rules.h"
#include "watertight.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

namespace lt {
namespace {

static_assert(uint32_t(EditOp::Set) == LT_EDIT_SET && uint32_t(EditOp::Add) == LT_EDIT_ADD &&
                  uint32_t(EditOp::Subtract) == LT_EDIT_SUBTRACT,
              "edit ops as apply_edits.comp reads them");

uint32_t floatBits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

// Appends arrays to the word buffer and hands back their offsets.
class Writer {
public:
    explicit Writer(std::vector<uint32_t>& words) : w_(words) {}

    uint32_t size() const { return uint32_t(w_.size()); }
    void set(uint32_t at, uint32_t value) { w_[at] = value; }
    uint32_t get(uint32_t at) const { return w_[at]; }

    uint32_t reserve(size_t n, uint32_t fill = 0) {
        grow(n);
        uint32_t at = size();
        w_.resize(w_.size() + n, fill);
        return at;
    }
    uint32_t append(const std::vector<uint32_t>& v) {
        uint32_t at = reserve(v.size());
        std::copy(v.begin(), v.end(), w_.begin() + at);
        return at;
    }
    uint32_t appendFloats(const std::vector<float>& v) {
        uint32_t at = reserve(v.size());
        for (size_t i = 0; i < v.size(); ++i) w_[at + i] = floatBits(v[i]);
        return at;
    }
    // A CSR start array rebased onto an array stored at `base`.
    uint32_t appendStarts(const std::vector<uint32_t>& start, uint32_t base) {
        uint32_t at = reserve(start.size());
        for (size_t i = 0; i < start.size(); ++i) w_[at + i] = base + start[i];
        return at;
    }

private:
    // Offsets are 32-bit words: refuse to grow past 2^32 - 1 (caught by buildGpuTables).
    void grow(size_t n) {
        if (n > size_t(std::numeric_limits<uint32_t>::max()) - w_.size()) throw std::length_error("tables");
    }
    std::vector<uint32_t>& w_;
};

uint32_t packUV(const PatchParam& p) { return uint32_t(p.ui) | uint32_t(p.vi) << 16; }
uint32_t packInfo(const PatchParam& p, uint8_t boundaryMask) {
    return uint32_t(boundaryMask) | uint32_t(p.level) << 8 | uint32_t(p.rotated ? 1 : 0) << 16;
}

// Smooth vertex rule: ring weight per valence, for the valences the asset uses.
uint32_t smoothEdgeTable(const Asset& asset, Writer& w) {
    std::vector<float> table;
    for (size_t l = 1; l < asset.levels.size(); ++l) {
        const Refinement& r = asset.levels[l].refinement;
        size_t mask = 0;
        for (uint32_t i = 0; i < r.vertexPointCount(); ++i) {
            if (mask < r.maskedVertex.size() && r.maskedVertex[mask] == i) {
                ++mask;
                continue;
            }
            uint32_t n = r.vertexRingStart[i + 1] - r.vertexRingStart[i];
            if (n >= table.size()) table.resize(n + 1, -1.0f);
            if (table[n] == -1.0f) table[n] = loopSmoothWeights(n).edge;
        }
    }
    for (float& x : table)
        if (x == -1.0f) x = 0.0f;
    if (table.empty()) table.push_back(0.0f);
    return w.appendFloats(table);
}

// Smooth limit masks: (position weight, tangent pairs offset) per valence.
uint32_t smoothLimitTable(const Asset& asset, Writer& w) {
    std::map<uint32_t, SmoothLimitWeights> used;
    for (const Level& level : asset.levels) {
        const LimitStencils& ls = level.limit;
        size_t m = 0;
        for (uint32_t i = 0; i < ls.count(); ++i) {
            if (m < ls.masked.size() && ls.masked[m] == i) {
                ++m;
                continue;
            }
            uint32_t n = ls.start[i + 1] - ls.start[i];
            if (!used.count(n)) used.emplace(n, loopSmoothLimitWeights(n));
        }
    }
    uint32_t maxValence = used.empty() ? 0 : used.rbegin()->first;
    uint32_t table = w.reserve(2 * size_t(maxValence + 1));
    for (const auto& [n, sw] : used) {
        uint32_t pairs = w.reserve(2 * size_t(n));
        for (uint32_t k = 0; k < n; ++k) {
            w.set(pairs + 2 * k, floatBits(sw.tangentU[k]));
            w.set(pairs + 2 * k + 1, floatBits(sw.tangentV[k]));
        }
        w.set(table + 2 * n, floatBits(sw.position));
        w.set(table + 2 * n + 1, pairs);
    }
    return table;
}

// --- the displacement map (gpu_layout.h's LT_D_*) -------------------------------------

// The displacement block, or LT_NONE without a map. The caller has checked that
// sample indices fit 32 bits (the shaders index with uint).
uint32_t displacementTable(const Asset& asset, Writer& w) {
    const DisplacementMap& m = asset.displacement;
    if (!m.present()) return LT_NONE;
    const uint32_t R = m.resolution, faces = asset.faceCount();
    const uint32_t block = w.reserve(LT_D_SIZE);
    w.set(block + LT_D_RESOLUTION, R);
    w.set(block + LT_D_SCALE, floatBits(m.scale));
    w.set(block + LT_D_BIAS, floatBits(m.bias));
    w.set(block + LT_D_VERTICES, asset.controlVertexCount());
    w.set(block + LT_D_EDGE_BASE, uint32_t(asset.controlVertexCount() + uint64_t(faces) * ((R - 1) * (R - 2) / 2)));
    const uint32_t perFace = w.reserve(LT_D_FACE_WORDS * size_t(faces));
    for (uint32_t f = 0; f < faces; ++f)
        for (uint32_t k = 0; k < 3; ++k) {
            w.set(perFace + LT_D_FACE_WORDS * f + k, asset.faces[3 * size_t(f) + k]);
            w.set(perFace + LT_D_FACE_WORDS * f + 3 + k, m.faceEdges[3 * size_t(f) + k]);
        }
    w.set(block + LT_D_FACES, perFace);
    const uint32_t samples = w.reserve((m.values.size() + 1) / 2);  // zero-filled
    for (size_t k = 0; k < m.values.size(); ++k)
        w.set(samples + uint32_t(k >> 1), w.get(samples + uint32_t(k >> 1)) | uint32_t(m.values[k]) << (16 * (k & 1)));
    w.set(block + LT_D_SAMPLES, samples);
    return block;
}

void refinementTables(const Refinement& r, uint32_t header, Writer& w) {
    w.set(header + LT_L_FIRST_VERTEX, r.firstVertex);
    w.set(header + LT_L_VP_COUNT, r.vertexPointCount());
    w.set(header + LT_L_VP_PARENT, w.append(r.vertexParent));
    uint32_t ring = w.append(r.vertexRing);
    w.set(header + LT_L_VP_RING_START,
          r.vertexRingStart.empty() ? w.reserve(1) : w.appendStarts(r.vertexRingStart, ring));
    uint32_t masks = w.appendFloats(r.maskWeights);
    uint32_t perPoint = w.reserve(r.vertexPointCount(), LT_NONE);
    for (size_t k = 0; k < r.maskedVertex.size(); ++k) w.set(perPoint + r.maskedVertex[k], masks + r.maskStart[k]);
    w.set(header + LT_L_VP_WEIGHTS, perPoint);

    w.set(header + LT_L_EP_COUNT, r.edgePointCount());
    w.set(header + LT_L_EP_VERTS, w.append(r.edgeVerts));
    uint32_t perEdge = w.reserve(r.edgePointCount(), LT_NONE);
    uint32_t pairs = w.reserve(2 * r.creaseEdge.size());
    for (size_t k = 0; k < r.creaseEdge.size(); ++k) {
        EdgeWeights ew = edgeWeights(r.creaseWeight[k]);
        w.set(pairs + 2 * uint32_t(k), floatBits(ew.ends));
        w.set(pairs + 2 * uint32_t(k) + 1, floatBits(ew.opposite));
        w.set(perEdge + r.creaseEdge[k], pairs + 2 * uint32_t(k));
    }
    w.set(header + LT_L_EP_WEIGHTS, perEdge);
}

void limitTables(const LimitStencils& ls, uint32_t header, Writer& w) {
    w.set(header + LT_L_LS_COUNT, ls.count());
    w.set(header + LT_L_LS_VERTEX, w.append(ls.vertex));
    uint32_t ring = w.append(ls.ring);
    w.set(header + LT_L_LS_RING_START, ls.start.empty() ? w.reserve(1) : w.appendStarts(ls.start, ring));
    uint32_t perStencil = w.reserve(ls.count(), LT_NONE);
    for (size_t k = 0; k < ls.masked.size(); ++k) {
        uint32_t st = ls.masked[k], n = ls.start[st + 1] - ls.start[st], from = ls.maskStart[k];
        uint32_t block = w.reserve(3 * size_t(n));  // wP[n], wU[n], wV[n]
        for (uint32_t j = 0; j < n; ++j) {
            w.set(block + j, floatBits(ls.position[from + j]));
            w.set(block + n + j, floatBits(ls.tangentU[from + j]));
            w.set(block + 2 * n + j, floatBits(ls.tangentV[from + j]));
        }
        w.set(perStencil + st, block);
    }
    w.set(header + LT_L_LS_WEIGHTS, perStencil);
}

// Level `l`'s edited vertices and their CSR starts rebased to the flat edit order
// (`first`: the level's first flat edit).
void editTables(const VertexEdits& e, uint32_t header, uint32_t first, Writer& w) {
    w.set(header + LT_L_ED_COUNT, uint32_t(e.vertex.size()));
    w.set(header + LT_L_ED_VERTEX, w.append(e.vertex));
    w.set(header + LT_L_ED_START, e.start.empty() ? w.reserve(1, first) : w.appendStarts(e.start, first));
}

// The ops of every edit in the flat order (EDIT_OPS), and room for their values
// (EDIT_VALUES, filled with the baked ones; the surface rewrites them every frame).
void editGlobals(const Asset& asset, Writer& w, GpuTables& out) {
    std::vector<uint32_t> ops;
    std::vector<float> values;
    for (const Level& level : asset.levels) {
        for (EditOp op : level.edits.op) ops.push_back(uint32_t(op));
        values.insert(values.end(), level.edits.value.begin(), level.edits.value.end());
    }
    w.set(LT_H_EDIT_OPS, w.append(ops));
    out.editValues = w.appendFloats(values);
    w.set(LT_H_EDIT_VALUES, out.editValues);
    out.editCount = uint32_t(ops.size());
}

uint32_t irregularTables(const std::vector<IrregularFace>& faces, Writer& w) {
    uint32_t at = w.reserve(LT_IRR_WORDS * faces.size());
    for (size_t f = 0; f < faces.size(); ++f) {
        const IrregularFace& face = faces[f];
        uint32_t base = at + uint32_t(LT_IRR_WORDS * f);
        for (int c = 0; c < 3; ++c) w.set(base + c, face.corners[c]);
        w.set(base + LT_IRR_FACE, face.param.baseFace);
        w.set(base + LT_IRR_UV, packUV(face.param));
        w.set(base + LT_IRR_INFO, packInfo(face.param, 0));
    }
    return at;
}

uint32_t record(uint32_t patch, const SubTriangle& q) {
    return patch | uint32_t(q.p[0]) << LT_RECORD_PATCH_BITS | uint32_t(q.p[1]) << (LT_RECORD_PATCH_BITS + 3) |
           uint32_t(q.p[2]) << (LT_RECORD_PATCH_BITS + 6);
}

// Ranks of point or normal sources sorted by their patch's level (stable), so the
// records levels <= l use are a prefix (gpu_layout.h's watertight pass).
template <class Source>
std::vector<uint32_t> levelRanks(const std::vector<Source>& sources) {
    std::vector<uint32_t> order(sources.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return sources[a].level < sources[b].level; });
    std::vector<uint32_t> rank(sources.size());
    for (uint32_t k = 0; k < order.size(); ++k) rank[order[k]] = k;
    return rank;
}

// The watertight records (gpu_layout.h, LT_WT_*): point sources and edge roots with
// global patch indices; fills every patch's LT_PATCH_WT words, every level's
// LT_L_LS_WT array and LT_L_WT_*_COUNT, and the LT_H_WT_* header words (results
// after the limit stencils). Returns the words written.
size_t watertightTables(const Asset& asset, uint32_t patches, Writer& w, GpuTables& out) {
    uint32_t begin = w.size();
    WatertightPlan plan;
    buildWatertightPlan(asset, plan);
    std::vector<uint32_t> firstPatch(asset.levels.size() + 1, 0);
    for (size_t l = 0; l < asset.levels.size(); ++l)
        firstPatch[l + 1] = firstPatch[l] + uint32_t(asset.levels[l].regular.size());
    const std::vector<uint32_t> pointRank = levelRanks(plan.points), normalRank = levelRanks(plan.normals);
    uint32_t points = w.reserve(LT_WT_POINT_WORDS * plan.points.size());
    for (size_t i = 0; i < plan.points.size(); ++i) {
        const PointSource& ps = plan.points[i];
        uint32_t at = points + LT_WT_POINT_WORDS * pointRank[i];
        w.set(at, firstPatch[ps.level] + ps.patch);
        w.set(at + 1, ps.edge);
        w.set(at + 2, floatBits(ps.x));
    }
    uint32_t normals = w.reserve(LT_WT_NORMAL_WORDS * plan.normals.size());
    for (size_t i = 0; i < plan.normals.size(); ++i) {
        const NormalSource& ns = plan.normals[i];
        uint32_t at = normals + LT_WT_NORMAL_WORDS * normalRank[i];
        w.set(at, firstPatch[ns.level] + ns.patch);
        w.set(at + 1, ns.corner);
    }
    uint64_t pointResults = uint64_t(LT_LIMIT_FLOATS) * out.maxStencils;
    uint64_t normalResults = pointResults + uint64_t(LT_WT_POINT_FLOATS) * plan.points.size();
    out.watertightResultFloats = normalResults + uint64_t(LT_WT_NORMAL_FLOATS) * plan.normals.size() - pointResults;
    if (normalResults + out.watertightResultFloats > std::numeric_limits<uint32_t>::max())
        throw std::length_error("results");
    w.set(LT_H_WT_POINTS, points);
    w.set(LT_H_WT_NORMALS, normals);
    w.set(LT_H_WT_POINT_RESULTS, uint32_t(pointResults));
    w.set(LT_H_WT_NORMAL_RESULTS, uint32_t(normalResults));
    // Only the roots a patch edge refers to (the plan keeps every patch edge's), in
    // the order of their first use, level by level, and the edges they lie on (two
    // halves of a split edge share one; the roots pass turns each edge's points once).
    // Those levels <= l use are a prefix of both.
    std::map<uint32_t, uint32_t> rootIndex;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> rootEdgeIndex;
    std::vector<uint32_t> rootOrder, rootEdge;  // rootEdge: per root, its edge's index
    std::vector<std::pair<uint32_t, uint32_t>> rootEdges;
    for (size_t l = 0; l < asset.levels.size(); ++l)
        for (uint32_t r : plan.levels[l].regularEdge) {
            if (r == kNoSource || !rootIndex.emplace(r, uint32_t(rootOrder.size())).second) continue;
            const EdgeRoot& root = plan.roots[r];
            std::pair<uint32_t, uint32_t> edge(firstPatch[root.level] + root.patch, root.edge);
            auto [it, added] = rootEdgeIndex.emplace(edge, uint32_t(rootEdges.size()));
            if (added) rootEdges.push_back(edge);
            rootOrder.push_back(r);
            rootEdge.push_back(it->second);
        }
    uint32_t edges = w.reserve(LT_WT_ROOT_EDGE_WORDS * rootEdges.size());
    for (size_t i = 0; i < rootEdges.size(); ++i) {
        w.set(edges + uint32_t(LT_WT_ROOT_EDGE_WORDS * i), rootEdges[i].first);
        w.set(edges + uint32_t(LT_WT_ROOT_EDGE_WORDS * i + 1), rootEdges[i].second);
    }
    uint32_t roots = w.reserve(LT_WT_ROOT_WORDS * rootOrder.size());
    for (size_t i = 0; i < rootOrder.size(); ++i) {
        const EdgeRoot& root = plan.roots[rootOrder[i]];
        uint32_t at = roots + uint32_t(LT_WT_ROOT_WORDS * i);
        w.set(at, rootEdge[i]);
        w.set(at + 1, floatBits(root.offset));
        w.set(at + 2, floatBits(root.scale));
    }
    uint64_t rootResults = out.watertightResultFloats + pointResults;
    out.watertightResultFloats += uint64_t(LT_WT_ROOT_FLOATS) * rootEdges.size();
    if (pointResults + out.watertightResultFloats > std::numeric_limits<uint32_t>::max())
        throw std::length_error("results");
    w.set(LT_H_WT_ROOTS, roots);
    w.set(LT_H_WT_ROOT_EDGES, edges);
    w.set(LT_H_WT_ROOT_RESULTS, uint32_t(rootResults));
    uint32_t usedRoots = 0;  // root edges
    auto rootRecord = [&](uint32_t r) {
        if (r == kNoSource) return LT_NONE;
        uint32_t i = rootIndex[r];
        usedRoots = std::max(usedRoots, rootEdge[i] + 1);
        return i;
    };
    // Sources by index k; `used` counts the prefix of records the levels so far refer to.
    uint32_t usedPoints = 0, usedNormals = 0;
    auto pointIndex = [&](uint32_t i) {
        if (i == kNoSource) return LT_NONE;
        usedPoints = std::max(usedPoints, pointRank[i] + 1);
        return pointRank[i];
    };
    auto normalIndex = [&](uint32_t i) {
        if (i == kNoSource) return LT_NONE;
        usedNormals = std::max(usedNormals, normalRank[i] + 1);
        return normalRank[i];
    };
    for (size_t l = 0; l < asset.levels.size(); ++l) {
        const WatertightLevel& wl = plan.levels[l];
        for (size_t k = 0; k < asset.levels[l].regular.size(); ++k) {
            uint32_t at = patches + LT_PATCH_WORDS * (firstPatch[l] + uint32_t(k));
            const RegularPatch& patch = asset.levels[l].regular[k];
            uint32_t extra[LT_WT_EXTRA_WORDS];
            uint32_t bits = 0;  // LT_WT_BIT_*
            bool any = false;
            for (int i = 0; i < 3; ++i) {
                w.set(at + LT_PATCH_WT + i, pointIndex(wl.regularCorner[3 * k + i]));
                extra[i] = rootRecord(wl.regularEdge[3 * k + i]);
                bool sharp = patch.boundaryMask >> i & 1u, crease = sharp;
                if (extra[i] != LT_NONE) {
                    const EdgeRoot& root = plan.roots[wl.regularEdge[3 * k + i]];
                    crease = asset.levels[root.level].regular[root.patch].boundaryMask >> root.edge & 1u;
                    out.smoothCreaseRoots |= sharp && !crease;
                    bits |= LT_WT_BIT_ROOT << i;
                }
                if (edgeFlipped(patch.points, i)) bits |= LT_WT_BIT_FLIP << i;
                if (sharp) bits |= LT_WT_BIT_SHARP << i;
                if (crease) bits |= LT_WT_BIT_CREASE << i;
                extra[3 + i] = normalIndex(wl.regularNormal[3 * k + i]);
                any = any || extra[i] != LT_NONE || extra[3 + i] != LT_NONE;
            }
            uint32_t block = any ? w.reserve(LT_WT_EXTRA_WORDS) : LT_NONE;
            for (int i = 0; any && i < LT_WT_EXTRA_WORDS; ++i) w.set(block + i, extra[i]);
            w.set(at + LT_PATCH_WT + 3, block);
            w.set(at + LT_PATCH_WT_BITS, bits);
        }
        uint32_t stencils = w.reserve(4 * wl.stencilSource.size());
        for (size_t i = 0; i < wl.stencilSource.size(); ++i) {
            w.set(stencils + uint32_t(4 * i), pointIndex(wl.stencilSource[i]));
            w.set(stencils + uint32_t(4 * i + 1), wl.stencilPosition[i]);
            w.set(stencils + uint32_t(4 * i + 2), normalIndex(wl.stencilNormal[i]));
            w.set(stencils + uint32_t(4 * i + 3),
                  wl.stencilBaseNormal[i] == kNoSource ? LT_NONE : wl.stencilBaseNormal[i]);
        }
        uint32_t header = LT_H_SIZE + LT_L_SIZE * uint32_t(l);
        w.set(header + LT_L_LS_WT, stencils);
        w.set(header + LT_L_WT_POINT_COUNT, usedPoints);
        w.set(header + LT_L_WT_NORMAL_COUNT, usedNormals);
        w.set(header + LT_L_WT_ROOT_COUNT, usedRoots);
        out.levels[l].watertightPoints = usedPoints;
        out.levels[l].watertightNormals = usedNormals;
        out.levels[l].watertightRoots = usedRoots;
    }
    return w.size() - begin;
}

// The sort region of screen-space factors on the pattern path (gpu_layout.h),
// sized for the largest frame; the commands' fixed words filled.
void sortRegion(GpuTables& out, Writer& w) {
    const SortRegionSize size = sortRegionSize(out);
    const PatternLibrary& library = patternLibrary();
    uint32_t commands = w.reserve(size_t(LT_PATTERN_KEYS) * LT_SORT_COMMAND_WORDS);
    for (uint32_t k = 0; k < LT_PATTERN_KEYS; ++k) {
        w.set(commands + LT_SORT_COMMAND_WORDS * k, library.count[k]);      // index count
        w.set(commands + LT_SORT_COMMAND_WORDS * k + 2, library.first[k]);  // first index
    }
    w.set(LT_H_SORT, commands);
    w.set(LT_H_SORT_RECORDS, w.reserve(size.records));
    w.set(LT_H_SORT_COUNTS, w.reserve(size_t(LT_PATTERN_KEYS) * size.chunks));
    w.set(LT_H_SORT_CHUNKS, size.chunks);
    out.sortWords = size_t(LT_PATTERN_KEYS) * (LT_SORT_COMMAND_WORDS + size.chunks) + size.records;
}

}  // namespace

Status buildGpuTables(const Asset& asset, GpuTables& out) {
    out = GpuTables{};
    size_t patchCount = 0;
    for (const Level& level : asset.levels) patchCount += level.regular.size();
    if (patchCount > LT_RECORD_PATCH_MASK + size_t(1))
        return Status::error(Status::Unsupported,
                             std::to_string(patchCount) + " regular patches: the Vulkan path draws at most 2^23");
    if (asset.levels.size() > 256) return Status::error(Status::Unsupported, "more than 255 subdivision levels");
    if (asset.displacement.values.size() > size_t(std::numeric_limits<uint32_t>::max()))
        return Status::error(Status::Unsupported,
                             std::to_string(asset.displacement.values.size()) +
                                 " displacement samples: the Vulkan path indexes at most 2^32 - 1");

    out.controlVertices = asset.controlVertexCount();
    out.displaced = asset.displacement.present();
    out.totalVertices = asset.totalVertexCount();
    out.levels.resize(asset.levels.size());
    Writer w(out.words);
    try {
        w.reserve(LT_H_SIZE + LT_L_SIZE * asset.levels.size());
        w.set(LT_H_LEVELS, uint32_t(asset.levels.size()));
        w.set(LT_H_SMOOTH_EDGE, smoothEdgeTable(asset, w));
        w.set(LT_H_SMOOTH_LIMIT, smoothLimitTable(asset, w));
        w.set(LT_H_DISPLACEMENT, displacementTable(asset, w));
        w.set(LT_H_FACE_UVS, asset.faceUVs.empty() ? LT_NONE : w.appendFloats(asset.faceUVs));
        w.set(LT_H_FACE_UV1S, asset.faceUV1s.empty() ? LT_NONE : w.appendFloats(asset.faceUV1s));
        w.set(LT_H_FACE_COLORS, asset.faceColors.empty() ? LT_NONE : w.appendFloats(asset.faceColors));
        editGlobals(asset, w, out);

        SplitVertexIndex splitIndex(asset);
        out.lodVertices.resize(patchCount);
        uint32_t patches = w.reserve(LT_PATCH_WORDS * patchCount);
        w.set(LT_H_PATCHES, patches);
        uint32_t patch = 0, firstEdit = 0;
        for (size_t l = 0; l < asset.levels.size(); ++l) {
            const Level& level = asset.levels[l];
            GpuLevelInfo& info = out.levels[l];
            uint32_t header = LT_H_SIZE + LT_L_SIZE * uint32_t(l);
            refinementTables(level.refinement, header, w);
            limitTables(level.limit, header, w);
            w.set(header + LT_L_IRR_COUNT, uint32_t(level.irregular.size()));
            w.set(header + LT_L_IRR_FACES, irregularTables(level.irregular, w));
            editTables(level.edits, header, firstEdit, w);
            firstEdit += level.edits.count();

            info.firstVertex = level.refinement.firstVertex;
            info.vertexPoints = level.refinement.vertexPointCount();
            info.edgePoints = level.refinement.edgePointCount();
            info.stencils = level.limit.count();
            info.irregular = uint32_t(level.irregular.size());
            info.editedVertices = uint32_t(level.edits.vertex.size());
            out.maxStencils = std::max(out.maxStencils, info.stencils);

            for (const RegularPatch& p : level.regular) {
                uint32_t at = patches + LT_PATCH_WORDS * patch;
                for (int i = 0; i < 12; ++i) w.set(at + i, p.points[i]);
                w.set(at + LT_PATCH_INFO, packInfo(p.param, p.boundaryMask));
                w.set(at + LT_PATCH_FACE, p.param.baseFace);
                w.set(at + LT_PATCH_UV, packUV(p.param));
                PatchLodVertices& lv = out.lodVertices[patch];
                if (!splitIndex.find(p, uint32_t(l), lv))
                    return Status::error(Status::Unsupported, "a non-plain patch of level " + std::to_string(l) +
                                                                  " has a split edge whose level " +
                                                                  std::to_string(l + 1) +
                                                                  " vertices are not in the tables");
                uint32_t split = LT_NONE;
                if (p.splitMask) {
                    split = w.reserve(LT_SPLIT_WORDS, LT_NONE);
                    for (int i = 0; i < 3; ++i) {
                        w.set(split + i, lv.child[i]);
                        w.set(split + 3 + i, lv.edgePoint[i]);
                    }
                }
                w.set(at + LT_PATCH_SPLIT, split);
                SubTriangle subs[4];
                subTriangles(0, subs);
                info.whole.records.push_back(record(patch, subs[0]));
                int count = subTriangles(p.splitMask, subs);
                for (int k = 0; k < count; ++k) info.split.records.push_back(record(patch, subs[k]));
                ++patch;
            }
            info.whole.offset = w.append(info.whole.records);
            info.split.offset = w.append(info.split.records);
        }
        out.watertightWords = watertightTables(asset, patches, w, out) + 5 * patchCount;
        sortRegion(out, w);
    } catch (const std::length_error&) {
        return Status::error(Status::Unsupported, "the asset's tables exceed 2^32 words");
    }
    return Status::ok();
}

}  // namespace lt
