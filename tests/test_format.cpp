// tests/test_format.cpp -- EXT_mesh_loop_subdivision GLB: round trip, determinism,
// index widths, the corruption catalogue (each rejected citing its spec rule), a
// mutation sweep for reader safety, and the Khronos glTF-Validator.
//
// The assets here are synthetic: a tetrahedron control mesh with two levels of
// small, in-range tables that satisfy every rule of the spec without being a real
// subdivision.
#include "looptess/asset.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Json = nlohmann::json;
const char* kExt = "EXT_mesh_loop_subdivision";

lt::PatchParam param(uint32_t face, uint16_t ui, uint16_t vi, uint8_t level, bool rotated = false) {
    return lt::PatchParam{face, ui, vi, level, rotated};
}

lt::RegularPatch regular(uint32_t first, uint32_t count, uint32_t salt, uint8_t boundary, uint8_t split,
                         lt::PatchParam p) {
    lt::RegularPatch r;
    for (uint32_t k = 0; k < 12; ++k) r.points[k] = first + (salt + 5 * k) % count;
    r.boundaryMask = boundary;
    r.splitMask = split;
    r.param = p;
    return r;
}

lt::IrregularFace irregular(uint32_t a, uint32_t b, uint32_t c, lt::PatchParam p) {
    return lt::IrregularFace{{a, b, c}, p};
}

// Appends one stencil: the vertex, then `ring` (smallest first), with weights.
void stencil(lt::LimitStencils& s, uint32_t v, std::vector<uint32_t> ring) {
    if (s.start.empty()) s.start.push_back(0);
    s.vertex.push_back(v);
    ring.insert(ring.begin(), v);
    for (size_t i = 0; i < ring.size(); ++i) {
        s.ring.push_back(ring[i]);
        s.position.push_back(i == 0 ? 0.5f : 0.5f / float(ring.size() - 1));
        s.tangentU.push_back(float(i) * 0.25f - 0.125f);
        s.tangentV.push_back(i == 0 ? 0.0f : -1.0f / 3.0f);
    }
    s.start.push_back(uint32_t(s.ring.size()));
}

