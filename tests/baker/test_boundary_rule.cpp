// The boundary rule chosen when reading (InputOptions::boundary, loopbake --boundary)
// reaches the asset and the CPU evaluator, against OpenSubdiv's limit surface with
// the same rule: a vertex of one face on the boundary is a corner with
// edge-and-corner (the limit there is the control point), a smooth boundary point
// with edge.
#include "looptess/runtime.h"
#include "looptess/tools/baker.h"
#include "osd_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace boundary_rule_test {

using lt::BoundaryInterpolation;

// A flat open unit quad as two triangles: vertices 1 and 3 (0-based) have one face,
// 0 and 2 two (the diagonal).
const char* const kQuadObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";

struct Corners {
    double distance[4] = {-1, -1, -1, -1};  // limit to control point, per vertex
    double worstToOracle = 0;
};

// Parses `obj` with `rule`, bakes, evaluates on the CPU at factor 4 and compares every
// vertex with OpenSubdiv; records each control vertex's limit point distance.
Corners evaluate(const std::string& obj, BoundaryInterpolation rule) {
    Corners c;
    lt::InputOptions options;
    options.boundary = rule;
    lt::InputMesh mesh;
    lt::Status st = lt::parseObj(obj, "quad.obj", options, mesh);
    EXPECT_TRUE(st) << st.message;
    EXPECT_EQ(mesh.boundary, rule);
    lt::Asset asset;
    lt::BakeSettings settings;
    settings.maxDepth = 3;
    st = lt::bake(mesh, settings, asset);
    EXPECT_TRUE(st) << st.message;
    EXPECT_EQ(asset.boundary, rule);
    lt::EvalSettings es;
    es.tessFactor = 4;
    lt::Tessellation soup;
    lt::evaluateCpu(asset, asset.positions.data(), es, soup);
    EXPECT_GT(soup.vertexCount(), 0u);
    lt::test::OsdLimit osd(mesh);
    for (size_t i = 0; i < soup.vertexCount(); ++i) {
        const uint32_t face = soup.face[i];
        const double u = soup.uv[2 * i], v = soup.uv[2 * i + 1];
        double pos[3], n[3];
        EXPECT_TRUE(osd.evaluate(int(face), u, v, pos, n));
        for (int k = 0; k < 3; ++k)
            c.worstToOracle = std::max(c.worstToOracle, std::fabs(pos[k] - double(soup.positions[3 * i + k])));
        const int corner = u == 0 && v == 0 ? 0 : u == 1 && v == 0 ? 1 : u == 0 && v == 1 ? 2 : -1;
        if (corner < 0) continue;
        const uint32_t vertex = mesh.faces[3 * size_t(face) + size_t(corner)];
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = double(soup.positions[3 * i + k]) - double(mesh.positions[3 * size_t(vertex) + k]);
            d2 += d * d;
        }
        c.distance[vertex] = std::sqrt(d2);
    }
    return c;
}

TEST(BoundaryRule, EdgeAndCornerKeepsTheCornersOfOneFace) {
    const Corners corner = evaluate(kQuadObj, BoundaryInterpolation::EdgeAndCorner);
    const Corners edge = evaluate(kQuadObj, BoundaryInterpolation::EdgeOnly);
    EXPECT_LT(corner.worstToOracle, 1e-6);
    EXPECT_LT(edge.worstToOracle, 1e-6);
    for (uint32_t v : {1u, 3u}) {
        SCOPED_TRACE("vertex " + std::to_string(v));
        EXPECT_EQ(corner.distance[v], 0.0);  // the control point, bit for bit
        EXPECT_GT(edge.distance[v], 0.1);    // edge-only: rounded off (1/6 of the diagonal)
    }
    // Vertices 0 and 2 have two faces: a smooth boundary point under either rule, as
    // OpenSubdiv's (a corner there needs a corner tag).
    for (uint32_t v : {0u, 2u}) {
        SCOPED_TRACE("vertex " + std::to_string(v));
        EXPECT_GT(corner.distance[v], 0.1);
        EXPECT_NEAR(corner.distance[v], edge.distance[v], 1e-6);
    }
}

