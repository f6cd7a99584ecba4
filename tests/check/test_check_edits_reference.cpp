// loopcheck's accuracy reference for meshes with hierarchical edits
// (OsdLimitSurface with InputMesh::edits, check/src/osd_edits.h) against the Hbr
// oracle (hbr_reference.h), which implements Loop vertex edits itself.
//
// Matching. Hbr's final level L holds sub-triangles (face; c_1 .. c_L); corner j of
// one lies at a (u, v) of its base face that follows from the path alone: the
// sub-triangle's corner coordinates, child by child, as the child order defines
// them (child 0 = (v0, e0, e2), 1 = (e0, v1, e1), 2 = (e2, e1, v2), 3 = (e1, e2, e0),
// e_i the midpoint of corner i and i+1). The reference is evaluated there and
// compared with Hbr's exact limit point of that vertex, from every sub-triangle
// that has it as a corner (so every path to a vertex is tried).
//
// Tolerance: 1e-6 of the control mesh's bounding-box diagonal; Hbr's
// float weights leave about 1e-8. At level-L vertices the PatchTable is exact
// (regular patch interiors and patch corners), so nothing else is expected.
#include "hbr_reference.h"
#include "osd_reference.h"

#include "check_internal.h"  // looptess_check_internal

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace lt::test {
namespace {

std::string shape(const char* name) { return std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/" + name + ".obj"; }

// The same edits as InputMesh::edits.
void addEdits(InputMesh& mesh, const std::vector<HbrVertexEdit>& edits) {
    for (const HbrVertexEdit& h : edits) {
        InputMesh::VertexEdit e;
        e.face = h.face;
        e.path = h.children;
        e.vertex = h.vertex;
        e.op = h.op == HbrEditOp::Set ? EditOp::Set : h.op == HbrEditOp::Add ? EditOp::Add : EditOp::Subtract;
        for (int k = 0; k < 3; ++k) e.value[k] = h.value[k];
        mesh.edits.push_back(e);
    }
}

double distance(const double* a, const double* b) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (a[k] - b[k]) * (a[k] - b[k]);
    return std::sqrt(d2);
}

// A sub-triangle: its index among its level's (HbrReference::subFace) and its
// corners' (u, v) on the base face.
struct SubTriangle {
    uint64_t index;
    double uv[3][2];
};

// Every sub-triangle of level `levels` of base face `face`, from its path.
void subTriangles(uint32_t face, int levels, std::vector<SubTriangle>& out) {
    SubTriangle root{face, {{0, 0}, {1, 0}, {0, 1}}};
    std::vector<std::pair<SubTriangle, int>> stack{{root, 0}};
    while (!stack.empty()) {
        auto [t, l] = stack.back();
        stack.pop_back();
        if (l == levels) {
            out.push_back(t);
            continue;
        }
        double mid[3][2];  // e_i: corner i and i+1
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 2; ++k) mid[i][k] = 0.5 * (t.uv[i][k] + t.uv[(i + 1) % 3][k]);
        const double* corners[4][3] = {
            {t.uv[0], mid[0], mid[2]}, {mid[0], t.uv[1], mid[1]}, {mid[2], mid[1], t.uv[2]}, {mid[1], mid[2], mid[0]}};
        for (int c = 0; c < 4; ++c) {
            SubTriangle child{t.index * 4 + uint64_t(c), {}};
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 2; ++k) child.uv[j][k] = corners[c][j][k];
            stack.push_back({child, l + 1});
        }
    }
}

