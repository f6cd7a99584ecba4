// test_input.cpp -- parseObj, checkInput, addCreasesByAngle, the corpus, and the
// malformed-input catalogue (tests/data/bad, run through the real loopbake binary).
#include "looptess/tools/baker.h"
#include "looptess/version.h"

#include "tool_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using lt::test::readText;
using lt::test::RunResult;

lt::Status parse(const std::string& text, lt::InputMesh& mesh, bool strict = false) {
    lt::InputOptions options;
    options.strict = strict;
    return lt::parseObj(text, "t.obj", options, mesh);
}

lt::InputMesh parseOk(const std::string& text) {
    lt::InputMesh mesh;
    lt::Status st = parse(text, mesh);
    EXPECT_TRUE(st) << st.message;
    return mesh;
}

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
}

const char* const kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
const char* const kTetVerts = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
const char* const kTetFaces = "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";

// ---- parseObj -------------------------------------------------------------------

TEST(ParseObj, FaceSyntaxes) {
    const std::string verts = std::string(kTetVerts) + "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n";
    const char* const forms[] = {"f 1 2 3\n",    "f 1/1 2/2 3/3\n",   "f 1//1 2//1 3//1\n", "f 1/1/1 2/2/1 3/3/1\n",
                                 "f -4 -3 -2\n", "f 1/-3 2/-2 3/-1\n"};
    for (const char* f : forms) {
        lt::InputMesh m = parseOk(verts + f);
        EXPECT_EQ(m.faces, (std::vector<uint32_t>{0, 1, 2})) << f;
        bool uv = contains(f, "1/1") || contains(f, "/-");
        // v is flipped into glTF's convention (down from the image's top).
        EXPECT_EQ(m.faceUVs, (uv ? std::vector<float>{0, 1, 1, 1, 0, 0} : std::vector<float>{})) << f;
        EXPECT_TRUE(m.warnings.empty()) << f << joined(m.warnings);
    }
}

