// tests/formats/test_format_corrupt.cpp -- the corruption catalogue of the
// EXT_mesh_loop_subdivision reader and validator: each broken file or Asset is
// rejected citing its spec rule (formats/EXT_mesh_loop_subdivision/README.md).
#include "format_fixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace fmttest;

// --- container rules (through the reader) ------------------------------------------------

TEST(Corrupt, GlbHeader) {
    corruptBytes([](auto& b) { b.resize(10); }, 1);
    corruptBytes([](auto& b) { b.resize(b.size() - 4); }, 1);  // truncated
    corruptBytes([](auto& b) { b[0] = 'X'; }, 1);
    corruptBytes([](auto& b) { putU32(b, 4, 1); }, 1);
    corruptBytes([](auto& b) { b.clear(); }, 1);
}

TEST(Corrupt, GlbChunks) {
    corruptBytes([](auto& b) { putU32(b, 12, u32At(b, 12) + 400); }, 2);  // JSON runs into BIN
    corruptBytes([](auto& b) { putU32(b, 16, 0x004E4942); }, 2);          // first chunk claims BIN
    corruptBytes(
        [](auto& b) {
            b.resize(b.size() - 16);
            putU32(b, 8, uint32_t(b.size()));
        },
        2);  // BIN cut
}

TEST(Corrupt, Json) {
    Glb g(fixtureBytes());
    expectRule(read(g.bytesWithJson("{\"asset\": ")), 3);
    expectRule(read(g.bytesWithJson(std::string(100, '[') + std::string(100, ']'))), 3);
    corrupt([](Edit g) { g.doc["asset"]["version"] = "1.0"; }, 3);
}

TEST(Corrupt, UriPresent) {
    corrupt([](Edit g) { g.doc["buffers"][0]["uri"] = "data.bin"; }, 4);
    corrupt([](Edit g) { g.doc["images"] = Json::array({Json{{"uri", "x.png"}}}); }, 4);
    corrupt([](Edit g) { g.doc["buffers"][0]["byteLength"] = g.bin.size() + 4; }, 4);  // more than BIN
}

TEST(Corrupt, BufferViewOutOfRange) {
    corrupt([](Edit g) { view(g, g.accessor(1, "edgeVerts"))["byteOffset"] = g.bin.size() - 2; }, 5);
    corrupt([](Edit g) { view(g, g.accessor(1, "edgeVerts"))["buffer"] = 1; }, 5);
}

TEST(Corrupt, AccessorOutOfRange) {
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "edgeVerts")]["count"] = 1000; }, 6);
    corrupt([](Edit g) { g.ext()["levels"][1]["edgeVerts"] = 5000; }, 6);  // no such accessor
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "vertexRing")]["byteOffset"] = 1; }, 6);
    corrupt(
        [](Edit g) {
            g.doc["accessors"][g.accessor(1, "vertexRing")]["sparse"] = Json::object({{"count", 1}});
        },
        6);
}

TEST(Corrupt, BadComponentType) {
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "edgeVerts")]["componentType"] = 5126; }, 7);
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(0, "irregularCorners")]["type"] = "SCALAR"; }, 7);
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "regularOrigin")]["componentType"] = 5125; }, 7);
}

TEST(Corrupt, ExtensionPlacement) {
    corrupt([](Edit g) { g.doc["extensionsRequired"] = Json::array({kExt}); }, 8);
    corrupt([](Edit g) { g.doc["extensionsUsed"] = Json::array({"KHR_other"}); }, 8);
    corrupt([](Edit g) { g.doc["meshes"][0]["primitives"][0].erase("extensions"); }, 8);  // a surface without a cage
    corrupt(
        [](Edit g) {  // a cage primitive on a mesh without a surface object
            g.doc["meshes"].push_back(g.doc["meshes"][0]);
            g.doc["meshes"][1].erase("extensions");
        },
        8);
    // Two meshes with one surface's tables: a reader would decode them twice.
    corrupt([](Edit g) { g.doc["meshes"].push_back(g.doc["meshes"][0]); }, 14);
}

