// tests/runtime/test_watertight.cpp -- watertight evaluation (paper 3.4, runtime/src/
// watertight.h) on the CPU path, checked bit for bit: weld the unwelded soup by the
// exact bits of each position and every edge must be used by exactly two triangles,
// except edges on the control mesh's boundary; every welded vertex must carry one
// normal (bits), except on creases, where each side keeps its own.
#include "displacement_map.h"
#include "lod_check.h"
#include "osd_reference.h"  // loadObj, corpusMesh
#include "sanitizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>

namespace lt::test {
namespace {

constexpr int kDepth = 3;

struct Baked {
    std::string name;
    Asset asset;
    Asset displaced;                                        // with a procedural map
    std::set<std::pair<uint32_t, uint32_t>> boundaryEdges;  // control edges with one face
};

// The asset with tests/support/displacement_map.h's pattern at R = 8, scaled to 5% of the
// bounding box; meshes without UVs get a planar projection (x, z).
Status addDisplacement(const InputMesh& mesh, Asset& asset) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], mesh.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], mesh.positions[i]);
    }
    float size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    if (asset.faceUVs.empty())
        for (uint32_t v : asset.faces) {
            asset.faceUVs.push_back((asset.positions[3 * v] - lo[0]) / size);
            asset.faceUVs.push_back((asset.positions[3 * v + 2] - lo[2]) / size);
        }
    GrayImage image;
    image.width = image.height = 64;
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) image.texels.push_back(patternTexel(x, y, 64, 64));
    DisplacementSettings ds;
    ds.scale = 0.05f * size;
    ds.bias = -0.025f * size;
    ds.resolution = 8;
    return bakeDisplacement(image, ds, asset, "pattern");
}

// `creaseAngle` >= 0: loopbake --crease-angle.
const Baked* baked(const std::string& path, float creaseAngle = -1) {
    static std::map<std::pair<std::string, float>, std::unique_ptr<Baked>> cache;
    auto& slot = cache[{path, creaseAngle}];
    if (slot) return slot.get();
    auto b = std::make_unique<Baked>();
    b->name = path.substr(path.find_last_of('/') + 1);
    InputMesh mesh = loadObj(path);
    if (creaseAngle >= 0) addCreasesByAngle(mesh, creaseAngle);
    Status st = checkInput(mesh, path);
    BakeSettings settings;
    settings.maxDepth = kDepth;
    if (st) st = bake(mesh, settings, b->asset);
    b->displaced = b->asset;
    if (st) st = addDisplacement(mesh, b->displaced);
    EXPECT_TRUE(st) << path << ": " << st.message;
    if (!st) return nullptr;
    std::map<std::pair<uint32_t, uint32_t>, int> count;
    const std::vector<uint32_t>& f = b->asset.faces;
    for (size_t i = 0; i < f.size(); ++i) {
        uint32_t a = f[i], c = f[i - i % 3 + (i + 1) % 3];
        ++count[{std::min(a, c), std::max(a, c)}];
    }
    for (auto& [e, n] : count)
        if (n == 1) b->boundaryEdges.insert(e);
    slot = std::move(b);
    return slot.get();
}

// The control edge of base face `face` that (u,v) lies on, or none.
bool onBoundary(const Baked& b, uint32_t face, float u, float v) {
    const uint32_t* c = &b.asset.faces[size_t(face) * 3];
    auto boundary = [&](int i) {
        uint32_t a = c[i], d = c[(i + 1) % 3];
        return b.boundaryEdges.count({std::min(a, d), std::max(a, d)}) > 0;
    };
    return (v == 0.0f && boundary(0)) || (u + v == 1.0f && boundary(1)) || (u == 0.0f && boundary(2));
}

struct BitReport {
    size_t vertices = 0, welded = 0, openEdges = 0, overusedEdges = 0, normalMismatches = 0;
};

