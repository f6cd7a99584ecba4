// Private to looptess_usd: a USD layer's meshes and prim hierarchy as plain data,
// read by usd_layer.cpp (the only source that includes OpenUSD) and turned into the
// glTF scene by usd_mesh.cpp and usd_scene.cpp, which need no OpenUSD (a fuzzer
// or test can fill these structs directly).
#pragma once

#include "looptess/status.h"
#include "looptess/tools/baker.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lt::usd {

// A primvar as authored: its values (`components` floats each), its indices when it
// is indexed, its interpolation ("constant", "uniform", "vertex", "varying",
// "faceVarying"; USD's default is "constant").
struct Primvar {
    bool present = false;
    int components = 0;
    std::vector<float> values;
    bool indexed = false;
    std::vector<int> indices;
    std::string interpolation = "constant";
};

// A Mesh prim's attributes as authored (absent: `has*` false or the UsdGeom default).
struct MeshData {
    std::string path;  // "/root/body"
    std::string scheme = "catmullClark";
    std::string boundary = "edgeAndCorner";
    std::string orientation = "rightHanded";
    bool hasPoints = false, hasCounts = false, hasIndices = false;
    std::vector<float> points;  // 3 a point
    std::vector<int> counts, indices;
    std::vector<int> creaseIndices, creaseLengths, cornerIndices, holeIndices;
    std::vector<float> creaseSharpnesses, cornerSharpnesses;
    Primvar st, displayColor;
};

struct Node {
    std::string name;
    bool hasMatrix = false;
    double matrix[16] = {};  // glTF's column-major order (USD's row-major, row vectors)
    int mesh = -1;           // into Layer::meshes
    std::vector<int> children;
};

struct Layer {
    std::vector<Node> nodes;
    std::vector<int> roots;
    std::vector<MeshData> meshes;
    bool zUp = false;
    std::vector<std::string> warnings;
};

// What a mesh becomes in the glTF file: one TRIANGLES primitive. Its vertices are
// the points split where st or displayColor differ between the faces around one
// point; controlVertex maps them back to the points.
struct Cage {
    std::vector<float> positions;  // 3 a vertex
    std::vector<float> texcoords;  // 2 a vertex (glTF's v), or empty
    std::vector<float> colors;     // 3 a vertex, or empty
    std::vector<uint32_t> indices;
    std::vector<uint32_t> controlVertex;
};

// Checks `m` and builds its cage; for a Loop mesh (`loop`) also the control mesh.
// Errors: BadInput "<file>: <prim path>: <attribute>: what".
Status buildMesh(const MeshData& m, const std::string& file, const InputOptions& options, bool loop, InputMesh& mesh,
                 Cage& cage, std::vector<std::string>& warnings);

// The glTF document and buffer for `layer` with one cage a mesh (cages[i] for
// layer.meshes[i]); fills scene.document and scene.bin, and each Loop mesh's
// primitives (GltfScene::Mesh::index is its glTF mesh, which is its index in
// layer.meshes).
void buildScene(const Layer& layer, const std::vector<Cage>& cages, GltfScene& scene);

// Reads `path` with Sdf into `layer` (usd_layer.cpp). `time`: nullptr for the default.
Status readLayer(const std::string& path, const double* time, Layer& layer);

}  // namespace lt::usd
