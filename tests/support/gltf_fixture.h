// tests/support/gltf_fixture.h -- small glTF files built in memory for the glTF input tests
// (test_gltf_input.cpp, test_scene_input.cpp): a GLB container and a tetrahedron.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <vector>

namespace gltftest {

using Json = nlohmann::json;
using Bytes = std::vector<uint8_t>;

inline Bytes makeGlb(const Json& json, const Bytes& bin) {
    std::string text = json.dump();
    while (text.size() % 4) text += ' ';
    Bytes data = bin;
    while (data.size() % 4) data.push_back(0);
    Bytes out;
    auto u32 = [&](size_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
    };
    u32(0x46546C67);
    u32(2);
    u32(12 + 8 + text.size() + (data.empty() ? 0 : 8 + data.size()));
    u32(text.size());
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (!data.empty()) {
        u32(data.size());
        u32(0x004E4942);
        out.insert(out.end(), data.begin(), data.end());
    }
    return out;
}

template <class T>
void append(Bytes& out, std::initializer_list<T> values) {
    for (T v : values) {
        uint8_t b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        out.insert(out.end(), b, b + sizeof(T));
    }
}

// One triangle primitive: POSITION (accessor 0, bufferView 0), indices (accessor 1,
// u16, bufferView 1, padded to 4 bytes), TEXCOORD_0 (accessor 2, bufferView 2), all
// in buffer 0 = `bin` (replaced).
inline Json triangles(Bytes& bin, std::initializer_list<float> positions, std::initializer_list<uint16_t> indices,
                      std::initializer_list<float> uvs) {
    bin.clear();
    append<float>(bin, positions);
    const size_t p = bin.size();
    append<uint16_t>(bin, indices);
    if (indices.size() % 2) append<uint16_t>(bin, {0});
    const size_t i = bin.size() - p;
    append<float>(bin, uvs);
    const size_t vertices = positions.size() / 3;
    Json j = Json::parse(R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1}]}]})");
    j["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC3"}},
                      {{"bufferView", 1}, {"componentType", 5123}, {"count", indices.size()}, {"type", "SCALAR"}},
                      {{"bufferView", 2}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC2"}}};
    j["bufferViews"] = {{{"buffer", 0}, {"byteLength", p}},
                        {{"buffer", 0}, {"byteOffset", p}, {"byteLength", i}},
                        {{"buffer", 0}, {"byteOffset", p + i}, {"byteLength", bin.size() - p - i}}};
    j["buffers"] = {{{"byteLength", bin.size()}}};
    return j;
}

// A unit tetrahedron with outward counter-clockwise faces and UVs (`triangles`).
inline Json tetra(Bytes& bin) {
    return triangles(bin, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3},
                     {0, 0, 1, 0, 0, 1, 1, 1});
}

inline Bytes tetraGlb(const std::function<void(Json&, Bytes&)>& edit = {}) {
    Bytes bin;
    Json j = tetra(bin);
    if (edit) edit(j, bin);
    return makeGlb(j, bin);
}

}  // namespace gltftest
