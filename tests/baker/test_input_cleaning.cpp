// tests/baker/test_input_cleaning.cpp -- input cleaning (baker/internal/mesh_clean.h): the
// FaceCleaner's rules, how parseObj, parseGltf and parseGltfScene keep texture
// coordinates, holes, edits, creases and the glTF cage consistent with what they drop,
// InputCleaning::Refuse and Keep, and loopbake's warnings, --json counts and --strict
// end to end. Also: loopbake's errors quote no more than an excerpt of the input.
#include "looptess/tools/baker.h"

#include "gltf_fixture.h"
#include "mesh_clean.h"
#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using Fate = lt::FaceCleaner::Fate;
using gltftest::Bytes;
using gltftest::Json;
using lt::test::contains;
using lt::test::readText;
using lt::test::RunResult;

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
}

std::string lineName(uint64_t tag) { return "line " + std::to_string(tag); }

// ---- FaceCleaner ----------------------------------------------------------------

// Eight vertices in general position (no three on a line), for the rules that are
// about indices only.
const std::vector<float> kGeneral = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 1, 2, 1, 1, 3, 2, 0, 0, 3, 2};

struct Cleaned {
    Fate fate;
    std::vector<uint32_t> corners;
};

Cleaned clean(lt::FaceCleaner& c, std::vector<uint32_t> face, uint64_t tag = 1) {
    Cleaned r;
    r.fate = c.clean(face.data(), face.size(), tag, r.corners);
    return r;
}

TEST(FaceCleaner, RepairRemovesRepeatsAndSpikesAroundTheCycle) {
    // Corners kept, by position in the face as written: of two at one vertex, the earlier.
    const std::vector<std::pair<std::vector<uint32_t>, std::vector<uint32_t>>> cases = {
        {{0, 0, 1, 2}, {0, 2, 3}},                 // a a b c -> a b c
        {{0, 1, 2, 3, 2}, {0, 1, 2}},              // a b c d c: the spike c d c
        {{0, 1, 2, 3, 4, 3, 2, 5}, {0, 1, 2, 7}},  // a spike two edges long
        {{1, 2, 3, 1}, {0, 1, 2}},                 // a repeat across the seam
        {{0, 1, 2, 3, 0, 5}, {0, 1, 2, 3}},        // .. x | y x: the spike 0 5 0 across the seam
        {{5, 0, 1, 2, 3, 0}, {1, 2, 3, 4}},        // y x .. x: the same, turned
        {{4, 4, 5, 6, 7, 7, 7}, {0, 2, 3, 4}},
    };
    for (const auto& [face, kept] : cases) {
        lt::FaceCleaner c(kGeneral, lt::InputCleaning::Repair);  // (several repair into one face)
        const Cleaned r = clean(c, face);
        EXPECT_EQ(r.fate, Fate::Repaired) << ::testing::PrintToString(face);
        EXPECT_EQ(r.corners, kept) << ::testing::PrintToString(face);
    }
    lt::FaceCleaner c(kGeneral, lt::InputCleaning::Repair);
    EXPECT_EQ(clean(c, {0, 1, 2}, 9).fate, Fate::Kept);
    EXPECT_EQ(clean(c, {4, 4, 5, 6}, 10).fate, Fate::Repaired);
    EXPECT_EQ(clean(c, {0, 1, 2, 3, 3}, 11).fate, Fate::Repaired);
    EXPECT_EQ(c.report().repaired, 2u);
    std::vector<std::string> warnings;
    c.warn("t.obj", "polygon", lineName, warnings);
    EXPECT_EQ(joined(warnings),
              "t.obj: 2 polygons with repeated vertices repaired (first: line 10): repeats and "
              "spikes (x y x) removed\n");
}

