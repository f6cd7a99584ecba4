// test_edits_input.cpp -- the input side of hierarchical edits: OBJ
// `t vertexedit` tags (parseObj), the JSON side-car (parseEditsJson), checkInput's
// edit checks and loopbake --edits. The expected edits are written out by hand from
// docs/hierarchical-edits.md section 2 and from how OpenSubdiv's
// regression/common/hbr_utils.h (applyTags, v3_5_0) walks a tag: a path takes
// pathlength + 1 ints, and path i reads floats [3i, 3i + 3) (floatstride 3 for one
// `P value` op), whatever the declared float count.
#include "input_edit.h"
#include "looptess/tools/baker.h"

#include "tool_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using Edit = lt::InputMesh::VertexEdit;
using lt::EditOp;
using lt::test::inputEdit;

// An octahedron: 8 triangles, polygons 0..7 are triangles 0..7.
const char* const kOcta =
    "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
    "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
}

lt::Status parse(const std::string& text, lt::InputMesh& mesh) {
    return lt::parseObj(text, "t.obj", lt::InputOptions{}, mesh);
}

lt::InputMesh parseOk(const std::string& text) {
    lt::InputMesh mesh;
    lt::Status st = parse(text, mesh);
    EXPECT_TRUE(st) << st.message;
    return mesh;
}

void expectEdits(const std::vector<Edit>& got, const std::vector<Edit>& want) {
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < got.size(); ++i) {
        SCOPED_TRACE("edit " + std::to_string(i));
        EXPECT_EQ(got[i].face, want[i].face);
        EXPECT_EQ(got[i].path, want[i].path);
        EXPECT_EQ(got[i].vertex, want[i].vertex);
        EXPECT_EQ(got[i].op, want[i].op);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(got[i].value[c], want[i].value[c]) << c;
    }
}

// ---- OBJ tags ------------------------------------------------------------------

TEST(EditsObj, DocsLoopExample) {
    // docs/hierarchical-edits.md section 2, verbatim.
    lt::InputMesh m = parseOk(std::string(kOcta) +
                              "t vertexedit 5/3/3 4 7 1 3 2  0 0.1 0  add P value\n"
                              "t vertexedit 4/3/3 3 0 2 1  0.5 1.25 0  set P value\n");
    expectEdits(m.edits,
                {inputEdit(7, {1, 3}, 2, EditOp::Add, 0, 0.1f, 0), inputEdit(0, {2}, 1, EditOp::Set, 0.5f, 1.25f, 0)});
    EXPECT_TRUE(m.warnings.empty()) << joined(m.warnings);
    EXPECT_TRUE(lt::checkInput(m, "t.obj"));
}

TEST(EditsObj, LevelZeroSubtractNegativeValuesAndTagsBeforeFaces) {
    // Tags may come before the faces they name; values may be negative (they are not
    // sharpness); edits keep file order across tags.
    lt::InputMesh m = parseOk(
        "t vertexedit 3/3/3 2 5 0  -1 -2.5 3e-3  subtract P value\n"
        "t vertexedit 6/3/3 5 4 0 1 2 0  0 0 -0.25  add P value\n" +
        std::string(kOcta));
    expectEdits(m.edits, {inputEdit(5, {}, 0, EditOp::Subtract, -1, -2.5f, 3e-3f),
                          inputEdit(4, {0, 1, 2}, 0, EditOp::Add, 0, 0, -0.25f)});
    EXPECT_TRUE(lt::checkInput(m, "t.obj"));
}

