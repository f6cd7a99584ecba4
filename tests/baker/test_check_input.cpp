// test_check_input.cpp -- checkInput's verdicts on hand-made meshes and
// addCreasesByAngle (parseObj and the corpus: test_input.cpp).
#include "looptess/tools/baker.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

bool hasText(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

lt::InputMesh tetrahedron() {
    lt::InputMesh m;
    m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    m.faces = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    return m;
}

// ---- checkInput -----------------------------------------------------------------

TEST(CheckInput, AcceptsValidAndNonManifoldMeshes) {
    EXPECT_TRUE(lt::checkInput(tetrahedron(), "m"));
    // Three fins on edge 0-1: non-manifold, accepted; each fin is its own component.
    lt::InputMesh fins;
    fins.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1};
    fins.faces = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    lt::Status st = lt::checkInput(fins, "m");
    EXPECT_TRUE(st) << st.message;
}

TEST(CheckInput, EachError) {
    struct Case {
        const char* what;
        void (*edit)(lt::InputMesh&);
        const char* expected;
    };
    const Case cases[] = {
        {"empty", [](lt::InputMesh& m) { m.faces.clear(); }, "m: mesh has no faces"},
        {"nan", [](lt::InputMesh& m) { m.positions[7] = NAN; }, "m: vertex 2 has a non-finite position (nan)"},
        {"inf", [](lt::InputMesh& m) { m.positions[0] = -INFINITY; }, "vertex 0 has a non-finite"},
        {"range", [](lt::InputMesh& m) { m.faces[4] = 7; },
         "face 1 references vertex 7, out of range (mesh has 4 vertices)"},
        {"degenerate", [](lt::InputMesh& m) { m.faces[5] = 0; }, "face 1 is degenerate"},
        {"repeated",
         [](lt::InputMesh& m) {
             m.faces.insert(m.faces.end(), {3, 1, 2});
         },
         "face 4 repeats face 2 (same vertices 1, 2, 3, same orientation)"},
        {"flipped", [](lt::InputMesh& m) { std::swap(m.faces[0], m.faces[1]); }, "both use edge"},
        {"crease sharpness",
         [](lt::InputMesh& m) {
             m.creases.push_back({0, 1, -2});
         },
         "crease 0 (vertices 0-1) has negative sharpness -2"},
        {"crease nan",
         [](lt::InputMesh& m) {
             m.creases.push_back({0, 1, NAN});
         },
         "crease 0 (vertices 0-1) has an invalid sharpness"},
        {"crease range",
         [](lt::InputMesh& m) {
             m.creases.push_back({0, 4, 1});
         },
         "crease 0 (vertices 0-4) names vertex 4, out of range"},
        {"crease self",
         [](lt::InputMesh& m) {
             m.creases.push_back({2, 2, 1});
         },
         "crease 0 (vertices 2-2) is not an edge of the mesh"},
        {"corner range",
         [](lt::InputMesh& m) {
             m.corners.push_back({9, 1});
         },
         "corner 0 names vertex 9, out of range"},
        {"corner sharpness",
         [](lt::InputMesh& m) {
             m.corners.push_back({1, -1});
         },
         "corner 0 has negative sharpness -1"},
        {"hole range", [](lt::InputMesh& m) { m.holes.push_back(4); },
         "hole 0 names face 4, out of range (mesh has 4 faces)"},
        {"uv count", [](lt::InputMesh& m) { m.faceUVs.resize(6); }, "texture coordinate count does not match"},
    };
    for (const Case& c : cases) {
        lt::InputMesh m = tetrahedron();
        c.edit(m);
        lt::Status st = lt::checkInput(m, "m");
        EXPECT_EQ(st.code, lt::Status::BadInput) << c.what;
        EXPECT_TRUE(hasText(st.message, c.expected)) << c.what << "\ngot: " << st.message;
    }
}

TEST(CheckInput, ZeroAreaIsAWarning) {
    lt::InputMesh m;
    m.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0};
    m.faces = {0, 1, 3, 1, 2, 3, 0, 2, 1};  // the last is collinear
    std::vector<std::string> warnings;
    lt::Status st = lt::checkInput(m, "z", warnings);
    EXPECT_TRUE(st) << st.message;
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], "z: 1 faces have zero area (first: face 2)");
}

// ---- addCreasesByAngle ----------------------------------------------------------

lt::InputMesh cube() {
    lt::InputMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.insert(m.positions.end(), {float(i & 1), float((i >> 1) & 1), float(i >> 2)});
    const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) m.faces.insert(m.faces.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    return m;
}

TEST(CreaseAngle, CubeEdgesOnly) {
    lt::InputMesh m = cube();
    ASSERT_TRUE(lt::checkInput(m, "cube"));
    lt::addCreasesByAngle(m, 95);
    EXPECT_TRUE(m.creases.empty());
    lt::addCreasesByAngle(m, 30);
    ASSERT_EQ(m.creases.size(), 12u);  // the 12 cube edges, not the 6 face diagonals
    for (size_t i = 0; i < m.creases.size(); ++i) {
        const auto& c = m.creases[i];
        EXPECT_EQ(c.sharpness, 10.0f);
        EXPECT_LT(c.a, c.b);
        EXPECT_EQ(__builtin_popcount(c.a ^ c.b), 1) << c.a << "-" << c.b << " is a diagonal";
        if (i > 0) { EXPECT_LT(std::make_pair(m.creases[i - 1].a, m.creases[i - 1].b), std::make_pair(c.a, c.b)); }
    }
    EXPECT_TRUE(lt::checkInput(m, "cube"));
}

TEST(CreaseAngle, ExplicitCreasesWinAndBoundariesAreSkipped) {
    lt::InputMesh m = cube();
    m.creases.push_back({3, 1, 0.5f});
    lt::addCreasesByAngle(m, 30);
    ASSERT_EQ(m.creases.size(), 12u);
    EXPECT_EQ(m.creases[0].sharpness, 0.5f);
    lt::InputMesh open = cube();
    open.faces.resize(open.faces.size() - 6);  // drop one side: its 4 edges become boundary
    lt::addCreasesByAngle(open, 30);
    EXPECT_EQ(open.creases.size(), 8u);
}

}  // namespace
