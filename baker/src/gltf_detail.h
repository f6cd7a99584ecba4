// baker/src/gltf_detail.h -- what the glTF reader's files share (gltf_reader.cpp,
// gltf_source.cpp, gltf_accessor.cpp, gltf_draco.cpp): the limits that bound every
// allocation on untrusted input, and one decoded primitive.
//
// Error messages are "<file>: <glTF object>: <what is wrong>", e.g.
//   Duck.glb: meshes[0].primitives[0].attributes.POSITION: accessor 2 count 2399 overruns bufferView 1
// Each function takes `where` (file and object, already joined) and appends the rest.
#pragma once

#include "looptess/asset.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lt::gltf {

// A .gltf/.glb file, and each external buffer file, may have at most this many bytes
// (tinygltf 2.7.0 takes lengths as 32-bit unsigned).
constexpr size_t kMaxFileBytes = size_t(1) << 30;
// Triangles in the whole welded mesh (instances included) and in one Draco payload.
// A control mesh for subdivision is far smaller; the cap keeps a small file from
// asking for gigabytes.
constexpr uint32_t kMaxTriangles = 1u << 20;
// Elements of one accessor (vertices or indices of one primitive).
constexpr size_t kMaxAccessorCount = 3 * size_t(kMaxTriangles);
// JSON nesting (tinygltf converts extras and extensions recursively).
constexpr int kMaxJsonDepth = 64;
// Elements (accessor elements, Draco points and corners) one file may decode in
// total. Bounds time and memory when many primitives share one large accessor or
// Draco payload: each primitive is decoded on its own.
constexpr size_t kMaxDecodedElements = size_t(1) << 24;

// What is left of kMaxDecodedElements while one file is read.
class DecodeBudget {
public:
    // Takes `n` elements; false (nothing taken) when fewer are left.
    bool take(uint64_t n) {
        if (n > left_) return false;
        left_ -= n;
        return true;
    }
    static std::string exhausted() {
        return "the file decodes more than " + std::to_string(kMaxDecodedElements) +
               " elements in total (limit)";
    }

private:
    uint64_t left_ = kMaxDecodedElements;
};

// One TRIANGLES primitive in its mesh's local space, every index checked.
struct Primitive {
    std::vector<double> positions;   // 3 per vertex
    std::vector<double> uvs;         // 2 per vertex (TEXCOORD_0), or empty when absent
    std::vector<uint32_t> triangles; // 3 per triangle, each < vertex count

    size_t vertexCount() const { return positions.size() / 3; }
};

inline Status badInput(const std::string& where, const std::string& what) {
    return Status::error(Status::BadInput, where + ": " + what);
}

} // namespace lt::gltf