// The reference of `mesh` with `edits` against Hbr refined to `levels`, at every
// corner of every final-level sub-triangle where Hbr has an exact limit.
void checkAgainstHbr(const std::string& label, const std::string& path, const std::vector<HbrVertexEdit>& edits,
                     int levels) {
    SCOPED_TRACE(label);
    InputMesh mesh = loadObj(path);
    const double diag = bboxDiagonal(mesh);
    HbrReference hbr;
    Status st = hbr.build(mesh, edits, levels);
    ASSERT_TRUE(st) << st.message;
    addEdits(mesh, edits);
    OsdLimitSurface ref;
    st = ref.build(mesh);
    ASSERT_TRUE(st) << st.message;
    int deepest = 0;
    for (const HbrVertexEdit& e : edits) deepest = std::max(deepest, e.level());
    EXPECT_EQ(ref.editCount(), edits.size());
    EXPECT_EQ(ref.editLevel(), deepest);

    const HbrLevel& last = hbr.level(levels);
    std::vector<SubTriangle> subs;
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) subTriangles(f, levels, subs);
    ASSERT_EQ(subs.size(), last.faceCount());
    size_t compared = 0, skipped = 0;
    double worst = 0;
    std::vector<uint8_t> seen(last.vertexCount(), 0);
    for (const SubTriangle& t : subs) {
        const uint32_t face = uint32_t(t.index >> (2 * levels));
        for (int j = 0; j < 3; ++j) {
            const uint32_t v = last.faceVertices[3 * t.index + size_t(j)];
            if (!hbr.hasLimit(v)) {
                skipped += !seen[v];
                seen[v] = 1;
                continue;
            }
            seen[v] = 1;
            double pos[3], nrm[3];
            ASSERT_TRUE(ref.evaluate(int(face), t.uv[j][0], t.uv[j][1], pos, nrm))
                << "face " << face << " (u, v) = (" << t.uv[j][0] << ", " << t.uv[j][1] << ")";
            const double err = distance(pos, hbr.limit(v)) / diag;
            EXPECT_LE(err, 1e-6) << "sub-triangle " << t.index << " corner " << j << " face " << face << " (u, v) = ("
                                 << t.uv[j][0] << ", " << t.uv[j][1] << ")";
            worst = std::max(worst, err);
            ++compared;
        }
    }
    EXPECT_GT(compared, 3 * subs.size() / 2);
    std::printf("%-44s K=%d L=%d  %zu corners of %zu vertices, %zu without an exact limit, worst %.1e\n", label.c_str(),
                deepest, levels, compared, size_t(last.vertexCount()), skipped, worst);
}

const auto kAdd = HbrEditOp::Add;
const auto kSet = HbrEditOp::Set;
const auto kSub = HbrEditOp::Subtract;

// The shapes and edits of test_hbr_oracle.cpp: levels 0 to 3, add, set, subtract,
// interior and boundary vertices, extraordinary vertices, creases.
TEST(CheckEditsReference, MatchesHbrOnOneEdit) {
    for (const char* name : {"loop_cube", "loop_icosahedron", "loop_xord_interior", "loop_triangle_edgeonly"})
        checkAgainstHbr(std::string(name) + " add (0; 1 3) v2", shape(name), {hbrEdit(0, {1, 3}, 2, kAdd, 0, 0.1f, 0)},
                        4);
    checkAgainstHbr("loop_xord_interior add (5; 3 3) v0", shape("loop_xord_interior"),
                    {hbrEdit(5, {3, 3}, 0, kAdd, 0, 0.1f, 0)}, 4);
    checkAgainstHbr("loop_triangle_edgeonly add (3; 0 0) v0 boundary", shape("loop_triangle_edgeonly"),
                    {hbrEdit(3, {0, 0}, 0, kAdd, 0, 0.1f, 0)}, 4);
    checkAgainstHbr("loop_cube add (2;) v1 level 0", shape("loop_cube"), {hbrEdit(2, {}, 1, kAdd, 0.05f, 0, 0)}, 3);
    checkAgainstHbr("loop_cube set (2; 2) v1", shape("loop_cube"), {hbrEdit(2, {2}, 1, kSet, 0.3f, 0.2f, 0.1f)}, 3);
    checkAgainstHbr("loop_icosahedron subtract (7; 3) v0", shape("loop_icosahedron"),
                    {hbrEdit(7, {3}, 0, kSub, 0, 0, 0.2f)}, 3);
    checkAgainstHbr("loop_icosahedron add (7; 0 1 2) v1", shape("loop_icosahedron"),
                    {hbrEdit(7, {0, 1, 2}, 1, kAdd, 0.02f, -0.03f, 0.01f)}, 4);
    checkAgainstHbr("loop_xord_interior set (11; 3 0 3) v2", shape("loop_xord_interior"),
                    {hbrEdit(11, {3, 0, 3}, 2, kSet, 0, 1, 0)}, 4);
}

