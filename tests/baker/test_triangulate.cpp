// Polygon triangulation (looptess/tools/triangulate.h) and the OBJ reader's use of it:
// no split repeats a triangle or gives an edge a third face where another split
// exists; quads take the shorter diagonal that keeps the mesh so, the inner one of a
// non-convex quad; a polygon with no such split is named in a warning.
#include "looptess/tools/baker.h"
#include "looptess/tools/triangulate.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

// A named namespace: in a unity build this file shares one with others.
namespace triangulate_test {

using lt::test::contains;

using Tri = std::array<uint32_t, 3>;

// The triangles as vertex triples (corners mapped through `indices`).
std::vector<Tri> vertexTriangles(const lt::Triangulation& t, const std::vector<uint32_t>& indices) {
    std::vector<Tri> out;
    for (size_t i = 0; i < t.corners.size(); i += 3)
        out.push_back({indices[t.corners[i]], indices[t.corners[i + 1]], indices[t.corners[i + 2]]});
    return out;
}

// Faces at the most-used edge, and how many triangles repeat another's vertices.
struct Defects {
    size_t maxEdgeFaces = 0, repeatedTriangles = 0;
};
Defects defects(const std::vector<Tri>& tris) {
    std::map<std::pair<uint32_t, uint32_t>, size_t> edges;
    std::set<Tri> seen;
    Defects d;
    for (Tri t : tris) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = t[k], b = t[(k + 1) % 3];
            d.maxEdgeFaces = std::max(d.maxEdgeFaces, ++edges[{std::min(a, b), std::max(a, b)}]);
        }
        std::sort(t.begin(), t.end());
        d.repeatedTriangles += !seen.insert(t).second;
    }
    return d;
}

lt::InputMesh parse(const std::string& text, std::vector<std::string>* warnings = nullptr) {
    lt::InputMesh m;
    lt::Status st = lt::parseObj(text, "t.obj", lt::InputOptions{}, m);
    EXPECT_TRUE(st) << st.message;
    if (warnings) *warnings = m.warnings;
    return m;
}

std::vector<Tri> faces(const lt::InputMesh& m) {
    std::vector<Tri> out;
    for (size_t i = 0; i < m.faces.size(); i += 3) out.push_back({m.faces[i], m.faces[i + 1], m.faces[i + 2]});
    return out;
}

// a=0 (0,0), b=1 (2,0), c=2 (1,1) on the line b-d, d=3 (0,2), e=4 (2,2): the square
// cut along b-c-d into two quads that share the edges b-c and c-d (c of valence 2),
// each written from a corner whose fan splits it along b-d (the old reader's fin).
const char* const kValence2 =
    "v 0 0 0\nv 2 0 0\nv 1 1 0\nv 0 2 0\nv 2 2 0\n"
    "f 2 3 4 1\n"
    "f 4 3 2 5\n";

TEST(Triangulate, QuadsSharingTwoEdgesMakeNoFin) {
    std::vector<std::string> warnings;
    const lt::InputMesh m = parse(kValence2, &warnings);
    const std::vector<Tri> tris = faces(m);
    ASSERT_EQ(tris.size(), 4u);
    const Defects d = defects(tris);
    EXPECT_EQ(d.repeatedTriangles, 0u);
    EXPECT_LE(d.maxEdgeFaces, 2u);
    // Both split through c (vertex 2): four triangles around it, none of zero area.
    for (const Tri& t : tris) EXPECT_NE(std::find(t.begin(), t.end(), 2u), t.end());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "2 polygons with more than 3 sides were triangulated (first at line 6)"))
        << warnings[0];
    std::vector<std::string> checkWarnings;
    EXPECT_TRUE(lt::checkInput(m, "t.obj", checkWarnings));
    EXPECT_TRUE(checkWarnings.empty()) << checkWarnings[0];
}

// The same topology off the plane (c lifted): the first quad may take b-d, the second
// then cannot, as b-d would get its third and fourth faces.
TEST(Triangulate, ALaterPolygonAvoidsAnEarlierDiagonal) {
    const std::vector<float> positions = {0, 0, 0, 2, 0, 0, 1.2f, 1.2f, 0.9f, 0, 2, 0, 2, 2, 0};
    const std::vector<uint32_t> counts = {4, 4}, indices = {1, 2, 3, 0, 3, 2, 1, 4};
    const lt::Triangulation t = lt::triangulatePolygons(positions, counts, indices);
    const Defects d = defects(vertexTriangles(t, indices));
    EXPECT_EQ(d.repeatedTriangles, 0u);
    EXPECT_LE(d.maxEdgeFaces, 2u);
    EXPECT_TRUE(t.unsplittable.empty());
    EXPECT_EQ(t.polygon, (std::vector<uint32_t>{0, 0, 1, 1}));
}

