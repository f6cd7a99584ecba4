// baker/src/gltf_draco.h -- decodes one KHR_draco_mesh_compression payload with the
// draco library. Kept apart from tinygltf: Debian's libdraco carries its own older
// tinygltf, and this file includes only draco headers.
#pragma once

#include "gltf_detail.h"

#include <string>

namespace lt::gltf {

// Decodes the Draco mesh in `data` into `out`: positions from the attribute whose
// unique id is `positionId`, TEXCOORD_0 from `texcoordId` and NORMAL from `normalId`
// (< 0: none), triangles in
// decoded order (edgebreaker renumbers vertices; the reader welds by position, so the
// order does not matter). Before decoding, the Draco header's triangle and vertex
// counts are read and more than budget.maxTriangles() triangles (or maxElements()
// vertices) are rejected: Draco 1.5.5 sizes its buffers from those counts before
// reading the data they describe. Bitstream versions
// 2.0 to 2.2 (Draco 1.0 and later); the declared vertices and corners are taken from
// `budget` first. `where` names the primitive's extension.
Status decodeDraco(const uint8_t* data, size_t size, int positionId, int texcoordId, int normalId,
                   const std::string& where, DecodeBudget& budget, Primitive& out);

}  // namespace lt::gltf
