// The Hbr oracle (hbr_reference.h) checked against OpenSubdiv Far, so that the
// hierarchical-edit tests can trust it.
//
// Matching. Far (RefineUniform + PrimvarRefinerReal<double>) and the oracle are
// matched through sub-triangle paths: level 0's faces are the input's in both;
// Far's GetFaceChildFaces(f)[i] is given the path of f followed by i, and corner j
// of a Far face is compared with corner j of the oracle's sub-triangle of the same
// path (HbrReference::vertex). The map from Far's vertices to the oracle's must
// come out one-to-one, and the positions must agree; ChildOrderIsLoopOrder checks
// the child order itself against Far's parent-to-child vertex links.
//
// Tolerance: 1e-6 of the control mesh's bounding-box diagonal. Hbr takes
// its weights in float (0.375f, cosf), so it agrees with Far to about 1e-8 only.
#include "hbr_reference.h"
#include "osd_reference.h"
#include "looptess/tools/osd.h"  // the mesh as Far topology, refined uniformly

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/sdc/crease.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace lt::test {
namespace {

using Point3 = OsdPoint;

// Far's uniform refinement of `mesh`: topology, points per level, sub-triangle
// paths per level, the limit of the last level.
struct FarUniform {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::vector<std::vector<Point3>> points;      // per level
    std::vector<std::vector<uint64_t>> facePath;  // per level: Far face -> HbrReference::subFace

    const Far::TopologyLevel& level(int l) const { return refiner->GetLevel(l); }
    int levels() const { return refiner->GetMaxLevel(); }

    // Far's own refinement of `parent` (points of level l-1) into level l.
    std::vector<Point3> interpolate(int l, const std::vector<Point3>& parent) const {
        std::vector<Point3> out(size_t(level(l).GetNumVertices()));
        const Point3* src = parent.data();
        Point3* dst = out.data();
        Far::PrimvarRefinerReal<double>(*refiner).Interpolate(l, src, dst);
        return out;
    }
    std::vector<Point3> limit(const std::vector<Point3>& last) const {
        std::vector<Point3> out(last.size());
        const Point3* src = last.data();
        Point3* dst = out.data();
        Far::PrimvarRefinerReal<double>(*refiner).Limit(src, dst);
        return out;
    }
};

FarUniform farUniform(const InputMesh& mesh, int levels) {
    FarUniform far;
    const Status st = createRefiner(mesh, "far", far.refiner);
    EXPECT_TRUE(st) << st.message;
    if (!far.refiner) return far;
    refineUniform(*far.refiner, levels);
    far.points.resize(size_t(levels) + 1);
    far.facePath.resize(size_t(levels) + 1);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        Point3 p;
        for (int k = 0; k < 3; ++k) p.p[k] = mesh.positions[3 * size_t(v) + size_t(k)];
        far.points[0].push_back(p);
    }
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) far.facePath[0].push_back(f);
    for (int l = 1; l <= levels; ++l) {
        far.points[size_t(l)] = far.interpolate(l, far.points[size_t(l) - 1]);
        far.facePath[size_t(l)].assign(size_t(far.level(l).GetNumFaces()), ~uint64_t(0));
        for (OsdIndex f = 0; f < far.level(l - 1).GetNumFaces(); ++f) {
            auto children = far.level(l - 1).GetFaceChildFaces(f);
            EXPECT_EQ(children.size(), 4);
            for (int i = 0; i < children.size(); ++i)
                far.facePath[size_t(l)][size_t(children[i])] = far.facePath[size_t(l) - 1][size_t(f)] * 4 + uint64_t(i);
        }
    }
    return far;
}

// Far vertex -> oracle vertex at level l, through the sub-triangle paths; checks
// that the map is one-to-one and onto.
std::vector<uint32_t> matchLevel(const FarUniform& far, const HbrReference& hbr, int l) {
    const auto& topo = far.level(l);
    const HbrLevel& h = hbr.level(l);
    std::vector<uint32_t> farToHbr(size_t(topo.GetNumVertices()), ~0u), hbrToFar(h.vertexCount(), ~0u);
    EXPECT_EQ(uint32_t(topo.GetNumFaces()), h.faceCount()) << "level " << l;
    EXPECT_EQ(uint32_t(topo.GetNumVertices()), h.vertexCount()) << "level " << l;
    for (OsdIndex f = 0; f < topo.GetNumFaces(); ++f) {
        const uint64_t path = far.facePath[size_t(l)][size_t(f)];
        if (path >= h.faceCount()) {
            ADD_FAILURE() << "level " << l << " face " << f << ": path " << path << " out of range";
            continue;
        }
        auto fv = topo.GetFaceVertices(f);
        for (int j = 0; j < 3; ++j) {
            const uint32_t hv = h.faceVertices[3 * path + size_t(j)];
            uint32_t& a = farToHbr[size_t(fv[j])];
            uint32_t& b = hbrToFar[hv];
            if (a == ~0u) a = hv;
            if (b == ~0u) b = uint32_t(fv[j]);
            EXPECT_TRUE(a == hv && b == uint32_t(fv[j])) << "level " << l << " face " << f << " corner " << j;
        }
    }
    for (uint32_t x : farToHbr) EXPECT_NE(x, ~0u) << "level " << l << ": a Far vertex in no face";
    return farToHbr;
}

