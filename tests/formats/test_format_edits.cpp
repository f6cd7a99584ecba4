// tests/formats/test_format_edits.cpp -- hierarchical edits in EXT_mesh_loop_subdivision (spec
// "Hierarchical edits"): GLB round trip of a baked corpus shape with edits added by
// hand on levels 0, 1 and 2, byte-identical rewrite, files without edits unchanged,
// the values alone on their own bufferView in the flat edit order, the Khronos
// validator, and rules 40..44 (plus the generic accessor rule 7 on the new
// accessors) through the validator and the reader.
//
// The oracle for the layout is the spec read independently: the test decodes the
// JSON and BIN chunks itself (fmttest::Glb) and checks the values against the edits
// it put in, in the order the spec prescribes.
#include "format_fixture.h"

#include "looptess/tools/baker.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace fmttest;
using lt::EditOp;
using Value = std::array<float, 3>;

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// loop_cube baked to depth 3, without edits (as loopbake does it, without its I/O).
const lt::Asset& bakedCube() {
    static const lt::Asset asset = [] {
        const std::string obj = std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/loop_cube.obj";
        lt::InputMesh mesh;
        lt::Asset a;
        lt::Status st = lt::parseObj(slurp(obj), obj, lt::InputOptions{}, mesh);
        if (st) st = lt::checkInput(mesh, obj);
        lt::BakeSettings settings;
        settings.maxDepth = 3;
        if (st) st = lt::bake(mesh, settings, a);
        EXPECT_TRUE(st) << st.message << " (LOOPTESS_CORPUS_DIR=" << LOOPTESS_CORPUS_DIR << ")";
        return a;
    }();
    return asset;
}

// Level l's vertices [first, first + count) as the spec numbers them.
std::pair<uint32_t, uint32_t> levelRange(const lt::Asset& a, size_t l) {
    if (l == 0) return {0, a.controlVertexCount()};
    return {a.levels[l].refinement.firstVertex, a.levels[l].refinement.vertexCount()};
}

void addEdits(lt::VertexEdits& e, uint32_t vertex, const std::vector<std::pair<EditOp, Value>>& edits) {
    if (e.start.empty()) e.start.push_back(0);
    e.vertex.push_back(vertex);
    for (const auto& [op, value] : edits) {
        e.op.push_back(op);
        e.value.insert(e.value.end(), value.begin(), value.end());
    }
    e.start.push_back(uint32_t(e.op.size()));
}

// The baked cube with edits on levels 0, 1 and 2 (none on 3): first, middle and
// last vertices of each level's range, every operation, several edits per vertex,
// values with -0, a subnormal and the extremes of float.
lt::Asset editedCube() {
    lt::Asset a = bakedCube();
    if (a.levels.size() != 4) return a;
    const auto [f0, n0] = levelRange(a, 0);
    const auto [f1, n1] = levelRange(a, 1);
    const auto [f2, n2] = levelRange(a, 2);
    const float tiny = std::numeric_limits<float>::denorm_min(), big = std::numeric_limits<float>::max();
    addEdits(a.levels[0].edits, f0, {{EditOp::Add, {0.125f, -0.0f, 1.0f / 3.0f}}});
    addEdits(a.levels[0].edits, f0 + n0 - 1, {{EditOp::Set, {1.0f, 2.0f, 3.0f}}});
    addEdits(a.levels[1].edits, f1, {{EditOp::Add, {0.0f, 0.1f, 0.0f}}, {EditOp::Subtract, {tiny, 0.0f, -0.5f}}});
    addEdits(a.levels[1].edits, f1 + n1 / 2, {{EditOp::Set, {-big, big, 0.25f}}});
    addEdits(a.levels[1].edits, f1 + n1 - 1,
             {{EditOp::Add, {1, 1, 1}}, {EditOp::Add, {2, 2, 2}}, {EditOp::Subtract, {0.5f, 0.5f, 0.5f}}});
    addEdits(a.levels[2].edits, f2 + n2 / 3, {{EditOp::Subtract, {-7.0f, 1e-3f, 42.0f}}});
    return a;
}

const std::vector<uint8_t>& editedBytes() {
    static const std::vector<uint8_t> bytes = write(editedCube(), nullptr, lt::Compression::None);  // edited below
    return bytes;
}

