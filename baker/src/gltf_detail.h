// baker/src/gltf_detail.h -- what the glTF reader's files share (gltf_reader.cpp,
// gltf_source.cpp, gltf_accessor.cpp, gltf_draco.cpp): the limits that bound every
// allocation on untrusted input, and one decoded primitive.
//
// Error messages are "<file>: <glTF object>: <what is wrong>", e.g.
//   Duck.glb: meshes[0].primitives[0].attributes.POSITION: accessor 2 count 2399 overruns bufferView 1
// Each function takes `where` (file and object, already joined) and appends the rest.
#pragma once

#include "looptess/tools/baker.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace lt::gltf {

// A .gltf/.glb file, and each external buffer file, may have at most this many bytes
// (tinygltf 2.7.0 takes lengths as 32-bit unsigned). The user's limit on input bytes
// (Limits::maxInputBytes) is checked by the caller, before the file is read.
constexpr size_t kMaxFileBytes = size_t(1) << 30;
// JSON nesting (tinygltf converts extras and extensions recursively).
constexpr int kMaxJsonDepth = 64;

// What one file may decode, from the user's Limits (looptess/tools/baker.h), checked before
// anything is allocated by a count the file declares:
//   - triangles in the whole welded mesh (instances included) and in one Draco
//     payload: limits.maxFaces; welded vertices: limits.maxVertices;
//   - elements of one accessor (vertices or indices of one primitive, before welding)
//     and vertices of one Draco payload: 3 x maxFaces;
//   - elements in total (accessor elements, Draco points and corners; 16 x maxFaces):
//     bounds time and memory when many primitives share one large accessor or Draco
//     payload, as each primitive is decoded on its own.
class DecodeBudget {
public:
    explicit DecodeBudget(const Limits& limits) : limits_(limits), left_(16 * uint64_t(limits.maxFaces)) {}

    const Limits& limits() const { return limits_; }
    uint64_t maxTriangles() const { return limits_.maxFaces; }
    uint64_t maxElements() const { return 3 * uint64_t(limits_.maxFaces); }  // per accessor

    // Takes `n` elements; false (nothing taken) when fewer are left.
    bool take(uint64_t n) {
        if (n > left_) return false;
        left_ -= n;
        return true;
    }
    std::string exhausted() const {
        return "the file decodes more than " + std::to_string(16 * uint64_t(limits_.maxFaces)) +
               " elements in total (16 x the face limit; raise it with --max-faces)";
    }

private:
    Limits limits_;
    uint64_t left_;
};

// One TRIANGLES primitive in its mesh's local space, every index checked.
struct Primitive {
    std::vector<double> positions;  // 3 per vertex
    std::vector<double> uvs;        // 2 per vertex (TEXCOORD_0), or empty when absent
    std::vector<double> normals;    // 3 per vertex (NORMAL), read only for hard edges
                                    // (InputOptions::hardEdges), else empty
    // JOINTS_n and WEIGHTS_n of sets n = 0, 1, ...: 4 per set per vertex (set after
    // set), or empty when absent, unreadable or in a Draco payload: only for the
    // weld's warning (the attributes themselves pass through).
    std::vector<double> joints, weights;
    std::vector<uint32_t> triangles;  // 3 per triangle, each < vertex count
    std::string where;                // "meshes[M].primitives[P]"

    size_t vertexCount() const { return positions.size() / 3; }
};

// A position's weld key: the bit patterns of its float xyz, -0 taken as +0.
inline uint32_t weldBits(float f) {
    if (f == 0) f = 0.0f;
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

struct Key {
    uint32_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct KeyHash {
    size_t operator()(const Key& k) const {
        uint64_t h = (uint64_t(k.x) << 32 | k.y) * 0x9E3779B97F4A7C15ull;
        h ^= (h >> 29) + uint64_t(k.z) * 0xBF58476D1CE4E5B9ull;
        return size_t(h ^ (h >> 32));
    }
};

inline Status badInput(const std::string& where, const std::string& what) {
    return Status::error(Status::BadInput, where + ": " + what);
}

}  // namespace lt::gltf
