// looptess/tools/baker.h -- turns a triangle control mesh into a baked Asset.
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
#include "looptess/tools/mesh.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lt {

// Resource limits, every default in this one place. A bake of untrusted input in a
// build farm stays within them or fails with a BadInput status whose message names
// the file, the value, the limit and the loopbake option that raises it, e.g.
//   hero.obj: 2100000 faces, more than the limit of 1048576 (raise it with --max-faces)
// The depth limit is BakeSettings::maxDepth (--max-depth, 1..8) itself: the baker
// never refines deeper than asked.
struct Limits {
    uint64_t maxInputBytes = uint64_t(512) << 20;  // the input file (--max-input-bytes)
    uint32_t maxFaces = 1u << 20;                  // triangles, after triangulation and
                                                   // glTF instancing (--max-faces)
    uint32_t maxVertices = 1u << 20;               // control vertices (--max-vertices)
    uint32_t maxValence = 1024;                    // edges at one vertex (--max-valence)
    uint64_t maxOutputBytes = uint64_t(1) << 30;   // the written GLB (--max-output-bytes)
    uint64_t maxMemoryBytes = uint64_t(4) << 30;   // the bake's estimated memory, checked
                                                   // before refining (--max-memory-mb)
};

struct InputOptions {
    bool strict = false;                             // reject quads and n-gons instead of triangulating
    InputCleaning cleaning = InputCleaning::Repair;  // loopbake --strict: Refuse
    Limits limits;                                   // maxFaces and maxVertices stop parsing early
    // glTF: edges along which the exporter split the vertex normals (two faces whose
    // corners at the same position carry normals more than 1 degree apart) become
    // infinitely sharp creases (loopbake --hard-edges; docs/loopbake.md "Hard edges").
    bool hardEdges = false;
    // The boundary rule of every mesh read (loopbake --boundary); unset: the input's
    // own (an OBJ's interpolateboundary tag), else edge-only. An OBJ tag that says
    // otherwise is overridden with a warning naming its line.
    std::optional<BoundaryInterpolation> boundary;
};

// Parses OBJ text: v, vt, f (v, v/vt, v//vn, v/vt/vn, negative indices) and
// OpenSubdiv's tags (crease, corner, interpolateboundary, creasemethod, hole, and
// vertexedit: InputMesh::VertexEdit; edgeedit and faceedit are rejected).
// Each polygon is cleaned as written (options.cleaning; the rules are
// docs/loopbake.md "Input cleaning"), each kind counted in mesh.cleaning and in one
// warning naming its first line; polygons with more than 3 sides are then
// triangulated with a warning (or rejected with options.strict), once every face is
// read, by triangulatePolygons (looptess/tools/triangulate.h): no split that repeats
// a triangle or gives an edge a third face where another split exists; a warning
// names each polygon (its line) without one.
// Unknown tags and statements warn. Safe on untrusted text; errors name `name`, the
// line number and what is wrong.
Status parseObj(std::string_view text, const std::string& name, const InputOptions& options, InputMesh& mesh);

// Parses glTF 2.0 (.gltf with data URIs or sibling buffers, or .glb; Draco
// primitives included): every TRIANGLES primitive of the default scene, with node
// transforms applied, vertices welded by position into one control mesh,
// TEXCOORD_0 kept per face corner. A triangle with two corners at one position is
// dropped (mesh.cleaning.collapsed); the others are cleaned as parseObj's polygons
// are (InputCleaning; a triangle is dropped or kept whole). `baseDir` is where sibling
// files are looked up; no path outside it is opened. Messages quote at most a short
// excerpt of the input.
Status parseGltf(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                 InputMesh& mesh);
// As above, with `limits.maxFaces` and `limits.maxVertices` bounding the welded mesh
// and every accessor and Draco payload before it is decoded (the overload above uses
// Limits{}).
Status parseGltf(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                 const Limits& limits, InputMesh& mesh);
// As above with options.limits, options.cleaning and options.boundary (options.strict:
// n/a).
Status parseGltf(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                 const InputOptions& options, InputMesh& mesh);

// A glTF scene read for baking (parseGltfScene): the document kept whole, and the
// control mesh of every mesh that has primitives of triangles.
struct GltfScene {
    // The input's JSON, changed only where the format needs it: its buffers merged
    // into one (`bin`, no uri), images with a uri moved into bufferViews, and cage
    // primitives given new accessors where theirs cannot be read as they are (a
    // warning names what was dropped). lt::writeSceneGlb takes it as it is.
    std::string document;
    std::vector<uint8_t> bin;
    struct Mesh {
        uint32_t index = 0;                                // meshes[index]
        std::string name;                                  // its name ("" when it has none)
        std::vector<uint32_t> primitives;                  // its primitives of triangles: the cage
        std::vector<std::vector<uint32_t>> controlVertex;  // per cage primitive, per vertex
        InputMesh mesh;                                    // in the mesh's own space; faces in cage order
    };
    std::vector<Mesh> meshes;        // in mesh order
    std::vector<std::string> files;  // the buffer and image files read (baseDir/name)
    std::vector<std::string> warnings;
};

