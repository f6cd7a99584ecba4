// looptess/glb.h -- the GLB container of glTF 2.0 ("Binary glTF Layout"): a 12-byte
// header (magic, version, length), then chunks of (length, type, bytes). readGlb finds
// the JSON and BIN chunks in untrusted bytes; what the JSON says is the caller's to
// check (readAssetGlb and readSceneGlb in asset.h do, for this format's files).
//
//   lt::GlbChunks chunks;
//   lt::Status st = lt::readGlb(bytes.data(), bytes.size(), "hero.glb", lt::GlbLayout::Strict, chunks);
//   if (!st) return st;   // "hero.glb: GLB chunk 1: length 112 overruns the file (...)"
//   auto doc = nlohmann::json::parse(chunks.json, nullptr, false);
//
// Its own header (not asset.h) because its users are every tool that opens a GLB,
// most of which never touch an Asset; it needs nothing but Status (status.h), and no JSON
// library, so it adds no dependency to an engine that includes it.
#pragma once

#include "looptess/status.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace lt {

// The layout's little-endian words, for code that writes a GLB.
inline constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
inline constexpr uint32_t kGlbVersion = 2;
inline constexpr uint32_t kGlbChunkJson = 0x4E4F534A;  // "JSON"
inline constexpr uint32_t kGlbChunkBin = 0x004E4942;   // "BIN\0"

// The chunks readGlb found: views into the caller's bytes, valid while those are.
struct GlbChunks {
    std::string_view json;         // chunk 0, padding included (spaces; some writers pad with NULs)
    const uint8_t* bin = nullptr;  // chunk 1 when it is a BIN chunk (possibly empty), else null
    size_t binLength = 0;
};

// How much of glTF's layout rules readGlb enforces. Both check the header (at least
// 12 bytes, magic, version 2, length equal to the file's size), that every chunk
// header and chunk lies inside the file, and that chunk 0 is a JSON chunk.
enum class GlbLayout {
    // glTF 2.0's remaining rules, which files this library writes follow: every
    // chunk length a multiple of 4, the JSON chunk not empty, a BIN chunk only as
    // chunk 1, no second JSON or BIN chunk.
    Strict,
    // For input from other writers, whose files break those rules in ways that still
    // have one meaning: any chunk length, an empty JSON chunk, and a JSON or BIN chunk
    // out of place skipped like a chunk of unknown type.
    Lenient,
};

// True when `data` starts with the GLB magic: a GLB rather than a .gltf's JSON text
// (which never starts with 'g'). Reads at most 4 bytes; any `size`.
bool isGlb(const uint8_t* data, size_t size);

// Reads the header and the chunk table of the `size` bytes at `data` (null when
// `size` is 0) and sets `out` to the JSON and BIN chunks. Chunks of other types are
// skipped, as glTF requires.
//
// Contract: any bytes are safe. Every length is checked against the bytes left
// before it is used (no read outside [data, data + size), no arithmetic that wraps);
// the only allocation is the error message, and nothing is thrown (but bad_alloc
// for that message). On failure `out` is empty and the status is BadInput with
// "<name>: <what is wrong>", e.g. "x.glb: GLB version 1, expected 2" or
// "x.glb: GLB chunk 0: length 9 is not a multiple of 4": the chunk by number and
// the lengths concerned.
Status readGlb(const uint8_t* data, size_t size, const std::string& name, GlbLayout layout, GlbChunks& out);

}  // namespace lt