// Tetrahedron with `extraVertices` unused control vertices appended (to push
// indices past 65535), levels 0..2.
lt::Asset makeAsset(bool uvs, uint32_t extraVertices = 0) {
    lt::Asset a;
    a.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (uint32_t i = 0; i < extraVertices; ++i) {
        a.positions.push_back(float(i) * 0.001f);
        a.positions.push_back(-0.5f);
        a.positions.push_back(0.1f);
    }
    a.faces = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    if (uvs)   // per-corner UVs with seams: vertex 0 gets three different UVs
        for (uint32_t f = 0; f < 4; ++f)
            for (uint32_t k = 0; k < 3; ++k) {
                const uint32_t v = a.faces[3 * f + k];
                a.faceUVs.push_back(v == 0 ? 0.1f * float(f) : 0.2f * float(v));
                a.faceUVs.push_back(v == 0 ? 0.7f : 0.3f + 0.1f * float(v));
            }
    a.boundary = lt::BoundaryInterpolation::EdgeAndCorner;
    a.creaseMethod = lt::CreaseMethod::Chaikin;
    const uint32_t n = a.controlVertexCount();
    a.levels.resize(3);

    lt::Level& l0 = a.levels[0];
    l0.regular.push_back(regular(0, 4, 1, 7, 1, param(1, 0, 0, 0)));
    for (uint32_t f = 0; f < 4; ++f)
        l0.irregular.push_back(irregular(a.faces[3 * f], a.faces[3 * f + 1], a.faces[3 * f + 2], param(f, 0, 0, 0)));
    stencil(l0.limit, 0, {1, 2, 3});
    stencil(l0.limit, 1, {0, 2, 3});
    stencil(l0.limit, 2, {0, 1, 3});
    stencil(l0.limit, 3, {0, 1, 2});

    lt::Refinement& r1 = a.levels[1].refinement;   // level 1: [n, n + 10)
    r1.firstVertex = n;
    r1.vertexParent = {0, 1, 2, 3};
    r1.vertexRingStart = {0, 3, 6, 9, 12};
    r1.vertexRing = {1, 2, 3, 2, 3, 0, 3, 0, 1, 0, 1, 2};
    r1.maskedVertex = {2};
    r1.maskStart = {0, 4};
    r1.maskWeights = {0.75f, 0.125f, 0.125f, 0.0f};
    r1.edgeVerts = {0, 1, 2, 3, 1, 2, 0, 3, 2, 0, 1, 3, 0, 3, 1, 2, 1, 3, 0, 2, 2, 3, 0, 1};
    r1.creaseEdge = {3};
    r1.creaseWeight = {0.5f};
    a.levels[1].regular.push_back(regular(n, 10, 0, 5, 2, param(0, 1, 0, 1)));
    a.levels[1].regular.push_back(regular(n, 10, 3, 0, 0, param(0, 1, 1, 1, true)));
    a.levels[1].irregular.push_back(irregular(0, 1, 2, param(2, 0, 0, 1)));
    stencil(a.levels[1].limit, n + 0, {n + 3, n + 6, n + 8});
    stencil(a.levels[1].limit, n + 1, {n + 4, n + 9});
    stencil(a.levels[1].limit, n + 2, {n + 0, n + 5, n + 7});

    lt::Refinement& r2 = a.levels[2].refinement;   // level 2: [n + 10, n + 15)
    const uint32_t m = n + 10;
    r2.firstVertex = m;
    r2.vertexParent = {n + 0, n + 1};
    r2.vertexRingStart = {0, 2, 4};
    r2.vertexRing = {n + 2, n + 3, n + 4, n + 5};
    r2.edgeVerts = {n + 0, n + 2, n + 3, n + 3, n + 1, n + 4, n + 5, n + 0, n + 2, n + 3, n + 0, n + 1};
    a.levels[2].regular.push_back(regular(m, 5, 2, 56, 0, param(3, 2, 1, 2)));
    a.levels[2].irregular.push_back(irregular(0, 1, 2, param(1, 1, 3, 2, true)));
    stencil(a.levels[2].limit, m + 0, {m + 1, m + 3});
    stencil(a.levels[2].limit, m + 2, {m + 0});
    stencil(a.levels[2].limit, m + 4, {m + 0, m + 1, m + 2, m + 3});
    return a;
}

// --- comparing Assets bitwise ---------------------------------------------------

template <typename T> bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
bool sameParam(const lt::PatchParam& a, const lt::PatchParam& b) {
    return a.baseFace == b.baseFace && a.ui == b.ui && a.vi == b.vi && a.level == b.level && a.rotated == b.rotated;
}

void expectEqual(const lt::Asset& a, const lt::Asset& b) {
    EXPECT_TRUE(sameBits(a.positions, b.positions));
    EXPECT_TRUE(sameBits(a.faces, b.faces));
    EXPECT_TRUE(sameBits(a.faceUVs, b.faceUVs));
    EXPECT_EQ(a.boundary, b.boundary);
    EXPECT_EQ(a.creaseMethod, b.creaseMethod);
    ASSERT_EQ(a.levels.size(), b.levels.size());
    using R = lt::Refinement;
    using S = lt::LimitStencils;
    for (size_t l = 0; l < a.levels.size(); ++l) {
        SCOPED_TRACE("level " + std::to_string(l));
        const lt::Level &x = a.levels[l], &y = b.levels[l];
        EXPECT_EQ(x.refinement.firstVertex, y.refinement.firstVertex);
        for (auto m : {&R::vertexParent, &R::vertexRingStart, &R::vertexRing, &R::maskedVertex, &R::maskStart,
                       &R::edgeVerts, &R::creaseEdge})
            EXPECT_TRUE(sameBits(x.refinement.*m, y.refinement.*m));
        for (auto m : {&R::maskWeights, &R::creaseWeight}) EXPECT_TRUE(sameBits(x.refinement.*m, y.refinement.*m));
        for (auto m : {&S::vertex, &S::start, &S::ring}) EXPECT_TRUE(sameBits(x.limit.*m, y.limit.*m));
        for (auto m : {&S::position, &S::tangentU, &S::tangentV}) EXPECT_TRUE(sameBits(x.limit.*m, y.limit.*m));
        ASSERT_EQ(x.regular.size(), y.regular.size());
        for (size_t i = 0; i < x.regular.size(); ++i) {
            const lt::RegularPatch &p = x.regular[i], &q = y.regular[i];
            EXPECT_EQ(0, std::memcmp(p.points, q.points, sizeof p.points));
            EXPECT_TRUE(p.boundaryMask == q.boundaryMask && p.splitMask == q.splitMask && sameParam(p.param, q.param));
        }
        ASSERT_EQ(x.irregular.size(), y.irregular.size());
        for (size_t i = 0; i < x.irregular.size(); ++i) {
            EXPECT_EQ(0, std::memcmp(x.irregular[i].corners, y.irregular[i].corners, sizeof x.irregular[i].corners));
            EXPECT_TRUE(sameParam(x.irregular[i].param, y.irregular[i].param));
        }
    }
}

