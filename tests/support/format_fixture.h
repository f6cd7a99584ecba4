// tests/support/format_fixture.h -- shared by the EXT_mesh_loop_subdivision format tests
// (test_format.cpp, test_format_corrupt.cpp): a synthetic asset that satisfies
// every rule of the spec without being a real subdivision (a tetrahedron control
// mesh with two levels of small, in-range tables), Asset comparison, and GLB
// editing helpers for the corruption catalogue.
#pragma once

#include "looptess/asset.h"
#include "looptess/glb.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fmttest {

using Json = nlohmann::json;
inline constexpr const char* kExt = "EXT_mesh_loop_subdivision";

inline lt::PatchParam param(uint32_t face, uint16_t ui, uint16_t vi, uint8_t level, bool rotated = false) {
    return lt::PatchParam{face, ui, vi, level, rotated};
}

inline lt::RegularPatch regular(uint32_t first, uint32_t count, uint32_t salt, uint8_t boundary, uint8_t split,
                                lt::PatchParam p) {
    lt::RegularPatch r;
    for (uint32_t k = 0; k < 12; ++k) r.points[k] = first + (salt + 5 * k) % count;
    r.boundaryMask = boundary;
    r.splitMask = split;
    r.param = p;
    return r;
}

inline lt::IrregularFace irregular(uint32_t a, uint32_t b, uint32_t c, lt::PatchParam p) {
    return lt::IrregularFace{{a, b, c}, p};
}

// Appends one stencil of vertex v with its neighbours `ring` (smallest first):
// smooth (no weights, at least 2 neighbours) or masked (explicit weights).
inline void stencil(lt::LimitStencils& s, uint32_t v, const std::vector<uint32_t>& ring, bool masked) {
    if (s.start.empty()) s.start.push_back(0);
    if (masked) {
        if (s.maskStart.empty()) s.maskStart.push_back(0);
        s.masked.push_back(s.count());
        for (size_t i = 0; i < ring.size(); ++i) {
            s.position.push_back(0.5f / float(ring.size()));
            s.tangentU.push_back(float(i) * 0.25f - 0.125f);
            s.tangentV.push_back(-1.0f / 3.0f);
        }
        s.maskStart.push_back(uint32_t(s.position.size()));
    }
    s.vertex.push_back(v);
    s.ring.insert(s.ring.end(), ring.begin(), ring.end());
    s.start.push_back(uint32_t(s.ring.size()));
}

