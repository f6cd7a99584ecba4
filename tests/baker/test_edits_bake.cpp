// Baked hierarchical edits against OpenSubdiv's Hbr (tests/support/hbr_reference.h,
// itself checked against Far in test_hbr_oracle.cpp).
//
// 1. Refined vertices. Every vertex the asset stores, at every level, is matched to
//    Hbr's vertex by its sub-triangle path (BakeTrace) and compared after that
//    level's edits: within 1e-6 of the bounding-box diagonal.
// 2. Limit positions of the final level d. At F = 2^d the runtime depth is d: a
//    level-d patch or IPP emits its corners, a coarser patch of level l 2^(d-l)
//    segments per edge, so these points sit on level d's dyadic lattice of their
//    base face and are limit points of level-d vertices (the D3D11 pattern's inner
//    rings are not on the lattice and are skipped). Each such captured position is
//    compared with Hbr's limit of the level-d vertex at that lattice point.
// 3. Away from the edits the capture is the unedited bake's, bit for bit.
// 4. New edit values at runtime (EvalSettings::editValues) equal a re-bake with them.
// 5. Edited assets stay watertight (weld by exact bits, loopcheck's weld).
#include "bake_trace.h"  // bakeTraced (looptess_baker_internal)
#include "input_edit.h"
#include "hbr_reference.h"
#include "osd_reference.h"
#include "sanitizer.h"

#include "check_internal.h"  // looptess_check_internal
#include "looptess/runtime.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>

namespace lt::test {
namespace {

std::string shape(const char* name) { return std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/" + name + ".obj"; }

std::vector<HbrVertexEdit> toHbr(const InputMesh& mesh) {
    std::vector<HbrVertexEdit> out;
    for (const auto& e : mesh.edits) {
        HbrVertexEdit h;
        h.face = e.face;
        h.children = e.path;
        h.vertex = e.vertex;
        h.op = e.op == EditOp::Set ? HbrEditOp::Set : e.op == EditOp::Add ? HbrEditOp::Add : HbrEditOp::Subtract;
        std::copy(e.value, e.value + 3, h.value);
        out.push_back(h);
    }
    return out;
}

// Hbr's level-d vertex at each lattice point (i, j) of each base face, i + j <= 2^d.
class Lattice {
public:
    Lattice(const HbrReference& hbr, uint32_t faces, int d) : hbr_(hbr), d_(d), n_(1u << d) {
        for (uint32_t f = 0; f < faces; ++f) walk(f, {}, {0, 0}, {int(n_), 0}, {0, int(n_)});
    }
    // The vertex at (u, v) of `face`, or -1 when (u, v) is not on the lattice.
    int64_t at(uint32_t face, float u, float v) const {
        const double i = double(u) * n_, j = double(v) * n_;
        if (i != std::floor(i) || j != std::floor(j)) return -1;
        auto it = map_.find({face, int(i), int(j)});
        return it == map_.end() ? -1 : int64_t(it->second);
    }

private:
    using P = std::array<int, 2>;
    void walk(uint32_t face, std::vector<uint8_t> path, P a, P b, P c) {
        if (int(path.size()) == d_) {
            const P corner[3] = {a, b, c};
            for (int k = 0; k < 3; ++k) map_[{face, corner[k][0], corner[k][1]}] = hbr_.vertex(face, path, k);
            return;
        }
        auto mid = [](P x, P y) { return P{(x[0] + y[0]) / 2, (x[1] + y[1]) / 2}; };
        const P e0 = mid(a, b), e1 = mid(b, c), e2 = mid(c, a);
        const P child[4][3] = {{a, e0, e2}, {e0, b, e1}, {e2, e1, c}, {e1, e2, e0}};
        for (uint8_t i = 0; i < 4; ++i) {
            path.push_back(i);
            walk(face, path, child[i][0], child[i][1], child[i][2]);
            path.pop_back();
        }
    }
    const HbrReference& hbr_;
    int d_;
    uint32_t n_;
    std::map<std::tuple<uint32_t, int, int>, uint32_t> map_;
};

double distance(const float* a, const double* b) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s += (double(a[k]) - b[k]) * (double(a[k]) - b[k]);
    return std::sqrt(s);
}

struct Case {
    const char* name;
    std::string path;
    int depth;
    std::vector<InputMesh::VertexEdit> edits;
};

std::vector<Case> cases() {
    const auto add = EditOp::Add, set = EditOp::Set, sub = EditOp::Subtract;
    return {
        {"loop_cube", shape("loop_cube"), 4, {inputEdit(0, {1, 3}, 2, add, 0.0f, 0.1f, 0.0f)}},
        {"loop_icosahedron",
         shape("loop_icosahedron"),
         4,
         {inputEdit(7, {3}, 0, sub, 0.0f, 0.0f, 0.2f), inputEdit(7, {0, 1, 2}, 1, add, 0.02f, -0.03f, 0.01f)}},
        {"loop_xord_interior",
         shape("loop_xord_interior"),
         4,
         {inputEdit(5, {3, 3}, 0, add, 0.0f, 0.1f, 0.0f), inputEdit(11, {3, 0, 3}, 2, set, 0.0f, 1.0f, 0.0f)}},
        {"loop_triangle_edgeonly",
         shape("loop_triangle_edgeonly"),
         4,
         {inputEdit(3, {0, 0}, 0, add, 0.0f, 0.1f, 0.0f)}},
        {"loop_cube_level0",
         shape("loop_cube"),
         3,
         {inputEdit(2, {}, 1, add, 0.05f, 0.0f, 0.0f), inputEdit(2, {2}, 1, set, 0.3f, 0.2f, 0.1f)}},
        {"spot", corpusMesh("spot.obj"), 3, {inputEdit(1000, {2, 3}, 1, add, 0.0f, 0.05f, 0.0f)}},
    };
}

struct Baked {
    InputMesh mesh;
    Asset asset;
    BakeTrace trace;
};

Baked bakeCase(const Case& c, bool withEdits = true) {
    Baked b;
    b.mesh = loadObj(c.path);
    if (withEdits) b.mesh.edits = c.edits;
    BakeSettings settings;
    settings.maxDepth = c.depth;
    settings.name = c.name;
    Status st = bakeTraced(b.mesh, settings, b.asset, nullptr, &b.trace);
    EXPECT_TRUE(st) << st.message;
    if (st) st = validateAsset(b.asset, c.name);
    EXPECT_TRUE(st) << st.message;
    return b;
}

TEST(EditsBake, RefinedVerticesAndLimitsMatchHbr) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        Baked b = bakeCase(c);
        if (HasFailure()) return;
        const double diag = bboxDiagonal(b.mesh);
        HbrReference hbr;
        Status st = hbr.build(b.mesh, toHbr(b.mesh), c.depth);
        ASSERT_TRUE(st) << st.message;