TEST(FaceCleaner, DegenerateFacesAndFigureEightsAreDropped) {
    lt::FaceCleaner c(kGeneral, lt::InputCleaning::Repair);
    const std::vector<std::vector<uint32_t>> degenerate = {
        {0, 1, 2, 1},                                 // a b c b: the polygon of the report, a there and back
        {0, 1, 1},                                    // a triangle with a repeated vertex
        {0, 1, 0, 1}, {3, 3, 3}, {0, 1, 2, 0, 4, 5},  // a figure-eight: two loops through vertex 0
    };
    for (const std::vector<uint32_t>& face : degenerate) {
        const Cleaned r = clean(c, face);
        EXPECT_EQ(r.fate, Fate::Degenerate) << ::testing::PrintToString(face);
        EXPECT_TRUE(r.corners.empty());
    }
    EXPECT_TRUE(contains(c.defect(Fate::Degenerate, lineName), "passes through a vertex twice (a figure-eight)"));
    clean(c, {0, 1, 1});
    EXPECT_EQ(c.defect(Fate::Degenerate, lineName),
              "has fewer than 3 distinct vertices once repeats and spikes are removed (refused in strict mode; "
              "otherwise dropped)");
    EXPECT_EQ(c.report().droppedDegenerate, 6u);
    EXPECT_EQ(clean(c, {0, 1, 2}).fate, Fate::Kept);
}

TEST(FaceCleaner, DuplicatesInEitherWindingAreDropped) {
    lt::FaceCleaner c(kGeneral, lt::InputCleaning::Repair);
    EXPECT_EQ(clean(c, {0, 1, 2}, 5).fate, Fate::Kept);
    EXPECT_EQ(clean(c, {1, 2, 0}, 6).fate, Fate::Duplicate);  // turned
    EXPECT_EQ(clean(c, {2, 1, 0}, 7).fate, Fate::Duplicate);  // the other winding
    EXPECT_EQ(clean(c, {0, 1, 2, 3}, 8).fate, Fate::Kept);
    EXPECT_EQ(clean(c, {0, 2, 1, 3}, 9).fate, Fate::Kept);  // the same vertices, another polygon
    EXPECT_EQ(clean(c, {3, 2, 1, 0}, 10).fate, Fate::Duplicate);
    const Cleaned repaired = clean(c, {2, 2, 3, 0, 1}, 11);  // repaired into a face already kept
    EXPECT_EQ(repaired.fate, Fate::Duplicate);
    EXPECT_TRUE(repaired.corners.empty());
    EXPECT_EQ(c.defect(Fate::Duplicate, lineName),
              "has the vertices of line 8 (refused in strict mode; otherwise dropped)");
    EXPECT_EQ(c.report().droppedDuplicate, 4u);
    EXPECT_EQ(c.report().repaired, 0u);
    std::vector<std::string> warnings;
    c.warn("x.glb", "triangle", lineName, warnings);
    EXPECT_EQ(joined(warnings), "x.glb: 4 duplicate triangles dropped (first: line 6, the vertices of line 5)\n");
}