bool sameEdits(const lt::VertexEdits& a, const lt::VertexEdits& b) {
    return sameBits(a.vertex, b.vertex) && sameBits(a.start, b.start) && sameBits(a.op, b.op) &&
           sameBits(a.value, b.value);
}

// Reads `bytes` and expects rejection by `rule` with `path` (a JSON or table path
// after "t.glb: ") in the message.
void expectReadRule(const std::vector<uint8_t>& bytes, int rule, const std::string& path) {
    const lt::Status st = read(bytes);
    ASSERT_NO_FATAL_FAILURE(expectRule(st, rule));
    EXPECT_NE(st.message.find(path + ": rule "), std::string::npos) << st.message;
}

void corruptEdited(const std::function<void(Glb&)>& edit, int rule, const std::string& path) {
    Glb g(editedBytes());
    edit(g);
    expectReadRule(g.bytes(), rule, path);
}

// validateAsset on the edited cube changed by `edit`: rejected by `rule`, the
// message naming `path`.
void invalidEdits(const std::function<void(lt::Asset&)>& edit, int rule, const std::string& path) {
    lt::Asset a = editedCube();
    edit(a);
    const lt::Status st = lt::validateAsset(a, "t.glb");
    ASSERT_NO_FATAL_FAILURE(expectRule(st, rule));
    EXPECT_NE(st.message.find("t.glb: " + path + ": rule "), std::string::npos) << st.message;
}

const std::string kExtPath = std::string("meshes[0].extensions.") + kExt;

TEST(FormatEdits, RoundTrip) {
    const lt::Asset a = editedCube();
    ASSERT_EQ(a.levels.size(), 4u);
    ASSERT_EQ(a.editCount(), 9u);
    const lt::Status valid = lt::validateAsset(a, "edited");
    ASSERT_TRUE(valid) << valid.message;
    lt::TableBytes tb;
    const std::vector<uint8_t> bytes = write(a, &tb);
    // Every edit level here has fewer than 65536 vertices: u16 vertices and starts.
    EXPECT_EQ(tb.edits, (2 * 2 + 2 * 3 + 2) + (2 * 3 + 2 * 4 + 6) + (2 * 1 + 2 * 2 + 1) + 12 * 9);
    EXPECT_EQ(tb.total(), tb.controlMesh + tb.refinement + tb.masks + tb.patches + tb.irregular + tb.limit +
                              tb.displacement + tb.edits);
    lt::Asset back;
    const lt::Status st = read(bytes, &back);
    ASSERT_TRUE(st) << st.message;
    expectEqual(a, back);
    for (size_t l = 0; l < a.levels.size(); ++l)
        EXPECT_TRUE(sameEdits(a.levels[l].edits, back.levels[l].edits)) << "level " << l;
    EXPECT_TRUE(back.levels[3].edits.start.empty());
    EXPECT_EQ(write(back), bytes);  // byte-identical rewrite
}

// The asset without its edits is written exactly as the bake without edits, with
// none of the edit properties; and the committed golden file (written before edits
// existed) reads and rewrites to the same bytes.
TEST(FormatEdits, FilesWithoutEditsUnchanged) {
    lt::Asset a = editedCube();
    for (lt::Level& level : a.levels) level.edits = lt::VertexEdits{};
    const std::vector<uint8_t> plain = write(bakedCube());
    EXPECT_EQ(write(a), plain);
    Glb g(plain);
    EXPECT_FALSE(g.ext().contains("editValues"));
    for (const Json& level : g.ext()["levels"])
        for (const char* key : {"editVertex", "editStart", "editOp"}) EXPECT_FALSE(level.contains(key)) << key;
    lt::TableBytes tb;
    write(bakedCube(), &tb);
    EXPECT_EQ(tb.edits, 0u);

    const std::string golden = slurp(std::string(LOOPTESS_TEST_DATA) + "/golden/loop_icos_semisharp.glb");
    ASSERT_FALSE(golden.empty());
    const std::vector<uint8_t> goldenBytes(golden.begin(), golden.end());
    lt::Asset fromGolden;
    const lt::Status st = read(goldenBytes, &fromGolden);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(fromGolden.editCount(), 0u);
    EXPECT_EQ(write(fromGolden), goldenBytes);
}