// Tetrahedron with `extraVertices` unused control vertices appended (to push
// indices past 65535), levels 0..2.
inline lt::Asset makeAsset(bool uvs, uint32_t extraVertices = 0) {
    lt::Asset a;
    a.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (uint32_t i = 0; i < extraVertices; ++i) {
        a.positions.push_back(float(i) * 0.001f);
        a.positions.push_back(-0.5f);
        a.positions.push_back(0.1f);
    }
    a.faces = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    if (uvs)  // per-corner UVs with seams: vertex 0 gets three different UVs
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
    stencil(l0.limit, 0, {1, 2, 3}, false);
    stencil(l0.limit, 1, {0, 2, 3}, true);
    stencil(l0.limit, 2, {0, 1, 3}, false);
    stencil(l0.limit, 3, {0, 1, 2}, true);

    lt::Refinement& r1 = a.levels[1].refinement;  // level 1: [n, n + 10)
    r1.firstVertex = n;
    r1.vertexParent = {0, 1, 2, 3};
    r1.vertexRingStart = {0, 3, 6, 9, 12};
    r1.vertexRing = {1, 2, 3, 2, 3, 0, 3, 0, 1, 0, 1, 2};
    r1.maskedVertex = {2};
    r1.maskStart = {0, 3};
    r1.maskWeights = {0.125f, 0.125f, 0.0f};
    r1.edgeVerts = {0, 1, 2, 3, 1, 2, 0, 3, 2, 0, 1, 3, 0, 3, 1, 2, 1, 3, 0, 2, 2, 3, 0, 1};
    r1.creaseEdge = {3};
    r1.creaseWeight = {0.5f};
    a.levels[1].regular.push_back(regular(n, 10, 0, 5, 2, param(3, 1, 0, 1)));  // base faces 3, 0: unsorted
    a.levels[1].regular.push_back(regular(n, 10, 3, 0, 0, param(0, 1, 1, 1, true)));
    a.levels[1].irregular.push_back(irregular(0, 1, 2, param(2, 0, 0, 1)));
    stencil(a.levels[1].limit, n + 0, {n + 3, n + 6, n + 8}, false);
    stencil(a.levels[1].limit, n + 1, {n + 4, n + 9}, true);
    stencil(a.levels[1].limit, n + 2, {n + 0, n + 5, n + 7}, false);
    stencil(a.levels[1].limit, n + 2, {n + 5, n + 7}, true);  // a second sector of vertex n + 2

    lt::Refinement& r2 = a.levels[2].refinement;  // level 2: [n + 10, n + 15)
    const uint32_t m = n + 10;
    r2.firstVertex = m;
    r2.vertexParent = {n + 0, n + 1};
    r2.vertexRingStart = {0, 2, 4};
    r2.vertexRing = {n + 2, n + 3, n + 4, n + 5};
    r2.edgeVerts = {n + 0, n + 2, n + 3, n + 3, n + 1, n + 4, n + 5, n + 0, n + 2, n + 3, n + 0, n + 1};
    a.levels[2].regular.push_back(regular(m, 5, 2, 56, 0, param(3, 2, 1, 2)));
    a.levels[2].irregular.push_back(irregular(0, 1, 2, param(1, 1, 3, 2, true)));
    stencil(a.levels[2].limit, m + 0, {m + 1, m + 3}, false);
    stencil(a.levels[2].limit, m + 2, {m + 0}, true);
    stencil(a.levels[2].limit, m + 4, {m + 0, m + 1, m + 2, m + 3}, false);
    return a;
}

// makeAsset with 70000 extra control vertices, the last of which a level 0 patch
// and a level 1 edge point use: those two arrays need u32.
inline lt::Asset makeBigAsset() {
    lt::Asset a = makeAsset(true, 70000);
    const uint32_t last = a.controlVertexCount() - 1;
    a.levels[0].regular[0].points[3] = last;
    a.levels[1].refinement.edgeVerts[4] = last;  // edge point 1: a = last, b = 2
    return a;
}

// --- comparing Assets bitwise ---------------------------------------------------

template <typename T>
inline bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
inline bool sameParam(const lt::PatchParam& a, const lt::PatchParam& b) {
    return a.baseFace == b.baseFace && a.ui == b.ui && a.vi == b.vi && a.level == b.level && a.rotated == b.rotated;
}

inline void expectEqual(const lt::Asset& a, const lt::Asset& b) {
    EXPECT_TRUE(sameBits(a.positions, b.positions));
    EXPECT_TRUE(sameBits(a.faces, b.faces));
    EXPECT_TRUE(sameBits(a.faceUVs, b.faceUVs));
    EXPECT_TRUE(sameBits(a.faceUV1s, b.faceUV1s));
    EXPECT_TRUE(sameBits(a.faceColors, b.faceColors));
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
        for (auto m : {&S::vertex, &S::start, &S::ring, &S::masked, &S::maskStart})
            EXPECT_TRUE(sameBits(x.limit.*m, y.limit.*m));
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

inline std::vector<uint8_t> write(const lt::Asset& a, lt::TableBytes* tb = nullptr,
                                  lt::Compression compression = lt::Compression::Fast) {
    std::vector<uint8_t> bytes;
    const lt::Status st = lt::writeAssetGlb(a, bytes, tb, compression);
    EXPECT_TRUE(st) << st.message;
    return bytes;
}

// --- editing a GLB ------------------------------------------------------------------

inline uint32_t u32At(const std::vector<uint8_t>& b, size_t at) {
    return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}
inline void putU32(std::vector<uint8_t>& b, size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) b[at + k] = uint8_t(v >> (8 * k));
}