// Largest distance between Far's `points` and the oracle's level l (mapped).
double maxError(const std::vector<Point3>& points, const HbrReference& hbr, int l, const std::vector<uint32_t>& map) {
    double worst = 0;
    for (size_t v = 0; v < points.size(); ++v) {
        const double* h = hbr.position(l, map[v]);
        double d2 = 0;
        for (int k = 0; k < 3; ++k) d2 += (points[v].p[k] - h[k]) * (points[v].p[k] - h[k]);
        worst = std::max(worst, std::sqrt(d2));
    }
    return worst;
}

// The oracle's level l in Far's numbering.
std::vector<Point3> inFarOrder(const HbrReference& hbr, int l, const std::vector<uint32_t>& map) {
    std::vector<Point3> out(map.size());
    for (size_t v = 0; v < map.size(); ++v)
        for (int k = 0; k < 3; ++k) out[v].p[k] = hbr.position(l, map[v])[k];
    return out;
}

// Oracle limits against Far's limit masks on the oracle's own final level (Far
// numbering). Returns {compared, worst}.
std::pair<size_t, double> limitError(const FarUniform& far, const HbrReference& hbr, const std::vector<uint32_t>& map) {
    const int n = far.levels();
    std::vector<Point3> ref = far.limit(inFarOrder(hbr, n, map));
    size_t compared = 0;
    double worst = 0;
    for (size_t v = 0; v < ref.size(); ++v) {
        if (!hbr.hasLimit(map[v])) continue;
        ++compared;
        double d2 = 0;
        for (int k = 0; k < 3; ++k) d2 += (ref[v].p[k] - hbr.limit(map[v])[k]) * (ref[v].p[k] - hbr.limit(map[v])[k]);
        worst = std::max(worst, std::sqrt(d2));
    }
    return {compared, worst};
}

