// tests/check/test_loopcheck_pieces.cpp -- a tessellation too large for memory is
// checked in pieces of whole base faces (CheckSettings::pieceTriangles forces them
// here; the memory limit does for a user). The weld of pieces (PieceWeld) is the
// weld of their concatenated soup, count for count and first failure alike, on
// shapes with boundaries, creases and non-manifold edges, with a crack planted on a
// seam between two pieces or not, and on a cone that touches itself split at every
// face (an edge settled in one piece and used in the other); and a whole run in
// pieces (runChecks) finds what the whole does: every base corner against
// OpenSubdiv, the same welded mesh, normals and escaped rays.
#include "osd_reference.h"  // loadObj, corpusMesh, corpusShapes
#include "sanitizer.h"

#include "check_internal.h"  // looptess_check_internal
#include "looptess/runtime.h"
#include "looptess/tools/baker.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace lt {
namespace {

void expectSameWeld(const WeldResult& a, const WeldResult& b) {
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.weldedVertices, b.weldedVertices);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.degenerateTriangles, b.degenerateTriangles);
    EXPECT_EQ(a.nonFiniteVertices, b.nonFiniteVertices);
    EXPECT_EQ(a.edges, b.edges);
    EXPECT_EQ(a.openEdges, b.openEdges);
    EXPECT_EQ(a.boundaryEdges, b.boundaryEdges);
    EXPECT_EQ(a.crackEdges, b.crackEdges);
    EXPECT_EQ(a.nonManifoldEdges, b.nonManifoldEdges);
    EXPECT_EQ(a.unexpectedNonManifoldEdges, b.unexpectedNonManifoldEdges);
    EXPECT_EQ(a.misorientedEdges, b.misorientedEdges);
    EXPECT_EQ(a.contactEdges, b.contactEdges);
    EXPECT_EQ(a.tJunctions, b.tJunctions);
    EXPECT_EQ(a.tJunctionVertices, b.tJunctionVertices);
    EXPECT_EQ(a.normalSplitVertices, b.normalSplitVertices);
    EXPECT_EQ(a.firstFailure, b.firstFailure);
}

// `b` appended to `a` (a soup: positions, normals, faces and (u, v)).
void append(Tessellation& a, const Tessellation& b) {
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
    a.face.insert(a.face.end(), b.face.begin(), b.face.end());
    a.uv.insert(a.uv.end(), b.uv.begin(), b.uv.end());
}

Asset baked(const std::string& path, int depth) {
    InputMesh mesh = test::loadObj(path);
    Asset asset;
    BakeSettings bs;
    bs.maxDepth = depth;
    EXPECT_TRUE(checkInput(mesh, path) && bake(mesh, bs, asset));
    return asset;
}

// `asset` evaluated whole at factor `factor` without attributes, and in pieces.
struct Evaluated {
    Evaluated(const Asset& a, float factor) : asset(a), topology(analyzeControlMesh(a)), evaluator(a) {
        eval.tessFactor = factor;
        eval.attributes = false;
        evaluator.evaluate(asset.positions.data(), eval, whole);
    }
    // The evaluation of base faces [first, end).
    Tessellation piece(uint32_t first, uint32_t end) {
        EvalSettings e = eval;
        e.firstFace = first, e.faceCount = end - first;
        Tessellation out;
        evaluator.evaluate(asset.positions.data(), e, out);
        return out;
    }
    const Asset& asset;
    ControlTopology topology;
    EvalSettings eval;
    CpuEvaluator evaluator;
    Tessellation whole;
};

std::vector<std::string> weldShapes() {
    std::vector<std::string> out = {test::corpusMesh("spot.obj")};
    for (const std::string& shape : test::corpusShapes())
        for (const char* name : {"loop_saddle_edgecorner", "loop_nonman_edge100", "loop_nonman_verts",
                                 "loop_cube_creases1", "loop_xord_boundary"})
            if (shape.find(name) != std::string::npos) out.push_back(shape);
    return out;
}

TEST(LoopcheckPieces, ThePiecesWeldAsTheirWholeSoup) {
    const std::vector<std::string> shapes = weldShapes();
    ASSERT_EQ(shapes.size(), 6u);
    for (const std::string& path : shapes) {
        SCOPED_TRACE(path);
        const Asset asset = baked(path, 3);
        Evaluated at(asset, 5);
        const ControlTopology& topology = at.topology;
        const uint32_t n = asset.faceCount();
        std::vector<Tessellation> pieces;
        for (uint32_t k = 0; k < 3; ++k) pieces.push_back(at.piece(k * n / 3, (k + 1) * n / 3));
        for (bool crack : {false, true}) {
            SCOPED_TRACE(crack ? "a crack on the seam of pieces 0 and 1" : "as evaluated");
            if (crack) {  // one ulp on a vertex of piece 0 that piece 1 has too
                std::vector<float>& p = pieces[0].positions;
                const std::vector<float>& q = pieces[1].positions;
                bool planted = false;
                for (size_t i = 0; i < p.size() / 3 && !planted; ++i)
                    for (size_t j = 0; j < q.size() / 3 && !planted; ++j)
                        if (std::memcmp(&p[3 * i], &q[3 * j], 12) == 0)
                            p[3 * i] = std::nextafter(p[3 * i], INFINITY), planted = true;
                ASSERT_TRUE(planted);
            }
            Tessellation concatenated;
            PieceWeld weld(&topology, nullptr, 0, true);
            for (const Tessellation& piece : pieces) append(concatenated, piece), weld.add(piece);
            if (weld.needsAgain())
                for (const Tessellation& piece : pieces) weld.addAgain(piece);
            WeldResult inPieces, together, fromWhole;
            weld.finish(inPieces);
            weldTessellation(concatenated, topology, together);
            expectSameWeld(inPieces, together);
            EXPECT_EQ(inPieces.crackEdges > 0, crack);
            if (crack) continue;
            weldTessellation(at.whole, topology, fromWhole);
            fromWhole.firstFailure.clear();  // the order differs
            inPieces.firstFailure.clear();
            expectSameWeld(inPieces, fromWhole);
        }
    }
}