std::vector<uint8_t> write(const lt::Asset& a, lt::TableBytes* tb = nullptr) {
    std::vector<uint8_t> bytes;
    const lt::Status st = lt::writeAssetGlb(a, bytes, tb);
    EXPECT_TRUE(st) << st.message;
    return bytes;
}

// --- editing a GLB ------------------------------------------------------------------

uint32_t u32At(const std::vector<uint8_t>& b, size_t at) {
    return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}
void putU32(std::vector<uint8_t>& b, size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) b[at + k] = uint8_t(v >> (8 * k));
}

struct Glb {
    Json doc;
    std::vector<uint8_t> bin;

    explicit Glb(const std::vector<uint8_t>& bytes) {
        const uint32_t jsonLength = u32At(bytes, 12);
        doc = Json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength);
        const size_t binAt = 20 + jsonLength;
        bin.assign(bytes.begin() + binAt + 8, bytes.begin() + binAt + 8 + u32At(bytes, binAt));
    }
    std::vector<uint8_t> bytes() const { return bytesWithJson(doc.dump()); }
    std::vector<uint8_t> bytesWithJson(std::string text) const {
        while (text.size() % 4) text.push_back(' ');
        std::vector<uint8_t> out(28 + text.size() + bin.size());
        for (auto [at, v] : {std::pair<size_t, uint32_t>{0, 0x46546C67}, {4, 2}, {8, uint32_t(out.size())},
                             {12, uint32_t(text.size())}, {16, 0x4E4F534A}, {20 + text.size(), uint32_t(bin.size())},
                             {24 + text.size(), 0x004E4942}})
            putU32(out, at, v);
        std::copy(text.begin(), text.end(), out.begin() + 20);
        std::copy(bin.begin(), bin.end(), out.begin() + 28 + text.size());
        return out;
    }
    Json& ext() { return doc["meshes"][0]["primitives"][0]["extensions"][kExt]; }
    int accessor(size_t level, const char* prop) { return ext()["levels"][level][prop].get<int>(); }
    // Byte address of element `i` of accessor `acc` in the BIN chunk.
    uint8_t* element(int acc, size_t i) {
        const Json& a = doc["accessors"][acc];
        const Json& v = doc["bufferViews"][a["bufferView"].get<int>()];
        const int ct = a["componentType"].get<int>();
        const size_t size = ct == 5121 ? 1 : ct == 5123 ? 2 : 4;
        return &bin[v.value("byteOffset", 0) + a.value("byteOffset", 0) + i * size];
    }
    void setIndex(int acc, size_t i, uint32_t value) {
        uint8_t* p = element(acc, i);
        const int ct = doc["accessors"][acc]["componentType"].get<int>();
        for (int k = 0; k < (ct == 5123 ? 2 : ct == 5121 ? 1 : 4); ++k) p[k] = uint8_t(value >> (8 * k));
    }
    void setFloat(int acc, size_t i, float value) { std::memcpy(element(acc, i), &value, 4); }
};

