// Binary little-endian PLY writer for captured triangle soups (looprender_common.h).
#include "looprender_common.h"

#include <cstring>
#include <string>

namespace looprender {
namespace {

template <typename T>
void put(std::vector<uint8_t>& bytes, T value) {
    static_assert(sizeof(T) == 4 || sizeof(T) == 1, "PLY scalars here are 1 or 4 bytes");
    uint8_t raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));  // x86-64 and every target we build for are little-endian
    bytes.insert(bytes.end(), raw, raw + sizeof(T));
}

}  // namespace

void writePly(const lt::Tessellation& soup, std::vector<uint8_t>& bytes) {
    const bool st = !soup.texcoords.empty();       // TEXCOORD_0 as `s t`
    const bool tangents = !soup.tangents.empty();  // TANGENT as `tx ty tz tw`
    const bool st1 = !soup.texcoords1.empty();     // TEXCOORD_1 as `s1 t1`
    const bool rgba = !soup.colors.empty();        // COLOR_0 as `red green blue alpha` (float, linear)
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment looptess " +
                         std::string(soup.indices.empty() ? "unwelded" : "indexed") +
                         " tessellation\n"
                         "element vertex " +
                         std::to_string(soup.vertexCount()) +
                         "\nproperty float x\nproperty float y\nproperty float z\n"
                         "property float nx\nproperty float ny\nproperty float nz\n"
                         "property int face\nproperty float u\nproperty float v\n" +
                         std::string(st ? "property float s\nproperty float t\n" : "") +
                         std::string(tangents ? "property float tx\nproperty float ty\nproperty float tz\n"
                                                "property float tw\n"
                                              : "") +
                         std::string(st1 ? "property float s1\nproperty float t1\n" : "") +
                         std::string(rgba ? "property float red\nproperty float green\nproperty float blue\n"
                                            "property float alpha\n"
                                          : "") +
                         "element face " + std::to_string(soup.triangleCount()) +
                         "\nproperty list uchar int vertex_indices\nend_header\n";
    bytes.assign(header.begin(), header.end());
    bytes.reserve(bytes.size() + soup.vertexCount() * 36 + soup.triangleCount() * 13);
    for (size_t i = 0; i < soup.vertexCount(); ++i) {
        for (int k = 0; k < 3; ++k) put(bytes, soup.positions[i * 3 + k]);
        for (int k = 0; k < 3; ++k) put(bytes, soup.normals[i * 3 + k]);
        put(bytes, int32_t(soup.face[i]));
        put(bytes, soup.uv[i * 2]);
        put(bytes, soup.uv[i * 2 + 1]);
        if (st) {
            put(bytes, soup.texcoords[i * 2]);
            put(bytes, soup.texcoords[i * 2 + 1]);
        }
        if (tangents)
            for (int k = 0; k < 4; ++k) put(bytes, soup.tangents[i * 4 + k]);
        if (st1)
            for (int k = 0; k < 2; ++k) put(bytes, soup.texcoords1[i * 2 + k]);
        if (rgba)
            for (int k = 0; k < 4; ++k) put(bytes, soup.colors[i * 4 + k]);
    }
    for (size_t t = 0; t < soup.triangleCount(); ++t) {
        put(bytes, uint8_t(3));
        for (int k = 0; k < 3; ++k) put(bytes, int32_t(soup.indices.empty() ? t * 3 + k : soup.indices[t * 3 + k]));
    }
}

}  // namespace looprender