struct Glb {
    Json doc;
    std::vector<uint8_t> bin;

    // Throws (the test fails) when `bytes` is not a GLB with a JSON chunk.
    explicit Glb(const std::vector<uint8_t>& bytes) {
        lt::GlbChunks chunks;
        const lt::Status st = lt::readGlb(bytes.data(), bytes.size(), "fixture.glb", lt::GlbLayout::Strict, chunks);
        if (!st) throw std::runtime_error(st.message);
        doc = Json::parse(chunks.json.begin(), chunks.json.end());
        bin.assign(chunks.bin, chunks.bin + chunks.binLength);
    }
    std::vector<uint8_t> bytes() const { return bytesWithJson(doc.dump()); }
    std::vector<uint8_t> bytesWithJson(std::string text) const {
        while (text.size() % 4) text.push_back(' ');
        std::vector<uint8_t> out(28 + text.size() + bin.size());
        for (auto [at, v] : {std::pair<size_t, uint32_t>{0, lt::kGlbMagic},
                             {4, lt::kGlbVersion},
                             {8, uint32_t(out.size())},
                             {12, uint32_t(text.size())},
                             {16, lt::kGlbChunkJson},
                             {20 + text.size(), uint32_t(bin.size())},
                             {24 + text.size(), lt::kGlbChunkBin}})
            putU32(out, at, v);
        std::copy(text.begin(), text.end(), out.begin() + 20);
        std::copy(bin.begin(), bin.end(), out.begin() + 28 + text.size());
        return out;
    }
    Json& ext() { return doc["meshes"][0]["extensions"][kExt]; }                    // the surface object
    Json& cage() { return doc["meshes"][0]["primitives"][0]["extensions"][kExt]; }  // its cage primitive's
    int accessor(size_t level, const char* prop) { return ext()["levels"][level][prop].get<int>(); }
    // Byte address of element `i` of accessor `acc` in the BIN chunk.
    uint8_t* element(int acc, size_t i) {
        const Json& a = doc["accessors"][acc];
        const Json& v = doc["bufferViews"][a["bufferView"].get<int>()];
        const int ct = a["componentType"].get<int>();
        const size_t size = ct == 5121 ? 1 : ct == 5123 ? 2 : 4;
        return &bin[v.value("byteOffset", 0) + a.value("byteOffset", 0) + i * size];
    }
    uint32_t index(int acc, size_t i) {
        const uint8_t* p = element(acc, i);
        const int ct = doc["accessors"][acc]["componentType"].get<int>();
        uint32_t v = 0;
        for (int k = 0; k < (ct == 5123 ? 2 : ct == 5121 ? 1 : 4); ++k) v |= uint32_t(p[k]) << (8 * k);
        return v;
    }
    void setIndex(int acc, size_t i, uint32_t value) {
        uint8_t* p = element(acc, i);
        const int ct = doc["accessors"][acc]["componentType"].get<int>();
        for (int k = 0; k < (ct == 5123 ? 2 : ct == 5121 ? 1 : 4); ++k) p[k] = uint8_t(value >> (8 * k));
    }
    void setFloat(int acc, size_t i, float value) { std::memcpy(element(acc, i), &value, 4); }
    // Copies accessor `acc`'s values, stored with an integer componentType, into a
    // new accessor on a new bufferView at the end of the BIN; returns its index.
    int widen(int acc, int componentType) {
        const size_t n =
            doc["accessors"][acc]["count"].get<size_t>() * (doc["accessors"][acc]["type"] == "VEC2" ? 2 : 1);
        std::vector<uint32_t> values(n);
        for (size_t i = 0; i < n; ++i) values[i] = index(acc, i);
        const size_t size = componentType == 5121 ? 1 : componentType == 5123 ? 2 : 4, at = bin.size();
        bin.resize(at + (n * size + 3) / 4 * 4);
        for (size_t i = 0; i < n; ++i)
            for (size_t k = 0; k < size; ++k) bin[at + i * size + k] = uint8_t(values[i] >> (8 * k));
        doc["buffers"][0]["byteLength"] = bin.size();
        doc["bufferViews"].push_back(Json{{"buffer", 0}, {"byteOffset", at}, {"byteLength", n * size}});
        Json a = doc["accessors"][acc];
        a["bufferView"] = doc["bufferViews"].size() - 1;
        a["componentType"] = componentType;
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size() - 1);
    }
};