// Zero area: every fan triangle flat. It waits for the whole mesh: sewn to a face of
// nonzero area by an edge it stays (the slit would show), else it goes.
TEST(FaceCleaner, ZeroAreaFacesGoUnlessSewnIntoTheSurface) {
    // 0..2 a triangle; 3, 4 on the line through 0 and 1; 5 at 1's position; 6, 7 off
    // it; 8..11 on a line far away.
    lt::InputMesh mesh;
    mesh.positions = {0, 0, 0, 2, 0, 0, 0,  1, 0, 1,  0, 0, 3,  0, 0, 2,  0, 0,
                      5, 5, 5, 6, 5, 5, 10, 0, 0, 11, 0, 0, 12, 0, 0, 13, 0, 0};
    lt::FaceCleaner c(mesh.positions, lt::InputCleaning::Repair);
    std::vector<lt::FaceCleaner::Pending> pending;
    auto add = [&](std::vector<uint32_t> face, uint64_t tag) {  // as a reader does
        std::vector<uint32_t> corners;
        const Fate fate = c.clean(face.data(), face.size(), tag, corners);
        if (fate == Fate::ZeroArea)
            pending.push_back({tag, mesh.faceCount(), uint32_t(corners.size() - 2), c.lastRepaired()});
        for (size_t k = 1; k + 1 < corners.size(); ++k)
            for (size_t i : {size_t(0), k, k + 1}) mesh.faces.push_back(face[corners[i]]);
        return fate;
    };
    EXPECT_EQ(add({0, 1, 2}, 1), Fate::Kept);
    EXPECT_EQ(add({1, 0, 3}, 2), Fate::ZeroArea);  // sewn to the triangle by edge 0-1
    EXPECT_EQ(add({3, 4, 6}, 3), Fate::Kept);
    EXPECT_EQ(add({0, 3, 4, 4}, 4), Fate::ZeroArea);  // repaired, then flat; sewn by edge 3-4
    EXPECT_EQ(add({6, 3, 0, 4}, 5), Fate::Kept);      // three corners on a line, but it has area
    EXPECT_EQ(add({0, 4, 3}, 6), Fate::ZeroArea);     // sewn by edge 0-4
    EXPECT_EQ(add({1, 5, 7}, 7), Fate::Kept);         // two corners at one position: not tested
    EXPECT_EQ(add({6, 6, 7, 6}, 8), Fate::Degenerate);
    EXPECT_EQ(add({8, 9, 10, 11}, 9), Fate::ZeroArea);  // alone
    EXPECT_EQ(c.report().droppedZeroArea, 0u);          // not yet decided
    EXPECT_EQ(c.settleZeroArea(mesh, pending), std::vector<size_t>{3});
    EXPECT_EQ(c.report().droppedZeroArea, 1u);
    EXPECT_EQ(c.report().repaired, 1u);  // line 4: repaired and kept
    std::vector<std::string> warnings;
    c.warn("t.obj", "polygon", lineName, warnings);
    EXPECT_TRUE(contains(joined(warnings),
                         "t.obj: 1 polygon of zero area dropped (first: line 9): no edge shared "
                         "with a face that has area\n"))
        << joined(warnings);
    std::vector<uint8_t> drop(mesh.faceCount(), 0);
    drop[pending[3].first] = drop[pending[3].first + 1] = 1;
    const std::vector<uint32_t> before = mesh.faces;
    lt::eraseTriangles(mesh, drop);
    EXPECT_EQ(mesh.faces, std::vector<uint32_t>(before.begin(), before.end() - 6));
}

TEST(FaceCleaner, KeepLeavesEveryFaceAsWritten) {
    lt::FaceCleaner c(kGeneral, lt::InputCleaning::Keep);
    for (const std::vector<uint32_t>& face : {std::vector<uint32_t>{0, 1, 2, 1}, {0, 1, 2}, {2, 1, 0}, {4, 4, 4}}) {
        const Cleaned r = clean(c, face);
        EXPECT_EQ(r.fate, Fate::Kept);
        EXPECT_EQ(r.corners.size(), face.size());
    }
    EXPECT_FALSE(c.report().renumbered());
}

// ---- parseObj -------------------------------------------------------------------

lt::Status parseObj(const std::string& text, lt::InputMesh& mesh,
                    lt::InputCleaning cleaning = lt::InputCleaning::Repair) {
    lt::InputOptions options;
    options.cleaning = cleaning;
    return lt::parseObj(text, "t.obj", options, mesh);
}

// A strip of three unit squares, 1-2-3-4 along y = 0 and 5-6-7-8 along y = 1.
const std::string kStrip = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nv 3 1 0\n";

// The report's quad `f a b c b` between two good ones: fan-triangulated it was two
// triangles over three points with opposite windings, making edges with four faces.
TEST(CleanObj, AQuadWithARepeatedVertexIsDroppedNotFanTriangulated) {
    lt::InputMesh m;
    ASSERT_TRUE(parseObj(kStrip + "f 1 2 6 5\nf 2 3 7 3\nf 3 4 8 7\n", m));
    EXPECT_EQ(m.faces, (std::vector<uint32_t>{0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6}));
    EXPECT_EQ(m.cleaning.droppedDegenerate, 1u);
    EXPECT_TRUE(contains(joined(m.warnings), "t.obj: 1 degenerate polygon dropped (first: line 10)"))
        << joined(m.warnings);
    EXPECT_TRUE(lt::checkInput(m, "t.obj"));
    lt::InputMesh asWritten;  // read as written: two triangles over 2 3 7, back to back
    ASSERT_TRUE(parseObj(kStrip + "f 1 2 6 5\nf 2 3 7 3\nf 3 4 8 7\n", asWritten, lt::InputCleaning::Keep));
    EXPECT_EQ(std::vector<uint32_t>(asWritten.faces.begin() + 6, asWritten.faces.begin() + 12),
              (std::vector<uint32_t>{1, 2, 6, 1, 6, 2}));
}

