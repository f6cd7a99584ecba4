// baker/src/gltf_source.h -- loads a .gltf or .glb into a tinygltf::Model without
// trusting tinygltf 2.7.0 with anything it gets wrong on hostile input.
//
// Before tinygltf sees the file, loadModel:
//   - checks the GLB container itself (tinygltf lets the BIN chunk overrun by 8 bytes);
//   - parses the JSON and rejects nesting deeper than kMaxJsonDepth and integers
//     tinygltf would cut to 32 bits (outside extras and unknown extensions);
//   - rejects required extensions that change geometry and that we do not read;
//   - checks every buffer uri: a base64 data URI, or a plain file name (no '/', '\',
//     ':', "..", control characters) that exists as a regular file (not a symbolic
//     link) in `baseDir` with exactly the buffer's byteLength. The uri handed to
//     tinygltf is replaced by a token that only our FsCallbacks resolve, so tinygltf
//     can open nothing else (no wordexp, no "./" fallback, no `../`);
//   - drops `images` (never loaded; an image loader that ignores data is installed too);
//   - drops `indices` of KHR_draco_mesh_compression primitives: tinygltf 2.7.0 built
//     without Draco rejects an indices accessor without a bufferView, which is how
//     Draco primitives are written. Faces come from the Draco payload.
// Then the sanitized JSON (and BIN chunk) is handed to tinygltf.
#pragma once

#include "gltf_detail.h"

#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace lt::gltf {

// `name` prefixes every message; `baseDir` is where buffer files are looked up (empty:
// external buffers are rejected); the file and its buffer files together may have at
// most limits.maxInputBytes bytes. Warnings from the checks and from tinygltf are
// appended to `warnings`. `document` (optional) receives the file's JSON text as it
// is (before the checks change it); `bufferFiles` (optional) the paths of the
// external buffer files read (baseDir/name, in token order).
Status loadModel(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                 const Limits& limits, tinygltf::Model& model, std::vector<std::string>& warnings,
                 std::string* document = nullptr, std::vector<std::string>* bufferFiles = nullptr);

// The bytes of an image's uri: a base64 data URI, or a plain file name in `baseDir`
// under the rules for buffer files (above); `mimeType` from the data URI's media type
// or the file name's extension (.png, .jpg, .jpeg, .ktx2, .webp). A file may have at
// most `budget` bytes, which it then uses up (what limits.maxInputBytes leaves).
// `what` ("hero.gltf: images[2].uri") prefixes messages; `path` receives the file's
// path (baseDir/name), or stays as it is for a data URI.
Status loadImageUri(const std::string& uri, const std::string& what, const std::string& baseDir, uint64_t& budget,
                    std::vector<uint8_t>& bytes, std::string& mimeType, std::string& path);

// Each node's parent (-1: a root), after checking that the nodes form a forest
// (glTF 2.0 "Nodes and Hierarchy"): every child exists, and no node is the child of
// two nodes or its own ancestor. Messages name `name` and the node.
Status nodeParents(const tinygltf::Model& model, const std::string& name, std::vector<int>& parent);

}  // namespace lt::gltf
