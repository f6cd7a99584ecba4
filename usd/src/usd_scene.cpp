// usd_scene.cpp -- the glTF document and buffer of a USD layer's nodes and meshes
// (usd_data.h, buildScene): one glTF node a prim, one mesh a Mesh prim with its cage
// as the only primitive (TRIANGLES; POSITION, TEXCOORD_0, COLOR_0, indices, each in
// a bufferView of its own), scene 0 the layer's root prims.
#include "usd_data.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>

namespace lt::usd {
namespace {

using Json = nlohmann::ordered_json;

struct Writer {
    Json accessors = Json::array(), views = Json::array();
    std::vector<uint8_t>& bin;

    // A bufferView holding `bytes`, 4-byte aligned, and an accessor over it.
    int add(const void* data, size_t bytes, size_t count, int componentType, const char* type, Json extra = {}) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t offset = bin.size();
        bin.resize(offset + bytes);
        if (bytes) std::memcpy(bin.data() + offset, data, bytes);
        views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
        Json a = {{"bufferView", views.size() - 1}, {"componentType", componentType}, {"count", count}, {"type", type}};
        if (!extra.is_null()) a.update(extra);
        accessors.push_back(std::move(a));
        return int(accessors.size() - 1);
    }
};

Json primitive(Writer& w, const Cage& cage) {
    const size_t n = cage.positions.size() / 3;
    std::vector<float> lo(3, 0.0f), hi(3, 0.0f);
    for (size_t v = 0; v < n; ++v)
        for (size_t k = 0; k < 3; ++k) {
            const float x = cage.positions[v * 3 + k];
            lo[k] = v == 0 ? x : std::min(lo[k], x);
            hi[k] = v == 0 ? x : std::max(hi[k], x);
        }
    Json attributes;
    attributes["POSITION"] =
        w.add(cage.positions.data(), cage.positions.size() * 4, n, 5126, "VEC3", {{"min", lo}, {"max", hi}});
    if (!cage.texcoords.empty())
        attributes["TEXCOORD_0"] = w.add(cage.texcoords.data(), cage.texcoords.size() * 4, n, 5126, "VEC2");
    if (!cage.colors.empty())
        attributes["COLOR_0"] = w.add(cage.colors.data(), cage.colors.size() * 4, n, 5126, "VEC3");
    const int indices = w.add(cage.indices.data(), cage.indices.size() * 4, cage.indices.size(), 5125, "SCALAR");
    return {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
}

}  // namespace

void buildScene(const Layer& layer, const std::vector<Cage>& cages, GltfScene& scene) {
    scene.bin.clear();
    Writer w{Json::array(), Json::array(), scene.bin};
    Json meshes = Json::array(), nodes = Json::array();
    for (size_t i = 0; i < layer.meshes.size(); ++i) {
        const std::string& path = layer.meshes[i].path;
        meshes.push_back({{"name", path.substr(path.rfind('/') + 1)}, {"primitives", {primitive(w, cages[i])}}});
    }
    for (const Node& n : layer.nodes) {
        Json node = {{"name", n.name}};
        if (n.hasMatrix) node["matrix"] = std::vector<double>(n.matrix, n.matrix + 16);
        if (n.mesh >= 0) node["mesh"] = n.mesh;
        if (!n.children.empty()) node["children"] = n.children;
        nodes.push_back(std::move(node));
    }
    Json roots = layer.roots;
    if (layer.zUp) {
        // glTF is Y up: a root turning the layer's Z up into Y up (x, y, z) -> (x, z, -y).
        nodes.push_back({{"name", "Z up to Y up"},
                         {"matrix", {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1}},
                         {"children", layer.roots}});
        roots = Json::array({nodes.size() - 1});
    }
    Json doc = {{"asset", {{"version", "2.0"}, {"generator", "looptess loopbake (USD input)"}}},
                {"scene", 0},
                {"scenes", {{{"nodes", roots}}}},
                {"nodes", nodes}};
    if (!meshes.empty()) {
        doc["meshes"] = meshes;
        doc["accessors"] = w.accessors;
        doc["bufferViews"] = w.views;
        doc["buffers"] = {{{"byteLength", scene.bin.size()}}};
    }
    scene.document = doc.dump();
}

}  // namespace lt::usd