TEST(CleanObj, RepairedPolygonsKeepTheTextureCoordinatesOfTheirCorners) {
    lt::InputMesh m;
    ASSERT_TRUE(parseObj(
        kStrip + "vt 0 0\nvt 0.5 0\nvt 1 0\nvt 1 1\nvt 0 1\n" + "f 1/1 2/2 2/3 6/4 5/5\nf 2/2 3/3 7/4 6/5\n", m));
    EXPECT_EQ(m.cleaning.repaired, 1u);
    // Polygon 1 -> (1 2 6 5) with corners 0, 1, 3, 4: triangles (1 2 6) (1 6 5); v flipped.
    EXPECT_EQ(m.faces, (std::vector<uint32_t>{0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5}));
    ASSERT_EQ(m.faceUVs.size(), 24u);
    EXPECT_EQ(std::vector<float>(m.faceUVs.begin(), m.faceUVs.begin() + 12),
              (std::vector<float>{0, 1, 0.5f, 1, 1, 0, 0, 1, 1, 0, 0, 0}));
    // A polygon without texture coordinates that is dropped does not drop the others'.
    ASSERT_TRUE(parseObj(kStrip + "vt 0 0\nvt 1 0\nvt 1 1\nf 1 2 1\nf 1/1 2/2 6/3\n", m));
    EXPECT_EQ(m.faceUVs.size(), 6u);
    EXPECT_TRUE(m.warnings.size() == 1 && contains(m.warnings[0], "1 degenerate polygon dropped"))
        << joined(m.warnings);
}

// Tags name the file's polygons: a hole of a dropped polygon hides nothing, an edit
// on a later one follows it to its new triangle, an edit on a dropped or repaired
// one is refused, a crease on an edge only dropped faces had goes with them.
TEST(CleanObj, HolesEditsAndCreasesFollowTheFacesKept) {
    // Polygon 2 is dropped (degenerate), 5 too (a copy of 0); polygons 3 and 4 are quads.
    const std::string faces = "f 1 2 6\nf 1 6 5\nf 1 3 1\nf 2 3 7 6\nf 3 4 8 7\nf 1 6 2\n";
    lt::InputMesh m;
    ASSERT_TRUE(parseObj(kStrip + faces + "t hole 2/0/0 2 4\nt crease 4/1/0 0 2 2 6 2\n", m));
    EXPECT_EQ(m.faceCount(), 6u);
    EXPECT_EQ(m.holes, (std::vector<uint32_t>{4, 5}));
    ASSERT_EQ(m.creases.size(), 1u);  // 2-6 is an edge of polygon 3; 0-2 only of polygon 2
    EXPECT_EQ(m.creases[0].a, 2u);
    EXPECT_EQ(m.cleaning.droppedCreases, 1u);
    EXPECT_EQ(m.cleaning.droppedDegenerate, 1u);
    EXPECT_EQ(m.cleaning.droppedDuplicate, 1u);
    EXPECT_TRUE(contains(joined(m.warnings),
                         "t.obj: 1 crease dropped: only dropped or repaired faces had its edge "
                         "(first: edge 0-2)"))
        << joined(m.warnings);
    EXPECT_TRUE(
        contains(joined(m.warnings), "t.obj: 1 duplicate polygon dropped (first: line 14, the vertices of line 9)"));
    EXPECT_TRUE(lt::checkInput(m, "t.obj"));
    // An edit names the polygon of the file: polygon 2, after dropped polygon 1, is triangle 1.
    ASSERT_TRUE(parseObj(kStrip + "f 1 2 6\nf 2 3 2\nf 3 4 7\nt vertexedit 3/3/3 2 2 1 0 0 1 set P value\n", m));
    ASSERT_EQ(m.edits.size(), 1u);
    EXPECT_EQ(m.edits[0].face, 1u);
    for (const char* face : {"2", "5"}) {  // dropped, a copy
        const lt::Status st = parseObj(kStrip + faces + "t vertexedit 3/3/3 2 " + face + " 0 0 0 1 add P value\n", m);
        EXPECT_TRUE(contains(st.message, "t.obj:15: 'vertexedit' tag: edit (face " + std::string(face) +
                                             " vertex 0) names polygon " + face +
                                             ", which input cleaning dropped (see its warning)"))
            << st.message;
    }
    const lt::Status st = parseObj(kStrip + "f 2 3 3 7\nt vertexedit 3/3/3 2 0 0 0 0 1 add P value\n", m);
    EXPECT_TRUE(contains(st.message, "names polygon 0, which input cleaning repaired")) << st.message;
}