// Parses glTF 2.0 (.gltf with data URIs or sibling files, or .glb; Draco primitives
// included) for a scene-preserving bake: each mesh with primitives of triangles
// (strips and fans become lists) is one control mesh in its own space, its cage
// primitives' vertices welded by position; POINTS and LINES pass through. Triangles
// are cleaned per mesh as parseGltf's (InputCleaning::Repair; docs/loopbake.md
// "Input cleaning" and "Scenes"). Messages quote at most a short excerpt of the input.
// `baseDir` is where sibling buffers and images are looked up; no path outside it is
// opened. Each mesh stays within limits.maxFaces and maxVertices; every accessor and
// Draco payload is bounded before decoding.
Status parseGltfScene(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                      const Limits& limits, GltfScene& scene);
// As above with options.limits, options.cleaning and options.boundary (options.strict:
// n/a).
Status parseGltfScene(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                      const InputOptions& options, GltfScene& scene);

// Marks every edge whose dihedral angle exceeds `degrees` as infinitely sharp.
// The angle is the one between the two face normals (0 for coplanar faces), taken
// only at edges with exactly two faces; edges that already have a crease keep it.
// New creases (a < b, sharpness 10) are appended sorted by edge. degrees: 0..180.
void addCreasesByAngle(InputMesh& mesh, float degrees);

// Parses a hierarchical-edits side-car for glTF input (loopbake --edits; README
// "Hierarchical edits"), the same edits an OBJ's `t vertexedit` tags hold:
//   {"edits": [{"face": 7, "path": [1, 3], "vertex": 2, "op": "add", "value": [0, 0.1, 0]}]}
// op is "set", "add" or "subtract"; path may be empty (a level-0 edit). Appends to
// mesh.edits in file order. Safe on untrusted text; errors name `name`, the entry
// and what is wrong. Ranges against the mesh are checkInput's and bake's. BadInput
// when input cleaning renumbered the mesh's triangles (mesh.cleaning.renumbered()):
// the side-car's face indices would name other faces than its author meant.
Status parseEditsJson(std::string_view text, const std::string& name, InputMesh& mesh);

// Checks a mesh for what subdivision cannot use: no faces, NaN/Inf positions,
// out-of-range indices, degenerate or repeated faces, inconsistent orientation,
// negative sharpness, tags naming missing vertices/edges/faces, vertex edits with a
// face out of range, a child > 3, a vertex > 2 or a non-finite value. (An edit
// deeper than BakeSettings::maxDepth, or a `set` sharing its vertex with another
// edit, is bake's error: it needs the settings and the topology.)
Status checkInput(const InputMesh& mesh, const std::string& name);
// As above, and appends non-fatal findings (zero-area faces) to `warnings`. Face
// numbers in messages are 0-based triangle indices (after triangulation).
Status checkInput(const InputMesh& mesh, const std::string& name, std::vector<std::string>& warnings);

// Checks `mesh` against limits.maxFaces, maxVertices and maxValence (edges at a
// vertex, boundary and non-manifold edges included). `mesh` need not have passed
// checkInput: out-of-range indices are skipped here. Errors name `name`.
Status checkLimits(const InputMesh& mesh, const Limits& limits, const std::string& name);

// Checks a file size against limits.maxInputBytes / maxOutputBytes; errors name `name`.
Status checkInputBytes(uint64_t bytes, const Limits& limits, const std::string& name);
Status checkOutputBytes(uint64_t bytes, const Limits& limits, const std::string& name);

// The depth a bake takes without an explicit one (BakeSettings::maxDepth = 0).
inline constexpr int kDefaultMaxDepth = 6;

struct BakeSettings {
    int maxDepth = 0;            // 1..8; 0: automatic, the deepest depth up to
                                 // kDefaultMaxDepth (and at least the deepest
                                 // edit) whose estimated memory and output fit
                                 // limits.maxMemoryBytes and maxOutputBytes
    Limits limits;               // faces, vertices, valence, memory (see bake)
    std::string name = "input";  // the input's name in messages
    unsigned threads = 0;        // threads of the per-face, per-vertex and per-patch
                                 // stages (OpenSubdiv's refiner runs on one);
                                 // 0: std::thread::hardware_concurrency(), 1:
                                 // serial. The asset is the same for every count.
};

// Per-level statistics (paper Table 3).
struct LevelStats {
    uint32_t vertices = 0;               // refined vertices stored for this level
    uint32_t rpp = 0, npp = 0, ipp = 0;  // regular plain, non-plain, irregular faces
    uint32_t limitStencils = 0;
};