inline lt::Status read(const std::vector<uint8_t>& bytes, lt::Asset* out = nullptr) {
    lt::Asset a;
    lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), "t.glb", a);
    if (out) *out = std::move(a);
    return st;
}

// Writes `a`, reads it back and expects the same asset; the written file.
inline Glb roundTrip(const lt::Asset& a) {
    const std::vector<uint8_t> bytes = write(a);
    lt::Asset b;
    const lt::Status st = read(bytes, &b);
    EXPECT_TRUE(st) << st.message;
    if (st) expectEqual(a, b);
    return Glb(bytes);
}

inline void expectRule(const lt::Status& st, int rule) {
    ASSERT_FALSE(st) << "accepted, expected rule " << rule;
    EXPECT_EQ(st.message.rfind("t.glb: ", 0), 0u) << st.message;
    EXPECT_NE(st.message.find(": rule " + std::to_string(rule) + ": "), std::string::npos) << st.message;
}

// --- corrupting the fixture -------------------------------------------------------------

// The catalogue edits plain accessors, so its fixture is uncompressed; the
// compressed cases are in test_format_compression.cpp.
inline const std::vector<uint8_t>& fixtureBytes() {
    static const std::vector<uint8_t> bytes = write(makeAsset(true), nullptr, lt::Compression::None);
    return bytes;
}

// Edits the fixture's JSON and/or BIN, repacks it and expects rejection by `rule`.
inline void corrupt(const std::function<void(Glb&)>& edit, int rule) {
    Glb g(fixtureBytes());
    edit(g);
    expectRule(read(g.bytes()), rule);
}

// Same on the raw GLB bytes.
inline void corruptBytes(const std::function<void(std::vector<uint8_t>&)>& edit, int rule) {
    std::vector<uint8_t> b = fixtureBytes();
    edit(b);
    expectRule(read(b), rule);
}

using Edit = Glb&;
inline Json& prim(Glb& g) { return g.doc["meshes"][0]["primitives"][0]; }
inline Json& view(Glb& g, int acc) { return g.doc["bufferViews"][g.doc["accessors"][acc]["bufferView"].get<int>()]; }

// Runs the Khronos glTF-Validator (node, VALIDATOR_JS) on `bytes` written to a
// temporary `name` and expects no errors and no warnings.
inline void expectValidatorClean(const std::vector<uint8_t>& bytes, const std::string& name) {
    ASSERT_EQ(std::system("command -v node > /dev/null 2>&1"), 0) << "node is not installed";
    const std::string file = ::testing::TempDir() + "/" + name, report = file + ".report.json";
    {
        std::ofstream out(file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    const std::string cmd = std::string("node '") + VALIDATOR_JS + "' '" + file + "' > '" + report + "' 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    std::ifstream in(report);
    const Json r = Json::parse(in, nullptr, false);
    ASSERT_FALSE(r.is_discarded());
    EXPECT_EQ(r["issues"]["numErrors"], 0) << r.dump(1);
    EXPECT_EQ(r["issues"]["numWarnings"], 0) << r.dump(1);
    std::remove(file.c_str());
    std::remove(report.c_str());
}

}  // namespace fmttest