// A side-car names faces by triangle: after cleaning renumbered them it would name
// other faces than its author meant.
TEST(CleanObj, AnEditsSideCarIsRefusedOnceCleaningRenumberedTheFaces) {
    lt::InputMesh m;
    const std::string edits = R"({"edits": [{"face": 0, "path": [], "vertex": 0, "op": "add", "value": [0, 0, 1]}]})";
    ASSERT_TRUE(parseObj(kStrip + "f 1 2 6\nf 2 3 7 6\n", m));
    EXPECT_TRUE(lt::parseEditsJson(edits, "e.json", m));
    ASSERT_TRUE(parseObj(kStrip + "f 1 2 6\nf 1 2 6\n", m));
    const lt::Status st = lt::parseEditsJson(edits, "e.json", m);
    EXPECT_EQ(st.code, lt::Status::BadInput);
    EXPECT_TRUE(contains(st.message,
                         "e.json: edits name faces by triangle index, and input cleaning renumbered the "
                         "mesh's triangles (0 faces repaired, 1 dropped; see the warnings)"))
        << st.message;
    EXPECT_TRUE(lt::parseEditsJson(R"({"edits": []})", "e.json", m));
}

TEST(CleanObj, RefuseNamesTheLineAndTheDefect) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"f 1 2 6\nf 2 3 7 3\n",
         "t.obj:10: face has fewer than 3 distinct vertices once repeats and spikes are removed "
         "(refused in strict mode; otherwise dropped)"},
        {"f 1 2 6\nf 1 2 2 6 5\n",
         "t.obj:10: face repeats a vertex (refused in strict mode; otherwise the repeats and "
         "spikes are removed)"},
        {"f 1 2 6\nf 6 1 2\n", "t.obj:10: face has the vertices of line 9 (refused in strict mode; otherwise dropped)"},
        {"f 1 2 6\nf 2 3 4\nf 6 7 3\n", "t.obj:10: face has zero area and shares no edge with a face that has area"},
    };
    for (const auto& [faces, message] : cases) {
        lt::InputMesh m;
        const lt::Status st = parseObj(kStrip + faces, m, lt::InputCleaning::Refuse);
        EXPECT_EQ(st.code, lt::Status::BadInput) << faces;
        EXPECT_TRUE(contains(st.message, message)) << st.message;
    }
    lt::InputMesh m;  // a flat face sewn into the surface is no defect cleaning would mend
    EXPECT_TRUE(parseObj(kStrip + "f 1 2 6\nf 2 3 4\nf 2 4 8 6\n", m, lt::InputCleaning::Refuse));
    EXPECT_EQ(m.faceCount(), 4u);
}

// Every corpus shape reads the same cleaned as written, but for the two OpenSubdiv
// shapes built from what cleaning mends: back-to-back triangles (loop_val2_interior)
// and triangles with a repeated vertex (loop_nonman_edges).
TEST(CleanObj, CorpusShapesChangeOnlyWhereTheyHaveDefects) {
    size_t shapes = 0;
    for (const char* dir : {"opensubdiv-loop", "meshes"})
        for (const auto& e : fs::directory_iterator(fs::path(LOOPTESS_CORPUS_DIR) / dir)) {
            if (e.path().extension() != ".obj") continue;
            const std::string name = e.path().stem().string(), text = readText(e.path());
            SCOPED_TRACE(name);
            lt::InputMesh cleaned, asWritten;
            ASSERT_TRUE(parseObj(text, cleaned));
            ASSERT_TRUE(parseObj(text, asWritten, lt::InputCleaning::Keep));
            ++shapes;
            const lt::CleaningReport& c = cleaned.cleaning;
            if (name == "loop_val2_interior") {
                EXPECT_EQ(c.droppedDuplicate, 3u);
                EXPECT_EQ(cleaned.faceCount(), asWritten.faceCount() - 3);
                EXPECT_TRUE(lt::checkInput(cleaned, name));
            } else if (name == "loop_nonman_edges") {
                EXPECT_EQ(c.droppedDegenerate, 4u);
                EXPECT_EQ(cleaned.faceCount(), asWritten.faceCount() - 4);
            } else {
                EXPECT_FALSE(c.renumbered() || c.droppedCreases);
                EXPECT_EQ(cleaned.faces, asWritten.faces);
                EXPECT_EQ(cleaned.faceUVs, asWritten.faceUVs);
                EXPECT_EQ(cleaned.warnings, asWritten.warnings);
            }
        }
    EXPECT_GE(shapes, 34u);
}

