// tests/baker/test_gltf_input.cpp -- lt::parseGltf: the Khronos Duck (.glb and .gltf), a
// Draco-compressed Duck made here with the draco encoder, node transforms and winding,
// path traversal, and malformed files.
//
// Small files are built in memory from a tetrahedron (tetra() below) and written to a
// temporary directory when a test needs sibling files.
#include "looptess/tools/baker.h"

#include "gltf_fixture.h"

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <random>

namespace {

namespace fs = std::filesystem;
using namespace gltftest;

const std::string kGltfDir = std::string(LOOPTESS_CORPUS_DIR) + "/gltf";

Bytes readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

void writeFile(const fs::path& path, const Bytes& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

Bytes bytesOf(const std::string& s) { return Bytes(s.begin(), s.end()); }

lt::Status parse(const Bytes& bytes, lt::InputMesh& mesh, const std::string& baseDir = "",
                 const std::string& name = "test.gltf") {
    return lt::parseGltf(bytes.data(), bytes.size(), name, baseDir, mesh);
}

lt::Status parseFile(const fs::path& path, lt::InputMesh& mesh) {
    return parse(readFile(path), mesh, path.parent_path().string(), path.filename().string());
}

// A fresh directory under the test temp dir, removed with the object.
struct TempDir {
    fs::path path;
    TempDir() {
        std::string tmpl = (fs::path(testing::TempDir()) / "gltf_input_XXXXXX").string();
        path = mkdtemp(tmpl.data());
    }
    ~TempDir() { fs::remove_all(path); }
};

// Expects `bytes` to be rejected with a message containing `text`.
void expectError(const Bytes& bytes, const std::string& text, const std::string& baseDir = "") {
    lt::InputMesh mesh;
    const lt::Status st = parse(bytes, mesh, baseDir);
    EXPECT_FALSE(st) << "accepted; expected an error containing: " << text;
    EXPECT_NE(st.message.find(text), std::string::npos) << st.message;
    EXPECT_EQ(st.message.rfind("test.gltf: ", 0), 0u) << st.message;
}

struct EdgeStats {
    size_t edges = 0, boundary = 0, nonManifold = 0, misoriented = 0;
};

// Undirected edges by the number of faces using them; directed edges used twice.
EdgeStats edgeStats(const lt::InputMesh& m) {
    std::map<std::pair<uint32_t, uint32_t>, int> undirected, directed;
    for (size_t f = 0; f < m.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = m.faces[3 * f + k], b = m.faces[3 * f + (k + 1) % 3];
            ++undirected[{std::min(a, b), std::max(a, b)}];
            ++directed[{a, b}];
        }
    EdgeStats s;
    s.edges = undirected.size();
    for (const auto& [e, n] : undirected) {
        s.boundary += n == 1;
        s.nonManifold += n > 2;
    }
    for (const auto& [e, n] : directed) s.misoriented += n > 1;
    return s;
}

// Six times the signed volume: positive when the faces point outward.
double volume6(const lt::InputMesh& m) {
    double v = 0;
    for (size_t f = 0; f < m.faceCount(); ++f) {
        const float* p[3];
        for (int k = 0; k < 3; ++k) p[k] = &m.positions[3 * m.faces[3 * f + k]];
        v += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
             p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
    }
    return v;
}

// Faces as sorted lists of corner (position, uv) values, each rotated to start at its
// smallest corner: equal for two meshes that differ only in vertex and face order.
std::vector<std::array<std::array<float, 5>, 3>> faceSet(const lt::InputMesh& m) {
    std::vector<std::array<std::array<float, 5>, 3>> out;
    for (size_t f = 0; f < m.faceCount(); ++f) {
        std::array<std::array<float, 5>, 3> face;
        for (int k = 0; k < 3; ++k) {
            const float* p = &m.positions[3 * m.faces[3 * f + k]];
            const float* uv = m.faceUVs.empty() ? nullptr : &m.faceUVs[6 * f + 2 * k];
            face[k] = {p[0], p[1], p[2], uv ? uv[0] : 0, uv ? uv[1] : 0};
        }
        std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
        out.push_back(face);
    }
    std::sort(out.begin(), out.end());
    return out;
}

const lt::InputMesh& duck() {
    static lt::InputMesh mesh;
    static bool loaded = false;
    if (!loaded) {
        const lt::Status st = parseFile(kGltfDir + "/Duck.glb", mesh);
        EXPECT_TRUE(st) << st.message;
        loaded = true;
    }
    return mesh;
}

TEST(GltfInput, DuckGlbAndGltfGiveTheSameMesh) {
    const lt::InputMesh& glb = duck();
    lt::InputMesh gltf;
    const lt::Status st = parseFile(kGltfDir + "/Duck.gltf", gltf);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(glb.positions, gltf.positions);
    EXPECT_EQ(glb.faces, gltf.faces);
    EXPECT_EQ(glb.faceUVs, gltf.faceUVs);
    EXPECT_TRUE(glb.warnings.empty()) << glb.warnings.front();
    EXPECT_TRUE(gltf.warnings.empty()) << gltf.warnings.front();
}

TEST(GltfInput, DuckIsWeldedIntoAClosedManifold) {
    const lt::InputMesh& m = duck();
    EXPECT_EQ(m.faceCount(), 4212u);
    EXPECT_LT(m.vertexCount(), 2399u);
    EXPECT_EQ(m.faceUVs.size(), 6 * size_t(m.faceCount()));
    const EdgeStats s = edgeStats(m);
    std::cout << "Duck: 2399 glTF vertices -> " << m.vertexCount() << " welded, " << m.faceCount() << " faces, "
              << s.edges << " edges, " << s.boundary << " boundary, " << s.nonManifold << " non-manifold, "
              << s.misoriented << " misoriented, Euler " << long(m.vertexCount()) - long(s.edges) + long(m.faceCount())
              << "\n";
    EXPECT_EQ(s.boundary, 0u);
    EXPECT_EQ(s.nonManifold, 0u);
    EXPECT_EQ(s.misoriented, 0u);
    EXPECT_GT(volume6(m), 0.0);  // outward faces
}

TEST(GltfInput, DuckNodeScaleIsApplied) {
    // POSITION min/max of the file, times the root node's 0.01 scale.
    const double lo[3] = {-69.2985, 9.92937, -61.3282}, hi[3] = {96.1799, 163.97, 53.9252};
    const lt::InputMesh& m = duck();
    for (int a = 0; a < 3; ++a) {
        float mn = m.positions[a], mx = m.positions[a];
        for (size_t v = 0; v < m.vertexCount(); ++v) {
            mn = std::min(mn, m.positions[3 * v + a]);
            mx = std::max(mx, m.positions[3 * v + a]);
        }
        EXPECT_NEAR(mn, lo[a] * 0.01, 1e-5);
        EXPECT_NEAR(mx, hi[a] * 0.01, 1e-5);
    }
}

// The welded Duck as a KHR_draco_mesh_compression GLB (per-corner UVs).
Bytes dracoDuck(int method) {
    const lt::InputMesh& m = duck();
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(int(m.faceCount()));
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        const uint32_t* v = &m.faces[3 * f];
        builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &m.positions[3 * v[0]], &m.positions[3 * v[1]],
                                          &m.positions[3 * v[2]]);
        builder.SetAttributeValuesForFace(uv, draco::FaceIndex(f), &m.faceUVs[6 * f], &m.faceUVs[6 * f + 2],
                                          &m.faceUVs[6 * f + 4]);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    EXPECT_TRUE(mesh);
    if (!mesh) return {};
    draco::Encoder encoder;
    encoder.SetEncodingMethod(method);  // no quantization: positions stay exact
    draco::EncoderBuffer buffer;
    const draco::Status st = encoder.EncodeMeshToBuffer(*mesh, &buffer);
    EXPECT_TRUE(st.ok()) << st.error_msg_string();
    const Bytes bin(buffer.data(), buffer.data() + buffer.size());
    Json ext = {{"bufferView", 0},
                {"attributes",
                 {{"POSITION", mesh->attribute(pos)->unique_id()}, {"TEXCOORD_0", mesh->attribute(uv)->unique_id()}}}};
    Json j = {{"asset", {{"version", "2.0"}}},
              {"extensionsUsed", {"KHR_draco_mesh_compression"}},
              {"extensionsRequired", {"KHR_draco_mesh_compression"}},
              {"scene", 0},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}},
              {"meshes",
               {{{"primitives",
                  {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
                    {"indices", 2},
                    {"extensions", {{"KHR_draco_mesh_compression", ext}}}}}}}}},
              {"accessors",
               {{{"componentType", 5126}, {"count", mesh->num_points()}, {"type", "VEC3"}},
                {{"componentType", 5126}, {"count", mesh->num_points()}, {"type", "VEC2"}},
                {{"componentType", 5125}, {"count", 3 * m.faceCount()}, {"type", "SCALAR"}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteLength", bin.size()}}}},
              {"buffers", {{{"byteLength", bin.size()}}}}};
    return makeGlb(j, bin);
}

TEST(GltfInput, DracoDuckGivesTheSameMeshUpToOrder) {
    for (int method : {draco::MESH_EDGEBREAKER_ENCODING, draco::MESH_SEQUENTIAL_ENCODING}) {
        const Bytes glb = dracoDuck(method);
        lt::InputMesh m;
        const lt::Status st = parse(glb, m);
        ASSERT_TRUE(st) << "method " << method << ": " << st.message;
        std::cout << "Draco Duck (method " << method << "): " << glb.size() << " bytes, " << m.vertexCount()
                  << " vertices, " << m.faceCount() << " faces\n";
        EXPECT_EQ(m.vertexCount(), duck().vertexCount());
        EXPECT_EQ(faceSet(m), faceSet(duck()));
        const EdgeStats s = edgeStats(m);
        EXPECT_EQ(s.boundary + s.nonManifold + s.misoriented, 0u);
    }
}

TEST(GltfInput, DracoCountsAreCheckedBeforeDecoding) {
    // Sequential mesh, bitstream 2.2, declaring 2^28 - 1 faces in a few bytes.
    const Bytes draco = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0, 0, 0, 0xff, 0xff, 0xff, 0x7f, 3, 1};
    Bytes bin;
    Json j = tetra(bin);
    j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", 3},
                                                                                   {"attributes", {{"POSITION", 0}}}};
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", draco.size()}});
    bin.insert(bin.end(), draco.begin(), draco.end());
    j["buffers"][0]["byteLength"] = bin.size();
    expectError(makeGlb(j, bin), "more than the limit");
}