lt::Status read(const std::vector<uint8_t>& bytes, lt::Asset* out = nullptr) {
    lt::Asset a;
    lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), "t.glb", a);
    if (out) *out = std::move(a);
    return st;
}

void expectRule(const lt::Status& st, int rule) {
    ASSERT_FALSE(st) << "accepted, expected rule " << rule;
    EXPECT_EQ(st.message.rfind("t.glb: ", 0), 0u) << st.message;
    EXPECT_NE(st.message.find(": rule " + std::to_string(rule) + ": "), std::string::npos) << st.message;
}

// --- round trip, determinism, widths --------------------------------------------------

TEST(Format, RoundTripWithUVs) {
    const lt::Asset a = makeAsset(true);
    ASSERT_TRUE(lt::validateAsset(a, "synthetic")) << lt::validateAsset(a, "synthetic").message;
    EXPECT_EQ(a.totalVertexCount(), 4u + 10u + 5u);
    lt::TableBytes tb;
    const std::vector<uint8_t> bytes = write(a, &tb);
    lt::Asset b;
    const lt::Status st = read(bytes, &b);
    ASSERT_TRUE(st) << st.message;
    expectEqual(a, b);
    EXPECT_GT(tb.controlMesh, 0u);
    EXPECT_GT(tb.refinement, 0u);
    EXPECT_GT(tb.masks, 0u);
    EXPECT_GT(tb.patches, 0u);
    EXPECT_GT(tb.irregular, 0u);
    EXPECT_GT(tb.limit, 0u);
    EXPECT_LE(tb.total(), Glb(bytes).bin.size());

    Glb g(bytes);   // seams: the primitive has more vertices than the control mesh
    EXPECT_TRUE(g.ext().contains("controlVertex"));
    EXPECT_FALSE(g.doc.contains("extensionsRequired"));
    EXPECT_EQ(g.doc["asset"]["generator"], std::string("looptess loopbake ") + LOOPTESS_VERSION);
    EXPECT_EQ(g.doc["meshes"][0]["primitives"][0]["attributes"].size(), 2u);
}

TEST(Format, RoundTripWithoutUVs) {
    const lt::Asset a = makeAsset(false);
    const std::vector<uint8_t> bytes = write(a);
    lt::Asset b;
    const lt::Status st = read(bytes, &b);
    ASSERT_TRUE(st) << st.message;
    expectEqual(a, b);
    Glb g(bytes);
    EXPECT_FALSE(g.ext().contains("controlVertex"));   // identity: omitted
    EXPECT_FALSE(g.doc["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_0"));
    // Empty arrays are omitted: level 0 has no refinement, level 2 no masks/creases.
    EXPECT_FALSE(g.ext()["levels"][0].contains("vertexParent"));
    EXPECT_EQ(g.ext()["levels"][0]["firstVertex"], 0);
    EXPECT_FALSE(g.ext()["levels"][2].contains("maskWeights"));
    EXPECT_FALSE(g.ext()["levels"][2].contains("creaseEdge"));
}

TEST(Format, Deterministic) {
    const lt::Asset a = makeAsset(true);
    const std::vector<uint8_t> first = write(a), second = write(makeAsset(true));
    EXPECT_EQ(first, second);
    lt::Asset b;
    ASSERT_TRUE(read(first, &b));
    EXPECT_EQ(write(b), first);   // write(read(write(a))) == write(a)
}