// ---- glTF -----------------------------------------------------------------------

// The tetrahedron of gltf_fixture.h (0 2 1, 0 1 3, 0 3 2, 1 2 3) with three more
// vertices on a line apart from it and, after its faces: (0 1 1), two corners at
// one vertex; (1 2 0), the first face in the other winding; (4 5 6), flat and alone.
Bytes defectiveGlb() {
    Bytes bin;
    const Json j = gltftest::triangles(bin, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 0, 3, 0, 0, 4, 0, 0},
                                       {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 1, 1, 1, 2, 0, 4, 5, 6},
                                       {0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0});
    return gltftest::makeGlb(j, bin);
}

TEST(CleanGltf, SceneDropsDuplicateAndLoneFlatTrianglesFromTheMeshAndTheCage) {
    const Bytes glb = defectiveGlb();
    lt::GltfScene scene;
    lt::Status st = lt::parseGltfScene(glb.data(), glb.size(), "d.glb", "", lt::Limits{}, scene);
    ASSERT_TRUE(st) << st.message;
    ASSERT_EQ(scene.meshes.size(), 1u);
    const lt::InputMesh& m = scene.meshes[0].mesh;
    EXPECT_EQ(m.faces, (std::vector<uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}));
    EXPECT_EQ(m.faceUVs.size(), 24u);
    EXPECT_EQ(m.cleaning.collapsed, 1u);
    EXPECT_EQ(m.cleaning.droppedDuplicate, 1u);
    EXPECT_EQ(m.cleaning.droppedZeroArea, 1u);
    const std::string w = joined(scene.warnings);
    EXPECT_TRUE(contains(w, "d.glb: meshes[0].primitives[0] triangle 4: two corners at one position")) << w;
    EXPECT_TRUE(contains(w,
                         "d.glb: 1 duplicate triangle dropped (first: meshes[0].primitives[0] triangle 5, the "
                         "vertices of meshes[0].primitives[0] triangle 0)"))
        << w;
    EXPECT_TRUE(contains(w, "d.glb: 1 triangle of zero area dropped (first: meshes[0].primitives[0] triangle 6)")) << w;
    // The cage's triangles stay the base faces: new indices without the two dropped,
    // with the one that is no base face (the format's rule), the old accessor unused.
    const Json doc = Json::parse(scene.document);
    const size_t indices = doc["meshes"][0]["primitives"][0]["indices"].get<size_t>();
    ASSERT_EQ(indices, 3u);
    const Json& acc = doc["accessors"][indices];
    EXPECT_EQ(acc["componentType"], 5125);
    ASSERT_EQ(acc["count"], 15);
    const Json& view = doc["bufferViews"][acc["bufferView"].get<size_t>()];
    std::vector<uint32_t> cage(15);
    std::memcpy(cage.data(), &scene.bin[view["byteOffset"].get<size_t>()], 60);
    EXPECT_EQ(cage, (std::vector<uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 1, 1}));

    lt::InputOptions strict;
    strict.cleaning = lt::InputCleaning::Refuse;
    st = lt::parseGltfScene(glb.data(), glb.size(), "d.glb", "", strict, scene);
    EXPECT_EQ(st.code, lt::Status::BadInput);
    EXPECT_EQ(st.message,
              "d.glb: meshes[0].primitives[0] triangle 5: has the vertices of meshes[0].primitives[0] "
              "triangle 0 (refused in strict mode; otherwise dropped)");
}

