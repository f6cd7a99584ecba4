// looptess/asset.h -- the in-memory form of a baked EXT_mesh_loop_subdivision asset,
// and the functions that read and write it as glTF 2.0 (GLB).
//
// This is the contract between the baker (which fills an Asset) and the runtime
// (which evaluates one). The on-disk layout is specified in
// formats/EXT_mesh_loop_subdivision/README.md; this header is its in-memory mirror.
//
// Vertex numbering. All refined vertices live in one buffer, level after level:
//
//   | level 0: control vertices | level 1: vertex pts | edge pts | level 2: ... |
//   0                           levels[1].firstVertex            levels[2].firstVertex
//
// Every index stored in an Asset is such a global vertex index, except where a
// field says otherwise.
//
// Triangle corner and edge numbering, used by every patch (OpenSubdiv's convention):
//
//            c2 (s,t) = (0,1)
//            | \  .
//   edge 2   |   \   edge 1
//   (s = 0)  |     \ (s + t = 1)
//            |       \  .
//            c0 ------ c1 (1,0)
//          (0,0) edge 0 (t = 0)
//
// Edge i runs from corner i to corner (i+1) % 3.
//
// Usage:
//   lt::Asset asset;
//   lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), "hero.glb", asset);
//   if (!st) { fprintf(stderr, "%s\n", st.message.c_str()); return 2; }
#pragma once

#include "looptess/status.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lt {

// Refinement from level l-1 to level l (l >= 1). Level l's vertices are the vertex
// points (one per kept parent vertex) followed by the edge points (one per kept
// parent edge).
struct Refinement {
    uint32_t firstVertex = 0;  // global index of level l's first vertex

    // Vertex points, CSR: vertex point i is computed from parent vertex
    // vertexParent[i] and its 1-ring vertexRing[vertexRingStart[i] ..
    // vertexRingStart[i+1]) (ring order: the reference baker starts at the
    // neighbour with the smallest global index, then follows OpenSubdiv's
    // counter-clockwise order of the vertex's edges; any order is valid).
    // Smooth vertex points use Loop's rule with beta(n):
    //   v' = (1 - n*beta) v + beta * sum(ring) = v + beta * sum(ring_j - v)
    std::vector<uint32_t> vertexParent;     // [vertexPointCount]
    std::vector<uint32_t> vertexRingStart;  // [vertexPointCount + 1]
    std::vector<uint32_t> vertexRing;       // [vertexRingStart.back()]

    // Vertex points whose Sdc mask is not the smooth rule (creases, corners,
    // boundaries, fractional sharpness, Chaikin, non-manifold): an explicit mask.
    // maskedVertex[k] is a local vertex point index; its weights are
    // maskWeights[maskStart[k] .. maskStart[k+1]), one per ring entry. Masks are
    // affine, so the parent's own weight is implied:
    //   v' = v + sum_j w_j (ring_j - v)
    std::vector<uint32_t> maskedVertex;
    std::vector<uint32_t> maskStart;  // [maskedVertex.size() + 1]
    std::vector<float> maskWeights;

    // Edge points: 4 per edge point: endpoints a, b, then opposite vertices c, d of
    // the two incident triangles (paper Fig. 5). Smooth rule:
    //   e = 3/8 (a + b) + 1/8 (c + d)
    // On a boundary (one face) d == c.
    std::vector<uint32_t> edgeVerts;  // [4 * edgePointCount]
    // Edge points with a crease weight w in (0, 1]: e = (1-w) smooth + w (a+b)/2.
    // creaseEdge[k] is a local edge point index (0-based within the edge points).
    std::vector<uint32_t> creaseEdge;
    std::vector<float> creaseWeight;

    uint32_t vertexPointCount() const { return uint32_t(vertexParent.size()); }
    uint32_t edgePointCount() const { return uint32_t(edgeVerts.size() / 4); }
    uint32_t vertexCount() const { return vertexPointCount() + edgePointCount(); }
};