BitReport weldByBits(const Baked& b, const Tessellation& soup) {
    BitReport r;
    r.vertices = soup.vertexCount();
    struct Key {
        uint32_t bits[3];
        bool operator==(const Key& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
    };
    struct Hash {
        size_t operator()(const Key& k) const {
            return (size_t(k.bits[0]) * 73856093u) ^ (size_t(k.bits[1]) * 19349663u) ^ k.bits[2];
        }
    };
    std::unordered_map<Key, uint32_t, Hash> ids;
    std::vector<uint32_t> id(r.vertices);
    std::vector<std::array<uint32_t, 3>> normal;
    for (size_t i = 0; i < r.vertices; ++i) {
        Key k;
        std::memcpy(k.bits, &soup.positions[3 * i], sizeof k.bits);
        auto [it, added] = ids.emplace(k, uint32_t(ids.size()));
        id[i] = it->second;
        std::array<uint32_t, 3> n;
        std::memcpy(n.data(), &soup.normals[3 * i], sizeof(uint32_t) * 3);
        if (added)
            normal.push_back(n);
        else if (normal[it->second] != n)
            ++r.normalMismatches;
    }
    r.welded = ids.size();
    // Edge -> uses; remember one soup vertex pair per edge to test the boundary.
    std::unordered_map<uint64_t, std::pair<uint32_t, size_t>> edges;
    for (size_t t = 0; t < soup.triangleCount(); ++t)
        for (int e = 0; e < 3; ++e) {
            size_t i = 3 * t + e, j = 3 * t + (e + 1) % 3;
            uint32_t a = id[i], c = id[j];
            if (a == c) continue;
            uint64_t key = a < c ? (uint64_t(a) << 32 | c) : (uint64_t(c) << 32 | a);
            auto& slot = edges[key];
            if (slot.first++ == 0) slot.second = i;
        }
    for (auto& [key, use] : edges) {
        if (use.first == 2) continue;
        if (use.first > 2) {
            ++r.overusedEdges;
            continue;
        }
        size_t i = use.second, t = i / 3, j = 3 * t + (i % 3 + 1) % 3;
        bool boundary = onBoundary(b, soup.face[i], soup.uv[2 * i], soup.uv[2 * i + 1]) &&
                        onBoundary(b, soup.face[j], soup.uv[2 * j], soup.uv[2 * j + 1]);
        if (!boundary) ++r.openEdges;
    }
    return r;
}

std::vector<std::string> shapes() {
    // Under ASan without bob (spot is the real mesh there): the sweeps below took 3.5 of
    // the sanitizer run's 26 CPU-minutes with it.
    std::vector<std::string> out = {corpusMesh("spot.obj")};
    if (!kAsan) out.push_back(corpusMesh("bob.obj"));
    for (const char* s :
         {"loop_cube", "loop_cube_asymmetric", "loop_icosahedron", "loop_icos_semisharp", "loop_cubes_semisharp",
          "loop_tetrahedron", "loop_triangle_edgeonly", "loop_xord_interior", "loop_xord_boundary", "loop_chaikin0",
          "loop_pole8", "loop_saddle_edgecorner", "loop_fvar_bound0", "loop_cubes_infsharp"})
        out.push_back(std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/" + s + ".obj");
    return out;
}

// The factors a sweep takes: under ASan every other one, the first included (the
// sanitizer run looks for memory errors; these sweeps took 68 of its 1,200 test-s).
std::vector<std::pair<float, Spacing>> factorCases(std::vector<std::pair<float, Spacing>> all) {
    return asanSample(std::move(all), 2);
}

EvalSettings settingsFor(float factor, Spacing spacing) {
    EvalSettings es;
    es.tessFactor = factor;
    es.spacing = spacing;
    return es;
}

TEST(Watertight, EveryEdgeWeldsBitForBit) {
    size_t total = 0, normalsChecked = 0;
    for (const std::string& path : shapes()) {
        const Baked* b = baked(path);
        ASSERT_NE(b, nullptr) << path;
        for (auto [factor, spacing] : factorCases({{1.0f, Spacing::Equal},
                                                   {4.0f, Spacing::Equal},
                                                   {5.5f, Spacing::Equal},
                                                   {3.3f, Spacing::FractionalOdd},
                                                   {7.0f, Spacing::FractionalOdd}})) {
            SCOPED_TRACE(b->name + " F=" + std::to_string(factor));
            Tessellation soup;
            evaluateCpu(b->asset, b->asset.positions.data(), settingsFor(factor, spacing), soup);
            BitReport r = weldByBits(*b, soup);
            EXPECT_EQ(r.openEdges, 0u) << r.welded << " welded of " << r.vertices;
            EXPECT_EQ(r.overusedEdges, 0u);
            // One normal per welded vertex, boundaries included (one sector); across
            // infinitely sharp creases each side keeps its own, and so does each face
            // at a boundary vertex of six or more faces (loop_xord_boundary's: no
            // tangent plane there, spec "Faces without a tangent plane").
            if (b->name.find("infsharp") == std::string::npos && b->name.find("xord_boundary") == std::string::npos) {
                EXPECT_EQ(r.normalMismatches, 0u);
                normalsChecked += r.vertices;
            }
            total += r.vertices;
        }
    }
    std::printf("[ figures  ] %zu vertices welded by bits, normals compared on %zu\n", total, normalsChecked);
}

// Displacement moves every shared point along one shared direction (watertight.h,
// rule 5) by the same sample (the map's shared borders): still no crack, creases
// and boundaries included.
TEST(Watertight, DisplacedSurfacesWeldBitForBit) {
    size_t total = 0;
    for (const std::string& path : shapes()) {
        const Baked* b = baked(path);
        ASSERT_NE(b, nullptr) << path;
        ASSERT_TRUE(b->displaced.displacement.present());
        for (auto [factor, spacing] : factorCases({{1.0f, Spacing::Equal},
                                                   {4.0f, Spacing::Equal},
                                                   {3.3f, Spacing::FractionalOdd},
                                                   {7.0f, Spacing::FractionalOdd}})) {
            SCOPED_TRACE(b->name + " F=" + std::to_string(factor));
            Tessellation soup, flat;
            evaluateCpu(b->displaced, b->displaced.positions.data(), settingsFor(factor, spacing), soup);
            evaluateCpu(b->asset, b->asset.positions.data(), settingsFor(factor, spacing), flat);
            EXPECT_NE(soup.positions, flat.positions);  // the map moved it
            BitReport r = weldByBits(*b, soup);
            EXPECT_EQ(r.openEdges, 0u) << r.welded << " welded of " << r.vertices;
            EXPECT_EQ(r.overusedEdges, 0u);
            total += r.vertices;
        }
    }
    std::printf("[ figures  ] %zu displaced vertices welded by bits\n", total);
}

// Limit stencils at corners where sharp creases meet take their tangents along the
// sector's bounding creases; a sector spanning more than 180 degrees (fandisk's
// concave corners) would get the inward normal without the baker's geometric
// orientation (baker/src/orient.h). Oracle: each drawn triangle's own geometric
// normal, which every corner normal of a coarse tessellation must face alike.
TEST(Watertight, ReflexCreaseCornersFaceOut) {
    InputMesh mesh = loadObj(corpusMesh("fandisk.obj"));
    addCreasesByAngle(mesh, 40.0f);
    BakeSettings settings;
    settings.maxDepth = 2;
    Asset asset;
    Status st = bake(mesh, settings, asset);
    ASSERT_TRUE(st) << st.message;
    for (float factor : {1.0f, 2.0f}) {
        Tessellation soup;
        evaluateCpu(asset, asset.positions.data(), settingsFor(factor, Spacing::Equal), soup);
        size_t against = 0;
        for (size_t t = 0; t < soup.triangleCount(); ++t) {
            const float* p = &soup.positions[9 * t];
            double e1[3], e2[3];
            for (int k = 0; k < 3; ++k) e1[k] = p[3 + k] - p[k], e2[k] = p[6 + k] - p[k];
            const double g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                 e1[0] * e2[1] - e1[1] * e2[0]};
            for (int c = 0; c < 3; ++c) {
                const float* n = &soup.normals[9 * t + 3 * c];
                against += g[0] * n[0] + g[1] * n[1] + g[2] * n[2] < 0;
            }
        }
        EXPECT_EQ(against, 0u) << "F=" << factor;
    }
}

// Across an infinitely sharp edge OpenSubdiv refines the two sides independently;
// the baker makes the transition (bake.cpp, selectCandidates), so a patch never
// borders patches two levels finer there and every factor welds, fractional ones
// too (before the transitions: 100-220 open edges on loop_icos_infsharp at F = 3.3
// and 5, 1,610 on fandisk with 40-degree creases at F = 5).
TEST(Watertight, InfinitelySharpCreasesWeldAtEveryFactor) {
    const Baked* icos = baked(std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/loop_icos_infsharp.obj");
    const Baked* fandisk = baked(corpusMesh("fandisk.obj"), 40.0f);
    ASSERT_NE(icos, nullptr);
    ASSERT_NE(fandisk, nullptr);
    for (const Baked* b : {icos, fandisk})
        // Under ASan the two factors that opened edges before (54 s there with all five).
        for (float factor : kAsan ? std::vector<float>{3.3f, 5.0f} : std::vector<float>{1.0f, 2.0f, 3.3f, 5.0f, 8.0f}) {
            Tessellation soup;
            evaluateCpu(b->asset, b->asset.positions.data(), settingsFor(factor, Spacing::FractionalOdd), soup);
            BitReport r = weldByBits(*b, soup);
            EXPECT_EQ(r.openEdges, 0u) << b->name << " F=" << factor;
        }
}

// Global factors above 2^maxDepth: the deepest level's patches took factors over 1
// beside its IPPs, which are drawn flat (three vertices), and the weld opened there
// (a box baked to depth 2 at F = 5: 108 open edges, loopcheck W1 in its default
// list). Where the finest level has IPPs, F is capped at 2^maxDepth in Global mode
// as in the others; a mesh without any keeps every F (a regular torus at depth 3
// and F = 64: Patterns.APowerOfTwoFactorDrawsUniformRefinementsTriangles).
TEST(Watertight, GlobalFactorsAboveTheBakedDepthWeld) {
    InputMesh icosahedron = loadObj(std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/loop_icosahedron.obj");
    ASSERT_TRUE(checkInput(icosahedron, "icosahedron"));
    for (int depth : {1, 2}) {
        Baked b;
        b.name = "icosahedron at depth " + std::to_string(depth);
        BakeSettings bs;
        bs.maxDepth = depth;
        ASSERT_TRUE(bake(icosahedron, bs, b.asset));
        ASSERT_FALSE(b.asset.levels.back().irregular.empty());
        const float cap = std::ldexp(1.0f, depth);
        for (auto [factor, spacing] : {std::pair{5.0f, Spacing::Equal}, std::pair{16.0f, Spacing::Equal},
                                       std::pair{7.0f, Spacing::FractionalOdd}}) {
            SCOPED_TRACE(b.name + " F=" + std::to_string(factor));
            const EvalSettings es = settingsFor(factor, spacing);
            EXPECT_EQ(lodTessFactor(b.asset, b.asset.positions.data(), es), cap);
            Tessellation soup;
            evaluateCpu(b.asset, b.asset.positions.data(), es, soup);
            const BitReport r = weldByBits(b, soup);
            EXPECT_EQ(r.openEdges, 0u) << r.welded << " welded of " << r.vertices;
        }
    }
}

TEST(Watertight, ScreenSpaceFactorsWeldBitForBit) {
    for (const std::string& path : closedLodMeshes()) {
        const Baked* b = baked(path);
        ASSERT_NE(b, nullptr) << path;
        for (Spacing spacing : {Spacing::Equal, Spacing::FractionalOdd}) {
            EvalSettings es = lodForFactor(b->asset, LodMode::Screen, 0, 7.0f);
            es.spacing = spacing;
            Tessellation soup;
            evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
            BitReport r = weldByBits(*b, soup);
            EXPECT_EQ(r.openEdges, 0u) << b->name;
        }
    }
}

// Refinement patterns (DrawPath::Patterns): every edge's points are j / e from both
// sides, so the weld closes as the tessellator's does, at global factors (powers of
// two and others, rounded up per edge) and at screen-space factors.
TEST(Watertight, RefinementPatternsWeldBitForBit) {
    size_t total = 0;
    for (const std::string& path : shapes()) {
        const Baked* b = baked(path);
        ASSERT_NE(b, nullptr) << path;
        // Up to 2^kDepth (above it flat IPPs sit beside finer edges, runtime.h); fewer under ASan.
        for (float factor : kAsan ? std::vector<float>{3.0f, 8.0f} : std::vector<float>{1.0f, 3.0f, 5.5f, 8.0f}) {
            SCOPED_TRACE(b->name + " F=" + std::to_string(factor));
            EvalSettings es = settingsFor(factor, Spacing::Equal);
            es.path = DrawPath::Patterns;
            Tessellation soup;
            evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
            BitReport r = weldByBits(*b, soup);
            EXPECT_EQ(r.openEdges, 0u) << r.welded << " welded of " << r.vertices;
            EXPECT_EQ(r.overusedEdges, 0u);
            total += r.vertices;
        }
    }
    for (const std::string& path : closedLodMeshes()) {
        const Baked* b = baked(path);
        ASSERT_NE(b, nullptr) << path;
        EvalSettings es = lodForFactor(b->asset, LodMode::Screen, 0, 7.0f);
        es.path = DrawPath::Patterns;
        Tessellation soup;
        evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
        BitReport r = weldByBits(*b, soup);
        EXPECT_EQ(r.openEdges, 0u) << b->name << " at screen-space factors";
        EXPECT_EQ(r.overusedEdges, 0u) << b->name << " at screen-space factors";
    }
    std::printf("[ figures  ] refinement patterns: %zu vertices welded by bits\n", total);
}

// The check can fail: without the watertight rules shared edges differ in the last
// bits (paper 3.4's motivation).
TEST(Watertight, WithoutTheRulesSharedEdgesCrack) {
    const Baked* b = baked(corpusMesh("spot.obj"));
    ASSERT_NE(b, nullptr);
    EvalSettings es = settingsFor(3.3f, Spacing::FractionalOdd);
    es.watertight = false;
    Tessellation soup;
    evaluateCpu(b->asset, b->asset.positions.data(), es, soup);
    BitReport r = weldByBits(*b, soup);
    EXPECT_GT(r.openEdges, 0u);
    std::printf("[ figures  ] spot at F=3.3 odd without watertight rules: %zu open edges\n", r.openEdges);
}

// One CpuEvaluator over frames of moved control points, factors, spacings and
// watertight on and off (its kept plan) gives evaluateCpu's bits every time.
TEST(Watertight, ReusedCpuEvaluatorEqualsEvaluateCpu) {
    const Baked* b = baked(corpusMesh("spot.obj"));
    ASSERT_NE(b, nullptr);
    CpuEvaluator evaluator(b->displaced);
    size_t frames = 0, vertices = 0;
    for (int frame = 0; frame < 6; ++frame) {
        std::vector<float> moved = b->displaced.positions;
        for (size_t i = 0; i < moved.size(); i += 3) moved[i] += 0.02f * float(frame) * std::sin(4.0f * moved[i + 1]);
        // F = 8 is 4 for ASan (38 s there at 8: the plan is the same code at any factor).
        EvalSettings es = settingsFor(frame % 3 == 0   ? 1.0f
                                      : frame % 3 == 1 ? 3.3f
                                      : kAsan          ? 4.0f
                                                       : 8.0f,
                                      frame % 2 ? Spacing::FractionalOdd : Spacing::Equal);
        es.watertight = frame != 4;
        Tessellation reused, fresh;
        evaluator.evaluate(moved.data(), es, reused);
        evaluateCpu(b->displaced, moved.data(), es, fresh);
        ASSERT_EQ(reused.vertexCount(), fresh.vertexCount()) << "frame " << frame;
        EXPECT_EQ(std::memcmp(reused.positions.data(), fresh.positions.data(), fresh.positions.size() * 4), 0) << frame;
        EXPECT_EQ(std::memcmp(reused.normals.data(), fresh.normals.data(), fresh.normals.size() * 4), 0) << frame;
        EXPECT_TRUE(reused.face == fresh.face && reused.uv == fresh.uv) << frame;
        ++frames;
        vertices += fresh.vertexCount();
    }
    std::printf("[ figures  ] displaced spot: %zu frames, %zu vertices, one CpuEvaluator = evaluateCpu bit for bit\n",
                frames, vertices);
}

}  // namespace
}  // namespace lt::test