// A version-1 file (tables on the primitive) is unsupported, and says so.
TEST(Corrupt, VersionOneLayout) {
    Glb g(fixtureBytes());
    g.cage() = g.ext();
    g.cage()["version"] = 1;
    g.doc["meshes"][0].erase("extensions");
    const lt::Status st = read(g.bytes());
    expectRule(st, 12);
    EXPECT_EQ(st.code, lt::Status::Unsupported);
    EXPECT_NE(st.message.find("bake the asset again"), std::string::npos) << st.message;
}

TEST(Corrupt, FallbackPrimitive) {
    corrupt([](Edit g) { prim(g)["mode"] = 1; }, 9);
    corrupt([](Edit g) { g.setIndex(prim(g)["indices"].get<int>(), 4, 60000); }, 9);
    corrupt([](Edit g) { prim(g)["attributes"].erase("POSITION"); }, 9);
    // TEXCOORD_1 / COLOR_0 on an accessor of the wrong form (the indices: SCALAR
    // integers, not normalized), or with another count than POSITION's.
    corrupt([](Edit g) { prim(g)["attributes"]["TEXCOORD_1"] = prim(g)["indices"]; }, 7);
    corrupt([](Edit g) { prim(g)["attributes"]["COLOR_0"] = prim(g)["indices"]; }, 7);
    corrupt(
        [](Edit g) {
            Json shorter = g.doc["accessors"][prim(g)["attributes"]["TEXCOORD_0"].get<int>()];
            shorter["count"] = shorter["count"].get<int>() - 1;
            g.doc["accessors"].push_back(shorter);
            prim(g)["attributes"]["TEXCOORD_1"] = g.doc["accessors"].size() - 1;
        },
        9);
}

TEST(Corrupt, ControlVertexMapping) {
    corrupt(
        [](Edit g) {  // the largest entry 50 leaves control vertices 4..49 unmapped
            const int cv = g.cage()["controlVertex"].get<int>();
            g.setIndex(cv, g.doc["accessors"][cv]["count"].get<size_t>() - 1, 50);
        },
        10);
    corrupt(
        [](Edit g) {  // control vertex 0 has several copies (UV seams): move its last copy
            const int cv = g.cage()["controlVertex"].get<int>(), pos = prim(g)["attributes"]["POSITION"].get<int>();
            size_t copy = 0;
            for (size_t v = 1; v < g.doc["accessors"][cv]["count"].get<size_t>(); ++v)
                if (g.element(cv, v)[0] == 0 && g.element(cv, v)[1] == 0) copy = v;
            ASSERT_NE(copy, 0u);
            g.setFloat(pos, 3 * copy + 1, 0.25f);
        },
        11);
}

TEST(Corrupt, WrongVersion) {
    Glb g(fixtureBytes());
    g.ext()["version"] = 1;  // the earlier layout (tables on the primitive)
    const lt::Status st = read(g.bytes());
    expectRule(st, 12);
    EXPECT_EQ(st.code, lt::Status::Unsupported);
}

TEST(Corrupt, ExtensionObject) {
    corrupt([](Edit g) { g.ext()["maxDepth"] = 3; }, 13);
    corrupt([](Edit g) { g.ext()["boundaryInterpolation"] = "SMOOTH"; }, 13);
    corrupt([](Edit g) { g.ext()["levels"][1].erase("firstVertex"); }, 13);
    corrupt([](Edit g) { g.ext()["levels"][1]["vertexRing"] = -3; }, 13);
}

TEST(Corrupt, SharedOrOverlappingAccessor) {
    corrupt([](Edit g) { g.ext()["levels"][2]["vertexRing"] = g.accessor(1, "vertexRing"); }, 14);
    corrupt(
        [](Edit g) {  // a second accessor over level 1's vertexRing bytes
            g.doc["accessors"].push_back(g.doc["accessors"][g.accessor(1, "vertexRing")]);
            g.ext()["levels"][2]["vertexRing"] = g.doc["accessors"].size() - 1;
        },
        14);
}

