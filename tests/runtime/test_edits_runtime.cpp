// tests/runtime/test_edits_runtime.cpp -- the runtime side of hierarchical edits
// on the CPU path: subdivideCpu's edit pass, EvalSettings::editValues, and the
// watertight plan around an edit (runtime/internal/watertight.h, rule 3). Edited assets
// are made by hand (hand_edits.h) from corpus bakes without edits.
//
// Oracles: level-0 edits equal moved control points; a level-k edit changes level k
// only at the edited vertices (the sequence applied here, in float) and level k+1
// only where a refinement rule reads an edited point; runtime values equal baked
// ones; the watertight evaluation equals the per-patch evaluation near an edit and
// welds by bits.
#include "hand_edits.h"
#include "lod_check.h"      // weldAndCountEdges
#include "osd_reference.h"  // loadObj, corpusMesh, bboxDiagonal
#include "sub_patches.h"    // kPatchCorner
#include "watertight.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>

namespace lt::test {
namespace {

struct Baked {
    Asset asset;
    double diagonal = 0;
};

const Baked& bakedOnce(const std::string& path, int depth) {
    static std::map<std::pair<std::string, int>, std::unique_ptr<Baked>> cache;
    auto& slot = cache[{path, depth}];
    if (!slot) {
        slot = std::make_unique<Baked>();
        InputMesh mesh = loadObj(path);
        Status st = checkInput(mesh, path);
        BakeSettings settings;
        settings.maxDepth = depth;
        if (st) st = bake(mesh, settings, slot->asset);
        EXPECT_TRUE(st) << path << ": " << st.message;
        slot->diagonal = bboxDiagonal(mesh);
    }
    return *slot;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}
bool sameSoup(const Tessellation& a, const Tessellation& b) {
    return sameBits(a.positions, b.positions) && sameBits(a.normals, b.normals) && sameBits(a.uv, b.uv) &&
           a.face == b.face;
}

Tessellation evaluate(const Asset& asset, float factor, bool watertight = true, const float* editValues = nullptr) {
    EvalSettings es;
    es.tessFactor = factor;
    es.watertight = watertight;
    es.editValues = editValues;
    Tessellation soup;
    evaluateCpu(asset, asset.positions.data(), es, soup);
    return soup;
}

// Level-0 edits are moved control points: every level and the surface, bit for bit.
TEST(EditsRuntime, LevelZeroEditsEqualMovedControlPoints) {
    const Baked& b = bakedOnce(corpusMesh("spot.obj"), 3);
    Asset edited = b.asset;
    float s = float(b.diagonal) * 0.01f;
    setEdits(edited, {{0, 7, EditOp::Add, {s, 0, -s}},
                      {0, 7, EditOp::Subtract, {0.5f * s, s, 0}},
                      {0, 100, EditOp::Set, {0.1f, 0.2f, 0.3f}}});
    std::vector<float> moved = b.asset.positions;
    for (int c = 0; c < 3; ++c)
        moved[21 + c] = (moved[21 + c] + std::array<float, 3>{s, 0, -s}[c]) - std::array<float, 3>{0.5f * s, s, 0}[c];
    moved[300] = 0.1f, moved[301] = 0.2f, moved[302] = 0.3f;
    std::vector<float> a, c;
    subdivideCpu(edited, edited.positions.data(), 3, a);
    subdivideCpu(b.asset, moved.data(), 3, c);
    EXPECT_TRUE(sameBits(a, c));
    EvalSettings es;
    es.tessFactor = 4;
    Tessellation x, y;
    evaluateCpu(edited, edited.positions.data(), es, x);
    evaluateCpu(b.asset, moved.data(), es, y);
    EXPECT_TRUE(sameSoup(x, y));
}

// A level-k edit: levels below k untouched; at level k exactly the edited vertices
// change, to their edits applied in order; at level k+1 exactly the points whose
// refinement rule reads an edited point change.
TEST(EditsRuntime, EditsApplyInOrderAndReachTheNextLevel) {
    const Baked& b = bakedOnce(corpusMesh("spot.obj"), 3);
    std::vector<float> plain;
    subdivideCpu(b.asset, b.asset.positions.data(), 3, plain);
    for (uint32_t k = 1; k <= 2; ++k) {
        SCOPED_TRACE("level " + std::to_string(k));
        auto [begin, end] = levelVertices(b.asset, k);
        ASSERT_LT(begin + 40, end);
        // Vertex A: add, subtract, add (1e7 first: the order shows in the rounding);
        // vertex B: set, then add; vertex C: subtract only.
        const uint32_t A = begin + 3, B = begin + 17, C = end - 5;
        std::vector<HandEdit> edits = {
            {k, A, EditOp::Add, {1e7f, 0.25f, -0.5f}},         {k, B, EditOp::Set, {1.5f, -2.0f, 0.75f}},
            {k, A, EditOp::Subtract, {1e7f, 0.125f, 0.0625f}}, {k, C, EditOp::Subtract, {0.01f, 0.02f, -0.03f}},
            {k, B, EditOp::Add, {0.1f, 0.1f, 0.1f}},           {k, A, EditOp::Add, {0.003f, -0.007f, 0.011f}}};
        Asset edited = b.asset;
        setEdits(edited, edits);
        ASSERT_EQ(edited.editCount(), 6u);
        std::vector<float> v;
        subdivideCpu(edited, edited.positions.data(), 3, v);
        std::map<uint32_t, std::array<float, 3>> expect;
        for (uint32_t x : {A, B, C}) expect[x] = {plain[3 * x], plain[3 * x + 1], plain[3 * x + 2]};
        for (const HandEdit& h : edits)
            for (int c = 0; c < 3; ++c) {
                float& p = expect[h.vertex][c];
                p = h.op == EditOp::Set ? h.value[c] : h.op == EditOp::Add ? p + h.value[c] : p - h.value[c];
            }
        EXPECT_NE(expect[A][0], plain[3 * A]);  // 1e7 - 1e7 rounds away the original's low bits
        for (uint32_t x = 0; x < end; ++x) {
            auto it = expect.find(x);
            for (int c = 0; c < 3; ++c) {
                float want = it != expect.end() ? it->second[c] : plain[3 * x + c];
                ASSERT_EQ(v[3 * x + c], want) << "vertex " << x << " coordinate " << c;
            }
        }
        // Level k+1: changed exactly where a rule reads A, B or C.
        const Refinement& r = b.asset.levels[k + 1].refinement;
        auto isEdited = [&](uint32_t x) { return x == A || x == B || x == C; };
        size_t changed = 0, reading = 0;
        for (uint32_t i = 0; i < r.vertexCount(); ++i) {
            bool reads = false;
            if (i < r.vertexPointCount()) {
                reads = isEdited(r.vertexParent[i]);
                for (uint32_t j = r.vertexRingStart[i]; j < r.vertexRingStart[i + 1]; ++j)
                    reads = reads || isEdited(r.vertexRing[j]);
            } else {
                const uint32_t* e = &r.edgeVerts[4 * size_t(i - r.vertexPointCount())];
                reads = isEdited(e[0]) || isEdited(e[1]) || isEdited(e[2]) || isEdited(e[3]);
            }
            size_t x = 3 * size_t(r.firstVertex + i);
            bool differs = std::memcmp(&v[x], &plain[x], 12) != 0;
            EXPECT_EQ(differs, reads) << "level " << k + 1 << " vertex " << i;
            changed += differs;
            reading += reads;
        }
        EXPECT_GT(reading, 0u);
        std::printf("[ figures  ] level %u edits: %zu level-%u points read them, %zu changed\n", k, reading, k + 1,
                    changed);
    }
}

// EvalSettings::editValues (and subdivideCpu's) equal an asset with those values
// baked, bit for bit; scale 0 of add/subtract edits equals no edits.
TEST(EditsRuntime, RuntimeValuesEqualBakedValues) {
    const Baked& b = bakedOnce(corpusMesh("spot.obj"), 3);
    Asset edited = b.asset;
    setEdits(edited, editsOnEveryLevel(b.asset, float(b.diagonal)));
    std::vector<float> values = bakedEditValues(edited);
    ASSERT_EQ(values.size(), 3 * size_t(edited.editCount()));
    std::vector<float> changed = values;
    for (size_t i = 0; i < changed.size(); ++i) changed[i] = changed[i] * 1.75f + float(i % 5) * 1e-3f;
    Asset rebaked = edited;
    size_t at = 0;
    for (Level& level : rebaked.levels)
        for (float& x : level.edits.value) x = changed[at++];
    std::vector<float> a, c;
    subdivideCpu(edited, edited.positions.data(), 3, a, changed.data());
    subdivideCpu(rebaked, rebaked.positions.data(), 3, c);
    EXPECT_TRUE(sameBits(a, c));
    for (float factor : {1.0f, 2.0f, 4.0f}) {
        EXPECT_TRUE(sameSoup(evaluate(edited, factor, true, changed.data()), evaluate(rebaked, factor)));
        EXPECT_TRUE(sameSoup(evaluate(edited, factor, true, values.data()), evaluate(edited, factor)));
    }

    // Scale 0 with add and subtract only: the unedited asset, bit for bit.
    std::vector<HandEdit> addSub;
    for (const HandEdit& h : editsOnEveryLevel(b.asset, float(b.diagonal)))
        if (h.op != EditOp::Set) addSub.push_back(h);
    Asset adds = b.asset;
    setEdits(adds, addSub);
    std::vector<float> zero = bakedEditValues(adds);
    for (float& x : zero) x = x * 0.0f;
    subdivideCpu(adds, adds.positions.data(), 3, a, zero.data());
    subdivideCpu(b.asset, b.asset.positions.data(), 3, c);
    EXPECT_TRUE(sameBits(a, c));
    // Per patch, bit for bit; watertight, the edits' locations choose other (equal)
    // sources for the points they could move (watertight.h, rule 3): within rounding.
    EXPECT_TRUE(sameSoup(evaluate(adds, 4, false, zero.data()), evaluate(b.asset, 4, false)));
    Tessellation x = evaluate(adds, 4, true, zero.data()), y = evaluate(b.asset, 4, true);
    ASSERT_EQ(x.positions.size(), y.positions.size());
    double worst = 0;
    for (size_t i = 0; i < x.positions.size(); ++i)
        worst = std::max(worst, double(std::fabs(x.positions[i] - y.positions[i])));
    EXPECT_LE(worst, 1e-6 * b.diagonal);
}

// Level l's triangles drawn or refined at level l (regular patches and irregular
// faces) around each vertex: vertex -> its neighbours across those triangles, each
// counted once per triangle edge. A vertex whose every neighbour counts twice has
// its whole fan at level l (spot is closed).
std::unordered_map<uint32_t, std::map<uint32_t, int>> levelFans(const Asset& asset, uint32_t l) {
    std::unordered_map<uint32_t, std::map<uint32_t, int>> fans;
    auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
        for (auto [x, y, z] : {std::array<uint32_t, 3>{a, b, c}, {b, c, a}, {c, a, b}}) ++fans[x][y], ++fans[x][z];
    };
    for (const RegularPatch& p : asset.levels[l].regular) add(p.points[4], p.points[5], p.points[8]);
    const LimitStencils& ls = asset.levels[l].limit;
    for (const IrregularFace& f : asset.levels[l].irregular)
        add(ls.vertex[f.corners[0]], ls.vertex[f.corners[1]], ls.vertex[f.corners[2]]);
    return fans;
}

// A level-2 edit on spot at a vertex whose limit support (the level-2 triangles
// touching it and its ring) is all at level 2 or finer, preferring a corner of a
// level-2 regular patch: such an edit is consistent (no coarser patch's surface
// depends on it; checked again by welding the per-patch evaluation). Watertight
// evaluation must equal per-patch evaluation within 1e-6 of the diagonal
// everywhere (rule 3's sources of the vertices the edit moves are of level 2),
// and still weld by bits.
TEST(EditsRuntime, WatertightAroundALevelTwoEdit) {
    const Baked& b = bakedOnce(corpusMesh("spot.obj"), 3);
    const Asset& asset = b.asset;
    float s = float(b.diagonal) * 0.01f;
    auto fans = levelFans(asset, 2);
    auto closed = [&](uint32_t v) {
        auto it = fans.find(v);
        if (it == fans.end()) return false;
        for (auto& [n, count] : it->second)
            if (count != 2) return false;
        return true;
    };
    std::vector<bool> corner(asset.totalVertexCount(), false);
    for (const RegularPatch& p : asset.levels[2].regular)
        for (int c = 0; c < 3; ++c) corner[p.points[kPatchCorner[c]]] = true;
    std::vector<uint32_t> candidates;
    for (auto& [v, ring] : fans) {
        bool inside = closed(v);
        for (auto& [n, count] : ring) inside = inside && closed(n);
        if (inside) candidates.push_back(v);
    }
    std::sort(candidates.begin(), candidates.end(),
              [&](uint32_t x, uint32_t y) { return corner[x] != corner[y] ? corner[x] > corner[y] : x < y; });
    // (In a bake without edits the level-2 region is about two rings around each
    // extraordinary vertex, so these are the extraordinary vertices: no corner of a
    // regular patch has all its support there.)
    std::printf(
        "[ figures  ] spot level 2: %zu vertices with their support at level 2, %zu of them patch corners\n",
        candidates.size(),
        size_t(std::count_if(candidates.begin(), candidates.end(), [&](uint32_t x) { return bool(corner[x]); })));
    std::vector<uint32_t> tried;
    for (uint32_t v : candidates) {
        if (tried.size() >= 4) break;
        tried.push_back(v);
        Asset edited = asset;
        setEdits(edited, {{2, v, EditOp::Add, {s, -0.5f * s, 0.75f * s}}});
        // Consistent? The per-patch evaluation has no crack (weld within 2.5e-7).
        Tessellation loose = evaluate(edited, 4, false);
        WeldReport weld = weldAndCountEdges(loose, b.diagonal);
        if (weld.unmatchedEdges != 0) continue;
        Tessellation tight = evaluate(edited, 4, true), plain = evaluate(asset, 4, true);
        ASSERT_EQ(tight.vertexCount(), loose.vertexCount());
        double worst = 0, moved = 0;
        for (size_t i = 0; i < tight.positions.size(); ++i) {
            worst = std::max(worst, double(std::fabs(tight.positions[i] - loose.positions[i])));
            moved = std::max(moved, double(std::fabs(tight.positions[i] - plain.positions[i])));
        }
        EXPECT_LE(worst, 1e-6 * b.diagonal) << "vertex " << v;
        EXPECT_GT(moved, 0.1 * s) << "the edit shows";
        // Bitwise weld of the watertight soup: every edge used twice (spot is closed).
        std::unordered_map<std::string, uint32_t> ids;
        std::vector<uint32_t> id(tight.vertexCount());
        for (size_t i = 0; i < id.size(); ++i) {
            std::string key(reinterpret_cast<const char*>(&tight.positions[3 * i]), 12);
            id[i] = ids.emplace(key, uint32_t(ids.size())).first->second;
        }
        std::map<std::pair<uint32_t, uint32_t>, int> uses;
        for (size_t t = 0; t < tight.triangleCount(); ++t)
            for (int e = 0; e < 3; ++e) {
                uint32_t x = id[3 * t + e], y = id[3 * t + (e + 1) % 3];
                if (x != y) ++uses[{std::min(x, y), std::max(x, y)}];
            }
        size_t open = 0;
        for (auto& [edge, n] : uses) open += n != 2;
        EXPECT_EQ(open, 0u) << "vertex " << v;
        // Rule 3: the patches' corners at the moved vertices take level-2 sources.
        WatertightPlan plan;
        buildWatertightPlan(edited, plan);
        std::vector<uint32_t> moving = editedLimitVertices(edited, 2);
        EXPECT_EQ(moving.size(), 1 + fans[v].size());  // the vertex and its ring
        for (uint32_t k = 0; k < edited.levels[2].regular.size(); ++k)
            for (int c = 0; c < 3; ++c) {
                uint32_t corner = edited.levels[2].regular[k].points[kPatchCorner[c]];
                if (std::binary_search(moving.begin(), moving.end(), corner)) {
                    EXPECT_EQ(plan.points[plan.levels[2].regularCorner[3 * k + c]].level, 2u) << "vertex " << corner;
                }
            }
        std::printf(
            "[ figures  ] spot, level-2 add at vertex %u: %zu vertices moved, up to %.3g of the edit; "
            "watertight vs per-patch %.3g of the diagonal\n",
            v, moving.size(), moved / s, worst / b.diagonal);
        return;
    }
    FAIL() << "no consistent level-2 edit among " << tried.size() << " tried";
}

}  // namespace
}  // namespace lt::test