TEST(EditsObj, HbrMultiPathFormWithExtraFloats) {
    // catmark_square_hedit0's first tag: 4 paths (16 ints), 24 floats, one triple;
    // Loop corners only go to 2, so the last path edits corner 2 of child 3 here.
    std::string floats;
    for (int i = 1; i <= 24; ++i) floats += " " + std::to_string(i);
    lt::InputMesh m = parseOk(std::string(kOcta) + "t vertexedit 16/24/3 3 0 1 0 3 0 1 1 3 0 1 2 3 0 3 2" + floats +
                              " add P value\n"
                              // pathlength 4 and 5 paths mixed in one tag (hedit0's other lines)
                              "t vertexedit 11/6/3 4 4 1 1 0  5 6 0 1 3 2  0.5 0 0  0 0.5 0 subtract P value\n");
    // hbr_utils.h: path i reads floats [3i, 3i + 3): 1..12; 13..24 are ignored.
    expectEdits(m.edits, {inputEdit(0, {1}, 0, EditOp::Add, 1, 2, 3), inputEdit(0, {1}, 1, EditOp::Add, 4, 5, 6),
                          inputEdit(0, {1}, 2, EditOp::Add, 7, 8, 9), inputEdit(0, {3}, 2, EditOp::Add, 10, 11, 12),
                          inputEdit(4, {1, 1}, 0, EditOp::Subtract, 0.5f, 0, 0),
                          inputEdit(6, {0, 1, 3}, 2, EditOp::Subtract, 0, 0.5f, 0)});
    ASSERT_EQ(m.warnings.size(), 1u) << joined(m.warnings);
    EXPECT_TRUE(
        contains(m.warnings[0], "t.obj: line 15: 'vertexedit' tag has 24 floats for 4 paths; using the first 12"))
        << m.warnings[0];
}

TEST(EditsObj, PolygonIndicesMapToTriangles) {
    // Polygon 0 is a quad (triangles 0 and 1), polygon 1 the triangle 2.
    const std::string mesh = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 5 3\n";
    lt::InputMesh m = parseOk(mesh + "t vertexedit 4/3/3 3 1 3 0  1 2 3  add P value\n");
    expectEdits(m.edits, {inputEdit(2, {3}, 0, EditOp::Add, 1, 2, 3)});

    lt::InputMesh bad;
    lt::Status st = parse(mesh + "t vertexedit 4/3/3 3 0 3 0  1 2 3  add P value\n", bad);
    EXPECT_EQ(st.code, lt::Status::BadInput);
    EXPECT_EQ(st.message,
              "t.obj:8: 'vertexedit' tag: edit (face 0 path 3 vertex 0) names polygon 0, which "
              "has 4 sides and was triangulated; edits need a triangle");
    EXPECT_TRUE(bad.edits.empty() && bad.faces.empty()) << "a failed parse leaves an empty mesh";
}