TEST(Corrupt, PatchArraysDisagree) {
    corrupt([](Edit g) { g.ext()["levels"][1].erase("regularBaseFace"); }, 15);
    corrupt(
        [](Edit g) {  // a copy of level 0's one split mask for level 1's two patches
            g.ext()["levels"][1]["regularSplitMask"] = g.widen(g.accessor(0, "regularSplitMask"), 5121);
        },
        15);
    corrupt([](Edit g) { g.ext()["levels"][0].erase("regularPoints"); }, 15);
}

// --- table rules through the reader (BIN edits) ---------------------------------------

TEST(Format, WiderStoredTypesRead) {  // e.g. u16 origins (levels >= 8), u32 where u16 fits
    Glb g(fixtureBytes());
    g.ext()["levels"][1]["regularOrigin"] = g.widen(g.accessor(1, "regularOrigin"), 5123);
    g.ext()["levels"][2]["limitRing"] = g.widen(g.accessor(2, "limitRing"), 5125);
    lt::Asset b;
    const lt::Status st = read(g.bytes(), &b);
    ASSERT_TRUE(st) << st.message;
    expectEqual(makeAsset(true), b);
    g.setIndex(g.accessor(1, "regularOrigin"), 1, 256);
    expectRule(read(g.bytes()), 32);
}

TEST(Corrupt, IndexOutOfRange) {
    Glb g(fixtureBytes());
    g.setIndex(g.accessor(2, "edgeVerts"), 5, 12);  // level 2 reads level 1 = [4, 14), stored relative to 4
    const lt::Status st = read(g.bytes());
    expectRule(st, 25);
    EXPECT_NE(st.message.find("t.glb: levels[2].edgeVerts[5]: rule 25: relative index 12 (vertex 16) is not below "
                              "level 1's vertex count 10"),
              std::string::npos)
        << st.message;
    // The reader adds firstVertex mod 2^32; a sum that wraps lands below the level
    // (as limit.ring[1] = 3 in Validate.Catalogue) and is rejected the same way.
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "limitRing"), 3, 65535); }, 34);
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "regularPoints"), 7, 10); }, 30);
    corrupt([](Edit g) { g.setIndex(g.accessor(2, "limitVertex"), 1, 5); }, 34);
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "limitMasked"), 1, 9); }, 35);
}

TEST(Corrupt, TableRules) {
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "vertexRingStart"), 2, 1); }, 23);  // CSR not monotone
    corrupt([](Edit g) { g.setFloat(g.accessor(1, "maskWeights"), 2, std::nanf("")); }, 17);
    corrupt([](Edit g) { g.setFloat(g.accessor(0, "limitTangentV"), 0, INFINITY); }, 17);
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "regularBoundaryMask"), 0, 64); }, 31);
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "regularOrigin"), 0, 2); }, 32);      // u = 2 at level 1
    corrupt([](Edit g) { g.setIndex(g.accessor(0, "irregularBaseFace"), 3, 2); }, 32);  // faces 0 1 2 4
    corrupt([](Edit g) { g.setIndex(g.accessor(2, "irregularOrigin"), 1, 4); }, 32);    // v = 4 at level 2
    corrupt([](Edit g) { g.ext()["levels"][1]["firstVertex"] = 5; }, 22);
}

// --- table rules on in-memory Assets ------------------------------------------------

void expectInvalid(const std::function<void(lt::Asset&)>& edit, int rule) {
    lt::Asset a = makeAsset(true);
    edit(a);
    const lt::Status st = lt::validateAsset(a, "t.glb");
    expectRule(st, rule);
}

TEST(Validate, BoundaryMaskCornerOppositeEdge) {
    lt::Asset a = makeAsset(true);
    a.levels[1].regular[0].boundaryMask = 2 | 8;  // edge 1 and the opposite corner 0 (OpenSubdiv's case)
    EXPECT_TRUE(lt::validateAsset(a, "t.glb")) << lt::validateAsset(a, "t.glb").message;
}

