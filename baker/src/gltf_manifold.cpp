// baker/src/gltf_manifold.cpp -- manifoldMerges (gltf_manifold.h).
#include "gltf_manifold.h"

#include "gltf_accessor.h"

#include <tiny_gltf.h>

#include <cstring>
#include <numeric>

namespace lt::gltf {
namespace {

std::string str(uint64_t v) { return std::to_string(v); }

uint32_t find(std::vector<uint32_t>& parent, uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
}

}  // namespace

bool manifoldMerges(const tinygltf::Model& model, size_t m, const std::vector<double>& positions, DecodeBudget& budget,
                    std::vector<uint32_t>& merged, std::string& why) {
    merged.clear();
    const tinygltf::Mesh& mesh = model.meshes[m];
    auto ext = mesh.extensions.find("EXT_mesh_manifold");
    if (ext == mesh.extensions.end()) return true;
    const tinygltf::Value& mp = ext->second.Get("manifoldPrimitive");
    if (!mp.IsObject() || !mp.Get("indices").IsInt() || !mp.Get("attributes").Get("POSITION").IsInt()) {
        why = "manifoldPrimitive needs integer indices and attributes.POSITION";
        return false;
    }
    const int manIndices = mp.Get("indices").Get<int>(), position = mp.Get("attributes").Get("POSITION").Get<int>();
    if (manIndices < 0 || size_t(manIndices) >= model.accessors.size()) {
        why = "manifoldPrimitive.indices is not an accessor";
        return false;
    }
    const tinygltf::Accessor& man = model.accessors[size_t(manIndices)];
    const size_t vertices = positions.size() / 3;
    std::vector<double> manValues;
    if (!readAccessor(model, manIndices, Semantic::Indices, false, "", budget, manValues)) {
        why = "manifoldPrimitive.indices does not read as indices";
        return false;
    }
    std::vector<uint32_t> parent(vertices);
    std::iota(parent.begin(), parent.end(), 0u);
    const size_t size = man.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                        : man.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                                                                      : 4;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const tinygltf::Primitive& prim = mesh.primitives[p];
        const std::string at = "primitives[" + str(p) + "]";
        auto pos = prim.attributes.find("POSITION");
        if ((prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) || pos == prim.attributes.end() ||
            pos->second != position || prim.indices < 0 || size_t(prim.indices) >= model.accessors.size()) {
            why = at + " is not TRIANGLES with indices over the manifoldPrimitive's POSITION accessor";
            return false;
        }
        if (prim.extensions.count("KHR_draco_mesh_compression")) {  // its vertices are its payload's
            why = at + " is Draco-compressed: its vertices are not the shared POSITION accessor's";
            return false;
        }
        const tinygltf::Accessor& a = model.accessors[size_t(prim.indices)];
        if (a.bufferView != man.bufferView || a.componentType != man.componentType || a.sparse.isSparse ||
            a.byteOffset < man.byteOffset || (a.byteOffset - man.byteOffset) % size != 0) {
            why = at +
                  ".indices is not a range of the manifoldPrimitive's indices (bufferView, componentType, "
                  "byteOffset)";
            return false;
        }
        std::vector<double> own;
        if (!readAccessor(model, prim.indices, Semantic::Indices, false, "", budget, own)) {
            why = at + ".indices does not read as indices";
            return false;
        }
        const size_t first = (a.byteOffset - man.byteOffset) / size;
        if (first + own.size() > manValues.size()) {
            why = at + ".indices reaches past the manifoldPrimitive's";
            return false;
        }
        for (size_t c = 0; c < own.size(); ++c) {
            const double v = own[c], w = manValues[first + c];
            if (v >= double(vertices) || w >= double(vertices)) {
                why = at + " corner " + str(c) + " names a vertex past POSITION's count";
                return false;
            }
            if (std::memcmp(&positions[3 * size_t(v)], &positions[3 * size_t(w)], 3 * sizeof(double)) != 0) {
                why = "vertices " + str(uint64_t(v)) + " and " + str(uint64_t(w)) +
                      " are merged but have different positions";
                return false;
            }
            const uint32_t x = find(parent, uint32_t(v)), y = find(parent, uint32_t(w));
            parent[std::max(x, y)] = std::min(x, y);
        }
    }
    merged.resize(vertices);
    for (uint32_t v = 0; v < vertices; ++v) merged[v] = find(parent, v);
    return true;
}

}  // namespace lt::gltf
