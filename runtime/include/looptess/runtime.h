// looptess/runtime.h -- evaluates a baked asset: subdivision tables level by level,
// then every patch at the tessellator's domain points. No OpenSubdiv.
//
// This is the CPU path: it runs the same tables, in the same operation order, as
// the GPU pipeline, for tests and tools.
//
//   lt::Asset asset;                                  // from lt::readAssetGlb
//   lt::EvalSettings settings;
//   settings.tessFactor = 8;
//   lt::Tessellation soup;
//   lt::evaluateCpu(asset, asset.positions.data(), settings, soup);
//
// Level of detail: a global factor F >= 1 gives the runtime depth d = ceil(log2 F)
// capped at the asset's maximum depth (runtimeDepth); EvalSettings::lod picks F, and
// in Screen mode every patch edge's own factor. The rules (factors per level, NPP
// sub-patches, IPPs, fractional-odd rounding, edgeFactor and the Distance and Screen
// modes): docs/how-it-works.md, "Level of detail".
#pragma once

#include "looptess/asset.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace lt {

enum class Spacing : uint8_t { Equal, FractionalOdd };

// Where the domain points of regular patches come from (the IPPs are the same), and
// on the GPU (vulkan.h) which stages evaluate the surface:
//   Tessellator  the hardware tessellator's, with a Spacing (the CPU reproduces
//                lavapipe's); evaluated in tessellation evaluation shaders
//   Patterns     refinement patterns without a tessellator: each edge factor rounded
//                up to a power of two in [1, 64], the domain a uniform grid with
//                coarser edges snapped; Spacing unused; evaluated in the vertex
//                shader of instanced draws
//   Compute      the points of Patterns, evaluated in compute passes and drawn as
//                plain indexed triangles (VulkanSurface's batches)
//   Auto         VulkanSurface measures the paths the device has and keeps the
//                fastest (VulkanSurface::pathChoices)
// The CPU evaluates Patterns, Compute and Auto alike: the points of Patterns.
enum class DrawPath : uint8_t { Tessellator, Patterns, Compute, Auto };

// Whether `path` draws the points of refinement patterns (everything but Tessellator).
inline bool drawsPatterns(DrawPath path) { return path != DrawPath::Tessellator; }

enum class LodMode : uint8_t { Global, Distance, Screen };

// A camera for level of detail (see above). Object space.
struct Lod {
    LodMode mode = LodMode::Global;
    float eye[3] = {0, 0, 0};
    float pixelsPerUnit = 0;  // imageHeight / (2 tan(fovY / 2)): pixels of a unit length at distance 1
    float pixelsPerEdge = 8;  // target on-screen length of a tessellated edge
};

// A Lod for a perspective camera at `eye` with vertical field of view `fovYDegrees`
// rendering `imageHeight` rows.
Lod cameraLod(LodMode mode, const float eye[3], float fovYDegrees, uint32_t imageHeight, float pixelsPerEdge);

// How to evaluate the surface, on the CPU (evaluateCpu) and on the GPU: vulkan.h's
// FrameSettings is an EvalSettings plus what only a draw needs, so the same values
// give the same surface on both.
struct EvalSettings {
    float tessFactor = 1.0f;  // global factor F, >= 1 (LodMode::Global; lodTessFactor caps it)
    Spacing spacing = Spacing::Equal;
    DrawPath path = DrawPath::Tessellator;
    // DrawPath::Patterns only: indexed triangles (Tessellation::indices), each pattern
    // point evaluated once per patch, in the order VulkanSurface::recordEvaluate
    // writes them: per patch in draw order its pattern's points row by row, then the
    // IPPs' corners, 3 a triangle. The same vertices as the soup, bit for bit.
    bool indexed = false;
    Lod lod;  // default: Global
    // Watertight evaluation (paper 3.4; spec "Watertight evaluation"): every point
    // on a shared patch edge or corner is computed from the same control points in
    // the same operation order by every patch that contains it, so a welded
    // tessellation has no cracks, bit for bit. false: each patch evaluates alone
    // (faster; shared edges may differ in the last bits). Measure with --no-watertight.
    bool watertight = true;
    // Displace along the normal by the asset's displacement map (spec "Displacement
    // map"), when it has one. false: the undisplaced limit surface.
    bool displace = true;
    // Hierarchical edit values to use instead of the baked ones: 3 floats per edit,
    // asset.editCount() edits in the flat order of asset.h's VertexEdits (bakedEditValues
    // gives the baked ones to start from). nullptr: the asset's own values.
    const float* editValues = nullptr;
    // The CPU evaluator only: false leaves Tessellation's texcoords, tangents,
    // texcoords1 and colors empty (a collision mesh, a check of the surface alone);
    // the rest is the same bits.
    bool attributes = true;
    // The CPU evaluator only: threads the patches are evaluated on, in chunks of
    // contiguous patches written in place (0: std::thread::hardware_concurrency();
    // small frames use fewer): the calling thread and helper threads that the library
    // starts at the first use and keeps, idle, for the process. The output is the
    // same bits for every count.
    unsigned threads = 0;
    // The CPU evaluator only: the patches of base faces [firstFace, firstFace +
    // faceCount) alone (faceCount past the last face: to the end), in the whole
    // frame's order; every vertex the same bits as in the whole frame (the watertight
    // plan is the whole asset's). To evaluate a frame too large for memory in pieces
    // (loopcheck does), or only the faces an engine needs. Screen-mode factors are
    // the whole frame's.
    uint32_t firstFace = 0, faceCount = UINT32_MAX;
};