std::string shape(const char* name) { return std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/" + name + ".obj"; }

// Smooth closed shapes, EDGE_ONLY boundaries with corners (sharp and semi-sharp
// vertices), EDGE_AND_CORNER, creases, an extraordinary boundary vertex.
const char* const kShapes[] = {"loop_cube",           "loop_icosahedron",   "loop_triangle_edgeonly",
                               "loop_xord_interior",  "loop_xord_boundary", "loop_saddle_edgeonly",
                               "loop_tetrahedron",    "loop_pole8",         "loop_cube_creases0",
                               "loop_icos_semisharp", "loop_cubes_infsharp"};

// The oracle without edits against Far, level by level, and its limit masks.
void checkWithoutEdits(const char* name, const std::string& path, int levels) {
    SCOPED_TRACE(name);
    InputMesh mesh = loadObj(path);
    const double diag = bboxDiagonal(mesh);
    HbrReference hbr;
    Status st = hbr.build(mesh, {}, levels);
    ASSERT_TRUE(st) << st.message;
    FarUniform far = farUniform(mesh, levels);
    ASSERT_TRUE(far.refiner);
    std::vector<uint32_t> map;
    std::printf("%-24s", name);
    for (int l = 0; l <= levels; ++l) {
        map = matchLevel(far, hbr, l);
        const double err = maxError(far.points[size_t(l)], hbr, l, map) / diag;
        EXPECT_LE(err, 1e-6) << "level " << l;
        std::printf("  L%d %5u v %.1e", l, hbr.level(l).vertexCount(), err);
    }
    // The oracle's limit masks against Far's, on the oracle's last level (the same
    // points: agreement to rounding) and on Far's own (within Hbr's float weights).
    const auto [compared, worst] = limitError(far, hbr, map);
    std::vector<Point3> farLimit = far.limit(far.points[size_t(levels)]);
    double worstFar = 0;
    for (size_t v = 0; v < map.size(); ++v) {
        if (!hbr.hasLimit(map[v])) continue;
        for (int k = 0; k < 3; ++k) worstFar = std::max(worstFar, std::fabs(farLimit[v].p[k] - hbr.limit(map[v])[k]));
    }
    EXPECT_LE(worst / diag, 1e-12);
    EXPECT_LE(worstFar / diag, 1e-6);
    EXPECT_GT(compared, map.size() / 2);
    std::printf("  limit %zu/%zu %.1e (vs Far's refinement %.1e)\n", compared, map.size(), worst / diag,
                worstFar / diag);
}

TEST(HbrOracle, MatchesFarUniformWithoutEdits) {
    for (const char* name : kShapes) checkWithoutEdits(name, shape(name), 3);
}

// Child i keeps corner i: (v0, e0, e2), (e0, v1, e1), (e2, e1, v2); child 3 is
// (e1, e2, e0). Checked for Far by topology, for Hbr by position (the expected
// Far vertex is the nearest of all level-1 vertices to the oracle's corner).
TEST(HbrOracle, ChildOrderIsLoopOrder) {
    for (const char* name : {"loop_cube", "loop_xord_interior", "loop_triangle_edgeonly"}) {
        SCOPED_TRACE(name);
        InputMesh mesh = loadObj(shape(name));
        HbrReference hbr;
        ASSERT_TRUE(hbr.build(mesh, {}, 1));
        FarUniform far = farUniform(mesh, 1);
        const auto& base = far.level(0);
        const auto& fine = far.level(1);
        size_t checked = 0;
        for (OsdIndex f = 0; f < base.GetNumFaces(); ++f) {
            auto fv = base.GetFaceVertices(f);
            auto fe = base.GetFaceEdges(f);
            OsdIndex V[3], E[3];
            for (int i = 0; i < 3; ++i) {
                V[i] = base.GetVertexChildVertex(fv[i]);
                E[i] = base.GetEdgeChildVertex(fe[i]);
                auto ev = base.GetEdgeVertices(fe[i]);  // edge i joins corners i and i+1
                ASSERT_TRUE((ev[0] == fv[i] && ev[1] == fv[(i + 1) % 3]) ||
                            (ev[1] == fv[i] && ev[0] == fv[(i + 1) % 3]));
            }
            const OsdIndex expected[4][3] = {
                {V[0], E[0], E[2]}, {E[0], V[1], E[1]}, {E[2], E[1], V[2]}, {E[1], E[2], E[0]}};
            auto children = base.GetFaceChildFaces(f);
            for (int i = 0; i < 4; ++i) {
                auto cv = fine.GetFaceVertices(children[i]);
                for (int j = 0; j < 3; ++j) {
                    EXPECT_EQ(cv[j], expected[i][j]) << "Far face " << f << " child " << i << " corner " << j;
                    const double* h = hbr.position(1, hbr.vertex(uint32_t(f), {uint8_t(i)}, j));
                    OsdIndex nearest = -1;
                    double best = INFINITY;
                    for (OsdIndex v = 0; v < fine.GetNumVertices(); ++v) {
                        double d2 = 0;
                        for (int k = 0; k < 3; ++k) d2 += std::pow(far.points[1][size_t(v)].p[k] - h[k], 2);
                        if (d2 < best) best = d2, nearest = v;
                    }
                    EXPECT_EQ(nearest, expected[i][j]) << "Hbr face " << f << " child " << i << " corner " << j;
                    ++checked;
                }
            }
        }
        std::printf("%-24s child order checked on %zu corners\n", name, checked);
    }
}

// Vertices of level k+1 whose subdivision rule reads vertex `e` of level k.
std::vector<OsdIndex> readers(const Far::TopologyLevel& t, OsdIndex e) {
    std::vector<OsdIndex> out{t.GetVertexChildVertex(e)};
    for (OsdIndex edge : t.GetVertexEdges(e)) {
        out.push_back(t.GetEdgeChildVertex(edge));  // e is an end point
        const OsdIndex u = otherEnd(t, edge, e);
        const auto rule = t.GetVertexRule(u);
        const bool sharp = t.IsEdgeBoundary(edge) || t.IsEdgeInfSharp(edge) || t.GetEdgeSharpness(edge) > 0;
        if (rule == Sdc::Crease::RULE_SMOOTH || rule == Sdc::Crease::RULE_DART ||
            (rule == Sdc::Crease::RULE_CREASE && sharp))
            out.push_back(t.GetVertexChildVertex(u));  // u's vertex rule reads its ring
    }
    for (OsdIndex f : t.GetVertexFaces(e))
        for (OsdIndex edge : t.GetFaceEdges(f)) {  // the edge opposite e: its edge point reads e
            auto ev = t.GetEdgeVertices(edge);
            const bool infSharp = t.IsEdgeBoundary(edge) || t.IsEdgeInfSharp(edge);
            if (ev[0] != e && ev[1] != e && !infSharp && t.GetEdgeSharpness(edge) < 1.0f)
                out.push_back(t.GetEdgeChildVertex(edge));
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// One edit checked against the unedited oracle and Far: levels before the edit
// unchanged (bitwise), at its level only the edited vertex changes and by exactly
// the edit, every finer level is Far's refinement of the oracle's edited level
// above, the vertices that change at level k+1 are exactly those whose rules read
// the edited vertex, and the limits are Far's limit masks on the edited last level.
void checkEdit(const char* name, const HbrVertexEdit& edit, int levels, const std::string& path = "") {
    SCOPED_TRACE(std::string(name) + " edit at level " + std::to_string(edit.level()));
    InputMesh mesh = loadObj(path.empty() ? shape(name) : path);
    const double diag = bboxDiagonal(mesh);
    HbrReference plain, edited;
    ASSERT_TRUE(plain.build(mesh, {}, levels));
    Status st = edited.build(mesh, {edit}, levels);
    ASSERT_TRUE(st) << st.message;
    FarUniform far = farUniform(mesh, levels);
    const int k = edit.level();
    const uint32_t ev = edited.vertex(edit.face, edit.children, edit.vertex);
    std::printf("%-24s edit (%u;", name, edit.face);
    for (uint8_t c : edit.children) std::printf(" %d", c);
    std::printf("; %d) level %d:", edit.vertex, k);
    std::vector<uint32_t> map;
    for (int l = 0; l <= levels; ++l) {
        map = matchLevel(far, edited, l);
        ASSERT_EQ(plain.level(l).faceVertices, edited.level(l).faceVertices);  // same numbering
        const std::vector<double>& a = plain.level(l).positions;
        const std::vector<double>& b = edited.level(l).positions;
        std::vector<uint32_t> changed;
        for (uint32_t v = 0; v < edited.level(l).vertexCount(); ++v)
            if (a[3 * v] != b[3 * v] || a[3 * v + 1] != b[3 * v + 1] || a[3 * v + 2] != b[3 * v + 2])
                changed.push_back(v);
        if (l < k) {
            EXPECT_TRUE(changed.empty()) << "level " << l;
        } else if (l == k) {
            ASSERT_EQ(changed.size(), 1u) << "level " << l;
            EXPECT_EQ(changed[0], ev);
            for (int c = 0; c < 3; ++c) {
                const double before = a[3 * ev + size_t(c)], value = double(edit.value[c]);
                const double expect = edit.op == HbrEditOp::Set   ? value
                                      : edit.op == HbrEditOp::Add ? before + value
                                                                  : before - value;
                EXPECT_EQ(b[3 * ev + size_t(c)], expect) << "coordinate " << c;
            }
        } else {
            // Level l is Far's subdivision of the oracle's (edited) level l-1.
            std::vector<uint32_t> parentMap = matchLevel(far, edited, l - 1);
            std::vector<Point3> ref = far.interpolate(l, inFarOrder(edited, l - 1, parentMap));
            const double err = maxError(ref, edited, l, map) / diag;
            EXPECT_LE(err, 1e-6) << "level " << l;
            if (l == k + 1) {
                std::vector<OsdIndex> farEv;
                for (size_t v = 0; v < parentMap.size(); ++v)
                    if (parentMap[v] == ev) farEv.push_back(OsdIndex(v));
                ASSERT_EQ(farEv.size(), 1u);
                std::vector<uint32_t> expect;
                for (OsdIndex r : readers(far.level(k), farEv[0])) expect.push_back(map[size_t(r)]);
                std::sort(expect.begin(), expect.end());
                EXPECT_EQ(changed, expect) << "the vertices that read the edited one";
            }
            std::printf("  L%d %zu changed, %.1e", l, changed.size(), err);
        }
    }
    const auto [compared, worst] = limitError(far, edited, map);
    EXPECT_LE(worst / diag, 1e-12);
    std::printf("  limit %zu %.1e\n", compared, worst / diag);
}

TEST(HbrOracle, AddAtLevel2MovesTheVertexAndItsDescendants) {
    for (const char* name : {"loop_cube", "loop_icosahedron", "loop_xord_interior", "loop_triangle_edgeonly"})
        checkEdit(name, hbrEdit(0, {1, 3}, 2, HbrEditOp::Add, 0.0f, 0.1f, 0.0f), 4);
    // A vertex of the middle child's middle child, and one on a boundary.
    checkEdit("loop_xord_interior", hbrEdit(5, {3, 3}, 0, HbrEditOp::Add, 0.0f, 0.1f, 0.0f), 4);
    checkEdit("loop_triangle_edgeonly", hbrEdit(3, {0, 0}, 0, HbrEditOp::Add, 0.0f, 0.1f, 0.0f), 4);
}

// A real mesh (spot, 5,856 triangles, extraordinary vertices everywhere).
TEST(HbrOracle, Spot) {
    checkWithoutEdits("spot", corpusMesh("spot.obj"), 2);
    checkEdit("spot", hbrEdit(1000, {2, 3}, 1, HbrEditOp::Add, 0.0f, 0.05f, 0.0f), 3, corpusMesh("spot.obj"));
}

TEST(HbrOracle, SetAndSubtractAtLevels0To3) {
    checkEdit("loop_cube", hbrEdit(2, {}, 1, HbrEditOp::Add, 0.05f, 0.0f, 0.0f), 3);
    checkEdit("loop_cube", hbrEdit(2, {2}, 1, HbrEditOp::Set, 0.3f, 0.2f, 0.1f), 3);
    checkEdit("loop_icosahedron", hbrEdit(7, {3}, 0, HbrEditOp::Subtract, 0.0f, 0.0f, 0.2f), 3);
    checkEdit("loop_icosahedron", hbrEdit(7, {0, 1, 2}, 1, HbrEditOp::Add, 0.02f, -0.03f, 0.01f), 4);
    checkEdit("loop_xord_interior", hbrEdit(11, {3, 0, 3}, 2, HbrEditOp::Set, 0.0f, 1.0f, 0.0f), 4);
}

// Two edits on the same level-2 vertex named through two different sub-triangles
// both apply (Hbr walks the edits of every face around the vertex).
TEST(HbrOracle, EditsNamingOneVertexTwiceBothApply) {
    InputMesh mesh = loadObj(shape("loop_cube"));
    HbrReference plain, twice;
    ASSERT_TRUE(plain.build(mesh, {}, 2));
    // Both paths name the level-2 vertex point of face 0's edge-0 point e0: child 1
    // of face 0 is (e0, v1, e1) and its child 0 keeps corner 0; child 0 is
    // (v0, e0, e2) and its child 1 keeps corner 1.
    const uint32_t a = plain.vertex(0, {1, 0}, 0), b = plain.vertex(0, {0, 1}, 1);
    ASSERT_EQ(a, b);  // one vertex, two paths
    Status st = twice.build(mesh,
                            {hbrEdit(0, {1, 0}, 0, HbrEditOp::Add, 0.0f, 0.1f, 0.0f),
                             hbrEdit(0, {0, 1}, 1, HbrEditOp::Add, 0.0f, 0.0f, 0.2f)},
                            2);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(twice.position(2, a)[0], plain.position(2, a)[0]);
    EXPECT_EQ(twice.position(2, a)[1], plain.position(2, a)[1] + double(0.1f));
    EXPECT_EQ(twice.position(2, a)[2], plain.position(2, a)[2] + double(0.2f));
}

TEST(HbrOracle, RejectsBadEdits) {
    InputMesh mesh = loadObj(shape("loop_cube"));
    HbrReference hbr;
    const auto add = HbrEditOp::Add;
    for (const HbrVertexEdit& e :
         {hbrEdit(24, {0}, 0, add, 0, 1, 0), hbrEdit(0, {4}, 0, add, 0, 1, 0), hbrEdit(0, {0}, 3, add, 0, 1, 0),
          hbrEdit(0, {0, 0, 0, 0}, 0, add, 0, 1, 0), hbrEdit(0, {0}, 0, add, 0, NAN, 0)}) {
        Status st = hbr.build(mesh, {e}, 3);
        EXPECT_EQ(st.code, Status::BadInput) << st.message;
        EXPECT_NE(st.message.find("edit (face"), std::string::npos) << st.message;
    }
    mesh.creaseMethod = CreaseMethod::Chaikin;
    EXPECT_EQ(hbr.build(mesh, {}, 2).code, Status::Unsupported);
}

}  // namespace
}  // namespace lt::test