// Where a patch lies on its base face, in OpenSubdiv's (u,v) parameterization of
// the base triangle (corners 0,1,2 at (0,0),(1,0),(0,1)). A patch of level l covers
//   (u,v) = d * (ui, vi) + d * (s, t) * (rotated ? -1 : 1),  d = 2^-l
// for its own parameters (s,t) in the unit triangle.
struct PatchParam {
    uint32_t baseFace = 0;
    uint16_t ui = 0, vi = 0;
    uint8_t level = 0;
    bool rotated = false;
};

// Regular patch (RPP or NPP): 12 box-spline control points.
//
//          10-----11
//          / \   / \            patch triangle: c0 = 4, c1 = 5, c2 = 8
//         /   \ /   \         .
//        7-----8-----9          boundaryMask bits 0..2: edge i is a boundary
//       / \   / \   / \         (its 3 outer points are phantoms: edge 0 -> 0,1,2;
//      /   \ /   \ /   \         edge 1 -> 6,9,11; edge 2 -> 10,7,3)
//     3-----4-----5-----6       bits 3..5: corner i is a boundary vertex without
//      \   / \   / \   /         a boundary edge of this patch (its 2 outer points
//       \ /   \ /   \ /          are phantoms: c0 -> 3,0; c1 -> 2,6; c2 -> 11,10)
//        0-----1-----2
//
// Phantom point indices are stored as copies of point 4 (any valid index) and
// never read with a non-zero weight.
struct RegularPatch {
    uint32_t points[12] = {};
    uint8_t boundaryMask = 0;
    // Bit i set: edge i borders a patch of the next finer level, so the patch is
    // non-plain (NPP) and is split into sub-patches when the runtime depth is
    // greater than this patch's level. 0: regular plain patch (RPP).
    uint8_t splitMask = 0;
    PatchParam param;
};

// Irregular face: drawn as one flat triangle between exact limit points (an IPP)
// when this level is the runtime depth, refined further otherwise.
struct IrregularFace {
    uint32_t corners[3] = {};  // indices into Level::limitStencils' vertices
    PatchParam param;
};

// Limit stencils of one level: position and two tangents of the limit surface at a
// vertex, as weighted sums over the vertex and its ring. Weights are affine: the
// position's sum to 1 and the tangents' to 0, so the vertex's own weight is implied
// and evaluation sums over differences:
//   P = P[v] + sum_k wP_k (P[ring_k] - P[v]),  T = sum_k wT_k (P[ring_k] - P[v]).
// The ring starts at the neighbour with the smallest global index (paper 3.4.1),
// so every patch touching the vertex sums in the same order. A vertex on two or
// more infinitely sharp edges has one stencil per sector (its ring is the
// sector's), so `vertex` may repeat.
//
// Smooth stencils (a closed ring of n neighbours, Loop's smooth limit masks) store
// no weights: wP_k = 1 / (n + 3 / (8 gamma(n))) (1/12 for n = 6), with
// gamma(n) = (5/8 - (3/8 + 1/4 cos(2 pi / n))^2) / n, and wTu_k = cos(2 pi k / n),
// wTv_k = sin(2 pi k / n). Every other stencil is listed in `masked` with explicit
// weights parallel to its ring.
struct LimitStencils {
    std::vector<uint32_t> vertex;     // [count] global index of the vertex
    std::vector<uint32_t> start;      // [count + 1] CSR into ring
    std::vector<uint32_t> ring;       // neighbours, global indices
    std::vector<uint32_t> masked;     // increasing stencil indices with explicit weights
    std::vector<uint32_t> maskStart;  // [masked.size() + 1] CSR into the weight arrays
    std::vector<float> position;      // explicit weights, one per ring entry of each masked stencil
    std::vector<float> tangentU;      // for dP/du
    std::vector<float> tangentV;      // for dP/dv; normal = tangentU x tangentV
    uint32_t count() const { return uint32_t(vertex.size()); }
};