TEST(CleanGltf, FlattenedMeshIsCleanedAlike) {
    const Bytes glb = defectiveGlb();
    lt::InputMesh m;
    lt::Status st = lt::parseGltf(glb.data(), glb.size(), "d.glb", "", m);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(m.faceCount(), 4u);
    EXPECT_EQ(m.faceUVs.size(), 24u);
    EXPECT_EQ(m.cleaning.collapsed, 1u);
    EXPECT_EQ(m.cleaning.droppedDuplicate, 1u);
    EXPECT_EQ(m.cleaning.droppedZeroArea, 1u);
    EXPECT_TRUE(contains(joined(m.warnings),
                         "d.glb: 1 duplicate triangle dropped (first: nodes[0]: "
                         "meshes[0].primitives[0] triangle 5, the vertices of nodes[0]: "
                         "meshes[0].primitives[0] triangle 0)"))
        << joined(m.warnings);
    EXPECT_TRUE(lt::checkInput(m, "d.glb"));
    lt::InputOptions keep;
    keep.cleaning = lt::InputCleaning::Keep;
    ASSERT_TRUE(lt::parseGltf(glb.data(), glb.size(), "d.glb", "", keep, m));
    EXPECT_EQ(m.faceCount(), 6u);  // the collapsed triangle is no face in any case
}

// ---- loopbake -------------------------------------------------------------------

class CleaningCli : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ =
            fs::temp_directory_path() / ("looptess_test_cleaning_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(root_);
        fs::create_directories(root_);
    }
    void TearDown() override { fs::remove_all(root_); }

    RunResult loopbake(const std::vector<std::string>& args) { return lt::test::runTool(LOOPBAKE_EXE, args, root_); }
    fs::path write(const std::string& name, const std::string& text) {
        std::ofstream(root_ / name, std::ios::binary) << text;
        return root_ / name;
    }
    static Json report(const fs::path& path) { return Json::parse(readText(path)); }

    fs::path root_;
};