TEST(Format, IndexWidths) {
    Glb small(write(makeAsset(true)));
    auto type = [](Glb& g, int acc) { return g.doc["accessors"][acc]["componentType"].get<int>(); };
    EXPECT_EQ(type(small, small.accessor(1, "vertexParent")), 5123);
    EXPECT_EQ(type(small, small.accessor(1, "edgeVerts")), 5123);
    EXPECT_EQ(type(small, small.doc["meshes"][0]["primitives"][0]["indices"].get<int>()), 5123);
    EXPECT_EQ(type(small, small.accessor(1, "regularBoundaryMask")), 5121);
    EXPECT_EQ(type(small, small.accessor(1, "regularOrigin")), 5123);
    EXPECT_EQ(type(small, small.accessor(1, "maskWeights")), 5126);

    // 70000 control vertices: level 1 and 2 indices need u32, CSR starts stay u16.
    lt::Asset big = makeAsset(true, 70000);
    const std::vector<uint8_t> bytes = write(big);
    lt::Asset back;
    const lt::Status st = read(bytes, &back);
    ASSERT_TRUE(st) << st.message;
    expectEqual(big, back);
    Glb g(bytes);
    EXPECT_EQ(type(g, g.accessor(1, "vertexParent")), 5123);   // parents are control vertices 0..3
    EXPECT_EQ(type(g, g.accessor(2, "vertexParent")), 5125);
    EXPECT_EQ(type(g, g.accessor(1, "edgeVerts")), 5123);
    EXPECT_EQ(type(g, g.accessor(2, "edgeVerts")), 5125);
    EXPECT_EQ(type(g, g.accessor(1, "regularPoints")), 5125);
    EXPECT_EQ(type(g, g.accessor(1, "vertexRingStart")), 5123);
    EXPECT_EQ(type(g, g.accessor(1, "limitStart")), 5123);
    // The 70000 unused vertices come last in the primitive: indices stay u16.
    EXPECT_EQ(type(g, g.doc["meshes"][0]["primitives"][0]["indices"].get<int>()), 5123);
    EXPECT_EQ(type(g, g.ext()["controlVertex"].get<int>()), 5125);

    // Exactly 65535 primitive vertices: tables fit u16 but indices must not use
    // the u16 primitive restart value 65535.
    lt::Asset edge = makeAsset(false, 65535 - 4);
    edge.faces[11] = 65534;
    for (auto& l : edge.levels) l = lt::Level{};
    edge.levels.resize(1);
    Glb e(write(edge));
    EXPECT_EQ(type(e, e.doc["meshes"][0]["primitives"][0]["indices"].get<int>()), 5123);
    edge.positions.insert(edge.positions.end(), {1, 2, 3});
    edge.faces[11] = 65535;
    Glb e2(write(edge));
    EXPECT_EQ(type(e2, e2.doc["meshes"][0]["primitives"][0]["indices"].get<int>()), 5125);
}

TEST(Format, WriterRejectsInvalidAsset) {
    lt::Asset a = makeAsset(false);
    a.levels[1].refinement.edgeVerts[5] = 999;
    std::vector<uint8_t> bytes;
    const lt::Status st = lt::writeAssetGlb(a, bytes);
    EXPECT_FALSE(st);
    EXPECT_NE(st.message.find("levels[1].edgeVerts[5]: rule 25: index 999"), std::string::npos) << st.message;
}

// --- the corruption catalogue: container rules (through the reader) ------------------

const std::vector<uint8_t>& fixtureBytes() {
    static const std::vector<uint8_t> bytes = write(makeAsset(true));
    return bytes;
}

// Edits the fixture's JSON and/or BIN, repacks it and expects rejection by `rule`.
void corrupt(const std::function<void(Glb&)>& edit, int rule) {
    Glb g(fixtureBytes());
    edit(g);
    expectRule(read(g.bytes()), rule);
}

// Same on the raw GLB bytes.
void corruptBytes(const std::function<void(std::vector<uint8_t>&)>& edit, int rule) {
    std::vector<uint8_t> b = fixtureBytes();
    edit(b);
    expectRule(read(b), rule);
}

using Edit = Glb&;
Json& prim(Glb& g) { return g.doc["meshes"][0]["primitives"][0]; }
Json& view(Glb& g, int acc) { return g.doc["bufferViews"][g.doc["accessors"][acc]["bufferView"].get<int>()]; }