// Hierarchical edits of one level l (spec "Hierarchical edits"). After level l's
// points are computed (level 0: the control points as given), before level l+1's,
// each edited vertex's point p takes its edits in stored order:
//   Set: p = value      Add: p = p + value      Subtract: p = p - value
// (per coordinate, in float). Where the edits are and what they do is baked; the
// values are data an application may change every frame without re-baking
// (EvalSettings::editValues, VulkanSurface::setEditValues).
//
// The flat edit order used by those APIs: level 0's edits, then level 1's, ...; in
// a level, edit k = op[k] / value[3k .. 3k+3).
enum class EditOp : uint8_t { Set = 0, Add = 1, Subtract = 2 };
struct VertexEdits {
    std::vector<uint32_t> vertex;  // distinct global indices of level l's vertices, increasing
    std::vector<uint32_t> start;   // [vertex.size() + 1] CSR into op (empty without edits)
    std::vector<EditOp> op;        // one per edit; a vertex's edits in input order
    std::vector<float> value;      // 3 per edit
    uint32_t count() const { return uint32_t(op.size()); }
};

// Everything about one subdivision level l.
struct Level {
    Refinement refinement;              // empty for level 0
    VertexEdits edits;                  // applied after this level's points (often empty)
    std::vector<RegularPatch> regular;  // RPPs and NPPs of this level
    std::vector<IrregularFace> irregular;
    LimitStencils limit;  // for the corners of `irregular`
};

enum class BoundaryInterpolation : uint8_t { None = 0, EdgeAndCorner = 1, EdgeOnly = 2 };
enum class CreaseMethod : uint8_t { Normal = 0, Chaikin = 1 };

// Optional scalar displacement map (spec "Displacement map"): the surface is moved
// along its unit limit normal by
//   displacement(face, u, v) = scale * value + bias      (object units)
// with value in [0, 1] interpolated from per-face triangular tiles of resolution R
// whose border samples are shared: one sample per control vertex, R - 1 per
// control-mesh edge, (R-1)(R-2)/2 inside each face. Grid point (i, j) of a face's
// tile sits at (u, v) = (i / R, j / R), i + j <= R. Face f, R = 4:
//
//      (0,4) c2              c0, c1, c2  the face's corners: sample = control vertex index
//            | \             e           the face's edges: edge k (corner k -> k+1) is
//     (0,3)  e   e                       control-mesh edge faceEdges[3f + k], whose R - 1
//            |     \                     samples run from its smaller control vertex index
//     (0,2)  e  x    e                   to its larger, whichever way the face runs it
//            |         \     x           interior samples of face f, row by row:
//     (0,1)  e  x   x    e               j = 1 .. R-2, i = 1 .. R-1-j
//            |             \  .
//      (0,0) c0--e---e---e--c1 (4,0)
//
//   values: | V vertex samples | F * (R-1)(R-2)/2 interior samples | E * (R-1) edge samples |
//
// V = controlVertexCount(), F = faceCount(), E = max(faceEdges) + 1 (every edge index
// is used, one per unordered control-vertex pair). Samples are 16-bit unorm
// (value = q / 65535); displacementSample() maps a grid point to its index.
struct DisplacementMap {
    uint32_t resolution = 0;          // R: a power of two 1..64; 0: the asset has no map
    float scale = 1.0f, bias = 0.0f;  // displacement = scale * value + bias
    std::vector<uint32_t> faceEdges;  // 3 per base face (empty without a map)
    std::vector<uint16_t> values;     // the samples, layout above (empty without a map)
    bool present() const { return resolution != 0; }
};

struct Asset {
    // Control mesh (level 0). Faces are counter-clockwise triangles.
    std::vector<float> positions;   // 3 per control vertex
    std::vector<uint32_t> faces;    // 3 per base face
    std::vector<float> faceUVs;     // 6 per base face (per corner), or empty
    std::vector<float> faceUV1s;    // TEXCOORD_1: 6 per base face, or empty
    std::vector<float> faceColors;  // COLOR_0, linear RGBA: 12 per base face, or empty

    BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly;
    CreaseMethod creaseMethod = CreaseMethod::Normal;
    std::vector<Level> levels;     // levels[0 .. maxDepth]
    DisplacementMap displacement;  // optional (displacement.present())

    uint32_t controlVertexCount() const { return uint32_t(positions.size() / 3); }
    uint32_t faceCount() const { return uint32_t(faces.size() / 3); }
    uint32_t maxDepth() const { return levels.empty() ? 0 : uint32_t(levels.size() - 1); }
    // Total number of vertices in the refined vertex buffer (all levels).
    uint32_t totalVertexCount() const;
    // Hierarchical edits over all levels (the flat edit order of VertexEdits).
    uint32_t editCount() const;
    // The deepest level with hierarchical edits; 0 without edits.
    uint32_t editDepth() const;
};

// Number of samples of a displacement map of resolution R (a power of two 1..64)
// on V control vertices, F faces and E edges (see DisplacementMap).
inline uint64_t displacementSampleCount(uint32_t R, uint64_t V, uint64_t F, uint64_t E) {
    return V + F * ((R - 1) * uint64_t(R - 2) / 2) + E * (R - 1);  // R = 1: (R-1)(R-2) = 0
}

// Index into asset.displacement.values of grid point (i, j) of base face `face`'s
// tile (i + j <= R). The asset must have passed validateAsset and have a map.
inline uint64_t displacementSample(const Asset& asset, uint32_t face, uint32_t i, uint32_t j) {
    const uint32_t R = asset.displacement.resolution;
    const uint32_t* c = &asset.faces[3 * size_t(face)];
    const uint32_t* e = &asset.displacement.faceEdges[3 * size_t(face)];
    const uint64_t interior = (R - 1) * uint64_t(R - 2) / 2;
    const uint64_t edgeBase = asset.controlVertexCount() + uint64_t(asset.faceCount()) * interior;
    // Sample p = 1 .. R-1 of face edge k, counted from corner k.
    auto onEdge = [&](int k, uint32_t p) {
        const uint32_t from = c[k], to = c[(k + 1) % 3];
        return edgeBase + uint64_t(e[k]) * (R - 1) + (from < to ? p : R - p) - 1;
    };
    if (j == 0) return i == 0 ? c[0] : i == R ? c[1] : onEdge(0, i);
    if (i + j == R) return j == R ? c[2] : onEdge(1, j);
    if (i == 0) return onEdge(2, R - j);
    const uint64_t row = uint64_t(j - 1) * (R - 1) - uint64_t(j - 1) * j / 2;  // rows 1 .. j-1 hold R-1-j' each
    return asset.controlVertexCount() + uint64_t(face) * interior + row + (i - 1);
}

// Bytes of each table kind, for reports.
struct TableSizes {
    size_t controlMesh = 0, refinement = 0, masks = 0, patches = 0, irregular = 0, limit = 0;
    size_t displacement = 0;  // the displacement map's faceEdges and values
    size_t edits = 0;         // hierarchical edits: every level's CSR and ops, and the values
    size_t total() const {
        return controlMesh + refinement + masks + patches + irregular + limit + displacement + edits;
    }
};

// What writeAssetGlb / writeSceneGlb wrote: the tables' own bytes per kind (the
// fields inherited: accessor data, as a reader decodes it) and `encoded`, the
// bytes each kind takes in the file (equal to the raw bytes where the tables are
// not compressed; the fallback primitive's accessors never are). In a compressed
// stream each kind's share is exact at Zstandard's block boundaries (128 KiB of
// planes) and apportioned by raw bytes within a block; the kinds add up to the
// file's bytes.
struct TableBytes : TableSizes {
    TableSizes encoded;
};

// How the writer stores a surface's tables (spec "Compression"): `None` as plain
// accessors; `Fast` and `Max` as one compressed stream per surface (byte planes
// and Zstandard at level 4 or 19: Max is smaller, slower to write and a little
// slower to read). Either way the fallback primitive stays plain glTF.
enum class Compression { None, Fast, Max };