TEST(GltfInput, TetrahedronAndMirroredTetrahedronFaceOutward) {
    for (double sx : {1.0, -1.0}) {
        lt::InputMesh m;
        const lt::Status st =
            parse(tetraGlb([&](Json& j, Bytes&) {
                      j["nodes"] = Json::parse(R"([{"children": [1], "translation": [5, 0, 0]}, {"mesh": 0}])");
                      j["nodes"][1]["scale"] = {sx, 2.0, 1.0};
                  }),
                  m);
        ASSERT_TRUE(st) << st.message;
        EXPECT_EQ(m.vertexCount(), 4u);
        EXPECT_GT(volume6(m), 0.0) << "scale x " << sx;
        float minX = m.positions[0], maxX = m.positions[0];
        for (size_t v = 0; v < 4; ++v) {
            minX = std::min(minX, m.positions[3 * v]);
            maxX = std::max(maxX, m.positions[3 * v]);
        }
        EXPECT_EQ(minX, float(5 + std::min(0.0, sx)));
        EXPECT_EQ(maxX, float(5 + std::max(0.0, sx)));
    }
}

// A scene must list root nodes only; exporters sometimes list a child too (the
// Kenney cake of tests/data/real). Its tree is drawn once, with its parents'
// transforms, and a warning names it. A cycle of children is an error.
TEST(GltfInput, ASceneListingAChildNodeDrawsItOnce) {
    lt::InputMesh m;
    const lt::Status st = parse(tetraGlb([](Json& j, Bytes&) {
                                    j["nodes"] =
                                        Json::parse(R"([{"children": [1], "translation": [5, 0, 0]}, {"mesh": 0}])");
                                    j["scenes"] = Json::parse(R"([{"nodes": [1, 0]}])");
                                    j["scene"] = 0;
                                }),
                                m);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(m.faceCount(), 4u) << "drawn once";
    for (size_t v = 0; v < m.vertexCount(); ++v) EXPECT_GE(m.positions[3 * v], 5.0f) << "with its parent's translation";
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_EQ(m.warnings[0],
              "test.gltf: scenes[0].nodes: nodes[1] is not a root (its parent is nodes[0]); drawn once, "
              "in the tree of nodes[0]");
    expectError(tetraGlb([](Json& j, Bytes&) {
                    j["nodes"] = Json::parse(R"([{"children": [1]}, {"children": [0], "mesh": 0}])");
                    j["scenes"] = Json::parse(R"([{"nodes": [0]}])");
                    j["scene"] = 0;
                }),
                "nodes[0]: is its own ancestor (a cycle of children)");
}