// The JSON chunk as the spec describes it: three level rows where a level has edits,
// none elsewhere, and editValues (5126 VEC3, one per edit) alone on the last
// bufferView of the BIN chunk, in the flat edit order.
TEST(FormatEdits, ValuesOnTheirOwnBufferViewInFlatOrder) {
    const lt::Asset a = editedCube();
    Glb g(editedBytes());
    const Json& levels = g.ext()["levels"];
    for (size_t l = 0; l < 4; ++l) {
        const bool edited = l < 3;
        for (const char* key : {"editVertex", "editStart", "editOp"})
            EXPECT_EQ(levels[l].contains(key), edited) << "level " << l << " " << key;
        if (!edited) continue;
        const Json& op = g.doc["accessors"][levels[l]["editOp"].get<int>()];
        EXPECT_EQ(op["componentType"], 5121);
        EXPECT_EQ(op["type"], "SCALAR");
        // editVertex is stored relative to the level's first vertex.
        const int vertexAcc = levels[l]["editVertex"].get<int>();
        const uint32_t first = levelRange(a, l).first;
        for (size_t i = 0; i < a.levels[l].edits.vertex.size(); ++i)
            EXPECT_EQ(g.index(vertexAcc, i) + first, a.levels[l].edits.vertex[i]) << "level " << l << " vertex " << i;
    }
    ASSERT_TRUE(g.ext().contains("editValues"));
    const int acc = g.ext()["editValues"].get<int>();
    const Json& values = g.doc["accessors"][acc];
    EXPECT_EQ(values["componentType"], 5126);
    EXPECT_EQ(values["type"], "VEC3");
    EXPECT_EQ(values["count"], 9);
    const int viewIndex = values["bufferView"].get<int>();
    for (size_t i = 0; i < g.doc["accessors"].size(); ++i)
        EXPECT_TRUE(int(i) == acc || g.doc["accessors"][i]["bufferView"].get<int>() != viewIndex) << "accessor " << i;
    const Json& view = g.doc["bufferViews"][viewIndex];
    EXPECT_EQ(viewIndex + 1, int(g.doc["bufferViews"].size()));  // the last one
    EXPECT_EQ(view["byteLength"], 12 * 9);
    EXPECT_EQ(view["byteOffset"].get<size_t>() + 12 * 9, g.bin.size());
    EXPECT_FALSE(view.contains("byteStride"));
    EXPECT_FALSE(values.contains("byteOffset"));
    // Flat order: level 0's edits, then level 1's, then level 2's.
    std::vector<float> expected;
    for (const lt::Level& level : a.levels)
        expected.insert(expected.end(), level.edits.value.begin(), level.edits.value.end());
    std::vector<float> stored(27);
    std::memcpy(stored.data(), g.element(acc, 0), 27 * 4);
    EXPECT_TRUE(sameBits(stored, expected));

    // Replacing just those bytes changes the values and nothing else.
    for (size_t k = 0; k < 27; ++k) g.setFloat(acc, k, float(k) * 0.5f);
    lt::Asset replaced;
    ASSERT_TRUE(read(g.bytes(), &replaced));
    expectEqual(a, replaced);
    size_t k = 0;
    for (const lt::Level& level : replaced.levels) {
        for (float v : level.edits.value) EXPECT_EQ(v, float(k++) * 0.5f);
    }
    EXPECT_EQ(k, 27u);
    for (size_t l = 0; l < 4; ++l) {
        EXPECT_TRUE(sameBits(replaced.levels[l].edits.op, a.levels[l].edits.op));
        EXPECT_TRUE(sameBits(replaced.levels[l].edits.vertex, a.levels[l].edits.vertex));
    }
}

// The Khronos glTF-Validator accepts a file with edits (no errors, no warnings).
TEST(FormatEdits, KhronosValidator) { expectValidatorClean(editedBytes(), "edited.glb"); }