// The report's case end to end: the quad `f a b c b` in a closed mesh (a cube of
// quads, one face split in two by it) bakes as the mesh without it would, with one
// warning naming the file, the count and the line, and the counts in --json.
TEST_F(CleaningCli, AnObjQuadWithARepeatedVertexBakesAsIfItWereNotThere) {
    const std::string cube =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n";
    const fs::path defective = write("defective.obj", cube + "f 4 1 5 1\nf 4 1 5 8\n");
    const fs::path clean = write("clean.obj", cube + "f 4 1 5 8\n");
    const fs::path a = root_ / "a.glb", b = root_ / "b.glb", json = root_ / "a.json";
    const RunResult r = loopbake({defective.string(), "-o", a.string(), "--max-depth", "3", "--json", json.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(
        contains(r.err, "loopbake: warning: " + defective.string() + ": 1 degenerate polygon dropped (first: line 14)"))
        << r.err;
    const RunResult plain = loopbake({clean.string(), "-o", b.string(), "--max-depth", "3"});
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    EXPECT_EQ(readText(a), readText(b)) << "the cleaned bake differs from the bake without the polygon";
    const Json j = report(json);
    EXPECT_EQ(j["input"]["cleaning"], Json::parse(R"({"repaired": 0, "droppedDegenerate": 1, "droppedZeroArea": 0,
        "droppedDuplicate": 0, "droppedCreases": 0, "collapsed": 0})"));
    EXPECT_EQ(j["meshes"][0]["cleaning"]["droppedDegenerate"], 1);
    EXPECT_TRUE(contains(readText(json), "degenerate polygon dropped")) << "warnings are in the report";

    const RunResult strict = loopbake({defective.string(), "-o", a.string(), "--strict"});
    EXPECT_EQ(strict.exitCode, 2);
    EXPECT_TRUE(contains(strict.err, "loopbake: error: " + defective.string() + ":9: face has 4 vertices"))
        << strict.err;
    const fs::path triangles = write("triangles.obj",
                                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                     "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 4 2 1\n");
    const RunResult dup = loopbake({triangles.string(), "-o", a.string(), "--strict"});
    EXPECT_EQ(dup.exitCode, 2);
    EXPECT_TRUE(
        contains(dup.err, "loopbake: error: " + triangles.string() +
                              ":9: face has the vertices of line 6 (refused in strict mode; otherwise dropped)"))
        << dup.err;
}

// glTF alike: a repeated-index triangle stays in the cage as no base face (as
// before), a duplicate and a lone flat triangle are dropped from both; the file
// reads back, its surface of the tetrahedron's 4 faces.
TEST_F(CleaningCli, AGltfWithARepeatedIndexAndADuplicateTriangleBakesCleaned) {
    const Bytes glb = defectiveGlb();
    const fs::path in = root_ / "d.glb", out = root_ / "out.glb", json = root_ / "r.json";
    std::ofstream(in, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
    const RunResult r = loopbake({in.string(), "-o", out.string(), "--max-depth", "2", "--json", json.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "loopbake: warning: " + in.string() +
                                    ": meshes[0].primitives[0] triangle 4: two "
                                    "corners at one position"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "loopbake: warning: " + in.string() +
                                    ": 1 duplicate triangle dropped (first: "
                                    "meshes[0].primitives[0] triangle 5"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "loopbake: warning: " + in.string() + ": 1 triangle of zero area dropped")) << r.err;
    const Json j = report(json);
    EXPECT_EQ(j["input"]["cleaning"], Json::parse(R"({"repaired": 0, "droppedDegenerate": 0, "droppedZeroArea": 1,
        "droppedDuplicate": 1, "droppedCreases": 0, "collapsed": 1})"));
    EXPECT_EQ(j["meshes"][0]["cleaning"], j["input"]["cleaning"]);
    const std::string bytes = readText(out);
    std::vector<lt::SceneSurface> surfaces;
    const lt::Status st =
        lt::readSceneGlb(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "out.glb", surfaces);
    ASSERT_TRUE(st) << st.message;
    ASSERT_EQ(surfaces.size(), 1u);
    EXPECT_EQ(surfaces[0].asset.faceCount(), 4u);
    EXPECT_EQ(surfaces[0].primitiveFaces, (std::vector<uint32_t>{0, 4}));

    const RunResult strict = loopbake({in.string(), "-o", out.string(), "--strict"});
    EXPECT_EQ(strict.exitCode, 2);
    EXPECT_TRUE(contains(strict.err, "loopbake: error: " + in.string() +
                                         ": meshes[0].primitives[0] triangle 5: has "
                                         "the vertices of meshes[0].primitives[0] "
                                         "triangle 0"))
        << strict.err;
}

TEST_F(CleaningCli, HelpDescribesStrict) {
    const RunResult help = loopbake({"--help"});
    EXPECT_TRUE(contains(help.out, "--strict            accept the mesh only as written")) << help.out;
}

// The report: one unterminated string in a data URI was quoted whole, about 10 kB.
TEST_F(CleaningCli, AnErrorQuotesOnlyAnExcerptOfTheInput) {
    const fs::path in = write("unterminated.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 7500, )"
                                                   R"("uri": "data:application/octet-stream;base64,)" +
                                                       std::string(10000, 'A') + "}]}");
    const RunResult r = loopbake({in.string(), "-o", (root_ / "out.glb").string()});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_LT(r.err.size(), 300u + in.string().size()) << r.err;
    EXPECT_EQ(r.err.rfind("loopbake: error: " + in.string() + ": invalid JSON: ", 0), 0u) << r.err;
    EXPECT_TRUE(contains(r.err, "last read: '\"data:application/octet-stream;base64,AAAA")) << r.err;
}

// A glTF mesh's name is the input too: messages about the mesh show an excerpt.
TEST_F(CleaningCli, AMeshNameIsQuotedAsAnExcerpt) {
    const Bytes glb = gltftest::tetraGlb([](Json& j, Bytes& bin) {
        j["meshes"][0]["name"] = std::string(5000, 'x');
        const uint16_t flipped[3] = {0, 1, 2};  // the first face turned over
        std::memcpy(&bin[48], flipped, sizeof flipped);
    });
    const fs::path in = root_ / "named.glb";
    std::ofstream(in, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
    const RunResult r = loopbake({in.string(), "-o", (root_ / "out.glb").string()});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_TRUE(contains(r.err, in.string() + ": meshes[0] (" + std::string(80, 'x') + "...): faces ")) << r.err;
    EXPECT_LT(r.err.size(), 400u + in.string().size()) << r.err;
}

}  // namespace