// Several edits in one mesh, at several levels, on the extraordinary boundary
// vertex's faces and across creases; one vertex named through two paths.
TEST(CheckEditsReference, MatchesHbrOnSeveralEdits) {
    checkAgainstHbr("loop_xord_boundary 3 edits", shape("loop_xord_boundary"),
                    {hbrEdit(0, {}, 0, kAdd, 0, 0, 0.1f), hbrEdit(0, {0}, 0, kAdd, 0.05f, 0, 0.05f),
                     hbrEdit(1, {3, 1}, 2, kSub, 0, 0.1f, 0.02f)},
                    3);
    checkAgainstHbr("loop_cube_creases0 3 edits", shape("loop_cube_creases0"),
                    {hbrEdit(0, {1}, 0, kAdd, 0, 0.1f, 0), hbrEdit(3, {2, 3}, 1, kSub, 0.02f, 0, 0.1f),
                     hbrEdit(5, {0, 3, 3}, 2, kAdd, 0, 0, -0.1f)},
                    4);
    checkAgainstHbr("loop_cube one vertex through two paths", shape("loop_cube"),
                    {hbrEdit(0, {1, 0}, 0, kAdd, 0, 0.1f, 0), hbrEdit(0, {0, 1}, 1, kAdd, 0, 0, 0.2f)}, 3);
    checkAgainstHbr("loop_saddle_edgeonly 2 edits", shape("loop_saddle_edgeonly"),
                    {hbrEdit(2, {2, 1}, 1, kAdd, 0, 0.2f, 0), hbrEdit(3, {3}, 0, kSet, 0.5f, 0.5f, 0.5f)}, 3);
}

// A real mesh (spot, 5,856 triangles, extraordinary vertices everywhere).
TEST(CheckEditsReference, MatchesHbrOnSpot) {
    checkAgainstHbr("spot add (1000; 2 3) v1", corpusMesh("spot.obj"), {hbrEdit(1000, {2, 3}, 1, kAdd, 0, 0.05f, 0)},
                    3);
}

// Edits whose values are zero leave the surface unchanged: the reference through
// the uniform prefix equals the plain one, positions and normals, at random points
// and at dyadic ones.
TEST(CheckEditsReference, ZeroEditsEqualThePlainReference) {
    for (const char* name : {"loop_cube", "loop_xord_interior", "loop_xord_boundary", "loop_triangle_edgeonly",
                             "loop_cube_creases0", "loop_icos_semisharp", "loop_pole8"}) {
        SCOPED_TRACE(name);
        InputMesh plain = loadObj(shape(name));
        InputMesh zero = plain;
        const uint32_t last = plain.faceCount() - 1;
        addEdits(zero, {hbrEdit(0, {1, 2, 3}, 1, kAdd, 0, 0, 0), hbrEdit(last, {3}, 0, kSub, 0, 0, 0)});
        OsdLimitSurface a, b;
        ASSERT_TRUE(a.build(plain));
        ASSERT_TRUE(b.build(zero));
        EXPECT_EQ(b.editLevel(), 3);
        const double diag = bboxDiagonal(plain);
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<double> unit(0, 1);
        double worst = 0, worstNormal = 0;
        size_t n = 0;
        for (uint32_t f = 0; f < plain.faceCount(); ++f)
            for (int s = 0; s < 64; ++s) {
                double u = unit(rng), v = unit(rng);
                if (s < 15) u = (s % 5) / 4.0, v = (s / 5) / 4.0;  // dyadic, corners and edges
                if (u + v > 1) u = 1 - u, v = 1 - v;
                double pa[3], na[3], pb[3], nb[3];
                const bool ha = a.evaluate(int(f), u, v, pa, na), hb = b.evaluate(int(f), u, v, pb, nb);
                ASSERT_EQ(ha, hb) << "face " << f;
                if (!ha) continue;
                const double err = distance(pa, pb) / diag;
                EXPECT_LE(err, 1e-6) << "face " << f << " (u, v) = (" << u << ", " << v << ")";
                worst = std::max(worst, err);
                if (a.normalUndefined(int(f), u, v) || (na[0] == 0 && na[1] == 0 && na[2] == 0)) continue;
                const double cosine = na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2];
                EXPECT_LE(1 - cosine, 1e-6) << "face " << f << " (u, v) = (" << u << ", " << v << ")";
                worstNormal = std::max(worstNormal, 1 - cosine);
                ++n;
            }
        std::printf("%-24s %zu points: position %.1e, 1 - cos %.1e\n", name, n, worst, worstNormal);
    }
}