        // 1. Every stored vertex at every level.
        std::vector<float> vertices;
        subdivideCpu(b.asset, b.asset.positions.data(), b.asset.maxDepth(), vertices);
        ASSERT_EQ(b.trace.face.size(), b.asset.totalVertexCount());
        double worst = 0;
        for (size_t i = 0; i < b.trace.face.size(); ++i) {
            ASSERT_NE(b.trace.face[i], ~0u);
            const uint32_t v = hbr.vertex(b.trace.face[i], b.trace.path[i], b.trace.corner[i]);
            worst = std::max(worst, distance(&vertices[3 * i], hbr.position(int(b.trace.osdLevel[i]), v)) / diag);
        }
        EXPECT_LE(worst, 1e-6);

        // 2. Limit points of level d at F = 2^d.
        EvalSettings settings;
        settings.tessFactor = float(1u << c.depth);
        Tessellation soup;
        evaluateCpu(b.asset, b.asset.positions.data(), settings, soup);
        Lattice lattice(hbr, b.asset.faceCount(), c.depth);
        size_t compared = 0, offLattice = 0, noLimit = 0;
        double worstLimit = 0;
        for (size_t i = 0; i < soup.vertexCount(); ++i) {
            int64_t v = lattice.at(soup.face[i], soup.uv[2 * i], soup.uv[2 * i + 1]);
            if (v < 0) {
                ++offLattice;
                continue;
            }  // inside a D3D11 ring: not a level-d vertex
            if (!hbr.hasLimit(uint32_t(v))) {
                ++noLimit;
                continue;
            }
            worstLimit = std::max(worstLimit, distance(&soup.positions[3 * i], hbr.limit(uint32_t(v))) / diag);
            ++compared;
        }
        EXPECT_GT(compared, noLimit);  // semi-sharp creases: Hbr's oracle has no exact limit mask
        EXPECT_LE(worstLimit, 1e-6);
        std::printf(
            "[ figures  ] %-24s %zu edits, %u stored vertices within %.1e; %zu limit points within %.1e (%zu off the "
            "lattice)\n",
            c.name, c.edits.size(), b.asset.totalVertexCount(), worst, compared, worstLimit, offLattice);
    }
}