TEST(Corrupt, GlbHeader) {
    corruptBytes([](auto& b) { b.resize(10); }, 1);
    corruptBytes([](auto& b) { b.resize(b.size() - 4); }, 1);   // truncated
    corruptBytes([](auto& b) { b[0] = 'X'; }, 1);
    corruptBytes([](auto& b) { putU32(b, 4, 1); }, 1);
    corruptBytes([](auto& b) { b.clear(); }, 1);
}

TEST(Corrupt, GlbChunks) {
    corruptBytes([](auto& b) { putU32(b, 12, u32At(b, 12) + 400); }, 2);   // JSON runs into BIN
    corruptBytes([](auto& b) { putU32(b, 16, 0x004E4942); }, 2);          // first chunk claims BIN
    corruptBytes([](auto& b) { b.resize(b.size() - 16); putU32(b, 8, uint32_t(b.size())); }, 2);   // BIN cut
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
    corrupt([](Edit g) { g.doc["buffers"][0]["byteLength"] = g.bin.size() + 4; }, 4);   // more than BIN
}

TEST(Corrupt, BufferViewOutOfRange) {
    corrupt([](Edit g) { view(g, g.accessor(1, "edgeVerts"))["byteOffset"] = g.bin.size() - 2; }, 5);
    corrupt([](Edit g) { view(g, g.accessor(1, "edgeVerts"))["buffer"] = 1; }, 5);
}

TEST(Corrupt, AccessorOutOfRange) {
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "edgeVerts")]["count"] = 1000; }, 6);
    corrupt([](Edit g) { g.ext()["levels"][1]["edgeVerts"] = 5000; }, 6);   // no such accessor
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "vertexRing")]["byteOffset"] = 1; }, 6);
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "vertexRing")]["sparse"] = Json::object({{"count", 1}}); }, 6);
}

TEST(Corrupt, BadComponentType) {
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "edgeVerts")]["componentType"] = 5126; }, 7);
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(0, "irregularCorners")]["type"] = "SCALAR"; }, 7);
    corrupt([](Edit g) { g.doc["accessors"][g.accessor(1, "regularOrigin")]["componentType"] = 5125; }, 7);
}

TEST(Corrupt, ExtensionPlacement) {
    corrupt([](Edit g) { g.doc["extensionsRequired"] = Json::array({kExt}); }, 8);
    corrupt([](Edit g) { g.doc["extensionsUsed"] = Json::array({"KHR_other"}); }, 8);
    corrupt([](Edit g) { g.doc["meshes"].push_back(g.doc["meshes"][0]); }, 8);
}

TEST(Corrupt, FallbackPrimitive) {
    corrupt([](Edit g) { prim(g)["mode"] = 1; }, 9);
    corrupt([](Edit g) { g.setIndex(prim(g)["indices"].get<int>(), 4, 60000); }, 9);
    corrupt([](Edit g) { prim(g)["attributes"].erase("POSITION"); }, 9);
}

TEST(Corrupt, ControlVertexMapping) {
    corrupt([](Edit g) {   // the largest entry 50 leaves control vertices 4..49 unmapped
        const int cv = g.ext()["controlVertex"].get<int>();
        g.setIndex(cv, g.doc["accessors"][cv]["count"].get<size_t>() - 1, 50);
    }, 10);
    corrupt([](Edit g) {   // control vertex 0 has several copies (UV seams): move its last copy
        const int cv = g.ext()["controlVertex"].get<int>(), pos = prim(g)["attributes"]["POSITION"].get<int>();
        size_t copy = 0;
        for (size_t v = 1; v < g.doc["accessors"][cv]["count"].get<size_t>(); ++v)
            if (g.element(cv, v)[0] == 0 && g.element(cv, v)[1] == 0) copy = v;
        ASSERT_NE(copy, 0u);
        g.setFloat(pos, 3 * copy + 1, 0.25f);
    }, 11);
}

TEST(Corrupt, WrongVersion) {
    Glb g(fixtureBytes());
    g.ext()["version"] = 2;
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
    corrupt([](Edit g) {   // a second accessor over level 1's vertexRing bytes
        g.doc["accessors"].push_back(g.doc["accessors"][g.accessor(1, "vertexRing")]);
        g.ext()["levels"][2]["vertexRing"] = g.doc["accessors"].size() - 1;
    }, 14);
}