// With a corner tag on the two vertices of two faces, edge-and-corner keeps all four
// corners of the quad where it is.
TEST(BoundaryRule, FourCornersWithCornerTagsOnTheDiagonal) {
    const Corners c = evaluate(std::string(kQuadObj) + "t corner 2/1/0 0 2 10\n", BoundaryInterpolation::EdgeAndCorner);
    EXPECT_LT(c.worstToOracle, 1e-6);
    for (uint32_t v = 0; v < 4; ++v) EXPECT_EQ(c.distance[v], 0.0) << "vertex " << v;
}

// One quad polygon, as a DCC writes it: under edge-and-corner all four of its corners
// are corners (a vertex of one polygon), whatever diagonal splits it; the reader tags
// the two that the split gives a second triangle (keepPolygonCorners), and the
// surface still matches OpenSubdiv's with the mesh as read. Under edge-only none is.
TEST(BoundaryRule, EdgeAndCornerKeepsEveryCornerOfAPolygon) {
    const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    const Corners corner = evaluate(quad, BoundaryInterpolation::EdgeAndCorner);
    const Corners edge = evaluate(quad, BoundaryInterpolation::EdgeOnly);
    EXPECT_LT(corner.worstToOracle, 1e-6);
    EXPECT_LT(edge.worstToOracle, 1e-6);
    for (uint32_t v = 0; v < 4; ++v) {
        SCOPED_TRACE("vertex " + std::to_string(v));
        EXPECT_EQ(corner.distance[v], 0.0);
        EXPECT_GT(edge.distance[v], 0.1);
    }
}

// InputOptions::boundary overrides an OBJ's tag, with a warning naming the tag's line
// when they differ; without it the tag holds.
TEST(BoundaryRule, OptionOverridesTheObjTag) {
    const std::string tagged = std::string(kQuadObj) + "t interpolateboundary 1/0/0 2\n";
    lt::InputOptions options;
    lt::InputMesh mesh;
    ASSERT_TRUE(lt::parseObj(tagged, "quad.obj", options, mesh));
    EXPECT_EQ(mesh.boundary, BoundaryInterpolation::EdgeOnly);
    EXPECT_TRUE(mesh.warnings.empty());
    options.boundary = BoundaryInterpolation::EdgeAndCorner;
    ASSERT_TRUE(lt::parseObj(tagged, "quad.obj", options, mesh));
    EXPECT_EQ(mesh.boundary, BoundaryInterpolation::EdgeAndCorner);
    ASSERT_EQ(mesh.warnings.size(), 1u);
    EXPECT_EQ(mesh.warnings[0],
              "quad.obj: line 7: 'interpolateboundary' tag says edge; using --boundary edge-and-corner");
    options.boundary = BoundaryInterpolation::EdgeOnly;  // the same rule: no warning
    ASSERT_TRUE(lt::parseObj(tagged, "quad.obj", options, mesh));
    EXPECT_TRUE(mesh.warnings.empty());
    options.boundary = BoundaryInterpolation::None;  // no tag: no warning
    ASSERT_TRUE(lt::parseObj(kQuadObj, "quad.obj", options, mesh));
    EXPECT_EQ(mesh.boundary, BoundaryInterpolation::None);
    EXPECT_TRUE(mesh.warnings.empty());
}

TEST(BoundaryRule, OptionNames) {
    BoundaryInterpolation b = BoundaryInterpolation::None;
    for (BoundaryInterpolation r :
         {BoundaryInterpolation::None, BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::EdgeAndCorner}) {
        ASSERT_TRUE(lt::parseBoundaryOption(lt::boundaryOptionName(r), b));
        EXPECT_EQ(b, r);
    }
    EXPECT_STREQ(lt::boundaryOptionName(BoundaryInterpolation::EdgeOnly), "edge");
    EXPECT_FALSE(lt::parseBoundaryOption("edge-only", b));
    EXPECT_FALSE(lt::parseBoundaryOption("", b));
    EXPECT_EQ(b, BoundaryInterpolation::EdgeAndCorner);
}

}  // namespace boundary_rule_test
