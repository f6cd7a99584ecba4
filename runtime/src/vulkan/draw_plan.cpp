// Draw batches of the Vulkan path (see draw_plan.h).
#include "draw_plan.h"

#include "../patterns.h"
#include "../sub_patches.h"
#include "../tess_domain.h"

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

void planList(const GpuTables& tables, const RecordList& list, uint32_t level, bool split, const ScreenFactorInput* screen,
              DomainCounts& counts, DrawPlan& plan) {
    float coarse = std::ldexp(plan.tessFactor, -int(level));
    float fine = std::ldexp(plan.tessFactor, -int(level) - 1);
    const PatchFactors uniform = uniformPatchFactors(coarse, fine);
    DrawBatch batch;
    batch.listOffset = list.offset;
    for (uint32_t r = 0; r < list.records.size(); ++r) {
        uint32_t rec = list.records[r];
        SubTriangle q{{recordCorner(rec, 0), recordCorner(rec, 1), recordCorner(rec, 2)}};
        float outer[3], inner;
        subTriangleFactors(q, screen ? screenPatchFactors(screen->vertices, tables.lodVertices[recordPatch(rec)], level, split,
                                                          screen->eye, screen->scale, plan.tessFactor)
                                     : uniform,
                           counts.odd(), outer, inner);
        Counts c = counts.get(outer, inner);
        if (batch.recordCount > 0 && batch.points + c.points > plan.maxPointsPerDraw) {
            plan.batches.push_back(batch);
            batch.firstRecord = r;
            batch.recordCount = 0;
            batch.points = 0;
        }
        ++batch.recordCount;
        batch.points += c.points;
        plan.points += c.points;
        plan.tessTriangles += c.triangles;
        ++plan.patches;
    }
    if (batch.recordCount > 0) plan.batches.push_back(batch);
}

} // namespace

DrawPlan planDraws(const GpuTables& tables, uint32_t depth, float tessFactor, Spacing spacing, uint32_t maxPointsPerDraw,
                   const ScreenFactorInput* screen) {
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
        const uint32_t n = patternFactor(std::ldexp(tessFactor, -int(l)));
        const uint32_t points = (n + 1) * (n + 2) / 2;
        const uint32_t perBatch = std::max(plan.maxPointsPerDraw / points, 1u);
        for (uint32_t first = 0; first < list.records.size(); first += perBatch) {
            DrawBatch b;
            b.listOffset = list.offset;
            b.firstRecord = first;
            b.recordCount = std::min<uint32_t>(perBatch, uint32_t(list.records.size()) - first);
            b.points = b.recordCount * points;
            b.pattern = n;
            plan.batches.push_back(b);
            plan.points += b.points;
            plan.tessTriangles += uint64_t(b.recordCount) * n * n;
            plan.patches += b.recordCount;
        }
    }
    if (depth < tables.levels.size()) {
        plan.ippTriangles = tables.levels[depth].irregular;
        plan.ippLevel = depth;
    }
    return plan;
}

DrawPlan planSortedPatternDraws(const GpuTables& tables, uint32_t depth, float tessFactor, const ScreenFactorInput* screen,
                                std::vector<uint16_t>* keys) {
    DrawPlan plan;
    plan.tessFactor = tessFactor;
    plan.path = DrawPath::Patterns;
    plan.depth = depth;
    plan.sorted = true;
    const PatternLibrary& library = patternLibrary();
    if (keys) keys->clear();
    for (uint32_t l = 0; l <= depth && l < tables.levels.size(); ++l) {
        const PatchFactors uniform =
            uniformPatchFactors(std::ldexp(tessFactor, -int(l)), std::ldexp(tessFactor, -int(l) - 1));
        for (uint32_t rec : drawnList(tables, l, depth).records) {
            const SubTriangle q{{recordCorner(rec, 0), recordCorner(rec, 1), recordCorner(rec, 2)}};
            float outer[3], inner;
            subTriangleFactors(q, screen ? screenPatchFactors(screen->vertices, tables.lodVertices[recordPatch(rec)], l, l < depth,
                                                              screen->eye, screen->scale, tessFactor)
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

const PatternLibrary& patternLibrary() {
    static const PatternLibrary library = [] {
        PatternLibrary lib;
        lib.first.resize(LT_PATTERN_KEYS);
        lib.count.resize(LT_PATTERN_KEYS);
        lib.points.resize(LT_PATTERN_KEYS);
        TessDomain d;
        for (uint32_t k = 0; k < LT_PATTERN_KEYS; ++k) {
            const uint32_t e[3] = {1u << (k / 49), 1u << (k / 7 % 7), 1u << (k % 7)};
            const uint32_t c = std::max({k / 49, k / 7 % 7, k % 7}), n = 1u << c;   // the grid: the largest factor
            makePattern(e, d);
            lib.first[k] = uint32_t(lib.indices.size());
            lib.count[k] = uint32_t(d.triangles.size());
            lib.points[k] = uint32_t(d.pointCount());
            for (uint32_t p : d.triangles) {
                const uint32_t i = uint32_t(d.coords[3 * p] * float(n)), j = uint32_t(d.coords[3 * p + 1] * float(n));
                lib.indices.push_back(uint16_t(c * LT_PATTERN_GRID_INDICES + j * 65 + i));
            }
        }
        return lib;
    }();
    return library;
}

} // namespace lt