// Triangles with two corners at one position -- a repeated index, or two vertices
// the weld joins (RobotExpressive's feet have three) -- are lines or points that
// glTF viewers draw as nothing: dropped with one warning naming the first, without
// leaving their vertices behind.
TEST(GltfInput, TrianglesWithTwoCornersAtOnePositionAreDropped) {
    lt::InputMesh m;
    const lt::Status st =
        parse(tetraGlb([](Json& j, Bytes& bin) {
                  bin.clear();
                  append<float>(bin, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1});  // vertex 4 sits on vertex 3
                  append<uint16_t>(bin, {0, 2, 1, 0, 1, 3, 2, 2, 1, 0, 3, 2, 1, 2, 3, 1, 3, 4});
                  j["accessors"] = Json::parse(R"([
          {"bufferView": 0, "componentType": 5126, "count": 5, "type": "VEC3"},
          {"bufferView": 1, "componentType": 5123, "count": 18, "type": "SCALAR"}])");
                  j["bufferViews"] = Json::parse(R"([{"buffer": 0, "byteLength": 60},
                                           {"buffer": 0, "byteOffset": 60, "byteLength": 36}])");
                  j["buffers"][0]["byteLength"] = bin.size();
                  j["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
              }),
              m);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(m.faceCount(), 4u);
    EXPECT_EQ(m.vertexCount(), 4u);
    EXPECT_GT(volume6(m), 0.0);
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_EQ(m.warnings[0],
              "test.gltf: nodes[0]: meshes[0].primitives[0] triangle 2 and 1 more: two corners at "
              "one position (a line or a point, drawn as nothing); dropped");
    EXPECT_TRUE(lt::checkInput(m, "test.gltf"));
}

