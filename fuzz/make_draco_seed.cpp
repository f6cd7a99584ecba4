// fuzz/make_draco_seed.cpp -- seed tool for the glTF fuzzer:
//   make_draco_seed IN.obj OUT.glb [sequential]
// writes IN's triangles as one KHR_draco_mesh_compression primitive (POSITION only,
// edgebreaker encoding unless `sequential`). Exit 0 on success, 1 otherwise.
#include "looptess/tools/baker.h"

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace {

void put32(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(char(v >> (8 * i)));
}

// A GLB around `json` and `bin` (both padded to 4 bytes).
std::string glb(std::string json, std::string bin) {
    while (json.size() % 4) json.push_back(' ');
    while (bin.size() % 4) bin.push_back('\0');
    std::string out;
    put32(out, 0x46546C67);
    put32(out, 2);
    put32(out, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    put32(out, uint32_t(json.size()));
    put32(out, 0x4E4F534A);
    out += json;
    put32(out, uint32_t(bin.size()));
    put32(out, 0x004E4942);
    return out + bin;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) return std::fprintf(stderr, "usage: make_draco_seed IN.obj OUT.glb [sequential]\n"), 1;
    std::ifstream in(argv[1], std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    lt::InputMesh m;
    lt::Status st = lt::parseObj(text.str(), argv[1], lt::InputOptions{}, m);
    if (!st || m.faceCount() == 0) return std::fprintf(stderr, "%s\n", st.message.c_str()), 1;

    draco::TriangleSoupMeshBuilder builder;
    builder.Start(int(m.faceCount()));
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    for (uint32_t f = 0; f < m.faceCount(); ++f) {
        const uint32_t* v = &m.faces[3 * f];
        builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &m.positions[3 * v[0]], &m.positions[3 * v[1]],
                                          &m.positions[3 * v[2]]);
    }
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    const bool sequential = argc > 3 && std::strcmp(argv[3], "sequential") == 0;
    encoder.SetEncodingMethod(sequential ? draco::MESH_SEQUENTIAL_ENCODING : draco::MESH_EDGEBREAKER_ENCODING);
    draco::EncoderBuffer buffer;
    if (!mesh || !encoder.EncodeMeshToBuffer(*mesh, &buffer).ok()) return std::fprintf(stderr, "draco failed\n"), 1;

    using Json = nlohmann::json;
    const Json ext = {{"bufferView", 0}, {"attributes", {{"POSITION", mesh->attribute(pos)->unique_id()}}}};
    const Json doc = {{"asset", {{"version", "2.0"}}},
                      {"extensionsUsed", {"KHR_draco_mesh_compression"}},
                      {"extensionsRequired", {"KHR_draco_mesh_compression"}},
                      {"scene", 0},
                      {"scenes", {{{"nodes", {0}}}}},
                      {"nodes", {{{"mesh", 0}}}},
                      {"meshes",
                       {{{"primitives",
                          {{{"attributes", {{"POSITION", 0}}},
                            {"indices", 1},
                            {"extensions", {{"KHR_draco_mesh_compression", ext}}}}}}}}},
                      {"accessors",
                       {{{"componentType", 5126}, {"count", mesh->num_points()}, {"type", "VEC3"}},
                        {{"componentType", 5125}, {"count", 3 * m.faceCount()}, {"type", "SCALAR"}}}},
                      {"bufferViews", {{{"buffer", 0}, {"byteLength", buffer.size()}}}},
                      {"buffers", {{{"byteLength", buffer.size()}}}}};
    const std::string bytes = glb(doc.dump(), std::string(buffer.data(), buffer.size()));
    std::ofstream out(argv[2], std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return out ? 0 : 1;
}