TEST(FormatEdits, Rule40Values) {
    // In memory: 3 values per edit.
    invalidEdits([](lt::Asset& a) { a.levels[1].edits.value.pop_back(); }, 40, "levels[1]");
    invalidEdits([](lt::Asset& a) { a.levels[2].edits.value.push_back(1.0f); }, 40, "levels[2]");
    const std::string values = kExtPath + ".editValues";
    // Fewer or more values than edits of levels 0..maxDepth (more: edits no level holds).
    corruptEdited([](Edit g) { g.doc["accessors"][g.ext()["editValues"].get<int>()]["count"] = 8; }, 40, values);
    corruptEdited(
        [](Edit g) {
            Json& levels = g.ext()["levels"];
            for (const char* key : {"editVertex", "editStart", "editOp"}) levels[2].erase(key);
        },
        40, values);
    corruptEdited([](Edit g) { g.ext().erase("editValues"); }, 40, values);
    // Shared bufferView: another accessor on it (here an unused copy).
    corruptEdited([](Edit g) { g.doc["accessors"].push_back(g.doc["accessors"][g.ext()["editValues"].get<int>()]); },
                  40, values);
    // A file without edits but with values.
    Glb g(editedBytes());
    for (Json& level : g.ext()["levels"])
        for (const char* key : {"editVertex", "editStart", "editOp"}) level.erase(key);
    expectReadRule(g.bytes(), 40, values);
}

TEST(FormatEdits, Rule41Csr) {
    invalidEdits([](lt::Asset& a) { a.levels[1].edits.start.pop_back(); }, 41, "levels[1].editStart");
    invalidEdits([](lt::Asset& a) { a.levels[1].edits.start.clear(); }, 41, "levels[1].editStart");
    invalidEdits([](lt::Asset& a) { a.levels[0].edits.start[0] = 1; }, 41, "levels[0].editStart[0]");
    invalidEdits([](lt::Asset& a) { a.levels[1].edits.start[2] = a.levels[1].edits.start[1]; }, 41,
                 "levels[1].editStart[2]");  // vertex 1 without edits
    invalidEdits([](lt::Asset& a) { a.levels[1].edits.start[1] = 4; }, 41, "levels[1].editStart[2]");  // 4 > 3
    invalidEdits(
        [](lt::Asset& a) {
            lt::VertexEdits& e = a.levels[2].edits;
            e.op.push_back(EditOp::Add);
            e.value.insert(e.value.end(), {0, 0, 0});
        },
        41, "levels[2].editStart[1]");  // ends at 1, editOp has 2
    invalidEdits(
        [](lt::Asset& a) {  // edits without vertices
            lt::VertexEdits& e = a.levels[3].edits;
            e.op.push_back(EditOp::Add);
            e.value.insert(e.value.end(), {0, 0, 0});
        },
        41, "levels[3].editStart");
    // In the file: editStart missing, or its last entry changed.
    corruptEdited([](Edit g) { g.ext()["levels"][1].erase("editStart"); }, 41, "levels[1].editStart");
    corruptEdited([](Edit g) { g.setIndex(g.accessor(2, "editStart"), 1, 5); }, 41, "levels[2].editStart[1]");
}

TEST(FormatEdits, Rule42Vertices) {
    const lt::Asset& a = bakedCube();
    const uint32_t n0 = a.controlVertexCount(), n1 = levelRange(a, 1).second;
    // Level 0: a control vertex; level 1: not a vertex of level 2 (or level 0).
    invalidEdits([&](lt::Asset& e) { e.levels[0].edits.vertex[1] = n0; }, 42, "levels[0].editVertex[1]");
    invalidEdits([&](lt::Asset& e) { e.levels[1].edits.vertex[2] = levelRange(e, 2).first; }, 42,
                 "levels[1].editVertex[2]");
    invalidEdits([&](lt::Asset& e) { e.levels[1].edits.vertex[0] = 0; }, 42, "levels[1].editVertex[0]");
    // Strictly increasing.
    invalidEdits([&](lt::Asset& e) { e.levels[1].edits.vertex[1] = e.levels[1].edits.vertex[0]; }, 42,
                 "levels[1].editVertex[1]");
    invalidEdits([&](lt::Asset& e) { std::swap(e.levels[0].edits.vertex[0], e.levels[0].edits.vertex[1]); }, 42,
                 "levels[0].editVertex[1]");
    // In the file: a stored (relative) index equal to the level's vertex count.
    Glb g(editedBytes());
    g.setIndex(g.accessor(1, "editVertex"), 2, n1);
    const lt::Status st = read(g.bytes());
    ASSERT_NO_FATAL_FAILURE(expectRule(st, 42));
    const std::string relative = "levels[1].editVertex[2]: rule 42: relative index " + std::to_string(n1) +
                                 " (vertex " + std::to_string(levelRange(a, 1).first + n1) +
                                 ") is not below level 1's vertex count " + std::to_string(n1);
    EXPECT_NE(st.message.find(relative), std::string::npos) << st.message;
}