// Checks every count, offset and index range of `asset` against the spec's
// validity rules. Safe on untrusted data. `name` prefixes messages. An asset of
// 2^19 table values or more has its levels checked on one thread per core (the
// caller and the library's helper threads, finished before it returns); the status
// is the same as on one.
Status validateAsset(const Asset& asset, const std::string& name);

// Serializes `asset` as a GLB (the control mesh as the primitive's fallback, the
// tables in EXT_mesh_loop_subdivision, stored as `compression` says).
// Deterministic: same asset and setting, same bytes (for a given zstd version).
// `bytes` is replaced. `tableBytes` (optional) receives per-table sizes. The
// compressed stream's frames are encoded on up to `threads` threads (the caller and
// the library's helper threads, finished before it returns; 0:
// std::thread::hardware_concurrency(), 1: the calling thread alone): the same bytes
// for every count.
Status writeAssetGlb(const Asset& asset, std::vector<uint8_t>& bytes, TableBytes* tableBytes = nullptr,
                     Compression compression = Compression::Fast, unsigned threads = 0);

// Parses a GLB produced by writeAssetGlb or writeSceneGlb (or any conforming
// writer) and returns its first surface (in mesh order). Safe on untrusted bytes:
// every range is checked, then validateAsset runs. `name` (the file name) prefixes
// error messages. A compressed surface of 16 MiB or more of tables is decompressed
// on up to 8 threads, and one of 2^19 table values or more has its levels decoded
// and checked on one thread per core (the caller and the library's helper threads,
// finished before it returns; the result and any error are the same as on one);
// smaller ones on the calling thread.
Status readAssetGlb(const uint8_t* data, size_t size, const std::string& name, Asset& asset);

// One surface of a glTF scene: a mesh carrying the extension (spec "Scenes"). Its
// cage primitives are the mesh's primitives that carry the extension; their
// triangles, in primitive order, are the base faces, except triangles with two
// corners at one control vertex (a line or a point, drawn as nothing).
struct SceneSurface {
    uint32_t mesh = 0;                 // index into the file's meshes
    std::string name;                  // the mesh's name ("" when it has none)
    std::vector<uint32_t> primitives;  // cage primitives, indices into meshes[mesh].primitives
    // Per cage primitive, each primitive vertex's control vertex. Writer: empty
    // means the identity. Reader: always filled (the identity written out), so an
    // application can carry per-vertex data (skin weights, morph targets) of the
    // primitives over to the control vertices.
    std::vector<std::vector<uint32_t>> controlVertex;
    // Reader: [primitives.size() + 1]: cage primitive k's base faces are
    // [primitiveFaces[k], primitiveFaces[k + 1]). Writer: ignored.
    std::vector<uint32_t> primitiveFaces;
    Asset asset;
};

// Adds surfaces to a glTF scene and serializes it as a GLB. `json` is a glTF 2.0
// document whose only buffer (if any) is `bin`, with no uri and byteLength
// bin.size(); images live in bufferViews. Each surface's tables are appended
// (accessors and bufferViews after the document's own) and put on its mesh and cage
// primitives; everything else in the document is written as given, key order kept.
// The cage primitives must be TRIANGLES whose POSITION (5126, not sparse) mapped
// through controlVertex gives surface.asset's control mesh (readSceneGlb checks it).
// Tables stored as `compression` says, on `threads` threads (writeAssetGlb).
// Deterministic. Usage on a document that breaks these preconditions.
Status writeSceneGlb(std::string_view json, std::vector<uint8_t> bin, const std::vector<SceneSurface>& surfaces,
                     std::vector<uint8_t>& bytes, TableBytes* tableBytes = nullptr,
                     Compression compression = Compression::Fast, unsigned threads = 0);

// Parses every surface of a GLB, in mesh order. Safe on untrusted bytes, as
// readAssetGlb; a file without a surface is an error (rule 8).
Status readSceneGlb(const uint8_t* data, size_t size, const std::string& name, std::vector<SceneSurface>& surfaces);

}  // namespace lt