TEST(EditsObj, Rejections) {
    const std::string mesh = std::string(kOcta) + "f 1 2 3 4\n";  // polygon 8: a quad
    const int line = 16;                                          // the tag's line
    struct Case {
        const char* tag;
        const char* error;
    };
    const Case cases[] = {
        // counts and path shapes
        {"3/3/3 2 0 0  0 0 0  add P", "tag 'vertexedit' is missing string arguments"},
        {"3/3/3 2 0 0  0 0 0  add P value extra", "has more arguments than its counts declare"},
        {"3/3/0 2 0 0  0 0 0", "'vertexedit' tag has 0 strings; it needs one 'add|set|subtract P value' triple"},
        {"5/3/3 3 0 1 0 9  0 0 0  add P value", "path length 9 at integer 4 does not fit the tag's 5 integers"},
        {"3/3/3 1 0 0  0 0 0  add P value", "path length 1 at integer 0 does not fit"},
        {"3/3/3 -3 0 0  0 0 0  add P value", "path length -3 at integer 0"},
        {"0/0/3 add P value", "has 0 floats for 0 paths; it needs at least one path"},
        {"8/3/3 3 0 1 0 3 0 1 1  0 0 0  add P value", "has 3 floats for 2 paths"},
        {"4/2/3 3 0 1 0  0 0  add P value", "has 2 floats for 1 paths"},
        // path components
        {"4/3/3 3 0 4 0  0 0 0  add P value", "edit (face 0 path 4 vertex 0) has child 4; children are 0..3"},
        {"5/3/3 4 0 1 -1 0  0 0 0  add P value", "edit (face 0 path 1 -1 vertex 0) has child -1"},
        {"4/3/3 3 0 1 3  0 0 0  add P value",
         "edit (face 0 path 1 vertex 3) has vertex 3; triangles have corners 0..2"},
        {"3/3/3 2 0 -1  0 0 0  add P value", "edit (face 0 vertex -1) has vertex -1"},
        {"3/3/3 2 9 0  0 0 0  add P value", "edit (face 9 vertex 0) names face 9, out of range (9 faces)"},
        {"3/3/3 2 -1 0  0 0 0  add P value", "edit (face -1 vertex 0) names face -1, out of range"},
        {"3/3/3 2 8 0  0 0 0  add P value", "names polygon 8, which has 4 sides and was triangulated"},
        // values
        {"3/3/3 2 0 0  0 inf 0  add P value", "'vertexedit' tag has a non-finite value inf"},
        {"3/3/3 2 0 0  0 nan 0  add P value", "bad number 'nan' in tag"},
        // operations
        {"3/3/3 2 0 0  0 0 0  multiply P value", "'multiply P value' is not supported"},
        {"3/1/3 2 0 0  2  set P sharpness", "'set P sharpness' is not supported"},
        {"3/3/3 2 0 0  0 0 0  add N value", "'add N value' is not supported"},
        {"3/6/6 2 0 0  0 0 0 1 1 1  add P value add P value", "has 6 strings; it needs one"},
    };
    for (const Case& c : cases) {
        lt::InputMesh m;
        lt::Status st = parse(mesh + "t vertexedit " + c.tag + "\n", m);
        SCOPED_TRACE(c.tag);
        EXPECT_EQ(st.code, lt::Status::BadInput) << st.message;
        EXPECT_TRUE(contains(st.message, "t.obj:" + std::to_string(line) + ": ")) << st.message;
        EXPECT_TRUE(contains(st.message, c.error)) << st.message;
    }
    // Edge and face edits (catmark_square_hedit2 and hedit4) change the surface.
    for (const char* tag : {"t edgeedit 16/4/3 3 4 1 0 3 4 1 1 3 4 1 2 3 4 1 3 10 10 10 10 set P sharpness",
                            "t faceedit 4/0/1 3 4 1 1 hole"}) {
        lt::InputMesh m;
        lt::Status st = parse(mesh + tag + "\n", m);
        EXPECT_EQ(st.code, lt::Status::BadInput) << tag;
        EXPECT_TRUE(contains(st.message, "t.obj:16: '" + std::string(tag).substr(2, 8) + "' tags")) << st.message;
        EXPECT_TRUE(contains(st.message, "are not supported; ignoring them would change the surface")) << st.message;
    }
    // hedit0's own first line has Catmark's corner 3: not a triangle corner.
    lt::InputMesh m;
    lt::Status st = parse(mesh +
                              "t vertexedit 16/24/3 3 0 1 0 3 0 1 1 3 0 1 2 3 0 1 3 0 0 1 0 0 1 0 0 1 0 0 1 0 0 "
                              "1 0 0 1 0 0 1 0 0 1 add P value\n",
                          m);
    EXPECT_TRUE(contains(st.message, "edit (face 0 path 1 vertex 3) has vertex 3")) << st.message;
}

// ---- checkInput ---------------------------------------------------------------

lt::InputMesh octahedron() { return parseOk(kOcta); }

