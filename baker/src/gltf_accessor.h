// baker/src/gltf_accessor.h -- reads bufferViews and accessors of a tinygltf::Model
// after checking every index, format and byte range (tinygltf 2.7.0 checks none).
#pragma once

#include "gltf_detail.h"

#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace lt::gltf {

// What an accessor is read as; decides the allowed type and component types:
//   Position: VEC3 float; with KHR_mesh_quantization also (normalized) byte/short.
//   TexCoord: VEC2 float, normalized unsigned byte/short; with KHR_mesh_quantization
//             also (normalized) signed byte/short and unnormalized unsigned byte/short.
//   Indices:  SCALAR unsigned byte/short/int, not normalized, with a bufferView.
//   Joints:   VEC4 unsigned byte/short, not normalized (JOINTS_n).
//   Weights:  VEC4 float, normalized unsigned byte/short (WEIGHTS_n).
enum class Semantic { Position, TexCoord, Normal, Indices, Joints, Weights };

// Checks bufferView `view` (index, buffer index, range within the buffer) and returns
// its bytes. `where` names the referring object ("Duck.glb: meshes[0]...").
Status viewBytes(const tinygltf::Model& model, int view, const std::string& where, const uint8_t*& data, size_t& size);

// Checks accessor `index` for `semantic` and replaces `out` with its values, count x
// components, as double (normalized integers mapped as glTF specifies). Accessors
// without a bufferView read as zeros; sparse accessors are applied (indices strictly
// increasing and below count). `quantized`: the file uses KHR_mesh_quantization.
// The accessor's count is taken from `budget` before anything is allocated.
// Messages: "<where>: accessor 3 count 2399 overruns bufferView 1 (...)".
Status readAccessor(const tinygltf::Model& model, int index, Semantic semantic, bool quantized,
                    const std::string& where, DecodeBudget& budget, std::vector<double>& out);

}  // namespace lt::gltf