TEST(GltfInput, ExternalBufferAndMissingUVs) {
    TempDir dir;
    Bytes bin;
    Json j = tetra(bin);
    j["buffers"][0]["uri"] = "tetra%20data.bin";
    writeFile(dir.path / "tetra data.bin", bin);
    lt::InputMesh m;
    lt::Status st = parse(bytesOf(j.dump()), m, dir.path.string());
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(m.faceUVs.size(), 24u);

    // A second primitive without TEXCOORD_0 drops every UV, with a warning.
    Json second = j["meshes"][0]["primitives"][0];
    second.erase("attributes");
    second["attributes"] = {{"POSITION", 0}};
    j["meshes"][0]["primitives"].push_back(second);
    j["nodes"] = Json::parse(R"([{"mesh": 0, "translation": [3, 0, 0]}])");
    st = parse(bytesOf(j.dump()), m, dir.path.string());
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(m.vertexCount(), 4u);  // the same positions twice: welded
    EXPECT_EQ(m.faceCount(), 4u);    // then the same triangles twice: the copies dropped
    EXPECT_EQ(m.cleaning.droppedDuplicate, 4u);
    EXPECT_TRUE(m.faceUVs.empty());
    ASSERT_EQ(m.warnings.size(), 2u);
    EXPECT_NE(m.warnings[0].find("UVs dropped"), std::string::npos) << m.warnings[0];
    EXPECT_NE(m.warnings[1].find("4 duplicate triangles dropped"), std::string::npos) << m.warnings[1];
}

