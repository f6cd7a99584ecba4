// looprender's pieces shared by its CPU and GPU paths (see looprender.cpp).
#pragma once

#include "looptess/asset.h"
#include "looptess/runtime.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lt {
class VulkanContext;
}

namespace looprender {

struct Options {
    std::string input;
    bool cpu = false;
    float tess = 1.0f;
    lt::Spacing spacing = lt::Spacing::Equal;
    std::string path = "auto";  // --path: auto, tessellator, patterns or compute (choosePath, framePath)
    bool watertight = true;     // --no-watertight turns it off
    bool displace = true;       // --no-displacement: ignore the asset's map
    std::string capture, png, json;
    std::string mesh;  // --mesh: the indexed surface (recordEvaluate's layout)
    uint32_t width = 512, height = 512;
    uint32_t frames = 1;           // rendered frames timed (GPU)
    uint32_t threads = 0;          // --threads: CPU evaluation threads (EvalSettings::threads)
    std::string color = "shaded";  // --color: shaded, levels, texcoords or material (the scene)
    float time = -1;               // --time: seconds (material); < 0: the rest pose
    int animation = -1;            // --animation: index (material); < 0: the first with --time
    bool wireframe = false;
    bool verbose = false;
    bool validation = false;  // Vulkan validation layers; any message fails
    std::string device;       // substring of the Vulkan device name
    bool camera = false;      // else framed from the bounding box
    float eye[3] = {0, 0, 0}, target[3] = {0, 0, 0}, fovDegrees = 40;
    lt::LodMode lod = lt::LodMode::Global;  // --lod
    float pixelsPerEdge = 8;                // --pixels-per-edge
    float editScale = 1;                    // --edit-scale: multiplies every hierarchical edit value
};

// The asset's hierarchical edit values (lt::bakedEditValues) times o.editScale, for
// EvalSettings::editValues and VulkanSurface::setEditValues.
std::vector<float> scaledEditValues(const Options& o, const lt::Asset& asset);

// The draw path of --path for --capture, --mesh, --cpu and scenes: as named; auto:
// the tessellator with --spacing fractional_odd, and with --lod screen where the
// device has tessellation shaders (`tessellation`; without them patterns, given
// drawIndirectFirstInstance, `screenPatterns`), else patterns. The same on every
// device with tessellation shaders, so a capture is the same file with and without
// --cpu.
lt::DrawPath choosePath(const Options& o, bool tessellation, bool screenPatterns);
// The same for the device of `gpu` (looprender_gpu.cpp).
lt::DrawPath choosePath(const Options& o, lt::VulkanContext& gpu);
// The path of rendered frames: as named; auto: lt::DrawPath::Auto, which measures
// every path over the first frames and keeps the fastest (looprender's report says
// what it measured), or `single` (choosePath's) for one frame, which nothing
// measured could speed up.
lt::DrawPath framePath(const Options& o, lt::DrawPath single);
// "tessellator", "patterns", "compute" or "auto", for -v and --json.
const char* pathName(lt::DrawPath path);

// Prints "looprender: error: ..." and returns the Status code as exit code.
int fail(const lt::Status& st);

// Binary little-endian PLY of a tessellation: vertex x y z nx ny nz (float), face
// (int), u v (float), then s t (float, TEXCOORD_0) when the soup has texcoords and
// tx ty tz tw (float, TANGENT) when it has tangents, s1 t1 (float, TEXCOORD_1) and
// red green blue alpha (float, linear COLOR_0) when it has those, and one face
// element per triangle (an indexed tessellation's indices, else 3k, 3k+1, 3k+2).
// `bytes` is replaced. Little-endian hosts only.
void writePly(const lt::Tessellation& soup, std::vector<uint8_t>& bytes);

// Writes the capture as PLY (writePly) / a JSON report / raw bytes, atomically.
lt::Status writePlyFile(const std::string& path, const lt::Tessellation& soup);
lt::Status writeJsonFile(const std::string& path, const nlohmann::json& report);

// --mesh: one frame of the pattern path as indexed triangles, in
// VulkanSurface::recordEvaluate's layout (the CPU evaluator's EvalSettings::indexed
// order): per vertex kMeshFloats floats, position xyz, unit normal xyz, TANGENT xyzw
// ((0, 0, 0, 1) without TEXCOORD_0), TEXCOORD_0 s t ((0, 0) without); 3 indices a
// triangle.
inline constexpr size_t kMeshFloats = 12;
struct Mesh {
    std::vector<float> vertices;
    std::vector<uint32_t> indices;
    bool texcoords = false;  // the asset has TEXCOORD_0: the file gets TANGENT and s t
};
// --mesh's file, binary little-endian PLY: vertex x y z nx ny nz (float), then tx ty
// tz tw s t (float) when `texcoords`, and one face element per triangle (list uchar
// uint). `bytes` receives the header for `vertices` and `triangles` and is sized for
// the whole file, so that the vertices can be written in place from any layout:
// returns the offset of vertex 0, whose meshPlyFloats(texcoords) floats the others
// follow; putMeshFaces then writes the faces after the last vertex.
size_t meshPlyLayout(size_t vertices, size_t triangles, bool texcoords, std::vector<uint8_t>& bytes);
inline size_t meshPlyFloats(bool texcoords) { return texcoords ? kMeshFloats : 6; }
void putMeshFaces(const std::vector<uint32_t>& indices, std::vector<uint8_t>& bytes);
// The PLY of a device mesh (recordEvaluate's layout), written atomically.
lt::Status writeMeshFile(const std::string& path, const Mesh& mesh);
// --json's "mesh": its vertices and triangles, and its path (always the patterns',
// indexed, whatever path the frame drew).
nlohmann::json meshReport(size_t vertices, size_t triangles);
// Prints "OUT.ply: V vertices, T triangles, indexed (WHERE)" to stdout.
void printMesh(const Options& o, size_t vertices, size_t triangles, const std::string& where);

// Report fields both paths share; `tessFactor` is the factor F used (lt::lodTessFactor).
nlohmann::json baseReport(const Options& o, const lt::Asset& asset, float tessFactor, uint32_t depth,
                          uint64_t triangles, lt::DrawPath path);

// Column-major object-to-clip matrix for Vulkan (y down, depth 0..1) of a camera
// looking at the asset: from o.eye to o.target, or framing the control mesh's
// bounding box; `light` gets the unit direction towards the camera (a headlight).
void cameraMatrix(const Options& o, const lt::Asset& asset, float mvp[16], float light[3]);

// The evaluation the options ask for, drawn by `path`: o.tess, o.spacing,
// o.watertight and o.displace, at the global factor (lodSettings gives an asset's
// o.lod; the edit values are scaledEditValues').
lt::EvalSettings evalSettings(const Options& o, lt::DrawPath path);

// The level of detail of o.lod for the camera cameraMatrix uses (its eye, vertical
// field of view and o.height rows).
lt::Lod lodSettings(const Options& o, const lt::Asset& asset);

// Encodes RGBA8 rows (top first) as PNG and writes it atomically.
lt::Status writePngFile(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba);

int runCpu(const Options& o, const lt::Asset& asset);
int runGpu(const Options& o, const lt::Asset& asset);
// --color material: the whole scene of the GLB `bytes` (looprender_scene.cpp).
int runScene(const Options& o, const std::vector<uint8_t>& bytes);

}  // namespace looprender
