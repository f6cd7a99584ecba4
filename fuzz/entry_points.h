// fuzz/entry_points.h -- the untrusted-input entry points, driven exactly as the
// fuzzers drive them. Shared by the libFuzzer targets (fuzz_*.cpp) and the
// regression tests (tests/fuzz/test_fuzz_regressions.cpp), so a crash input replays the
// same calls in both.
//
// Contract: each function accepts any bytes. A rejected input is a non-ok Status,
// never a crash, hang or sanitizer report. Where one entry point promises something
// about another's output (readAssetGlb's result passes validateAsset, evaluateCpu
// emits whole triangles on base faces that exist), a broken promise prints what
// broke and aborts, so libFuzzer records it as a crash.
#pragma once

#include "looptess/asset.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace lt::fuzz {

// readSceneGlb, then validateAsset on what it accepted (must pass again); the
// surfaces' face ranges and controlVertex maps must cover what they promise.
Status asset(const uint8_t* data, size_t size);

// parseObj (non-strict), then checkInput; on an accepted mesh, addCreasesByAngle.
Status obj(const uint8_t* data, size_t size);

// parseGltf from memory with `baseDir` (an empty directory: sibling-file URIs find
// nothing), then checkInput.
Status gltf(const uint8_t* data, size_t size, const std::string& baseDir);

// parseEditsJson against a fixed icosahedron (20 faces), then checkInput, then bake
// to depth 3: the side-car's reader and the baker's edit region and tables. A bake
// that checkInput let through must succeed or fail with BadInput (an edit deeper
// than the depth, a set sharing its vertex), and its asset must pass validateAsset.
Status edits(const uint8_t* data, size_t size);

// Inputs above these sizes are skipped by evaluate(), so one run stays short.
constexpr uint32_t kMaxEvalVertices = 1u << 16;  // asset.totalVertexCount()
constexpr size_t kMaxEvalPatches = 1u << 14;     // regular + irregular, all levels

// readAssetGlb, then evaluateCpu at factor 3 (runtime depth <= 2) with equal or
// fractional-odd spacing (chosen by bit 2 of `size`).
Status evaluate(const uint8_t* data, size_t size);

// looprender's loadScene (viewer/scene.h: the scene around the surfaces,
// images decoded), then poseScene at rest and at 0.37 s of the first animation; a
// posed instance's control points must match its surface's count.
Status scene(const uint8_t* data, size_t size);

}  // namespace lt::fuzz