// Level-0 edits move control points and take the plain path: the same surface, bit
// for bit, as the mesh with the points moved.
TEST(CheckEditsReference, LevelZeroEditsMoveControlPoints) {
    InputMesh moved = loadObj(shape("loop_xord_interior"));
    InputMesh edited = moved;
    addEdits(edited, {hbrEdit(4, {}, 2, kAdd, 0.1f, 0.2f, -0.1f), hbrEdit(4, {}, 2, kSub, 0, 0.05f, 0),
                      hbrEdit(9, {}, 0, kSet, 0.25f, 0.5f, 1)});
    const uint32_t a = moved.faces[3 * 4 + 2], b = moved.faces[3 * 9 + 0];
    ASSERT_NE(a, b);
    for (int k = 0; k < 3; ++k) {
        const double add[3] = {0.1f, 0.2f, -0.1f}, sub[3] = {0, 0.05f, 0}, set[3] = {0.25f, 0.5f, 1};
        moved.positions[3 * a + k] = float(double(moved.positions[3 * a + k]) + add[k] - sub[k]);
        moved.positions[3 * b + k] = float(set[k]);
    }
    OsdLimitSurface x, y;
    ASSERT_TRUE(x.build(moved));
    ASSERT_TRUE(y.build(edited));
    EXPECT_EQ(y.editCount(), 3u);
    EXPECT_EQ(y.editLevel(), 0);
    const double diag = bboxDiagonal(moved);
    for (uint32_t f = 0; f < moved.faceCount(); ++f)
        for (double u : {0.0, 0.25, 0.5}) {
            double px[3], nx[3], py[3], ny[3];
            ASSERT_TRUE(x.evaluate(int(f), u, 0.375, px, nx) && y.evaluate(int(f), u, 0.375, py, ny));
            EXPECT_LE(distance(px, py) / diag, 1e-7) << "face " << f;  // float positions against double edits
        }
}

TEST(CheckEditsReference, RejectsBadEditsAndHugePrefixes) {
    InputMesh mesh = loadObj(shape("loop_cube"));
    for (const HbrVertexEdit& e :
         {hbrEdit(24, {0}, 0, kAdd, 0, 1, 0), hbrEdit(0, {4}, 0, kAdd, 0, 1, 0), hbrEdit(0, {0}, 3, kAdd, 0, 1, 0)}) {
        InputMesh m = mesh;
        addEdits(m, {e});
        OsdLimitSurface ref;
        const Status st = ref.build(m);
        EXPECT_EQ(st.code, Status::BadInput) << st.message;
        EXPECT_NE(st.message.find("edit 0 (face"), std::string::npos) << st.message;
        EXPECT_FALSE(ref.built());
    }
    // 24 faces x 4^10 is above the prefix limit: refused before refining.
    addEdits(mesh, {hbrEdit(0, std::vector<uint8_t>(10, 3), 0, kAdd, 0, 1, 0)});
    OsdLimitSurface ref;
    const Status st = ref.build(mesh);
    EXPECT_EQ(st.code, Status::Unsupported) << st.message;
    EXPECT_NE(st.message.find("level 10"), std::string::npos) << st.message;
}