TEST(GltfInput, BufferPathsOutsideTheBaseDirectoryAreRejected) {
    TempDir dir;
    fs::create_directory(dir.path / "base");
    Bytes bin;
    Json j = tetra(bin);
    writeFile(dir.path / "secret.bin", bin);  // exists, with the right size
    fs::create_symlink(dir.path / "secret.bin", dir.path / "base" / "link.bin");
    const std::string base = (dir.path / "base").string();
    const std::pair<const char*, const char*> cases[] = {
        {"../secret.bin", "refers outside the base directory"},
        {"%2e%2e/secret.bin", "refers outside the base directory"},
        {"..%5csecret.bin", "refers outside the base directory"},
        {"/etc/passwd", "is an absolute path"},
        {"file:///etc/passwd", "has a scheme"},
        {"sub/secret.bin", "not a plain file name"},
        {"link.bin", "symbolic link"},
        {"missing.bin", "cannot be opened"},
        {"data:text/plain;base64,AAAA", "unsupported data URI"},
        {"data:application/octet-stream;base64,AAAA", "data URI holds 3 bytes, byteLength is 104"},
        {"data:application/octet-stream;base64,AA\"AA==", "character 39 of the data URI is not base64 ('\"')"},
        {"data:application/octet-stream;base64,AAAA=AAA", "character 41 of the data URI is not base64 ('=')"},
        {"bad%zz.bin", "malformed %-escape"},
    };
    for (const auto& [uri, text] : cases) {
        j["buffers"][0]["uri"] = uri;
        SCOPED_TRACE(uri);
        expectError(bytesOf(j.dump()), std::string("buffers[0].uri \"") + uri + "\"", base);
        expectError(bytesOf(j.dump()), text, base);
    }
    j["buffers"][0]["uri"] = "secret.bin";
    expectError(bytesOf(j.dump()), "no base directory");
}