TEST(Validate, Catalogue) {
    expectInvalid([](lt::Asset& a) { a.positions.pop_back(); }, 16);
    expectInvalid([](lt::Asset& a) { a.faceUVs.pop_back(); }, 16);
    expectInvalid([](lt::Asset& a) { a.positions[4] = std::nanf(""); }, 17);
    expectInvalid([](lt::Asset& a) { a.faces[3] = 4; }, 18);
    expectInvalid([](lt::Asset& a) { a.faces[4] = a.faces[3]; }, 18);
    expectInvalid([](lt::Asset& a) { a.boundary = lt::BoundaryInterpolation(7); }, 19);
    expectInvalid([](lt::Asset& a) { a.levels.clear(); }, 20);
    expectInvalid([](lt::Asset& a) { a.levels.resize(17); }, 20);
    expectInvalid([](lt::Asset& a) { a.levels[0].refinement.creaseEdge = {0}; }, 21);
    expectInvalid([](lt::Asset& a) { a.levels[2].refinement.firstVertex = 13; }, 22);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.vertexRingStart.back() = 11; }, 23);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.vertexRingStart[0] = 1; }, 23);
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.start.pop_back(); }, 23);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.edgeVerts.pop_back(); }, 24);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.creaseWeight.push_back(1); }, 24);
    expectInvalid([](lt::Asset& a) { a.levels[0].limit.tangentU.pop_back(); }, 24);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.vertexParent[0] = 4; }, 25);
    expectInvalid([](lt::Asset& a) { a.levels[2].refinement.vertexRing[0] = 3; }, 25);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.vertexParent[1] = 0; }, 26);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.maskedVertex[0] = 4; }, 27);
    expectInvalid(
        [](lt::Asset& a) {
            a.levels[1].refinement.maskWeights.pop_back();
            a.levels[1].refinement.maskStart[1] = 2;
        },
        27);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.edgeVerts[1] = 0; }, 28);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.creaseWeight[0] = 0.0f; }, 29);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.creaseEdge[0] = 6; }, 29);
    expectInvalid([](lt::Asset& a) { a.levels[1].regular[0].points[7] = 3; }, 30);
    expectInvalid([](lt::Asset& a) { a.levels[1].regular[0].splitMask = 8; }, 31);
    expectInvalid([](lt::Asset& a) { a.levels[1].regular[0].boundaryMask = 1 | 16; }, 31);  // edge 0 + corner 1
    expectInvalid([](lt::Asset& a) { a.levels[1].regular[0].boundaryMask = 4 | 8; }, 31);   // edge 2 + corner 0

    expectInvalid([](lt::Asset& a) { a.levels[2].regular[0].splitMask = 1; }, 31);
    expectInvalid([](lt::Asset& a) { a.levels[1].irregular[0].param.level = 0; }, 32);
    expectInvalid([](lt::Asset& a) { a.levels[0].irregular[0].param.baseFace = 4; }, 32);
    expectInvalid([](lt::Asset& a) { a.levels[0].regular[0].param.rotated = true; }, 32);
    expectInvalid([](lt::Asset& a) { a.levels[2].irregular[0].param.vi = 4; }, 32);
    expectInvalid([](lt::Asset& a) { a.levels[1].irregular[0].corners[2] = 4; }, 33);
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.ring[1] = 3; }, 34);
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.ring[0] = 13; }, 34);  // larger than the other neighbours
    expectInvalid([](lt::Asset& a) { std::swap(a.levels[0].limit.ring[0], a.levels[0].limit.ring[1]); }, 34);
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.maskStart.back() = 1; }, 23);
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.tangentV.pop_back(); }, 24);
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.masked[1] = 1; }, 35);  // not increasing
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.masked[1] = 4; }, 35);  // no such stencil
    expectInvalid(
        [](lt::Asset& a) {  // masked stencil 3 of level 0: 2 weights for 3 neighbours
            lt::LimitStencils& s = a.levels[0].limit;
            for (auto* w : {&s.position, &s.tangentU, &s.tangentV}) w->pop_back();
            --s.maskStart.back();
        },
        35);
    expectInvalid(
        [](lt::Asset& a) {  // stencil 1 of level 2 (one neighbour) loses its weights: smooth
            lt::LimitStencils& s = a.levels[2].limit;
            for (auto* v : {&s.masked, &s.maskStart}) v->clear();
            for (auto* w : {&s.position, &s.tangentU, &s.tangentV}) w->clear();
        },
        35);
}

}  // namespace