TEST(ParseObj, NegativeIndicesAreRelativeToTheirLine) {
    lt::InputMesh m = parseOk("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nf -3 -1 -2\n");
    EXPECT_EQ(m.faces, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
    EXPECT_EQ(m.vertexCount(), 4u);
}

TEST(ParseObj, NumbersCommentsWhitespaceAndIgnoredStatements) {
    lt::InputMesh m = parseOk(
        "# header\r\nmtllib a.mtl\r\no thing\ng group\ns 1\nusemtl red\n"
        "v +1.5 -2e-1 3 1\t# w and a trailing comment\nv\t0 0 0\r\nv 1e-40 .5 5.\n"
        "vn 0 0 1\nf 1 2 3 # comment\n");
    EXPECT_TRUE(m.warnings.empty()) << joined(m.warnings);
    EXPECT_EQ(m.positions, (std::vector<float>{1.5f, -0.2f, 3, 0, 0, 0, 1e-40f, 0.5f, 5}));
}

// A UTF-8 byte order mark starts no statement: before, "\xEF\xBB\xBFv" was an unknown
// statement with a warning and every face after it named the vertex one further on.
TEST(ParseObj, AByteOrderMarkIsSkipped) {
    const lt::InputMesh plain = parseOk(std::string(kTetVerts) + kTetFaces);
    const lt::InputMesh marked = parseOk("\xEF\xBB\xBF" + std::string(kTetVerts) + kTetFaces);
    EXPECT_TRUE(marked.warnings.empty()) << joined(marked.warnings);
    EXPECT_EQ(marked.positions, plain.positions);
    EXPECT_EQ(marked.faces, plain.faces);
}

TEST(ParseObj, UnknownStatementsAndTagsWarnOncePerKeyword) {
    lt::InputMesh m = parseOk(std::string(kTetVerts) + kTetFaces +
                              "l 1 2\nl 2 3\ncstype bspline\nt smoothtriangles 1/0/0 1\n"
                              "t smoothtriangles 1/0/0 1\n");
    ASSERT_EQ(m.warnings.size(), 3u) << joined(m.warnings);
    EXPECT_TRUE(contains(m.warnings[0], "t.obj: line 9: ignoring unknown statement 'l'"));
    EXPECT_TRUE(contains(m.warnings[1], "unknown statement 'cstype'"));
    EXPECT_TRUE(contains(m.warnings[2], "unknown tag 'smoothtriangles'"));
}

TEST(ParseObj, PolygonsAreTriangulatedWithOneWarning) {
    lt::InputMesh m = parseOk(std::string(kQuad) + "v 2 0 0\nf 1 2 3 4\nf 1 2 3\nf 2 5 3 4 1\n");
    // The quad's fan from its first corner would repeat the triangle (1 2 3): it splits
    // along 2-4 instead; the pentagon's fans from 2 and 3 (1-based) would put third faces
    // on edges of the quad and the triangle: the fan from 5 has none (looptess/tools/triangulate.h).
    EXPECT_EQ(m.faces, (std::vector<uint32_t>{1, 2, 3, 1, 3, 0, 0, 1, 2, 4, 2, 3, 4, 3, 0, 4, 0, 1}));
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_TRUE(contains(m.warnings[0], "2 polygons with more than 3 sides were triangulated (first at line 6)"))
        << m.warnings[0];
}

TEST(ParseObj, StrictRejectsPolygons) {
    lt::InputMesh m;
    lt::Status st = parse(std::string(kQuad) + "f 1 2 3\nf 1 2 3 4\n", m, true);
    EXPECT_EQ(st.code, lt::Status::BadInput);
    EXPECT_TRUE(contains(st.message, "t.obj:6: face has 4 vertices; strict mode")) << st.message;
    EXPECT_TRUE(parse(std::string(kQuad) + "f 1 2 3\n", m, true));
}

TEST(ParseObj, UVsKeptOnlyWhenEveryFaceHasThem) {
    const std::string head = std::string(kQuad) + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    lt::InputMesh all = parseOk(head + "f 1/1 2/2 3/3 4/4\n");
    EXPECT_EQ(all.faceUVs, (std::vector<float>{0, 1, 1, 1, 1, 0, 0, 1, 1, 0, 0, 0}));
    lt::InputMesh mixed = parseOk(head + "f 1/1 2/2 3/3\nf 1 3 4\n");
    EXPECT_TRUE(mixed.faceUVs.empty());
    ASSERT_EQ(mixed.warnings.size(), 1u);
    EXPECT_TRUE(contains(mixed.warnings[0], "1 of 2 faces have no texture coordinates"));
    lt::InputMesh none = parseOk(head + "f 1 2 3\n");
    EXPECT_TRUE(none.faceUVs.empty());
    EXPECT_TRUE(none.warnings.empty());
}

// Crease ints are vertex pairs, as OpenSubdiv's shape reader takes them.
TEST(ParseObj, CreaseTagsArePairs) {
    lt::InputMesh m = parseOk(std::string(kTetVerts) + kTetFaces +
                              "t crease 2/1/0 0 1 2.5\n"
                              "t crease 4/1/0 1 2 2 3 10\n"
                              "t crease 4/2/0 3 0 0 2 1 0.5\n");
    const std::vector<std::array<float, 3>> expected = {{0, 1, 2.5f}, {1, 2, 10}, {2, 3, 10}, {3, 0, 1}, {0, 2, 0.5f}};
    ASSERT_EQ(m.creases.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(float(m.creases[i].a), expected[i][0]) << i;
        EXPECT_EQ(float(m.creases[i].b), expected[i][1]) << i;
        EXPECT_EQ(m.creases[i].sharpness, expected[i][2]) << i;
    }
    EXPECT_TRUE(lt::checkInput(m, "t.obj"));
}

TEST(ParseObj, CornerBoundaryMethodTags) {
    lt::InputMesh m = parseOk(std::string(kTetVerts) + kTetFaces +
                              "t corner 1/1/0 0 3\nt corner 2/1/0 1 2 10\nt corner 2/2/0 3 0 1 2\n"
                              "t interpolateboundary 1/0/0 1\nt creasemethod 0/0/1 chaikin\n");
    ASSERT_EQ(m.corners.size(), 5u);
    const uint32_t verts[] = {0, 1, 2, 3, 0};
    const float sharp[] = {3, 10, 10, 1, 2};
    for (size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(m.corners[i].vertex, verts[i]);
        EXPECT_EQ(m.corners[i].sharpness, sharp[i]);
    }
    EXPECT_EQ(m.boundary, lt::BoundaryInterpolation::EdgeAndCorner);
    EXPECT_EQ(m.creaseMethod, lt::CreaseMethod::Chaikin);
    lt::InputMesh d = parseOk(std::string(kTetVerts) + kTetFaces);
    EXPECT_EQ(d.boundary, lt::BoundaryInterpolation::EdgeOnly);
    EXPECT_EQ(d.creaseMethod, lt::CreaseMethod::Normal);
    EXPECT_EQ(parseOk(std::string(kTetVerts) + kTetFaces + "t interpolateboundary 1/0/0 0\n").boundary,
              lt::BoundaryInterpolation::None);
}

TEST(ParseObj, HolesNamePolygonsAndCoverTheirTriangles) {
    // Polygon 0 is a triangle, 1 a quad (triangles 1, 2), 2 a triangle (3). Tags may
    // come before the faces they name.
    lt::InputMesh m = parseOk("t hole 2/0/0 1 2\n" + std::string(kQuad) + "v 2 0 0\nf 2 5 3\nf 1 2 3 4\nf 1 3 4\n");
    EXPECT_EQ(m.holes, (std::vector<uint32_t>{1, 2, 3}));
}

// Every parse error: the message names file and line, and says what is wrong.
TEST(ParseObj, ErrorsNameFileLineAndProblem) {
    const std::string tet = std::string(kTetVerts) + kTetFaces;  // 8 lines
    const std::pair<std::string, std::string> cases[] = {
        {"v 1 2 x\n", "t.obj:1: bad number 'x' in vertex"},
        {"v 1 2\n", "t.obj:1: vertex needs at least 3 numbers, has 2"},
        {"v 1 2 nan\n", "t.obj:1: vertex has a non-finite coordinate 'nan'"},
        {"v 1 2 infinity\n", "non-finite coordinate"},
        {"v 1 2 1e39\n", "number '1e39' out of range in vertex"},
        {"v 1 2 ++3\n", "bad number '++3'"},
        {"vt x\n", "bad number 'x' in texture coordinate"},
        {tet + "f 1 2 0\n", "t.obj:9: vertex index 0 (OBJ indices start at 1)"},
        {tet + "f 1 2 5\n", "t.obj:9: vertex index 5 out of range (4 defined so far)"},
        {tet + "f 1 2 -5\n", "vertex index -5 out of range"},
        {tet + "f 1 2 99999999999999999999\n", "bad vertex index '99999999999999999999'"},
        {tet + "f 1 2 3x\n", "bad vertex index '3x'"},
        {tet + "f 1/ 2/ 3/\n", "bad face corner '1/'"},
        {tet + "f 1//x 2 3\n", "bad face corner '1//x'"},
        {tet + "f 1/1 2/1 3/1\n", "texture coordinate index 1 out of range (0 defined so far)"},
        {tet + "f\n", "face has 0 vertices, fewer than 3"},
        {tet + "t crease 2/1/0 0 9 1\n", "t.obj:9: 'crease' tag index 9 out of range (4 vertices)"},
        {tet + "t crease 2/1/0 0 -1 1\n", "'crease' tag index -1 out of range"},
        {tet + "t crease 1/1/0 0 1\n", "malformed tag counts 1/1/0 for 'crease'"},
        {tet + "t crease 3/1/0 0 1 2 1\n", "malformed tag counts 3/1/0"},
        {tet + "t corner 2/3/0 0 1 1 1 1\n", "malformed tag counts 2/3/0 for 'corner'"},
        {tet + "t hole 1/1/0 0 1\n", "malformed tag counts 1/1/0 for 'hole'"},
        {tet + "t creasemethod 1/0/0 1\n", "malformed tag counts 1/0/0 for 'creasemethod'"},
        {tet + "t crease 2/1\n", "bad tag counts '2/1'"},
        {tet + "t crease -2/1/0 0 1 1\n", "bad tag counts '-2/1/0'"},
        {tet + "t crease\n", "bad tag counts ''"},
        {tet + "t\n", "t.obj:9: tag without a name"},
        {tet + "t crease 2/1/0 0 1 x\n", "bad number 'x' in tag"},
        {tet + "t crease 2/1/0 0 x 1\n", "bad integer 'x' in tag"},
        {tet + "t corner 1/1/0 0 -0.5\n", "t.obj:9: negative sharpness -0.5 in 'corner' tag"},
        {tet + "t creasemethod 0/0/1 smooth\n", "creasemethod must be 'chaikin' or 'normal'"},
        {tet + "t interpolateboundary 1/0/0 -1\n", "interpolateboundary must be 0, 1 or 2, not -1"},
        {tet + "t hole 1/0/0 4\n", "'hole' tag index 4 out of range (4 faces)"},
    };
    for (const auto& [text, expected] : cases) {
        lt::InputMesh m;
        lt::Status st = parse(text, m);
        EXPECT_EQ(st.code, lt::Status::BadInput) << text;
        EXPECT_TRUE(contains(st.message, expected)) << text << "\ngot: " << st.message;
        EXPECT_EQ(m.faceCount(), 0u) << "a failed parse leaves an empty mesh";
    }
}

// Mutated inputs must never crash (run under ASan/UBSan to make this meaningful).
TEST(ParseObj, SurvivesMutatedInput) {
    const std::string seed = std::string(kTetVerts) + "vt 0 0\nvt 1 1\n" + kTetFaces +
                             "f 1/1 2/2 3/1 4/2\nt crease 3/1/0 0 1 2 5\nt corner 2/2/0 0 1 2 3\n"
                             "t hole 1/0/0 1\nt interpolateboundary 1/0/0 1\n";
    const char alphabet[] = "0123456789-+./ \nfvtne#\t\r\0\xff";
    std::mt19937 rng(1234);
    for (int iter = 0; iter < 3000; ++iter) {
        std::string text = seed;
        for (int k = 0, n = 1 + int(rng() % 8); k < n; ++k) {
            size_t pos = rng() % (text.size() + 1);
            char c = alphabet[rng() % (sizeof alphabet - 1)];
            switch (rng() % 3) {
            case 0: text.insert(pos, 1, c); break;
            case 1:
                if (pos < text.size()) text.erase(pos, 1);
                break;
            default:
                if (pos < text.size()) text[pos] = c;
                break;
            }
        }
        lt::InputMesh m;
        lt::Status st = parse(text, m, iter % 2 == 1);
        if (!st) {
            EXPECT_TRUE(st.code == lt::Status::BadInput) << st.message;
            continue;
        }
        if (lt::checkInput(m, "t.obj")) lt::addCreasesByAngle(m, 30);
    }
}

// ---- corpus ---------------------------------------------------------------------

std::vector<fs::path> corpusObjs() {
    std::vector<fs::path> files;
    for (const char* dir : {"opensubdiv-loop", "meshes"}) {
        fs::path d = fs::path(LOOPTESS_CORPUS_DIR) / dir;
        if (!fs::is_directory(d)) continue;
        for (const auto& e : fs::directory_iterator(d))
            if (e.path().extension() == ".obj") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// Every shape parses. Read as written (no input cleaning: test_input_cleaning.cpp
// has what cleaning changes), all pass checkInput except one OpenSubdiv shape with
// topology checkInput rejects by design: triangles with a repeated vertex (OSD's
// "degenerate edge" case). Back-to-back pairs (loop_val2_interior) are legal.
TEST(Corpus, EveryObjParsesAndPassesCheckInput) {
    const std::map<std::string, std::string> expectedFailures = {
        {"loop_nonman_edges.obj", "face 51 is degenerate (vertices 45, 45, 48"}};
    std::vector<fs::path> files = corpusObjs();
    ASSERT_FALSE(files.empty()) << "no corpus at " << LOOPTESS_CORPUS_DIR;
    EXPECT_GE(files.size(), 34u);
    lt::InputOptions asWritten;
    asWritten.cleaning = lt::InputCleaning::Keep;
    for (const fs::path& p : files) {
        lt::InputMesh m;
        const std::string name = p.filename().string();
        lt::Status st = lt::parseObj(readText(p), name, asWritten, m);
        ASSERT_TRUE(st) << st.message;
        EXPECT_GT(m.faceCount(), 0u) << p;
        std::vector<std::string> warnings;
        st = lt::checkInput(m, name, warnings);
        auto failure = expectedFailures.find(name);
        if (failure == expectedFailures.end())
            EXPECT_TRUE(st) << st.message;
        else
            EXPECT_TRUE(contains(st.message, failure->second)) << st.message;
        for (const std::string& w : m.warnings) std::cout << "  [parse] " << w << "\n";
        for (const std::string& w : warnings) std::cout << "  [check] " << w << "\n";
    }
}

TEST(Corpus, TagsOfKnownShapes) {
    fs::path dir = fs::path(LOOPTESS_CORPUS_DIR) / "opensubdiv-loop";
    ASSERT_TRUE(fs::is_directory(dir)) << dir << " is missing";
    lt::InputMesh m;
    ASSERT_TRUE(lt::parseObj(readText(dir / "loop_cube_creases0.obj"), "c", {}, m));
    EXPECT_EQ(m.faceCount(), 12u);
    EXPECT_EQ(m.faceUVs.size(), 72u);
    ASSERT_EQ(m.creases.size(), 2u);
    EXPECT_EQ(m.creases[1].a, 3u);
    EXPECT_EQ(m.creases[1].b, 2u);
    EXPECT_EQ(m.creases[1].sharpness, 2.8f);
    EXPECT_EQ(m.boundary, lt::BoundaryInterpolation::EdgeOnly);
    ASSERT_TRUE(lt::parseObj(readText(dir / "loop_chaikin1.obj"), "c", {}, m));
    EXPECT_EQ(m.creaseMethod, lt::CreaseMethod::Chaikin);
}

TEST(Corpus, FandiskCreasesByAngle) {
    fs::path path = fs::path(LOOPTESS_CORPUS_DIR) / "meshes" / "fandisk.obj";
    ASSERT_TRUE(fs::exists(path)) << path << " is missing";
    lt::InputMesh m;
    ASSERT_TRUE(lt::parseObj(readText(path), "fandisk.obj", {}, m));
    lt::addCreasesByAngle(m, 40);
    EXPECT_GT(m.creases.size(), 100u);
    EXPECT_LT(m.creases.size(), m.faces.size() / 10);  // feature lines, not the whole mesh
    EXPECT_TRUE(lt::checkInput(m, "fandisk.obj"));
}

// ---- loopbake CLI ---------------------------------------------------------------

RunResult loopbake(const std::vector<std::string>& args, const fs::path& scratch) {
    return lt::test::runTool(LOOPBAKE_EXE, args, scratch);
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() / ("looptess_test_input_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(root_);
        fs::create_directories(root_);
    }
    void TearDown() override { fs::remove_all(root_); }

    // A fresh scratch dir with an empty `out/` subdirectory.
    fs::path caseDir(const std::string& name) {
        fs::path d = root_ / name;
        fs::create_directories(d / "out");
        return d;
    }
    static std::vector<std::string> dirEntries(const fs::path& d) {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(d)) names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path root_;
};

struct CatalogueRow {
    std::string file, args, expected;
    int exitCode = -1;
};

std::string trimCell(const std::string& s) {
    size_t b = s.find_first_not_of(" `"), e = s.find_last_not_of(" `");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<CatalogueRow> readCatalogue(const fs::path& readme) {
    std::vector<CatalogueRow> rows;
    std::istringstream in(readText(readme));
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("| `", 0) != 0) continue;
        std::vector<std::string> cells;
        std::istringstream cs(line.substr(1));
        for (std::string cell; std::getline(cs, cell, '|');) cells.push_back(trimCell(cell));
        if (cells.size() < 4) continue;
        rows.push_back({cells[0], cells[1], cells[3], std::atoi(cells[2].c_str())});
    }
    return rows;
}

std::vector<std::string> splitArgs(const std::string& s) {
    std::vector<std::string> args;
    std::istringstream in(s);
    for (std::string a; in >> a;) args.push_back(a);
    return args;
}

TEST_F(Cli, BadInputCatalogue) {
    const fs::path dir = fs::path(LOOPTESS_TEST_DATA) / "bad";
    std::vector<CatalogueRow> rows = readCatalogue(dir / "README.md");
    ASSERT_GE(rows.size(), 20u);
    std::set<std::string> listed;
    for (const CatalogueRow& r : rows) listed.insert(r.file);
    for (const std::string& name : dirEntries(dir)) {
        if (name == "README.md") continue;
        EXPECT_TRUE(listed.count(name)) << name << " is not in README.md";
    }

    for (size_t i = 0; i < rows.size(); ++i) {
        const CatalogueRow& row = rows[i];
        fs::path scratch = caseDir("case" + std::to_string(i));
        std::vector<std::string> args = {(dir / row.file).string()};
        for (const std::string& a : splitArgs(row.args)) args.push_back(a);
        args.insert(args.end(), {"-o", (scratch / "out" / "out.glb").string()});
        RunResult r = loopbake(args, scratch);
        SCOPED_TRACE(row.file + " " + row.args + "\nstderr: " + r.err);
        EXPECT_EQ(r.exitCode, row.exitCode);
        EXPECT_TRUE(contains(r.err, "loopbake: error: ")) << "errors are prefixed";
        EXPECT_TRUE(contains(r.err, row.expected)) << "expected: " << row.expected;
        EXPECT_TRUE(dirEntries(scratch / "out").empty()) << "output or temporary file left behind";
    }
}

TEST_F(Cli, HelpVersionAndUsage) {
    fs::path s = caseDir("help");
    RunResult help = loopbake({"--help"}, s);
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_TRUE(contains(help.out, "usage: loopbake IN -o OUT.glb"));
    EXPECT_TRUE(contains(help.out, "4 write failed"));
    RunResult version = loopbake({"--version"}, s);
    EXPECT_EQ(version.exitCode, 0);
    EXPECT_EQ(version.out, std::string("loopbake ") + LOOPTESS_VERSION_STRING + "\n");
    const std::vector<std::vector<std::string>> bad = {
        {}, {"a.obj"}, {"a.obj", "-o", "b.gltf"}, {"a.obj", "-o"}, {"a.obj", "--json"}};
    for (const auto& args : bad) {
        RunResult r = loopbake(args, s);
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_TRUE(contains(r.err, "loopbake: error: ")) << r.err;
    }
}

TEST_F(Cli, WarningsArePrinted) {
    fs::path s = caseDir("warn");
    fs::path in = s / "quad.obj";
    std::ofstream(in) << kQuad << "f 1 2 3 4\nfoo bar\n";
    RunResult r = loopbake({in.string(), "-o", (s / "out" / "x.glb").string(), "--max-depth", "2"}, s);
    EXPECT_TRUE(
        contains(r.err, "loopbake: warning: " + in.string() + ": 1 polygons with more than 3 sides were triangulated"))
        << r.err;
    EXPECT_TRUE(contains(r.err, "ignoring unknown statement 'foo'")) << r.err;
}

TEST_F(Cli, BakesAtomicallyWithStableReport) {
    const fs::path cubeObj = fs::path(LOOPTESS_CORPUS_DIR) / "opensubdiv-loop" / "loop_cube_creases0.obj";
    ASSERT_TRUE(fs::exists(cubeObj)) << cubeObj << " is missing";
    fs::path s = caseDir("bake");
    std::string out = (s / "out" / "cube.glb").string();
    std::string json1 = (s / "r1.json").string(), json2 = (s / "r2.json").string();
    RunResult r1 = loopbake({cubeObj.string(), "-o", out, "--max-depth", "3", "--json", json1}, s);
    ASSERT_EQ(r1.exitCode, 0) << r1.err;
    RunResult r2 = loopbake({cubeObj.string(), "-o", out, "--max-depth=3", "--json", json2}, s);
    ASSERT_EQ(r2.exitCode, 0) << r2.err;
    EXPECT_EQ(dirEntries(s / "out"), std::vector<std::string>{"cube.glb"});
    std::string report = readText(json1);
    EXPECT_EQ(report, readText(json2)) << "report must be byte-stable";
    EXPECT_TRUE(contains(report, "\"maxDepth\": 3"));
    EXPECT_FALSE(contains(report, "timing"));

    std::string glb = readText(out);
    lt::Asset asset;
    lt::Status st = lt::readAssetGlb(reinterpret_cast<const uint8_t*>(glb.data()), glb.size(), out, asset);
    EXPECT_TRUE(st) << st.message;
    EXPECT_EQ(asset.maxDepth(), 3u);

    RunResult verbose = loopbake({cubeObj.string(), "-o", out, "-v", "--crease-angle", "30"}, s);
    EXPECT_EQ(verbose.exitCode, 0) << verbose.err;
    EXPECT_TRUE(contains(verbose.err, "level")) << verbose.err;
    EXPECT_TRUE(contains(verbose.err, "table bytes (raw -> in the file, --compress fast): control mesh"))
        << verbose.err;

    // Write failure: the output directory does not exist; nothing may be left.
    RunResult fail = loopbake({cubeObj.string(), "-o", (s / "missing" / "x.glb").string()}, s);
    EXPECT_EQ(fail.exitCode, 4) << fail.err;
    EXPECT_TRUE(contains(fail.err, "x.glb: cannot create")) << fail.err;
}

}  // namespace