// The baker's memory, estimated before refining from the control mesh's features
// (extraordinary vertices, semi-sharp and non-manifold edges: they set how many
// faces adaptive refinement makes per level), and the refinement actually made.
// estimatedBytes covers OpenSubdiv's topology, the baker's tables and the written
// GLB, not the input file or the parsed mesh.
struct MemoryStats {
    uint64_t estimatedRefinedFaces = 0;  // faces of levels 1..maxDepth, an upper estimate
    uint64_t estimatedBytes = 0;         // compared against Limits::maxMemoryBytes
    uint64_t estimatedOutputBytes = 0;   // the GLB, an upper estimate (automatic depth
                                         // compares it against Limits::maxOutputBytes)
    uint64_t refinedFaces = 0;           // faces OpenSubdiv made (0 if refused before)
};

struct BakeStats {
    int depth = 0;              // the depth baked (settings.maxDepth, or chosen)
    bool depthLowered = false;  // automatic depth: below kDefaultMaxDepth
    std::string depthReason;    // why that depth, one line (for the CLI to print)
    std::vector<LevelStats> levels;
    MemoryStats memory;
    double seconds = 0;
    // Wall-clock seconds of each stage of the bake, in the order they first ran
    // (for profiles: bench_bake --stages). A stage run per level adds up its
    // levels' times; on several threads two levels run at once, so the stages may
    // add up to more than `seconds`.
    struct Stage {
        const char* name = "";
        double seconds = 0;
    };
    std::vector<Stage> stages;
};

// Builds the subdivision tables. `mesh` must have passed checkInput. Returns a
// BadInput status when OpenSubdiv rejects the topology, when the mesh exceeds
// settings.limits (checkLimits), or when the estimated memory at an explicit
// settings.maxDepth exceeds limits.maxMemoryBytes (refused before refining;
// stats->memory says by how much). With settings.maxDepth = 0 the depth is chosen
// before refining (stats->depth, depthReason); BadInput only when even the
// shallowest possible depth (1, or the deepest edit's) does not fit.
Status bake(const InputMesh& mesh, const BakeSettings& settings, Asset& asset, BakeStats* stats = nullptr);

// --- Displacement maps (spec "Displacement map"; asset.h's DisplacementMap) ---------
//
//   lt::GrayImage map;
//   lt::Status st = lt::decodeGrayPng(pngBytes.data(), pngBytes.size(), "rock.png", map);
//   lt::DisplacementSettings ds;
//   ds.scale = 0.02f;
//   if (st) st = lt::bakeDisplacement(map, ds, asset, "hero.obj");   // after lt::bake

// A single-channel image, 16 bits per texel, row 0 at the top (glTF's v = 0).
struct GrayImage {
    uint32_t width = 0, height = 0;
    std::vector<uint16_t> texels;  // width * height, row by row
    uint32_t bitDepth = 16;        // of the source (8-bit texels are scaled by 257)
};

// Decodes a PNG from memory: 8- or 16-bit grayscale, with or without alpha (alpha
// is ignored). Any other PNG (RGB, RGBA, palette) is refused with Unsupported (a
// displacement map has one channel: convert it first), non-PNG or corrupt data
// with BadInput, more than kMaxDisplacementMapTexels texels with BadInput. Safe on
// untrusted bytes; messages start with `name`.
inline constexpr uint64_t kMaxDisplacementMapTexels = uint64_t(1) << 28;
Status decodeGrayPng(const uint8_t* data, size_t size, const std::string& name, GrayImage& image);

struct DisplacementSettings {
    float scale = 1.0f;       // displacement = scale * map value (0..1) + bias,
    float bias = 0.0f;        // in object units
    uint32_t resolution = 0;  // R, a power of two 1..64; 0: chooseDisplacementResolution
};

// The default resolution for `image` on `asset`'s UVs: the smallest power of two R
// (1..64) whose tiles hold at least as many samples as the image has texels over
// the faces' UV area on average (R^2 / 2 >= mean texels per face: about one sample
// per texel), lowered while the map would exceed kMaxDisplacementSamples samples.
// 1 when the asset has no faceUVs or the image no texels.
inline constexpr uint64_t kMaxDisplacementSamples = uint64_t(1) << 28;
uint32_t chooseDisplacementResolution(const Asset& asset, const GrayImage& image);

// Resamples `image` into asset.displacement (replaced) through the control mesh's
// per-corner UVs (asset.faceUVs, glTF convention: v down from the image's top row;
// texel centres at ((x + 0.5) / width, (y + 0.5) / height); bilinear filtering,
// wrap = repeat, as glTF's default sampler). Every sample on a shared vertex or
// edge gets one value: the mean of what each face around it reads at its own UVs
// ("seam-welded", so a UV seam never opens a crack). Samples are rounded to 16
// bits. Deterministic: same inputs, same samples. `asset` comes from lt::bake (its
// faces and faceUVs are the input's). BadInput when the mesh has no UVs or the
// image no texels, Usage for bad settings (non-finite scale or bias, R not a power
// of two 1..64), Unsupported past kMaxDisplacementSamples. `name` (the mesh's
// file) prefixes messages.
Status bakeDisplacement(const GrayImage& image, const DisplacementSettings& settings, Asset& asset,
                        const std::string& name);

}  // namespace lt
