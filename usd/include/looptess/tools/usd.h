// looptess/tools/usd.h -- USD input (looptess_usd, built when OpenUSD's Sdf is found:
// cmake/Usd.cmake). Reads one layer (.usd, .usda, .usdc, .usdz) with Sdf alone, no
// composition, into the same scene form as a glTF input (lt::GltfScene), so loopbake
// bakes and writes it as it does a glTF scene.
//
//   lt::UsdOptions options;               // options.time = 24.0 for --time 24
//   lt::GltfScene scene;
//   lt::Status st = lt::parseUsdScene("hero.usdc", options, scene);
//
// What a layer becomes (docs/loopbake.md "USD input"):
// - every Mesh prim with subdivisionScheme "loop" is one control mesh
//   (GltfScene::Mesh): its points in order (control vertex i is points[i]),
//   faceVertexCounts/faceVertexIndices (polygons split by lt::triangulatePolygons,
//   as OBJ input's: looptess/tools/triangulate.h),
//   creaseIndices/creaseLengths/creaseSharpnesses (one sharpness per crease or per
//   edge), cornerIndices/cornerSharpnesses, holeIndices (every triangle of the
//   polygon), interpolateBoundary (default edgeAndCorner; options.input.boundary
//   overrides it, with a warning when they differ), orientation (leftHanded
//   reverses each polygon: c0 c(n-1) .. c1), primvars:st (vertex, varying or
//   faceVarying, indexed or not; v flipped to glTF's v = 1 - v) as TEXCOORD_0 and
//   the faces' UVs, primvars:displayColor (constant, uniform, vertex, varying or
//   faceVarying) as COLOR_0 of its cage primitive;
// - a Mesh of another scheme (the default is catmullClark) is written as a plain
//   triangle mesh, with a warning naming it;
// - Xform, Scope and Mesh prims become nodes with the prim's name and its local
//   transform (xformOpOrder: translate, scale, rotate*, orient, transform, with
//   !invert!; !resetXformStack! is refused); a layer with upAxis "Z" gets a root node
//   turning Z up into glTF's Y up. Prims of other types are skipped with their
//   children, with one warning a type.
// - A value is read at `time`: the time sample at exactly that time, else the
//   default value, else the sample at the nearest earlier time, else the first
//   sample (USD's held interpolation, no linear blending). Without `time`: the
//   default value, else the first sample.
// Refused (BadInput, "<file>: <prim path>: <attribute>: what", nothing written):
// composition (sublayers, references, payloads, inherits, specializes, variant
// sets: "flatten it first: usdcat --flatten IN -o OUT.usdc"), a value of the wrong
// type, counts that do not match the indices, an index out of range, a negative
// count or a face of fewer than 3 vertices, a crease of fewer than 2 vertices,
// sharpness arrays of the wrong length, a layer Sdf cannot read, a layer without
// a Mesh. Limits: options.input.limits (faces, vertices) per mesh.
#pragma once

#include "looptess/status.h"
#include "looptess/tools/baker.h"

#include <optional>
#include <string>

namespace lt {

struct UsdOptions {
    InputOptions input;          // limits; cleaning (n/a); strict: refuse polygons
    std::optional<double> time;  // loopbake --time; unset: the default value
    // Read the layer in a child process (fork), which sends its contents back: a
    // corrupt crate file that crashes Sdf is then a BadInput error, not the caller's
    // crash, and the caller never runs Sdf (or its threads) itself, so any thread may
    // call this at any time. Off: read in this process (fuzzers, where a crash is the
    // finding).
    bool isolate = true;
};

// Reads the layer at `path` into `scene` (replaced). The document holds the node
// hierarchy, one glTF mesh a Mesh prim (in prim order), and each Loop mesh's cage
// primitive; scene.meshes the Loop meshes, names "<prim path>". scene.files: none.
Status parseUsdScene(const std::string& path, const UsdOptions& options, GltfScene& scene);

}  // namespace lt
