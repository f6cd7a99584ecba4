// Draw batches of the Vulkan path (see draw_plan.h).
#include "vulkan/draw_plan.h"

#include "patterns.h"
#include "sub_patches.h"
#include "tess_domain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace lt {
namespace {

struct Counts {
    uint32_t points = 0, triangles = 0;
};

// Point and triangle counts per factor combination, from the tessellator's own rules.
class DomainCounts {
public:
    explicit DomainCounts(Spacing spacing)
        : spacing_(spacing == Spacing::Equal ? TessSpacing::Equal : TessSpacing::FractionalOdd) {}

    bool odd() const { return spacing_ == TessSpacing::FractionalOdd; }
    Counts get(const float outer[3], float inner) {
        std::array<float, 4> key = {outer[0], outer[1], outer[2], inner};
        auto it = cache_.find(key);
        if (it != cache_.end()) return it->second;
        tessellateTriangle(outer, inner, spacing_, scratch_, TessWinding::Cw);
        Counts c{uint32_t(scratch_.pointCount()), uint32_t(scratch_.triangleCount())};
        cache_.emplace(key, c);
        return c;
    }

private:
    TessSpacing spacing_;
    TessDomain scratch_;
    std::map<std::array<float, 4>, Counts> cache_;
};

void planList(const GpuTables& tables, const RecordList& list, uint32_t level, bool split,
              const ScreenFactorInput* screen, DomainCounts& counts, DrawPlan& plan) {
    const PatchFactors uniform = levelPatchFactors(plan.tessFactor, level);
    DrawBatch batch;
    batch.listOffset = list.offset;
    for (uint32_t r = 0; r < list.records.size(); ++r) {
        uint32_t rec = list.records[r];
        SubTriangle q{{recordCorner(rec, 0), recordCorner(rec, 1), recordCorner(rec, 2)}};
        float outer[3], inner;
        subTriangleFactors(q,
                           screen ? screenPatchFactors(screen->vertices, tables.lodVertices[recordPatch(rec)], level,
                                                       split, screen->eye, screen->scale, plan.tessFactor)
                                  : uniform,
                           counts.odd(), outer, inner);
        Counts c = counts.get(outer, inner);
        if (batch.recordCount > 0 && batch.points + c.points > plan.maxPointsPerDraw) {
            plan.batches.push_back(batch);
            batch.firstRecord = r;
            batch.recordCount = 0;
            batch.points = batch.triangles = 0;
        }
        ++batch.recordCount;
        batch.points += c.points;
        batch.triangles += c.triangles;
        plan.points += c.points;
        plan.tessTriangles += c.triangles;
        ++plan.patches;
    }
    if (batch.recordCount > 0) plan.batches.push_back(batch);
}

}  // namespace

DrawPlan planDraws(const GpuTables& tables, uint32_t depth, float tessFactor, Spacing spacing,
                   uint32_t maxPointsPerDraw, const ScreenFactorInput* screen) {
    DrawPlan plan;
    plan.tessFactor = tessFactor;
    plan.spacing = spacing;
    plan.maxPointsPerDraw = std::max(maxPointsPerDraw, 1u);
    plan.depth = depth;
    DomainCounts counts(spacing);
    for (uint32_t l = 0; l <= depth && l < tables.levels.size(); ++l) {
        const GpuLevelInfo& level = tables.levels[l];
        planList(tables, l < depth ? level.split : level.whole, l, l < depth, screen, counts, plan);
    }
    if (depth < tables.levels.size()) {
        plan.ippTriangles = tables.levels[depth].irregular;
        plan.ippLevel = depth;
    }
    return plan;
}