TEST(Corrupt, PatchArraysDisagree) {
    corrupt([](Edit g) { g.ext()["levels"][1].erase("regularSplitMask"); }, 15);
    corrupt([](Edit g) { g.ext()["levels"][0].erase("regularPoints"); }, 15);
}

// --- table rules through the reader (BIN edits) ---------------------------------------

TEST(Corrupt, IndexOutOfRange) {
    Glb g(fixtureBytes());
    g.setIndex(g.accessor(2, "edgeVerts"), 5, 16);   // level 2 reads level 1 = [4, 14)
    const lt::Status st = read(g.bytes());
    expectRule(st, 25);
    EXPECT_NE(st.message.find("t.glb: levels[2].edgeVerts[5]: rule 25: index 16 is outside level 1's vertices [4, 14)"),
              std::string::npos)
        << st.message;
}

TEST(Corrupt, TableRules) {
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "vertexRingStart"), 2, 1); }, 23);   // CSR not monotone
    corrupt([](Edit g) { g.setFloat(g.accessor(1, "maskWeights"), 2, std::nanf("")); }, 17);
    corrupt([](Edit g) { g.setFloat(g.accessor(0, "limitTangentV"), 0, INFINITY); }, 17);
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "regularBoundaryMask"), 0, 64); }, 31);
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "regularLevel"), 1, 2 | 0x80); }, 32);   // level 2 in level 1
    corrupt([](Edit g) { g.setIndex(g.accessor(1, "regularOrigin"), 0, 2); }, 32);   // ui + vi = 2 at level 1
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
    a.levels[1].regular[0].boundaryMask = 2 | 8;   // edge 1 and the opposite corner 0 (OpenSubdiv's case)
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
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.maskWeights.pop_back(); a.levels[1].refinement.maskStart[1] = 3; }, 27);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.edgeVerts[1] = 0; }, 28);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.creaseWeight[0] = 0.0f; }, 29);
    expectInvalid([](lt::Asset& a) { a.levels[1].refinement.creaseEdge[0] = 6; }, 29);
    expectInvalid([](lt::Asset& a) { a.levels[1].regular[0].points[7] = 3; }, 30);
    expectInvalid([](lt::Asset& a) { a.levels[1].regular[0].splitMask = 8; }, 31);
    expectInvalid([](lt::Asset& a) { a.levels[1].regular[0].boundaryMask = 1 | 16; }, 31);   // edge 0 + corner 1
    expectInvalid([](lt::Asset& a) { a.levels[1].regular[0].boundaryMask = 4 | 8; }, 31);   // edge 2 + corner 0

    expectInvalid([](lt::Asset& a) { a.levels[2].regular[0].splitMask = 1; }, 31);
    expectInvalid([](lt::Asset& a) { a.levels[1].irregular[0].param.level = 0; }, 32);
    expectInvalid([](lt::Asset& a) { a.levels[0].irregular[0].param.baseFace = 4; }, 32);
    expectInvalid([](lt::Asset& a) { a.levels[0].regular[0].param.rotated = true; }, 32);
    expectInvalid([](lt::Asset& a) { a.levels[2].irregular[0].param.vi = 4; }, 32);
    expectInvalid([](lt::Asset& a) { a.levels[1].irregular[0].corners[2] = 3; }, 33);
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.ring[1] = 3; }, 34);
    expectInvalid([](lt::Asset& a) { a.levels[1].limit.ring[0] = 5; }, 34);
    expectInvalid([](lt::Asset& a) { std::swap(a.levels[0].limit.ring[1], a.levels[0].limit.ring[2]); }, 34);
}

// --- reader safety: truncations and random byte flips never crash -------------------

