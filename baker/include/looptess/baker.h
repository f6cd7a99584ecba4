// looptess/baker.h -- turns a triangle control mesh into a baked Asset.
//
// The pipeline is in-memory and does no I/O, so tests and fuzzers call it directly:
//
//   lt::InputMesh mesh;
//   lt::Status st = lt::parseObj(text, "hero.obj", lt::InputOptions{}, mesh);
//   if (st) st = lt::checkInput(mesh, "hero.obj");
//   lt::Asset asset;
//   lt::BakeStats stats;
//   if (st) st = lt::bake(mesh, lt::BakeSettings{}, asset, &stats);
//   // then lt::writeAssetGlb(asset, bytes) (looptess/asset.h)
#pragma once

#include "looptess/asset.h"

#include <string>
#include <string_view>
#include <vector>

namespace lt {

// A triangle control mesh as read from a file, before any checks.
struct InputMesh {
    std::vector<float> positions;        // 3 per vertex
    std::vector<uint32_t> faces;         // 3 per triangle, counter-clockwise
    std::vector<float> faceUVs;          // 6 per triangle (uv per corner, glTF's convention:
                                         // v down from the image's top), or empty
    struct Crease { uint32_t a, b; float sharpness; };
    struct Corner { uint32_t vertex; float sharpness; };
    std::vector<Crease> creases;         // edge sharpness (>= 10: infinitely sharp)
    std::vector<Corner> corners;         // vertex sharpness
    std::vector<uint32_t> holes;         // triangle indices (after triangulation)
    BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly;
    CreaseMethod creaseMethod = CreaseMethod::Normal;
    std::vector<std::string> warnings;   // non-fatal findings, for the CLI to print

    uint32_t vertexCount() const { return uint32_t(positions.size() / 3); }
    uint32_t faceCount() const { return uint32_t(faces.size() / 3); }
};

struct InputOptions {
    bool strict = false;                 // reject quads and n-gons instead of triangulating
};

// Parses OBJ text: v, vt, f (v, v/vt, v//vn, v/vt/vn, negative indices) and
// OpenSubdiv's tags (crease, corner, interpolateboundary, creasemethod, hole).
// Polygons with more than 3 sides are fan-triangulated with a warning (or rejected
// with options.strict). Unknown tags and statements warn. Safe on untrusted text;
// errors name `name`, the line number and what is wrong.
Status parseObj(std::string_view text, const std::string& name, const InputOptions& options,
                InputMesh& mesh);

// Parses glTF 2.0 (.gltf with data URIs or sibling buffers, or .glb; Draco
// primitives included): every TRIANGLES primitive of the default scene, with node
// transforms applied, vertices welded by position into one control mesh,
// TEXCOORD_0 kept per face corner. `baseDir` is where sibling files are looked up;
// no path outside it is opened.
Status parseGltf(const uint8_t* data, size_t size, const std::string& name,
                 const std::string& baseDir, InputMesh& mesh);

// Marks every edge whose dihedral angle exceeds `degrees` as infinitely sharp.
// The angle is the one between the two face normals (0 for coplanar faces), taken
// only at edges with exactly two faces; edges that already have a crease keep it.
// New creases (a < b, sharpness 10) are appended sorted by edge. degrees: 0..180.
void addCreasesByAngle(InputMesh& mesh, float degrees);

// Checks a mesh for what subdivision cannot use: no faces, NaN/Inf positions,
// out-of-range indices, degenerate or repeated faces, inconsistent orientation,
// negative sharpness, tags naming missing vertices/edges/faces.
Status checkInput(const InputMesh& mesh, const std::string& name);
// As above, and appends non-fatal findings (zero-area faces) to `warnings`. Face
// numbers in messages are 0-based triangle indices (after triangulation).
Status checkInput(const InputMesh& mesh, const std::string& name,
                  std::vector<std::string>& warnings);

struct BakeSettings {
    int maxDepth = 6;                    // 1..8
};

// Per-level statistics (paper Table 3).
struct LevelStats {
    uint32_t vertices = 0;               // refined vertices stored for this level
    uint32_t rpp = 0, npp = 0, ipp = 0;  // regular plain, non-plain, irregular faces
    uint32_t limitStencils = 0;
};

struct BakeStats {
    std::vector<LevelStats> levels;
    double seconds = 0;
};

// Debug information a test needs to compare against OpenSubdiv: for every global
// vertex of the asset, the OpenSubdiv (level, vertex index) it corresponds to in a
// TopologyRefiner built with the same options and RefineAdaptive(maxDepth).
struct BakeTrace {
    std::vector<uint32_t> osdLevel, osdVertex;
};

// Builds the subdivision tables. `mesh` must have passed checkInput. Returns a
// BadInput status when OpenSubdiv rejects the topology.
Status bake(const InputMesh& mesh, const BakeSettings& settings, Asset& asset,
            BakeStats* stats = nullptr, BakeTrace* trace = nullptr);

} // namespace lt