// An unwelded triangle soup: vertex 3k, 3k+1, 3k+2 form triangle k,
// counter-clockwise seen from the side the normals point to.
struct Tessellation {
    std::vector<float> positions;  // 3 per vertex
    std::vector<float> normals;    // 3 per vertex, unit length
    std::vector<uint32_t> face;    // base triangle per vertex
    std::vector<float> uv;         // 2 per vertex: location on the base triangle
    // 2 per vertex when the asset has per-corner UVs (TEXCOORD_0), else empty: the
    // base face's corner UVs c0, c1, c2 interpolated linearly (OpenSubdiv's
    // FVAR_LINEAR_ALL), in float, in this order: w = (1 - u) - v;
    // texcoord = (w * c0 + u * c1) + v * c2 per component (spec "Texture coordinates";
    // faceTexcoord). The CPU evaluator emits them, and so does every GPU draw
    // (the shaders compute the same bits; a capture records them).
    std::vector<float> texcoords;
    // TEXCOORD_1 (2 per vertex) and COLOR_0 (4 per vertex, linear RGBA) when the asset
    // has them, else empty: linear over the base face by faceTexcoord's rule (per
    // component), like TEXCOORD_0.
    std::vector<float> texcoords1, colors;
    // 4 per vertex when the asset has TEXCOORD_0 (glTF's TANGENT), else empty: xyz the
    // unit direction in which TEXCOORD_0's s grows, in the plane orthogonal to the
    // normal, and w = +1 or -1, the handedness (bitangent = cross(normal, xyz) * w).
    // faceTangent's rule (spec "Tangents"): from the surface's partial derivatives
    // where a regular patch is evaluated, from the IPP triangle's edges at its
    // corners. Not shared bit for bit across patch edges, unlike positions and
    // normals; the GPU emits the same bits as the CPU.
    std::vector<float> tangents;
    // EvalSettings::indexed: 3 per triangle, indices of the vertices above (each
    // refinement pattern point once per patch). Empty: the soup (vertices 3k, 3k+1,
    // 3k+2 are triangle k).
    std::vector<uint32_t> indices;
    size_t vertexCount() const { return face.size(); }
    size_t triangleCount() const { return indices.empty() ? face.size() / 3 : indices.size() / 3; }
};

// Surface attribute arithmetic. Out of line (runtime/src/face_attributes.cpp), so
// every caller gets the library's bits whatever its own compiler flags (no fused
// multiply-add: the library compiles with -ffp-contract=off); the CPU evaluator
// runs the same code.

// A face-corner attribute at (u, v) of a base face whose corners hold c[0 .. 3 width)
// (`width` components each: TEXCOORD_n 2, COLOR_0 4), linear over the face, per
// component in this order (Tessellation::texcoords' rule):
//
//   w = (1 - u) - v;   out[k] = (w * c0[k] + u * c1[k]) + v * c2[k]
void faceAttribute(const float* c, int width, float u, float v, float* out);
// The texture coordinate at (u, v) of a base face whose corner UVs are c[0..5]:
// faceAttribute(c, 2, u, v, st).
void faceTexcoord(const float c[6], float u, float v, float st[2]);

