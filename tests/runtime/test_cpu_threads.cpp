// tests/runtime/test_cpu_threads.cpp -- the CPU evaluator's output is the same bits
// for every EvalSettings::threads, on corpus shapes with creases, boundaries,
// non-manifold vertices and a valence-64 pole, and spot (texture coordinates, so
// tangents too), at global and screen-space factors, tessellator and pattern
// points, soup and indexed, watertight or not; and a CpuEvaluator reused across
// frames of different sizes, or of the same settings again, gives what a fresh one
// does, and counts beforehand what it then writes; without attributes the surface is
// the same bits; the watertight plan is the same for every thread count, and a first
// frame's plan of the levels it reads is the whole plan's first levels; a piece of
// base faces (EvalSettings::firstFace) is the whole frame's vertices of those faces.
#include "osd_reference.h"  // loadObj, corpusMesh, corpusShapes
#include "sanitizer.h"
#include "watertight.h"

#include "looptess/tools/baker.h"
#include "looptess/runtime.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace lt::test {
namespace {

template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectSame(const Tessellation& a, const Tessellation& b) {
    EXPECT_TRUE(same(a.positions, b.positions));
    EXPECT_TRUE(same(a.normals, b.normals));
    EXPECT_TRUE(same(a.face, b.face));
    EXPECT_TRUE(same(a.uv, b.uv));
    EXPECT_TRUE(same(a.texcoords, b.texcoords));
    EXPECT_TRUE(same(a.tangents, b.tangents));
    EXPECT_TRUE(same(a.texcoords1, b.texcoords1));
    EXPECT_TRUE(same(a.colors, b.colors));
    EXPECT_TRUE(same(a.indices, b.indices));
}

std::vector<EvalSettings> cases() {
    std::vector<EvalSettings> out;
    EvalSettings s;
    s.tessFactor = 5;
    out.push_back(s);  // tessellator, equal
    s.tessFactor = 3.3f;
    s.spacing = Spacing::FractionalOdd;
    out.push_back(s);  // tessellator, fractional odd
    s = EvalSettings{};
    s.tessFactor = 8;
    s.path = DrawPath::Patterns;
    out.push_back(s);  // pattern soup
    s.indexed = true;
    out.push_back(s);  // pattern mesh
    s = EvalSettings{};
    const float eye[3] = {0, 0, 4};
    s.lod = cameraLod(LodMode::Screen, eye, 45, 512, 8);
    s.tessFactor = 16;
    out.push_back(s);  // screen-space factors
    s.watertight = false;
    out.push_back(s);
    return out;
}

TEST(CpuThreads, EveryThreadCountGivesTheSameBits) {
    std::vector<std::string> meshes = {corpusMesh("spot.obj")};
    for (const std::string& shape : corpusShapes())
        for (const char* name : {"loop_icos_semisharp", "loop_cube_creases1", "loop_saddle_edgecorner",
                                 "loop_nonman_verts", "loop_pole64"})
            if (shape.find(name) != std::string::npos) meshes.push_back(shape);
    meshes = asanSample(std::move(meshes), 2);
    for (const std::string& path : meshes) {
        SCOPED_TRACE(path);
        InputMesh mesh = loadObj(path);
        Asset asset;
        BakeSettings bs;
        bs.maxDepth = 4;
        ASSERT_TRUE(checkInput(mesh, path) && bake(mesh, bs, asset));
        for (const EvalSettings& base : cases()) {
            SCOPED_TRACE(std::to_string(base.tessFactor) + (base.indexed ? " indexed" : ""));
            EvalSettings one = base;
            one.threads = 1;
            Tessellation reference;
            evaluateCpu(asset, asset.positions.data(), one, reference);
            ASSERT_GT(reference.vertexCount(), 0u);
            CpuEvaluator reused(asset);
            for (unsigned threads : {2u, 3u, 8u, 64u}) {
                EvalSettings many = base;
                many.threads = threads;
                Tessellation out;
                evaluateCpu(asset, asset.positions.data(), many, out);
                expectSame(reference, out);
                // Reused: a smaller frame first, so the output shrinks and grows again.
                EvalSettings small = many;
                small.tessFactor = 1;
                small.lod = Lod{};
                reused.evaluate(asset.positions.data(), small, out);
                // Its size first, as a caller sizing buffers (or loopcheck its memory) asks.
                size_t vertices = 0, indices = 0;
                reused.count(asset.positions.data(), many, vertices, indices);
                EXPECT_EQ(vertices, reference.vertexCount());
                EXPECT_EQ(indices, reference.indices.size());
                reused.evaluate(asset.positions.data(), many, out);
                expectSame(reference, out);
                // Again with the same settings: the patches' counts are kept.
                reused.evaluate(asset.positions.data(), many, out);
                expectSame(reference, out);
            }
        }
    }
}

// spot.obj baked to `depth`.
Asset bakedSpot(int depth) {
    InputMesh mesh = loadObj(corpusMesh("spot.obj"));
    Asset asset;
    BakeSettings bs;
    bs.maxDepth = depth;
    EXPECT_TRUE(checkInput(mesh, "spot") && bake(mesh, bs, asset));
    return asset;
}

// Without attributes the surface is the same bits and the attributes are left empty
// (loopcheck's soups: a third smaller on spot).
TEST(CpuThreads, WithoutAttributesTheSurfaceIsTheSame) {
    const Asset asset = bakedSpot(3);
    for (EvalSettings s : cases()) {
        Tessellation with, without;
        evaluateCpu(asset, asset.positions.data(), s, with);
        ASSERT_FALSE(with.texcoords.empty() || with.tangents.empty());
        s.attributes = false;
        evaluateCpu(asset, asset.positions.data(), s, without);
        EXPECT_TRUE(same(with.positions, without.positions) && same(with.normals, without.normals) &&
                    same(with.face, without.face) && same(with.uv, without.uv) && same(with.indices, without.indices));
        EXPECT_TRUE(without.texcoords.empty() && without.tangents.empty() && without.texcoords1.empty() &&
                    without.colors.empty());
    }
}

// `part`'s levels are the first of `whole`'s, bit for bit, and its points, roots and
// normals the first of `whole`'s.
void expectPlanPrefix(const WatertightPlan& part, const WatertightPlan& whole) {
    ASSERT_LE(part.levels.size(), whole.levels.size());
    for (size_t l = 0; l < part.levels.size(); ++l) {
        const WatertightLevel &a = part.levels[l], &b = whole.levels[l];
        EXPECT_TRUE(a.regularCorner == b.regularCorner && a.regularEdge == b.regularEdge &&
                    a.stencilSource == b.stencilSource && a.stencilPosition == b.stencilPosition &&
                    a.regularNormal == b.regularNormal && a.stencilNormal == b.stencilNormal &&
                    a.stencilBaseNormal == b.stencilBaseNormal)
            << "level " << l;
    }
    auto prefix = [](const auto& a, const auto& b, auto eq) {
        return a.size() <= b.size() && std::equal(a.begin(), a.end(), b.begin(), eq);
    };
    EXPECT_TRUE(prefix(part.points, whole.points, [](const PointSource& x, const PointSource& y) {
        return x.level == y.level && x.patch == y.patch && x.edge == y.edge && x.x == y.x;
    }));
    EXPECT_TRUE(prefix(part.roots, whole.roots, [](const EdgeRoot& x, const EdgeRoot& y) {
        return x.level == y.level && x.patch == y.patch && x.edge == y.edge && x.offset == y.offset &&
               x.scale == y.scale;
    }));
    EXPECT_TRUE(prefix(part.normals, whole.normals, [](const NormalSource& x, const NormalSource& y) {
        return x.level == y.level && x.patch == y.patch && x.corner == y.corner;
    }));
}

// The watertight plan's per-level parts run on threads (spot at depth 5 has enough
// corners for them): the same plan for every count.
TEST(CpuThreads, TheWatertightPlanIsTheSameForEveryThreadCount) {
    const Asset asset = bakedSpot(5);
    size_t corners = 0;
    for (const Level& l : asset.levels) corners += 3 * l.regular.size();
    ASSERT_GE(corners, kParallelCorners);
    WatertightPlan one;
    buildWatertightPlan(asset, one, 1);
    for (size_t threads : {2u, 3u, 8u}) {
        SCOPED_TRACE(std::to_string(threads) + " threads");
        WatertightPlan many;
        buildWatertightPlan(asset, many, threads);
        ASSERT_EQ(one.levels.size(), many.levels.size());
        EXPECT_TRUE(one.points.size() == many.points.size() && one.roots.size() == many.roots.size() &&
                    one.normals.size() == many.normals.size());
        expectPlanPrefix(many, one);
    }
}

// A first frame builds the plan's levels it reads (on spot at F = 8, half the time
// of all): the whole plan's first levels, so the same bits as an evaluator given the
// whole plan beforehand. An asset with crease or boundary corners gets every level
// (a sector may join its corners through deeper ones), and the same bits too.
TEST(CpuThreads, AFirstFramesPlanIsTheWholePlansFirstLevels) {
    std::vector<std::string> creased;
    for (const std::string& shape : corpusShapes())
        for (const char* name : {"loop_cube_creases1", "loop_saddle_edgecorner"})
            if (shape.find(name) != std::string::npos) creased.push_back(shape);
    ASSERT_EQ(creased.size(), 2u);
    std::vector<Asset> assets = {bakedSpot(5)};
    for (const std::string& path : creased) {
        InputMesh mesh = loadObj(path);
        BakeSettings bs;
        bs.maxDepth = 5;
        assets.emplace_back();
        ASSERT_TRUE(checkInput(mesh, path) && bake(mesh, bs, assets.back()));
    }
    for (const Asset& asset : assets) {
        const bool masked = &asset != &assets[0];
        SCOPED_TRACE(masked ? "creased" : "spot");
        ASSERT_EQ(hasMaskedCorners(asset), masked);
        WatertightPlan whole, part;
        buildWatertightPlan(asset, whole, 1);
        buildWatertightPlan(asset, part, 1, 2);
        EXPECT_EQ(part.levels.size(), masked ? asset.levels.size() : 3u);
        expectPlanPrefix(part, whole);
        for (EvalSettings s : cases()) {
            s.tessFactor = 4;  // depth 2 of 5
            Tessellation first, prepared;
            CpuEvaluator fresh(asset), given(asset);
            fresh.evaluate(asset.positions.data(), s, first);
            given.prepare(s);
            given.evaluate(asset.positions.data(), s, prepared);
            expectSame(first, prepared);
        }
    }
}

// What `whole` has of base faces [first, end): its vertices in order, and its
// triangles (indexed: renumbered to those vertices).
Tessellation piece(const Tessellation& whole, uint32_t first, uint32_t end) {
    Tessellation out;
    std::vector<uint32_t> renumbered(whole.vertexCount(), UINT32_MAX);
    auto copy = [](const std::vector<float>& from, std::vector<float>& to, size_t v, size_t n) {
        if (!from.empty()) to.insert(to.end(), from.begin() + long(n * v), from.begin() + long(n * (v + 1)));
    };
    for (size_t v = 0; v < whole.vertexCount(); ++v) {
        if (whole.face[v] < first || whole.face[v] >= end) continue;
        renumbered[v] = uint32_t(out.face.size());
        out.face.push_back(whole.face[v]);
        copy(whole.positions, out.positions, v, 3);
        copy(whole.normals, out.normals, v, 3);
        copy(whole.uv, out.uv, v, 2);
        copy(whole.texcoords, out.texcoords, v, 2);
        copy(whole.tangents, out.tangents, v, 4);
        copy(whole.texcoords1, out.texcoords1, v, 2);
        copy(whole.colors, out.colors, v, 4);
    }
    for (uint32_t i : whole.indices)
        if (renumbered[i] != UINT32_MAX) out.indices.push_back(renumbered[i]);
    return out;
}

// A frame evaluated in pieces of base faces (loopcheck's, for frames too large for
// memory) is the whole frame's vertices of each piece, bit for bit, in its order;
// the pieces' counts add up to the whole's.
TEST(CpuThreads, APieceOfBaseFacesIsTheWholeFramesVerticesOfThem) {
    std::vector<Asset> assets = {bakedSpot(3)};
    for (const std::string& shape : corpusShapes())
        if (shape.find("loop_cube_creases1") != std::string::npos) {
            InputMesh mesh = loadObj(shape);
            BakeSettings bs;
            bs.maxDepth = 4;
            assets.emplace_back();
            ASSERT_TRUE(checkInput(mesh, shape) && bake(mesh, bs, assets.back()));
        }
    ASSERT_EQ(assets.size(), 2u);
    for (const Asset& asset : assets) {
        const uint32_t n = asset.faceCount();
        for (EvalSettings s : cases()) {
            SCOPED_TRACE(std::to_string(s.tessFactor) + (s.indexed ? " indexed" : ""));
            s.threads = 2;
            Tessellation whole;
            CpuEvaluator evaluator(asset);
            evaluator.evaluate(asset.positions.data(), s, whole);
            size_t vertices = 0, indices = 0;
            for (uint32_t first : {0u, n / 3, 2 * n / 3}) {
                EvalSettings p = s;
                p.firstFace = first;
                p.faceCount = first == 2 * n / 3 ? UINT32_MAX : n / 3;  // the last: to the end
                Tessellation part;
                evaluator.evaluate(asset.positions.data(), p, part);
                ASSERT_GT(part.vertexCount(), 0u);
                expectSame(piece(whole, first, first == 2 * n / 3 ? n : first + n / 3), part);
                vertices += part.vertexCount(), indices += part.indices.size();
            }
            EXPECT_EQ(vertices, whole.vertexCount());
            EXPECT_EQ(indices, whole.indices.size());
        }
    }
}

}  // namespace
}  // namespace lt::test