DrawPlan planPatternDraws(const GpuTables& tables, uint32_t depth, float tessFactor, uint32_t maxPointsPerDraw) {
    DrawPlan plan;
    plan.tessFactor = tessFactor;
    plan.path = DrawPath::Patterns;
    plan.maxPointsPerDraw = std::max(maxPointsPerDraw, 1u);
    plan.depth = depth;
    for (uint32_t l = 0; l <= depth && l < tables.levels.size(); ++l) {
        const RecordList& list = tables.levels[l].whole;
        const uint32_t n = patternFactor(levelFactor(tessFactor, l));
        const uint32_t points = patternPoints(n);
        const uint32_t perBatch = std::max(plan.maxPointsPerDraw / points, 1u);
        for (uint32_t first = 0; first < list.records.size(); first += perBatch) {
            DrawBatch b;
            b.listOffset = list.offset;
            b.firstRecord = first;
            b.recordCount = std::min<uint32_t>(perBatch, uint32_t(list.records.size()) - first);
            b.points = b.recordCount * points;
            b.triangles = b.recordCount * n * n;
            b.pattern = n;
            plan.batches.push_back(b);
            plan.points += b.points;
            plan.tessTriangles += b.triangles;
            plan.patches += b.recordCount;
        }
    }
    if (depth < tables.levels.size()) {
        plan.ippTriangles = tables.levels[depth].irregular;
        plan.ippLevel = depth;
    }
    return plan;
}

DrawPlan planSortedPatternDraws(const GpuTables& tables, uint32_t depth, float tessFactor,
                                const ScreenFactorInput* screen, std::vector<uint16_t>* keys) {
    DrawPlan plan;
    plan.tessFactor = tessFactor;
    plan.path = DrawPath::Patterns;
    plan.depth = depth;
    plan.sorted = true;
    const PatternLibrary& library = patternLibrary();
    if (keys) keys->clear();
    for (uint32_t l = 0; l <= depth && l < tables.levels.size(); ++l) {
        const PatchFactors uniform = levelPatchFactors(tessFactor, l);
        const std::vector<uint32_t>& records = drawnList(tables, l, depth).records;
        plan.sortChunks += uint32_t((records.size() + LT_SORT_CHUNK - 1) / LT_SORT_CHUNK);
        for (uint32_t rec : records) {
            const SubTriangle q{{recordCorner(rec, 0), recordCorner(rec, 1), recordCorner(rec, 2)}};
            float outer[3], inner;
            subTriangleFactors(q,
                               screen ? screenPatchFactors(screen->vertices, tables.lodVertices[recordPatch(rec)], l,
                                                           l < depth, screen->eye, screen->scale, tessFactor)
                                      : uniform,
                               false, outer, inner);
            const uint32_t e[3] = {patternFactor(outer[0]), patternFactor(outer[1]), patternFactor(outer[2])};
            const uint32_t k = patternKey(e);
            if (keys) keys->push_back(uint16_t(k));
            plan.points += library.points[k];
            plan.tessTriangles += library.count[k] / 3;
            ++plan.patches;
        }
    }
    if (depth < tables.levels.size()) {
        plan.ippTriangles = tables.levels[depth].irregular;
        plan.ippLevel = depth;
    }
    return plan;
}

SortRegionSize sortRegionSize(const GpuTables& tables) {
    SortRegionSize most;
    for (uint32_t depth = 0; depth < tables.levels.size(); ++depth) {
        SortRegionSize s;
        for (uint32_t l = 0; l <= depth; ++l) {
            const uint32_t n = uint32_t(drawnList(tables, l, depth).records.size());
            s.records += n;
            s.chunks += (n + LT_SORT_CHUNK - 1) / LT_SORT_CHUNK;
        }
        most.records = std::max(most.records, s.records);
        most.chunks = std::max(most.chunks, s.chunks);
    }
    return most;
}

uint32_t patternKey(const uint32_t e[3]) {
    auto exponent = [](uint32_t f) {
        uint32_t k = 0;
        while ((1u << k) < f) ++k;
        return k;
    };
    return exponent(e[0]) * 49 + exponent(e[1]) * 7 + exponent(e[2]);
}