// A cone pinched almost to a slit touches itself (W6: edges of four uses where its
// surface folds, a pair from each side): split in two at every base face, a pair
// settled in one piece is found used in the other, and a second pass over the
// pieces counts its uses as one soup does.
TEST(LoopcheckPieces, AnEdgeUsedInTwoPiecesIsCountedAsInOneSoup) {
    const Asset asset = baked(std::string(LOOPTESS_TEST_DATA) + "/normals/hunt/pinch_nearslit_cone.obj", 6);
    Evaluated at(asset, 8);
    const ControlTopology& topology = at.topology;
    const uint32_t n = asset.faceCount();
    WeldResult fromWhole;
    weldTessellation(at.whole, topology, fromWhole);
    ASSERT_GT(fromWhole.contactEdges, 0u);
    size_t seconds = 0;  // splits that needed the second pass
    for (uint32_t split = 1; split < n; ++split) {
        SCOPED_TRACE("split at face " + std::to_string(split));
        const Tessellation pieces[2] = {at.piece(0, split), at.piece(split, n)};
        Tessellation concatenated;
        for (const Tessellation& piece : pieces) append(concatenated, piece);
        PieceWeld weld(&topology, nullptr, concatenated.triangleCount(), true);
        for (const Tessellation& piece : pieces) weld.add(piece);
        if (weld.needsAgain()) {
            ++seconds;
            for (const Tessellation& piece : pieces) weld.addAgain(piece);
        }
        WeldResult inPieces, together;
        weld.finish(inPieces);
        weldTessellation(concatenated, topology, together);
        expectSameWeld(inPieces, together);
        EXPECT_EQ(inPieces.contactEdges, fromWhole.contactEdges);
    }
    EXPECT_GT(seconds, 0u);
}

TEST(LoopcheckPieces, ACaseInPiecesFindsWhatTheWholeFinds) {
    if (test::kAsan) GTEST_SKIP() << "release build only: the oracle's isolation 10 takes minutes under ASan";
    SourceOracle source;
    source.mesh = test::loadObj(test::corpusMesh("spot.obj"));
    ASSERT_TRUE(source.build());
    Asset asset;
    ASSERT_TRUE(checkInput(source.mesh, "spot") && bake(source.mesh, BakeSettings{}, asset));
    CheckSettings settings;
    settings.rays = 2000;
    settings.cases = {{TessMode::Global, 5.0f, Spacing::FractionalOdd}};
    CheckInputs in;
    in.asset = &asset;
    in.source = &source;
    CheckReport whole, pieces;
    ASSERT_TRUE(runChecks(in, settings, whole));
    ASSERT_EQ(whole.tessellations.size(), 1u);
    settings.pieceTriangles = whole.tessellations[0].triangles / 5;
    ASSERT_TRUE(runChecks(in, settings, pieces));
    ASSERT_EQ(pieces.tessellations.size(), 1u);
    const TessellationChecks &a = whole.tessellations[0], &b = pieces.tessellations[0];
    EXPECT_TRUE(a.pass() && b.pass()) << b.weld.firstFailure << b.normals.firstFailure << b.accuracy.firstFailure;
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.pieces, 1u);
    EXPECT_GE(b.pieces, 5u);
    WeldResult wa = a.weld, wb = b.weld;
    expectSameWeld(wa, wb);
    EXPECT_EQ(a.accuracy.corners, b.accuracy.corners);  // every base corner, in pieces too
    EXPECT_GT(b.accuracy.corners, 3u * asset.faceCount() - 1);
    EXPECT_GE(b.accuracy.sampled, settings.accuracySamples);
    EXPECT_EQ(a.normals.judged + a.normals.unjudged, b.normals.judged + b.normals.unjudged);
    EXPECT_EQ(a.normals.against + a.normals.zero, b.normals.against + b.normals.zero);
    EXPECT_TRUE(b.rays.ran);
    EXPECT_EQ(b.rays.rays, settings.rays);
    EXPECT_EQ(b.rays.escaped, 0u);
    EXPECT_EQ(b.rays.distanceChecked, false);  // the (u, v) index needs the whole soup
    EXPECT_NE(b.rays.distanceSkipped.find("pieces"), std::string::npos) << b.rays.distanceSkipped;
    EXPECT_TRUE(a.rays.distanceChecked);
}

}  // namespace
}  // namespace lt