TEST(EditsBake, AwayFromTheEditsTheCaptureIsUnchanged) {
    size_t farVertices = 0;  // small shapes lie within 3 rings of their edits
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        Baked edited = bakeCase(c), plain = bakeCase(c, false);
        if (HasFailure()) return;
        const std::set<uint32_t> near = facesNearEdits(edited.mesh.edits, edited.mesh.faces, 3);
        for (float factor : asanSample(std::vector<float>{3.3f, 8.0f}, 2)) {  // ASan: 3.3 (28 s with both)
            EvalSettings settings;
            settings.tessFactor = factor;
            settings.spacing = Spacing::FractionalOdd;
            Tessellation a, b;
            evaluateCpu(edited.asset, edited.asset.positions.data(), settings, a);
            evaluateCpu(plain.asset, plain.asset.positions.data(), settings, b);
            const std::vector<float> fa = verticesOutside(a, near), fb = verticesOutside(b, near);
            farVertices += fa.size() / 6;
            ASSERT_EQ(fa.size(), fb.size()) << "F=" << factor;
            // (memcmp must not see the null data() of an empty vector)
            EXPECT_TRUE(fa.empty() || std::memcmp(fa.data(), fb.data(), fa.size() * sizeof(float)) == 0)
                << "F=" << factor;
        }
    }
    EXPECT_GT(farVertices, 100000u);
    std::printf("[ figures  ] %zu vertices away from the edits compared bit for bit\n", farVertices);
}

TEST(EditsBake, NewValuesAtRuntimeEqualARebake) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        Case other = c;
        for (auto& e : other.edits)
            for (float& x : e.value) x = -0.5f * x + 0.01f;
        Baked first = bakeCase(c), second = bakeCase(other);
        if (HasFailure()) return;
        std::vector<float> values = bakedEditValues(second.asset);
        ASSERT_EQ(values.size(), 3u * first.asset.editCount());
        EvalSettings settings;
        settings.tessFactor = 5.0f;
        Tessellation a, b;
        settings.editValues = values.data();
        evaluateCpu(first.asset, first.asset.positions.data(), settings, a);
        settings.editValues = nullptr;
        evaluateCpu(second.asset, second.asset.positions.data(), settings, b);
        ASSERT_EQ(a.positions.size(), b.positions.size());
        EXPECT_EQ(std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(float)), 0);
        EXPECT_EQ(std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(float)), 0);
    }
}

TEST(EditsBake, EditedAssetsWeldBitForBit) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        Baked b = bakeCase(c);
        if (HasFailure()) return;
        const ControlTopology topology = analyzeControlMesh(b.asset);
        // Under ASan 3.3 and the deepest (24 s with all four).
        for (float factor : asanSample(std::vector<float>{3.3f, 1.0f, float(1u << c.depth), 5.0f}, 2)) {
            EvalSettings settings;
            settings.tessFactor = factor;
            settings.spacing = Spacing::FractionalOdd;
            Tessellation soup;
            evaluateCpu(b.asset, b.asset.positions.data(), settings, soup);
            WeldResult weld;
            weldTessellation(soup, topology, weld);
            EXPECT_TRUE(weld.pass()) << "F=" << factor << ": " << weld.crackEdges << " cracks, " << weld.tJunctions
                                     << " T-junctions";
        }
    }
}

TEST(EditsBake, RejectsEditsTheBakeCannotHonour) {
    InputMesh mesh = loadObj(shape("loop_cube"));
    BakeSettings settings;
    settings.maxDepth = 2;
    settings.name = "cube.obj";
    Asset asset;
    mesh.edits = {inputEdit(0, {1, 2, 3}, 0, EditOp::Add, 0, 1, 0)};
    Status st = bake(mesh, settings, asset);
    EXPECT_EQ(st.code, Status::BadInput);
    EXPECT_NE(st.message.find("deeper than the maximum depth 2"), std::string::npos) << st.message;
    // One level-2 vertex through two paths (see test_hbr_oracle.cpp), one a set.
    mesh.edits = {inputEdit(0, {1, 0}, 0, EditOp::Add, 0, 0.1f, 0), inputEdit(0, {0, 1}, 1, EditOp::Set, 0, 0, 0.2f)};
    st = bake(mesh, settings, asset);
    EXPECT_EQ(st.code, Status::BadInput);
    EXPECT_NE(st.message.find("name the same vertex"), std::string::npos) << st.message;
    // Two adds there are fine, and stored on one vertex in input order.
    mesh.edits[1].op = EditOp::Add;
    st = bake(mesh, settings, asset);
    ASSERT_TRUE(st) << st.message;
    ASSERT_EQ(asset.levels[2].edits.vertex.size(), 1u);
    EXPECT_EQ(asset.levels[2].edits.count(), 2u);
    EXPECT_EQ(asset.levels[2].edits.value[1], 0.1f);
    EXPECT_EQ(asset.levels[2].edits.value[5], 0.2f);
}

}  // namespace
}  // namespace lt::test
