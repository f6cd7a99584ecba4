// apps/loopbake/bake_job.h -- one loopbake run on one input file: read, check, bake
// every mesh, write the GLB (loopbake.cpp parses the command line and reports).
//
//   .obj          one control mesh -> lt::writeAssetGlb (a new one-mesh scene)
//   .gltf / .glb  lt::parseGltfScene: each mesh with triangles (or those --mesh
//                 names) baked on its own -> lt::writeSceneGlb (the input's scene,
//                 everything else kept)
//   .usd .usda .usdc .usdz
//                 lt::parseUsdScene (looptess_usd, when built): the layer as a glTF
//                 scene, its Loop meshes baked as a glTF input's -> lt::writeSceneGlb
#pragma once

#include "looptess/asset.h"
#include "looptess/tools/baker.h"

#include <optional>
#include <string>
#include <vector>

namespace loopbake {

using lt::Status;

// Every option and its default, in one place.
struct Settings {
    std::string input;
    std::string output;
    std::string report;                                   // --json; empty: none
    int maxDepth = 0;                                     // --max-depth; 0: automatic (lt::BakeSettings)
    std::optional<float> creaseAngle;                     // --crease-angle; unset: off
    bool strict = false;                                  // --strict: triangles only, no input cleaning
    bool hardEdges = false;                               // --hard-edges: glTF split normals -> creases
    std::optional<lt::BoundaryInterpolation> boundary;    // --boundary; unset: the input's (OBJ tag) or edge
    std::vector<std::string> meshes;                      // --mesh NAME|INDEX (repeatable); empty: every mesh
    std::string depfile;                                  // --depfile OUT.d; empty: none
    std::string edits;                                    // --edits EDITS.json; empty: none
    std::string displacement;                             // --displacement MAP.png; empty: none
    std::optional<float> scale, bias;                     // --scale (required with a map), --bias (default 0)
    std::optional<int> displacementResolution;            // --displacement-resolution; unset: chosen
    lt::Compression compression = lt::Compression::Fast;  // --compress none|fast|max
    bool verbose = false;
    bool help = false;
    bool version = false;
    lt::Limits limits;           // --max-faces etc. (lt::cli::applyLimitOption)
    std::optional<double> time;  // --time T (USD input); unset: the default value
    std::string manifest;        // --manifest LIST.json; empty: one file
    unsigned threads = 1;        // --manifest: jobs at once (--threads N, 0 resolved to the cores)
    unsigned bakeThreads = 0;    // threads inside one bake (lt::BakeSettings::threads): --threads N
                                 // for one file; a manifest job's: the cores / jobs at once
};

// What baking one control mesh produced, for -v and --json.
struct MeshResult {
    std::string name;   // "hero.obj", or "hero.glb: meshes[2] (arm)"
    int64_t mesh = -1;  // glTF mesh index; -1 for OBJ
    uint32_t vertices = 0, faces = 0;
    size_t creases = 0, autoCreases = 0, corners = 0, holes = 0;
    bool uvs = false;
    lt::CleaningReport cleaning;  // what input cleaning did to the mesh
    lt::BakeStats stats;
    std::vector<uint32_t> levelEdits;  // hierarchical edits per level (asset.levels[l].edits)
};

// Everything a run produces besides the output file.
struct Results {
    std::vector<MeshResult> meshes;  // in mesh order
    size_t passedThrough = 0;        // glTF meshes left as they were (--mesh)
    std::vector<std::string> warnings;
    lt::TableBytes tableBytes;
    lt::GrayImage map;                    // --displacement, decoded (texels dropped after use)
    uint32_t displacementResolution = 0;  // 0: no map
    size_t displacementSamples = 0;
    size_t outputBytes = 0;
    std::vector<std::string> inputs;  // every file the output depends on, the input first
    double readSeconds = 0, bakeSeconds = 0, writeSeconds = 0;
};

// The lower-case extension of `path` (".obj"), "" without one.
std::string lowerExtension(const std::string& path);

// Reads, checks and bakes s.input into s.output; the output file is only renamed
// into place on success. Warnings go to stderr as they are found. With s.depfile,
// then writes it (depfileText), also atomically.
Status bakeFile(const Settings& s, Results& r);

// A Make-syntax depfile: "OUTPUT: INPUT1 INPUT2 ...\n", with spaces and '#' escaped by
// a backslash and '$' doubled (what Make and Ninja read).
std::string depfileText(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace loopbake