TEST(EditsCheck, BadEditsAreNamedByIndexAndPath) {
    lt::InputMesh base = octahedron();
    base.edits = {inputEdit(7, {1, 3}, 2, EditOp::Add, 0, 0.1f, 0), inputEdit(3, {}, 1, EditOp::Set, 1, 1, 1)};
    ASSERT_TRUE(lt::checkInput(base, "m.obj"));
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    struct Case {
        Edit e;
        std::vector<uint32_t> holes;
        const char* error;
    };
    const Case cases[] = {
        {inputEdit(8, {1, 3}, 2, EditOp::Add, 0, 0, 0),
         {},
         "m.obj: vertex edit 2 (face 8 path 1 3 vertex 2) names face 8, out of range (mesh has 8 faces)"},
        {inputEdit(7, {1, 4}, 2, EditOp::Add, 0, 0, 0),
         {},
         "m.obj: vertex edit 2 (face 7 path 1 4 vertex 2) has child 4; children are 0..3"},
        {inputEdit(7, {1, 3}, 3, EditOp::Add, 0, 0, 0),
         {},
         "m.obj: vertex edit 2 (face 7 path 1 3 vertex 3) has vertex 3; triangles have corners 0..2"},
        {inputEdit(7, {}, 0, EditOp::Add, 0, nan, 0),
         {},
         "m.obj: vertex edit 2 (face 7 vertex 0) has a non-finite value (nan)"},
        {inputEdit(7, {}, 0, EditOp::Subtract, -inf, 0, 0), {}, "has a non-finite value (-inf)"},
        {inputEdit(7, {}, 0, EditOp(7), 0, 0, 0),
         {},
         "m.obj: vertex edit 2 (face 7 vertex 0) has an unknown operation 7"},
        {inputEdit(5, {0}, 1, EditOp::Add, 0, 0, 0),
         {2, 5},
         "m.obj: vertex edit 2 (face 5 path 0 vertex 1) edits face 5, which is a hole"},
    };
    for (const Case& c : cases) {
        lt::InputMesh m = base;
        m.edits.push_back(c.e);
        m.holes = c.holes;
        lt::Status st = lt::checkInput(m, "m.obj");
        EXPECT_EQ(st.code, lt::Status::BadInput) << c.error;
        EXPECT_TRUE(contains(st.message, c.error)) << st.message;
    }
    // A hole elsewhere is fine.
    base.holes = {2};
    EXPECT_TRUE(lt::checkInput(base, "m.obj"));
}

// ---- JSON side-car ------------------------------------------------------------

TEST(EditsJson, ParsesAndAppendsInFileOrder) {
    lt::InputMesh m;
    m.edits = {inputEdit(1, {}, 0, EditOp::Add, 1, 1, 1)};  // e.g. from an OBJ's tags
    lt::Status st = lt::parseEditsJson(
        R"({"edits": [{"face": 7, "path": [1, 3], "vertex": 2, "op": "add", "value": [0, 0.1, 0]},
                      {"value": [-1.5, 2e-3, 4], "op": "subtract", "vertex": 0, "path": [], "face": 0},
                      {"face": 4294967295, "path": [0, 1, 2, 3, 3], "vertex": 1, "op": "set", "value": [1, 2, 3]}]})",
        "e.json", m);
    ASSERT_TRUE(st) << st.message;
    expectEdits(m.edits, {inputEdit(1, {}, 0, EditOp::Add, 1, 1, 1), inputEdit(7, {1, 3}, 2, EditOp::Add, 0, 0.1f, 0),
                          inputEdit(0, {}, 0, EditOp::Subtract, -1.5f, 2e-3f, 4),
                          inputEdit(4294967295u, {0, 1, 2, 3, 3}, 1, EditOp::Set, 1, 2, 3)});
    lt::InputMesh empty;
    EXPECT_TRUE(lt::parseEditsJson(R"({"edits": []})", "e.json", empty));
    EXPECT_TRUE(empty.edits.empty());
}