TEST(Triangulate, QuadTakesTheShorterDiagonal) {
    // c0 c2 is the long diagonal of this rhombus (4 against 2): split along c1 c3.
    const std::vector<float> rhombus = {-2, 0, 0, 0, -1, 0, 2, 0, 0, 0, 1, 0};
    const std::vector<uint32_t> counts = {4}, quad = {0, 1, 2, 3};
    lt::Triangulation t = lt::triangulatePolygons(rhombus, counts, quad);
    EXPECT_EQ(vertexTriangles(t, quad), (std::vector<Tri>{{1, 2, 3}, {1, 3, 0}}));
    // Rotated by one corner: c0 c2 is now the short one.
    const std::vector<uint32_t> rotated = {1, 2, 3, 0};
    t = lt::triangulatePolygons(rhombus, counts, rotated);
    EXPECT_EQ(vertexTriangles(t, rotated), (std::vector<Tri>{{1, 2, 3}, {1, 3, 0}}));
    // A square: equal diagonals, the tie goes to c0 c2 (the fan from c0).
    const std::vector<float> square = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    t = lt::triangulatePolygons(square, counts, quad);
    EXPECT_EQ(vertexTriangles(t, quad), (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}}));
    EXPECT_TRUE(t.unsplittable.empty());
    EXPECT_TRUE(t.folded.empty());
}

TEST(Triangulate, NonConvexQuadTakesItsInnerDiagonal) {
    // Arrowheads pointing down, c2 the reflex corner: c0 c2 is inside, c1 c3 outside.
    const std::vector<uint32_t> counts = {4}, quad = {0, 1, 2, 3};
    const std::vector<float> wide = {0, -1, 0, 4, 0, 0, 0, -0.5f, 0, -4, 0, 0};        // inner 0.5, outer 8
    const std::vector<float> tall = {0, -4, 0, 0.3f, 0, 0, 0, -0.1f, 0, -0.3f, 0, 0};  // inner 3.9, outer 0.6
    for (const auto* p : {&wide, &tall}) {
        const lt::Triangulation t = lt::triangulatePolygons(*p, counts, quad);
        EXPECT_EQ(vertexTriangles(t, quad), (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}}));
        EXPECT_TRUE(t.folded.empty());
    }
}

TEST(Triangulate, PentagonTakesTheFirstFanThatIsFree) {
    // A regular-ish pentagon whose diagonal 0-2 is an edge of a triangle beside it.
    const std::vector<float> positions = {1,      0,      0, 0.31f, 0.95f,  0, -0.81f, 0.59f, 0,
                                          -0.81f, -0.59f, 0, 0.31f, -0.95f, 0, 0,      0,     1};
    const std::vector<uint32_t> counts = {5, 3}, indices = {0, 1, 2, 3, 4, 2, 0, 5};
    const lt::Triangulation t = lt::triangulatePolygons(positions, counts, indices);
    const std::vector<Tri> tris = vertexTriangles(t, indices);
    ASSERT_EQ(tris.size(), 4u);
    // The fan from c0 (diagonals 0-2, 0-3) has 0-2; the fan from c1 (1-3, 1-4) is free.
    EXPECT_EQ(tris[0], (Tri{1, 2, 3}));
    EXPECT_EQ(tris[3], (Tri{2, 0, 5}));
    EXPECT_LE(defects(tris).maxEdgeFaces, 2u);
    EXPECT_TRUE(t.unsplittable.empty());
}

// A quad both of whose diagonals are edges of other faces: every split gives an edge
// a third face. The reader splits it anyway and names its line.
TEST(Triangulate, NoFreeSplitWarnsNamingThePolygon) {
    const std::string text =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nv 0.5 0.5 -1\n"
        "f 1 3 5\n"
        "f 2 4 6\n"
        "f 1 2 1\n"  // dropped by input cleaning: polygon numbers stay the file's
        "f 1 2 3 4\n";
    std::vector<std::string> warnings;
    const lt::InputMesh m = parse(text, &warnings);
    EXPECT_EQ(m.faceCount(), 4u);
    ASSERT_GE(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], "t.obj: line 10: polygon 3 of 4 sides has no triangulation without"))
        << warnings[0];

    const std::vector<uint32_t> counts = {3, 3, 4}, indices = {0, 2, 4, 1, 3, 5, 0, 1, 2, 3};
    const lt::Triangulation t = lt::triangulatePolygons(m.positions, counts, indices);
    EXPECT_EQ(t.unsplittable, (std::vector<uint32_t>{2}));
}

// Texture coordinates and vertex edits follow the split; a triangle stays itself.
TEST(Triangulate, ReaderKeepsCornersDataAndTriangles) {
    const std::string text =
        "v -2 0 0\nv 0 -1 0\nv 2 0 0\nv 0 1 0\nv 0 0 1\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "f 1/1 2/2 3/3 4/4\n"
        "f 3/3 5/1 4/4\n";
    const lt::InputMesh m = parse(text);
    ASSERT_EQ(m.faceCount(), 3u);
    // The rhombus splits along vertices 2-4 (1-3, 0-based): (1 2 3) (1 3 0).
    EXPECT_EQ(faces(m)[0], (Tri{1, 2, 3}));
    EXPECT_EQ(faces(m)[1], (Tri{1, 3, 0}));
    EXPECT_EQ(faces(m)[2], (Tri{2, 4, 3}));
    ASSERT_EQ(m.faceUVs.size(), 18u);
    // Corner 0 of triangle 0 is vertex 1 with vt 2 = (1, 0), v flipped to glTF's.
    EXPECT_EQ(m.faceUVs[0], 1.0f);
    EXPECT_EQ(m.faceUVs[1], 1.0f);
    // Corner 2 of triangle 1 is vertex 0 with vt 1 = (0, 0).
    EXPECT_EQ(m.faceUVs[10], 0.0f);
    EXPECT_EQ(m.faceUVs[11], 1.0f);
}

}  // namespace triangulate_test