TEST(Format, MutationsNeverCrash) {
    const std::vector<uint8_t> bytes = write(makeAsset(true));
    for (size_t n = 0; n < bytes.size(); n += 7) {
        std::vector<uint8_t> b(bytes.begin(), bytes.begin() + n);
        EXPECT_FALSE(read(b));
    }
    std::mt19937 rng(12345);
    int accepted = 0;
    for (int i = 0; i < 3000; ++i) {
        std::vector<uint8_t> b = bytes;
        const int flips = 1 + int(rng() % 4);
        for (int k = 0; k < flips; ++k) b[rng() % b.size()] ^= uint8_t(1u << (rng() % 8));
        lt::Asset a;
        if (lt::readAssetGlb(b.data(), b.size(), "m.glb", a)) {
            ++accepted;
            EXPECT_TRUE(lt::validateAsset(a, "m.glb"));
        }
    }
    EXPECT_LT(accepted, 3000);
}

// --- the spec files list exactly what the writer emits ----------------------------

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(Format, SpecMatchesWriter) {
    const std::string dir = std::string(LOOPTESS_TEST_DATA) + "/../../formats/EXT_mesh_loop_subdivision/";
    const std::string readme = slurp(dir + "README.md");
    const Json schema = Json::parse(slurp(dir + "schema/mesh.primitive.EXT_mesh_loop_subdivision.schema.json"),
                                    nullptr, false);
    ASSERT_FALSE(readme.empty());
    ASSERT_TRUE(schema.is_object());
    Glb g(write(makeAsset(true)));   // level 1 of the fixture has every array
    std::vector<std::string> written, specified;
    for (const auto& [key, value] : g.ext()["levels"][1].items()) written.push_back(key);
    for (const auto& [key, value] : schema["$defs"]["level"]["properties"].items())
        if (key != "extensions" && key != "extras") specified.push_back(key);
    std::sort(written.begin(), written.end());
    std::sort(specified.begin(), specified.end());
    EXPECT_EQ(written, specified);
    for (const std::string& name : written)
        EXPECT_NE(readme.find("| `" + name + "` |"), std::string::npos) << name << " missing from the README table";
    for (const auto& [key, value] : g.ext().items()) {
        EXPECT_TRUE(schema["properties"].contains(key)) << key;
    }
    for (int rule = 1; rule <= 34; ++rule)   // numbered rules 1..34, nothing after
        EXPECT_NE(readme.find("\n" + std::to_string(rule) + ". **"), std::string::npos) << "rule " << rule;
    EXPECT_EQ(readme.find("\n35. **"), std::string::npos);
}

// --- the Khronos glTF-Validator --------------------------------------------------------

void expectKhronosValid(const std::vector<uint8_t>& bytes, const std::string& fileName) {
    ASSERT_EQ(std::system("command -v node > /dev/null 2>&1"), 0)
        << "node is not installed: the Khronos glTF-Validator cannot run";
    const std::string dir = ::testing::TempDir();
    const std::string file = dir + "/" + fileName, report = file + ".report.json";
    {
        std::ofstream out(file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        ASSERT_TRUE(out.good());
    }
    const std::string cmd = std::string("node '") + VALIDATOR_JS + "' '" + file + "' > '" + report + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream in(report);
    std::stringstream text;
    text << in.rdbuf();
    ASSERT_EQ(rc, 0) << "glTF-Validator rejected " << file << ":\n" << text.str();
    const Json r = Json::parse(text.str(), nullptr, false);
    ASSERT_FALSE(r.is_discarded()) << text.str();
    EXPECT_EQ(r["issues"]["numErrors"], 0);
    EXPECT_EQ(r["issues"]["numWarnings"], 0);
    std::remove(file.c_str());
    std::remove(report.c_str());
}

TEST(Format, KhronosValidatorWithUVs) { expectKhronosValid(write(makeAsset(true)), "uvs.glb"); }
TEST(Format, KhronosValidatorWithoutUVs) { expectKhronosValid(write(makeAsset(false)), "plain.glb"); }
TEST(Format, KhronosValidatorU32) { expectKhronosValid(write(makeAsset(true, 70000)), "u32.glb"); }

} // namespace