TEST(GltfInput, MalformedAccessorsAndIndices) {
    expectError(tetraGlb([](Json& j, Bytes&) { j["accessors"][0]["count"] = 5; }),
                "meshes[0].primitives[0].attributes.POSITION: accessor 0 count 5 overruns bufferView 0");
    expectError(tetraGlb([](Json& j, Bytes&) { j["accessors"][0]["byteOffset"] = 4; }), "overruns bufferView 0");
    expectError(tetraGlb([](Json& j, Bytes&) { j["bufferViews"][2]["byteLength"] = 40; }),
                "bufferView 2 (byteOffset 72, byteLength 40) overruns buffer 0 (104 bytes)");
    expectError(tetraGlb([](Json& j, Bytes& bin) { bin[48 + 6] = 4; }),
                "meshes[0].primitives[0].indices: index 4 (entry 3) >= vertex count 4");
    expectError(tetraGlb([](Json& j, Bytes&) { j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7; }),
                "attributes.POSITION: accessor 7 does not exist (3 accessors)");
    expectError(tetraGlb([](Json& j, Bytes&) { j["accessors"][0]["componentType"] = 5122; }),
                "componentType 5122 is not allowed for POSITION");
    expectError(tetraGlb([](Json& j, Bytes&) { j["accessors"][1]["type"] = "VEC2"; }), "type VEC2 is not SCALAR");
    expectError(tetraGlb([](Json& j, Bytes&) { j["accessors"][2]["count"] = 3; }),
                "TEXCOORD_0: count 3 differs from POSITION count 4");
    expectError(tetraGlb([](Json& j, Bytes&) { j["accessors"][1]["count"] = 10; }),
                "indices: 10 corners is not a multiple of 3");
    expectError(tetraGlb([](Json& j, Bytes&) { j["accessors"][0]["bufferView"] = 4294967296; }),
                "outside the 32-bit range");
    expectError(tetraGlb([](Json& j, Bytes&) { j["bufferViews"][0]["byteOffset"] = -4; }), "is negative");
    expectError(tetraGlb([](Json& j, Bytes&) { j["accessors"][0]["byteOffset"] = 1; }),
                "attributes.POSITION: accessor 0 byteOffset 1 (1 in its buffer) is not a multiple of the component "
                "size 4");
    expectError(tetraGlb([](Json& j, Bytes&) {
                    j["bufferViews"][2]["byteOffset"] = 73;  // was 72
                    j["bufferViews"][2]["byteLength"] = 31;
                }),
                "TEXCOORD_0: accessor 2 byteOffset 0 (73 in its buffer) is not a multiple of the component size 4");
    expectError(tetraGlb([](Json& j, Bytes&) { j["extensionsRequired"] = {"EXT_meshopt_compression"}; }),
                "requires extension EXT_meshopt_compression");
    expectError(
        tetraGlb([](Json& j, Bytes&) { j["nodes"] = Json::parse(R"([{"children": [1]}, {"children": [1]}])"); }),
        "nodes[1].children: nodes[1] already has parent nodes[0]");
    expectError(tetraGlb([](Json& j, Bytes&) { j["nodes"][0]["matrix"] = {1, 2, 3}; }), "matrix is not 16");
    expectError(tetraGlb([](Json& j, Bytes&) { j["meshes"][0]["primitives"][0]["mode"] = 1; }),
                "no TRIANGLES primitive");
}

TEST(GltfInput, NonTrianglePrimitivesAreSkippedWithAWarning) {
    lt::InputMesh m;
    const lt::Status st = parse(tetraGlb([](Json& j, Bytes&) {
                                    Json lines = j["meshes"][0]["primitives"][0];
                                    lines["mode"] = 1;
                                    j["meshes"][0]["primitives"].push_back(lines);
                                }),
                                m);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(m.faceCount(), 4u);
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_EQ(m.warnings[0], "test.gltf: meshes[0].primitives[1]: mode 1 is not TRIANGLES (4); skipped");
}

TEST(GltfInput, SparseAccessorsAreApplied) {
    lt::InputMesh m;
    const lt::Status st =
        parse(tetraGlb([](Json& j, Bytes& bin) {
                  // Vertex 3 moves from (0, 0, 1) to (0, 0, 2).
                  const size_t at = bin.size();
                  append<uint8_t>(bin, {3, 0, 0, 0});
                  append<float>(bin, {0, 0, 2});
                  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 16}});
                  j["accessors"][0]["sparse"] = {{"count", 1},
                                                 {"indices", {{"bufferView", 3}, {"componentType", 5121}}},
                                                 {"values", {{"bufferView", 3}, {"byteOffset", 4}}}};
                  j["buffers"][0]["byteLength"] = bin.size();
              }),
              m);
    ASSERT_TRUE(st) << st.message;
    ASSERT_EQ(m.vertexCount(), 4u);
    float maxZ = 0;
    for (size_t v = 0; v < 4; ++v) maxZ = std::max(maxZ, m.positions[3 * v + 2]);
    EXPECT_EQ(maxZ, 2.0f);
}

