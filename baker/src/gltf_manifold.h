// baker/src/gltf_manifold.h -- a mesh's EXT_mesh_manifold (a Khronos vendor extension:
// extensions/2.0/Vendor/EXT_mesh_manifold in the glTF repository), read as the weld
// of its control mesh: which vertices of the primitives' shared POSITION accessor
// are one vertex of the manifold.
//
//   primitives[0].indices   | 0 1 2 | 2 1 3 |                 (one bufferView for all,
//   primitives[1].indices                   | 4 5 6 | ...      each a range of it)
//   manifoldPrimitive       | 0 1 2 | 2 1 3 | 1 5 6 | ...      (the same bufferView;
//     .indices, sparse applied                ^ 4 merged into 1  sparse: the merges)
//
// Corner c of a primitive and corner c of the manifold primitive's range at the same
// bytes name vertices that are one; vertices no corner names are their own.
#pragma once

#include "gltf_detail.h"

#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace lt::gltf {

// For mesh `m`: empty `merged` and true when it has no EXT_mesh_manifold. Else
// `merged[v]` is the representative (the smallest vertex index) of vertex v of the
// mesh's shared POSITION accessor, and true; or false with `why` when the extension
// breaks a rule this weld needs (all primitives TRIANGLES, none Draco-compressed,
// with one POSITION accessor and indices in the manifold primitive's bufferView,
// same component type, within its range; merged vertices at bitwise the same
// position): the caller
// then welds by position and warns. `positions` are the shared accessor's (3 per
// vertex, as read for the primitives).
bool manifoldMerges(const tinygltf::Model& model, size_t m, const std::vector<double>& positions, DecodeBudget& budget,
                    std::vector<uint32_t>& merged, std::string& why);

}  // namespace lt::gltf