// loopcheck's accuracy check (checkAccuracy through SourceOracle) uses the edited
// reference: a soup of Hbr's limit points passes against the edited source and
// fails against the source without its edits; the findings name the edits.
TEST(CheckEditsReference, AccuracyCheckUsesTheEdits) {
    const std::vector<HbrVertexEdit> edits = {hbrEdit(0, {1, 3}, 2, kAdd, 0, 0.1f, 0),
                                              hbrEdit(3, {2}, 1, kSub, 0.05f, 0, 0)};
    InputMesh mesh = loadObj(shape("loop_icosahedron"));
    HbrReference hbr;
    ASSERT_TRUE(hbr.build(mesh, edits, 3));
    SourceOracle edited, plain;
    plain.mesh = mesh;
    addEdits(mesh, edits);
    edited.mesh = mesh;
    ASSERT_TRUE(edited.build());
    ASSERT_TRUE(plain.build());
    // Every final-level corner with an exact limit, its normal from the reference
    // (positions are what this checks).
    Tessellation soup;
    std::vector<SubTriangle> subs;
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) subTriangles(f, 3, subs);
    for (const SubTriangle& t : subs)
        for (int j = 0; j < 3; ++j) {
            const uint32_t v = hbr.level(3).faceVertices[3 * t.index + size_t(j)];
            if (!hbr.hasLimit(v)) continue;
            const uint32_t face = uint32_t(t.index >> 6);
            double p[3], n[3];
            ASSERT_TRUE(edited.fine.evaluate(int(face), t.uv[j][0], t.uv[j][1], p, n));
            for (int k = 0; k < 3; ++k) {
                soup.positions.push_back(float(hbr.limit(v)[k]));
                soup.normals.push_back(float(n[k]));
            }
            soup.face.push_back(face);
            soup.uv.push_back(float(t.uv[j][0]));
            soup.uv.push_back(float(t.uv[j][1]));
        }
    CheckSettings settings;
    settings.accuracySamples = soup.vertexCount();
    const double diag = bboxDiagonal(mesh);
    AccuracyResult good, bad;
    checkAccuracy(edited, soup, 3, diag, settings, 1, good);
    checkAccuracy(plain, soup, 3, diag, settings, 1, bad);
    EXPECT_EQ(good.sampled, soup.vertexCount());
    EXPECT_EQ(good.positionFailures + good.normalFailures + good.noLimit, 0u) << good.firstFailure;
    EXPECT_GT(bad.positionFailures, 0u);
    std::printf("edited source: max error %.1e; source without its edits: %llu of %llu positions off (max %.1e)\n",
                good.maxPositionError, (unsigned long long)bad.positionFailures, (unsigned long long)bad.sampled,
                bad.maxPositionError);

    // The same soup moved to the unedited surface fails against the edited source.
    Tessellation unedited = soup;
    for (size_t i = 0; i < unedited.vertexCount(); ++i) {
        double p[3], n[3];
        ASSERT_TRUE(plain.fine.evaluate(int(soup.face[i]), soup.uv[2 * i], soup.uv[2 * i + 1], p, n));
        for (int k = 0; k < 3; ++k) unedited.positions[3 * i + size_t(k)] = float(p[k]);
    }
    AccuracyResult moved;
    checkAccuracy(edited, unedited, 3, diag, settings, 1, moved);
    EXPECT_GT(moved.positionFailures, 0u);
    EXPECT_EQ(moved.referenceEdits, 2u);
    EXPECT_EQ(moved.referenceEditLevel, 2);

    CheckReport report;
    report.structureValid = true;
    report.sourceName = "ico.obj";
    report.sourceEdits = edited.fine.editCount();
    report.sourceEditLevel = edited.fine.editLevel();
    TessellationChecks t;
    t.name = "F=8 equal";
    t.path = "cpu";
    t.accuracy = moved;
    report.tessellations.push_back(t);
    addFindings(settings, report);
    bool a1 = false, a2 = false;
    for (const Finding& f : report.findings) {
        const bool names = f.text.find("2 hierarchical edits down to level 2") != std::string::npos;
        a1 |= f.id == "A1" && names;
        a2 |= f.id == "A2" && f.severity == "info" && names;
    }
    EXPECT_TRUE(a1 && a2);
}

// At a runtime depth below the deepest edit level the runtime draws only the edits
// of levels <= depth: SourceOracle::atDepth is the oracle of that surface.
TEST(CheckEditsReference, OracleAtDepthHasTheEditsOfThatDepth) {
    InputMesh mesh = loadObj(shape("loop_xord_interior"));
    SourceOracle plain;
    plain.mesh = mesh;
    ASSERT_TRUE(plain.build());
    addEdits(mesh, {hbrEdit(0, {1, 3}, 2, kAdd, 0, 0.1f, 0), hbrEdit(5, {2}, 1, kSub, 0.1f, 0, 0),
                    hbrEdit(9, {3, 3}, 0, kAdd, 0, 0, 0.1f)});
    SourceOracle full;
    full.mesh = mesh;
    ASSERT_TRUE(full.build());
    SourceOracle* at = nullptr;
    for (uint32_t depth : {2u, 6u}) {
        ASSERT_TRUE(full.atDepth(depth, at));
        EXPECT_EQ(at, &full);
    }
    ASSERT_TRUE(full.atDepth(1, at));
    EXPECT_EQ(at->fine.editCount(), 1u);
    EXPECT_EQ(at->fine.editLevel(), 1);
    SourceOracle* again = nullptr;
    ASSERT_TRUE(full.atDepth(1, again));
    EXPECT_EQ(again, at);  // built once
    ASSERT_TRUE(full.atDepth(0, at));
    EXPECT_EQ(at->fine.editCount(), 0u);
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        double pa[3], na[3], pb[3], nb[3];
        ASSERT_TRUE(at->fine.evaluate(int(f), 0.25, 0.5, pa, na) && plain.fine.evaluate(int(f), 0.25, 0.5, pb, nb));
        for (int k = 0; k < 3; ++k) EXPECT_EQ(pa[k], pb[k]) << "face " << f;
    }
}

}  // namespace
}  // namespace lt::test