TEST(EditsJson, Rejections) {
    const std::string ok = R"("face": 7, "path": [1, 3], "vertex": 2, "op": "add", "value": [0, 0.1, 0])";
    auto one = [&](const std::string& extra) { return R"({"edits": [{)" + ok + "}, {" + extra + "}]}"; };
    auto with = [&](const std::string& key, const std::string& value) {
        std::string e = ok;
        const size_t at = e.find("\"" + key + "\": ") + key.size() + 4;
        const size_t end = key == "path" || key == "value" ? e.find(']', at) + 1 : e.find_first_of(",}", at);
        return one(e.replace(at, (end == std::string::npos ? e.size() : end) - at, value));
    };
    struct Case {
        std::string text, error;
    };
    const std::vector<Case> cases = {
        {"", "e.json: is not valid JSON: parse error at line 1, column 1"},
        {R"({"edits": [})", "e.json: is not valid JSON: parse error"},
        {"[]", "e.json: the top level must be an object with an \"edits\" array"},
        {R"({"edits": [], "version": 1})", "e.json: version: unknown key (the top level has only \"edits\")"},
        {R"({})", "e.json: edits: missing, or not an array"},
        {R"({"edits": {}})", "e.json: edits: missing, or not an array"},
        {R"({"edits": [7]})", "e.json: edits[0]: must be an object with \"face\""},
        {one(ok + R"(, "level": 2)"), "e.json: edits[1].level: unknown key"},
        {one(R"("face": 7, "path": [1, 3], "vertex": 2, "value": [0, 0.1, 0])"), "e.json: edits[1].op: missing"},
        {with("face", "-1"), "e.json: edits[1].face: must be an integer 0..4294967295, not -1"},
        {with("face", "7.0"), "edits[1].face: must be an integer 0..4294967295, not 7.0"},
        {with("face", "4294967296"), "edits[1].face: must be an integer 0..4294967295, not 4294967296"},
        {with("face", "\"7\""), "edits[1].face: must be an integer 0..4294967295, not \"7\""},
        {with("path", "3"), "edits[1].path: must be an array of children 0..3, not 3"},
        {with("path", "[1, 4]"), "edits[1].path[1]: must be an integer 0..3, not 4"},
        {with("path", "[true]"), "edits[1].path[0]: must be an integer 0..3, not true"},
        {with("vertex", "3"), "e.json: edits[1].vertex: must be an integer 0..2, not 3"},
        {with("op", "\"multiply\""), "edits[1].op: must be \"set\", \"add\" or \"subtract\", not \"multiply\""},
        {with("op", "1"), "edits[1].op: must be \"set\", \"add\" or \"subtract\", not 1"},
        {with("value", "[0, 1]"), "edits[1].value: must be an array of 3 numbers (x, y, z), not [0,1]"},
        {with("value", "[0, 1, 2, 3]"), "edits[1].value: must be an array of 3 numbers"},
        {with("value", "[0, null, 2]"), "edits[1].value[1]: must be a finite number (as a float), not null"},
        {with("value", "[0, 1, 1e39]"), "edits[1].value[2]: must be a finite number (as a float)"},
        {with("value", "[0, 1, 1e400]"), "e.json: is not valid JSON: number overflow parsing '1e400'"},
        {with("value", "[[0], 1, 2]"), "e.json: nests values deeper than the format's 4 levels"},
        {std::string(100000, '[') + std::string(100000, ']'), "nests values deeper"},
        {R"({"edits": [], "\u00ff": 1})", "e.json: ??: unknown key"},
        {R"({"edits": []})" + std::string("\xff"), "e.json: is not valid JSON"},
        {R"({"edits": [)" + std::string(size_t(16) << 20, ' ') + "]}",
         "bytes, more than the side-car limit of 16777216"},
    };
    for (const Case& c : cases) {
        lt::InputMesh m;
        m.edits = {inputEdit(1, {}, 0, EditOp::Add, 1, 1, 1)};
        lt::Status st = lt::parseEditsJson(c.text, "e.json", m);
        SCOPED_TRACE(c.text.substr(0, 200));
        EXPECT_EQ(st.code, lt::Status::BadInput) << st.message;
        EXPECT_TRUE(contains(st.message, c.error)) << st.message << "\nexpected: " << c.error;
        EXPECT_EQ(m.edits.size(), 1u) << "a rejected side-car adds no edits";
    }
}

// ---- loopbake --edits ------------------------------------------------------------

class EditsCli : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() /
                ("looptess_test_edits_input_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(root_);
        fs::create_directories(root_ / "out");
        std::ofstream(root_ / "octa.obj") << kOcta << "t vertexedit 3/3/3 2 1 0  0 0.1 0  add P value\n";
    }
    void TearDown() override { fs::remove_all(root_); }

    lt::test::RunResult loopbake(const std::string& sideCar, const std::string& text, const std::string& input = "") {
        std::ofstream(root_ / sideCar) << text;
        return lt::test::runTool(
            LOOPBAKE_EXE,
            {input.empty() ? (root_ / "octa.obj").string() : input, "--edits", (root_ / sideCar).string(), "-o",
             (root_ / "out" / "x.glb").string(), "--max-depth", "2"},
            root_);
    }
    std::string path(const std::string& name) const { return (root_ / name).string(); }

    fs::path root_;
};