namespace {

// Pattern `key`'s domain (makePattern) and the exponent c of its grid, N = 2^c the
// largest edge factor.
uint32_t keyPattern(uint32_t key, TessDomain& d) {
    const uint32_t e[3] = {1u << (key / 49), 1u << (key / 7 % 7), 1u << (key % 7)};
    makePattern(e, d);
    return std::max({key / 49, key / 7 % 7, key % 7});
}

// Point p of a pattern on the grid of 2^c segments, as pattern.vert's index.
uint16_t gridIndex(const TessDomain& d, uint32_t p, uint32_t c) {
    const float n = float(1u << c);
    const uint32_t i = uint32_t(d.coords[3 * p] * n), j = uint32_t(d.coords[3 * p + 1] * n);
    return uint16_t(c * LT_PATTERN_GRID_INDICES + j * 65 + i);
}

void appendHalves(std::vector<uint32_t>& words, const std::vector<uint16_t>& halves) {
    for (size_t k = 0; k < halves.size(); k += 2)
        words.push_back(halves[k] | (k + 1 < halves.size() ? uint32_t(halves[k + 1]) << 16 : 0u));
}

}  // namespace

const PatternLibrary& patternLibrary() {
    static const PatternLibrary library = [] {
        PatternLibrary lib;
        lib.first.resize(LT_PATTERN_KEYS);
        lib.count.resize(LT_PATTERN_KEYS);
        lib.points.resize(LT_PATTERN_KEYS);
        TessDomain d;
        for (uint32_t k = 0; k < LT_PATTERN_KEYS; ++k) {
            const uint32_t c = keyPattern(k, d);
            lib.first[k] = uint32_t(lib.indices.size());
            lib.count[k] = uint32_t(d.triangles.size());
            lib.points[k] = uint32_t(d.pointCount());
            for (uint32_t p : d.triangles) lib.indices.push_back(gridIndex(d, p, c));
        }
        return lib;
    }();
    return library;
}

std::vector<uint32_t> patternTable() {
    std::vector<uint32_t> words(LT_PT_LOCAL, 0);
    std::vector<uint16_t> local, points;
    TessDomain d;
    for (uint32_t k = 0; k < LT_PATTERN_KEYS; ++k) {
        const uint32_t c = keyPattern(k, d);
        words[LT_PT_POINT_FIRST + k] = uint32_t(points.size());
        words[LT_PT_POINT_COUNT + k] = uint32_t(d.pointCount());
        for (uint32_t p : d.triangles) local.push_back(uint16_t(p));
        for (uint32_t p = 0; p < d.pointCount(); ++p) points.push_back(gridIndex(d, p, c));
    }
    if (local.size() % 2) local.push_back(0);  // POINTS starts at a word
    appendHalves(words, local);
    words[LT_PT_POINTS] = uint32_t(words.size());
    appendHalves(words, points);
    return words;
}

std::vector<DrawPlan> captureSessions(const DrawPlan& plan, uint64_t maxBytes, uint32_t stride) {
    const uint64_t triangleBytes = 3 * uint64_t(stride);
    if (plan.sorted || maxBytes < 2 * triangleBytes) return {};
    const uint64_t room = maxBytes / triangleBytes - 1;  // triangles a session holds
    DrawPlan session = plan;
    session.batches.clear();
    session.patches = session.points = session.tessTriangles = session.ippTriangles = 0;
    std::vector<DrawPlan> sessions;
    auto fits = [&](uint64_t triangles) {
        if (session.tessTriangles + triangles <= room) return;
        sessions.push_back(session);
        session.batches.clear();
        session.patches = session.points = session.tessTriangles = 0;
    };
    for (const DrawBatch& b : plan.batches) {
        if (b.triangles > room) return {};
        fits(b.triangles);
        session.batches.push_back(b);
        session.patches += b.recordCount;
        session.points += b.points;
        session.tessTriangles += b.triangles;
    }
    if (plan.ippTriangles > room) return {};
    fits(plan.ippTriangles);
    session.ippTriangles = plan.ippTriangles;
    sessions.push_back(session);
    return sessions;
}

}  // namespace lt