// TANGENT (Tessellation::tangents) at a point of a base face with corner UVs c[0..5],
// unit normal n, and partial derivatives pu, pv of the surface along the face's u and
// v (any common scale; a negative one flips the tangent, so pass the patch's own
// derivatives times its rotation's sign). In this operation order (the shaders' too):
//
//   (s1, t1) = c1 - c0, (s2, t2) = c2 - c0; det = s1 t2 - s2 t1; w = det < 0 ? -1 : 1
//   g = (t2 pu - t1 pv) w        dP/ds up to a positive scale (zero: degenerate UVs,
//                                then g = pu, w = 1)
//   g = g - n (n . g)            into the tangent plane;  xyz = unitNormal(g)
//   out = (xyz, w)
void faceTangent(const float c[6], const float pu[3], const float pv[3], const float n[3], float out[4]);

// The unit vector every evaluator (CPU and shaders) makes of a normal, a tangent or a
// displacement direction `n` (spec "Unit normals"): n / |n|; n scaled by its largest
// component first where |n|^2 would under- or overflow; (0, 0, 1) where n has no
// direction (zero, subnormal, infinite or NaN). `out` is never zero or non-finite.
void unitNormal(const float n[3], float out[3]);

// The runtime depth for factor F (see above) of an asset baked to `maxDepth`:
// ceil(log2 F) capped at maxDepth, 0 for F <= 1.
uint32_t runtimeDepth(uint32_t maxDepth, float tessFactor);
// The same for `asset` (its maxDepth()).
inline uint32_t runtimeDepth(const Asset& asset, float tessFactor) {
    return runtimeDepth(asset.maxDepth(), tessFactor);
}

// The global factor F of `settings` for control points `controlPositions` (see
// above; settings.tessFactor in Global mode), at most 2^maxDepth in every mode where
// the asset's finest level has IPPs (their flat triangles take no more): watertight
// at any factor. Depth: runtimeDepth(asset, F).
float lodTessFactor(const Asset& asset, const float* controlPositions, const EvalSettings& settings);

// Runs the refinement tables of levels 1..depth on `controlPositions` (3 floats per
// control vertex) and returns every level's vertices in `vertices` (3 floats per
// global vertex; entries of levels above `depth` are left zero). `asset` must have
// passed validateAsset; depth <= asset.maxDepth().
// Each level's hierarchical edits are applied after its points, level 0's to the
// copied control points; `editValues` as EvalSettings::editValues.
void subdivideCpu(const Asset& asset, const float* controlPositions, uint32_t depth, std::vector<float>& vertices,
                  const float* editValues = nullptr);

// The asset's baked edit values in the flat edit order (3 floats per edit), e.g. to
// scale them and pass them back as EvalSettings::editValues.
std::vector<float> bakedEditValues(const Asset& asset);

// Subdivides and evaluates every patch for `settings` into `out` (replaced).
// `controlPositions` as for subdivideCpu (usually asset.positions.data()).
// Builds the watertight plan (what the rules need from the asset alone, O(asset))
// on every call: to evaluate one asset again and again, use a CpuEvaluator.
void evaluateCpu(const Asset& asset, const float* controlPositions, const EvalSettings& settings, Tessellation& out);

// evaluateCpu for one asset evaluated many times (animated control points, edit
// values or factors changing per frame): what depends on the asset alone is built
// once, on first need, and kept.
//
//   lt::CpuEvaluator evaluator(asset);
//   for (each frame) evaluator.evaluate(skinnedPositions, settings, soup);
//
// `asset` must outlive the evaluator and not change. One evaluator is not for
// concurrent use; evaluators of the same asset are independent.
class CpuEvaluator {
public:
    explicit CpuEvaluator(const Asset& asset);
    ~CpuEvaluator();
    CpuEvaluator(CpuEvaluator&&) noexcept;
    CpuEvaluator& operator=(CpuEvaluator&&) noexcept;

    // Builds now what evaluate with `settings` builds from the asset alone (the
    // watertight plan, for every factor; LodMode::Screen's split index), so that a
    // loading thread can pay for it instead of the first frame. Optional; changes no
    // result. (Without it, the first frame builds only the plan's levels it reads.)
    void prepare(const EvalSettings& settings);

    // The size of what evaluate(controlPositions, settings, out) writes, without
    // evaluating: out.vertexCount() and out.indices.size(), from the patches' counts
    // (kept for that evaluate). To size buffers, or to turn down a frame too large
    // for memory, first.
    void count(const float* controlPositions, const EvalSettings& settings, size_t& vertices, size_t& indices);

    // As evaluateCpu(asset, controlPositions, settings, out), bit for bit.
    void evaluate(const float* controlPositions, const EvalSettings& settings, Tessellation& out);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace lt