TEST_F(EditsCli, HelpAndUsage) {
    lt::test::RunResult help = lt::test::runTool(LOOPBAKE_EXE, {"--help"}, root_);
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_TRUE(contains(help.out, "--edits EDITS.json")) << help.out;
    lt::test::RunResult r = lt::test::runTool(LOOPBAKE_EXE, {path("octa.obj"), "-o", path("x.glb"), "--edits"}, root_);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_TRUE(contains(r.err, "option '--edits' needs a value")) << r.err;
}

TEST_F(EditsCli, LevelZeroSideCarIsAccepted) {
    // Level-0 edits move control points: no refinement to the edit level is needed.
    lt::test::RunResult r = loopbake(
        "e.json", R"({"edits": [{"face": 2, "path": [], "vertex": 1, "op": "subtract", "value": [0, 0.1, 0]}]})");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(root_ / "out" / "x.glb"));
}

TEST_F(EditsCli, BadSideCarsAreInputErrorsNamingTheFile) {
    struct Case {
        std::string text, error;
    };
    const std::vector<Case> cases = {
        {"{", path("bad.json") + ": is not valid JSON"},
        {R"({"edits": [{"face": 2, "path": [], "vertex": 3, "op": "add", "value": [0, 0, 0]}]})",
         path("bad.json") + ": edits[0].vertex: must be an integer 0..2, not 3"},
        // Ranges against the mesh are checkInput's: edit 0 is the OBJ's tag, edit 1 the side-car's edits[0].
        {R"({"edits": [{"face": 8, "path": [1], "vertex": 0, "op": "add", "value": [0, 0, 0]}]})",
         path("octa.obj") + ": vertex edit 1 (face 8 path 1 vertex 0) names face 8, out of range (mesh has 8 faces) (" +
             path("bad.json") + ": edits[0])"},
        // Deeper than --max-depth 2 is bake's error; it names the side-car entry the same way.
        {R"({"edits": [{"face": 3, "path": [0, 1, 2], "vertex": 0, "op": "add", "value": [0, 0, 0]}]})",
         path("octa.obj") + ": vertex edit 1 (face 3 path 0 1 2 vertex 0) "},
    };
    for (const Case& c : cases) {
        lt::test::RunResult r = loopbake("bad.json", c.text);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_TRUE(contains(r.err, "loopbake: error: " + c.error)) << r.err << "\nexpected: " << c.error;
        if (contains(c.error, "vertex edit 1")) {
            EXPECT_TRUE(contains(r.err, "(" + path("bad.json") + ": edits[0])\n")) << r.err;
        }
        EXPECT_TRUE(fs::is_empty(root_ / "out")) << "nothing written";
    }
    lt::test::RunResult r = lt::test::runTool(
        LOOPBAKE_EXE, {path("octa.obj"), "--edits", path("missing.json"), "-o", path("out/x.glb")}, root_);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_TRUE(contains(r.err, "loopbake: error: " + path("missing.json") + ": ")) << r.err;
    // Bad OBJ tags stay the OBJ's errors.
    std::ofstream(root_ / "edge.obj") << kOcta << "t edgeedit 4/1/3 3 0 1 0 10 set P sharpness\n";
    r = loopbake("e.json", R"({"edits": []})", path("edge.obj"));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_TRUE(contains(r.err, path("edge.obj") + ":15: 'edgeedit' tags")) << r.err;
}

TEST_F(EditsCli, GltfInputTakesASideCar) {
    const fs::path duck = fs::path(LOOPTESS_CORPUS_DIR) / "gltf" / "Duck.glb";
    ASSERT_TRUE(fs::exists(duck)) << duck << " is missing (tests/data/corpus)";
    lt::test::RunResult r = loopbake(
        "e.json", R"({"edits": [{"face": 100000000, "path": [], "vertex": 0, "op": "add", "value": [0, 0, 0]}]})",
        duck.string());
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_TRUE(contains(r.err, duck.string() + ": meshes[0] (LOD3spShape): vertex edit 0 (face 100000000 vertex 0) "
                                                "names face 100000000, out of range"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "(" + path("e.json") + ": edits[0])")) << r.err;
}

}  // namespace