TEST(FormatEdits, Rule43Ops) {
    invalidEdits([](lt::Asset& a) { a.levels[1].edits.op[3] = EditOp(3); }, 43, "levels[1].editOp[3]");
    corruptEdited([](Edit g) { g.setIndex(g.accessor(2, "editOp"), 0, 255); }, 43, "levels[2].editOp[0]");
    // Rule 7 on the new accessors: editOp is 5121, editValues 5126 VEC3.
    corruptEdited([](Edit g) { g.ext()["levels"][0]["editOp"] = g.widen(g.accessor(0, "editOp"), 5123); }, 7,
                  kExtPath + ".levels[0].editOp");
    corruptEdited(
        [](Edit g) {
            Json& acc = g.doc["accessors"][g.ext()["editValues"].get<int>()];
            acc["type"] = "SCALAR";
            acc["count"] = 27;
        },
        7, kExtPath + ".editValues");
}

TEST(FormatEdits, Rule44FiniteValues) {
    // Level 1's edit 3 is the first of its third vertex; its flat number is 2 + 3.
    invalidEdits([](lt::Asset& a) { a.levels[1].edits.value[3 * 3 + 1] = std::nanf(""); }, 44, "editValues[16]");
    lt::Asset a = editedCube();
    a.levels[1].edits.value[3 * 3 + 1] = std::nanf("");
    const lt::Status st = lt::validateAsset(a, "t.glb");
    const std::string vertex = std::to_string(a.levels[1].edits.vertex[2]);
    EXPECT_NE(st.message.find("level 1 edit 3 (of vertex " + vertex + ", editOp[3]): coordinate 1 is not finite"),
              std::string::npos)
        << st.message;
    corruptEdited([](Edit g) { g.setFloat(g.ext()["editValues"].get<int>(), 26, INFINITY); }, 44, "editValues[26]");
}

// The spec and the schema list what the writer emits for edits.
TEST(FormatEdits, SpecMatchesWriter) {
    const std::string dir = std::string(LOOPTESS_TEST_DATA) + "/../../formats/EXT_mesh_loop_subdivision/";
    const std::string readme = slurp(dir + "README.md");
    const Json schema = Json::parse(slurp(dir + "schema/mesh.EXT_mesh_loop_subdivision.schema.json"), nullptr, false);
    ASSERT_TRUE(schema.is_object());
    Glb g(editedBytes());
    for (const auto& [key, value] : g.ext()["levels"][1].items()) {
        EXPECT_TRUE(schema["$defs"]["level"]["properties"].contains(key)) << key;
        EXPECT_NE(readme.find("| `" + key + "` |"), std::string::npos) << key << " missing from the README table";
    }
    for (const auto& [key, value] : g.ext().items()) {
        EXPECT_TRUE(schema["properties"].contains(key)) << key;
        EXPECT_NE(readme.find("| `" + key + "` |"), std::string::npos) << key << " missing from the README table";
    }
    for (int rule = 40; rule <= 44; ++rule)
        EXPECT_NE(readme.find("\n" + std::to_string(rule) + ". **"), std::string::npos) << "rule " << rule;
    EXPECT_EQ(readme.find("\n47. **"), std::string::npos);
    EXPECT_NE(readme.find("\n## Hierarchical edits\n"), std::string::npos);
}

TEST(FormatEdits, MutationsNeverCrash) {
    const std::vector<uint8_t>& bytes = editedBytes();
    uint32_t state = 12345;
    auto next = [&] { return state = state * 1664525u + 1013904223u; };
    // Flip bits in the JSON's edit area and the BIN's tail (editValues and the last rows).
    for (int i = 0; i < 1500; ++i) {
        std::vector<uint8_t> b = bytes;
        const size_t at = i % 2 ? b.size() - 1 - next() % 300 : next() % b.size();
        b[at] ^= uint8_t(1u << (next() % 8));
        lt::Asset a;
        if (lt::readAssetGlb(b.data(), b.size(), "m.glb", a)) { EXPECT_TRUE(lt::validateAsset(a, "m.glb")); }
    }
}

}  // namespace
