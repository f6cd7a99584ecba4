// baker/src/gltf_primitive.h -- one glTF primitive of triangles (TRIANGLES,
// TRIANGLE_STRIP or TRIANGLE_FAN; plain or KHR_draco_mesh_compression) decoded into
// a Primitive: positions and TEXCOORD_0 in the mesh's local space, and a triangle
// list. Shared by the scene reader (gltf_scene.cpp) and the flattening reader
// (gltf_reader.cpp).
#pragma once

#include "gltf_detail.h"

#include <string>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace lt::gltf {

// Whether `p`'s mode draws triangles (4, 5, 6, or absent: 4).
bool isTriangles(const tinygltf::Primitive& p);

// Decodes `p` into `out` (out.where is left as it is). Strips and fans become
// triangle lists (glTF 2.0, "Topology types"):
//   TRIANGLES       triangle i = (c[3i], c[3i+1], c[3i+2])
//   TRIANGLE_STRIP  triangle i = (c[i], c[i+1+i%2], c[i+2-i%2])
//   TRIANGLE_FAN    triangle i = (c[i+1], c[i+2], c[0])
// where c is the indices, or 0, 1, 2, ... without them. `quantized`: the file
// uses KHR_mesh_quantization. `normals`: read NORMAL too, where the primitive has
// it (out.normals; an unreadable one is an error). `where` names the primitive in
// messages.
Status readPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& p, bool quantized, bool normals,
                     const std::string& where, DecodeBudget& budget, Primitive& out);

// Whether vertex `va` of `a` and vertex `vb` of `b` have the same skin influences:
// the same joints with non-zero weight, each with a weight within 1e-4, whatever
// the set and slot that holds it (sums over repeated joints). A primitive without
// JOINTS_n/WEIGHTS_n (Primitive::joints empty) has none.
bool sameInfluences(const Primitive& a, size_t va, const Primitive& b, size_t vb);

}  // namespace lt::gltf