TEST(GltfInput, QuantizedPositionsNeedKhrMeshQuantization) {
    auto quantized = [](bool declared) {
        return tetraGlb([declared](Json& j, Bytes& bin) {
            // The same tetrahedron as normalized shorts (32767 -> 1.0), 8 bytes per vertex.
            const size_t at = bin.size();
            append<int16_t>(bin, {0, 0, 0, 0, 32767, 0, 0, 0, 0, 32767, 0, 0, 0, 0, 32767, 0});
            j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 32}, {"byteStride", 8}});
            j["accessors"][0] = {
                {"bufferView", 3}, {"componentType", 5122}, {"normalized", true}, {"count", 4}, {"type", "VEC3"}};
            j["buffers"][0]["byteLength"] = bin.size();
            if (declared) j["extensionsUsed"] = {"KHR_mesh_quantization"};
        });
    };
    lt::InputMesh plain, m;
    ASSERT_TRUE(parse(tetraGlb(), plain));
    const lt::Status st = parse(quantized(true), m);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(m.positions, plain.positions);
    expectError(quantized(false), "normalized is not allowed for POSITION (without KHR_mesh_quantization)");
}

TEST(GltfInput, MalformedContainersAndJson) {
    Bytes glb = tetraGlb();
    Bytes overrun = glb;
    overrun[glb.size() - 104 - 8] += 8;  // BIN chunk length 8 bytes too long
    expectError(overrun, "GLB chunk 1: length 112 overruns the file");
    expectError(Bytes(glb.begin(), glb.begin() + 10), "GLB header truncated");
    expectError(tetraGlb([](Json& j, Bytes&) { j["buffers"][0]["byteLength"] = 200; }),
                "buffers[0].byteLength 200 exceeds the GLB BIN chunk (104 bytes)");
    expectError(bytesOf("{\"asset\": "), "invalid JSON");
    expectError(bytesOf("{\"extras\": " + std::string(100, '[') + std::string(100, ']') + "}"),
                "nested deeper than 64");
    expectError(bytesOf("[1]"), "not an object");
    expectError(Bytes(), "empty file");
    expectError(tetraGlb([](Json& j, Bytes&) { j["asset"]["version"] = "1.0"; }),
                "glTF version \"1.0\" is not supported");
}

// A parser's message quotes the input it choked on: no more than an excerpt of it.
TEST(GltfInput, ErrorsQuoteOnlyAnExcerptOfTheInput) {
    const std::string base64(10000, 'A');
    const std::string unterminated = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 7500, )"
                                     R"("uri": "data:application/octet-stream;base64,)" +
                                     base64 + "}]}";
    lt::InputMesh mesh;
    lt::Status st = parse(bytesOf(unterminated), mesh);
    EXPECT_FALSE(st);
    EXPECT_EQ(st.message.rfind("test.gltf: invalid JSON: ", 0), 0u) << st.message;
    EXPECT_LT(st.message.size(), 300u) << st.message;
    EXPECT_NE(st.message.find("missing closing quote; last read: '\"data:application/octet-stream;base64,AAA"),
              std::string::npos)
        << st.message;
    EXPECT_NE(st.message.find("AAA...'"), std::string::npos) << st.message;
    // A required extension's name is quoted the same way.
    st = parse(tetraGlb([](Json& j, Bytes&) { j["extensionsRequired"] = {"EXT_" + std::string(5000, 'x')}; }), mesh);
    EXPECT_FALSE(st);
    EXPECT_LT(st.message.size(), 200u) << st.message;
    EXPECT_NE(st.message.find("requires extension EXT_xxx"), std::string::npos) << st.message;
}

TEST(GltfInput, CorruptedDuckNeverCrashes) {
    const Bytes duckGlb = readFile(kGltfDir + "/Duck.glb");
    ASSERT_FALSE(duckGlb.empty());
    std::mt19937 rng(12345);
    for (int i = 0; i < 300; ++i) {
        Bytes b = duckGlb;
        if (i % 3 == 0) {
            b.resize(rng() % b.size());
        } else {
            // Mostly the JSON chunk (the first ~1.5 kB), where one byte changes meaning.
            const size_t span = i % 3 == 1 ? std::min<size_t>(b.size(), 2048) : b.size();
            for (int k = 0; k < 4; ++k) b[rng() % span] = uint8_t(rng());
        }
        lt::InputMesh m;
        const lt::Status st = parse(b, m);
        if (st) { EXPECT_LE(m.faceCount(), 4212u * 2); }
    }
}

}  // namespace
